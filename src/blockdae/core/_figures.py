"""What the figures of every system share: styles, a curve with its events marked, the
time grid; matplotlib is imported by the figures themselves, on demand."""

import numpy as np

from ..units import STANDARD_GRAVITY
from ._states import state_labels

BASE = dict(color="0.3", lw=1.2, label="base")
BLOCK = dict(color="C3", lw=1.2, ls="--", label="block")
EVENTS = dict(ls="none", marker="o", ms=4, mfc="none", color="C0", label="events")


def time_grid(solution, n_points):
    """``n_points`` times over [t_0, t_end] [s] and the solution's knots; n_points is
    checked (an integer >= 2)."""
    if not (isinstance(n_points, int) and n_points >= 2):
        raise ValueError(f"n_points must be an integer >= 2, got {n_points!r}")
    return np.union1d(np.linspace(solution.t[0], solution.t_end, n_points), solution.t)


def curve(ax, t, y, t_ev, y_ev, ylabel, style=None):
    """``y`` against ``t`` with the events (``t_ev``, ``y_ev``) marked and a zero line."""
    ax.plot(t, y, **(style or dict(color="C3", lw=1.2, label="block - base")))
    if t_ev is not None:
        ax.plot(t_ev, y_ev, **EVENTS)
    if ylabel:
        ax.set_ylabel(ylabel)
    ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)


def state_figure(solution, *, n_points, title=None):
    """Any driver model's solution: each state [its unit] against time, events marked."""
    import matplotlib.pyplot as plt

    t = time_grid(solution, n_points)
    state, _ = solution.dense_state(t)
    names = state_labels(solution.block, state.shape[-1])
    t_ev = solution.t_events
    fig, axes = plt.subplots(len(names), 1, sharex=True, figsize=(7, 2.2 * len(names)), squeeze=False,
                             constrained_layout=True)
    for i, (ax, name) in enumerate(zip(axes[:, 0], names)):
        curve(ax, t, state[..., i], t_ev, np.array([e.state[i] for e in solution.events]), name,
              style=dict(color="C3", lw=1.2, label=name))
    axes[-1, 0].set_xlabel("t [s]")
    if title:
        fig.suptitle(title)
    return fig


def batch_figure(batch, *, title=None):
    """u(t_end) and max |u| [its unit] of each parameter set against the parameter that varies."""
    import matplotlib.pyplot as plt

    grid, block = batch.parameters(), batch.block
    for tied in (block.tied_parameters().values() if block is not None else ()):
        for name in tied:  # moves with another parameter of the grid
            grid.pop(name, None)
    varied = [name for name, values in grid.items() if np.unique(values).size > 1]
    if len(varied) == 1:
        name = varied[0]
        x, xlabel = grid[name], block.parameter_labels.get(name, name)
    else:
        x = np.arange(len(batch))
        xlabel = "parameter set" + (f" ({', '.join(varied)} vary)" if varied else "")
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    ax.plot(x, batch.displacement, marker="o", ms=4, color="C3", label="u(t_end)")
    ax.plot(x, batch.max_abs_displacement, marker="s", ms=4, mfc="none", ls="--", color="0.3", label="max |u|")
    ax.set(xlabel=xlabel, ylabel=f"relative displacement (signed) [{batch.unit}]", title=title)
    ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    ax.legend(loc="best", fontsize="small")
    return fig


#: lines of an ensemble's figure labelled in a legend; beyond, the lines stay unlabelled
ENSEMBLE_LEGEND = 12


def ensemble_figure(ensemble, *, title=None):
    """max |displacement| [its unit] against the scaled motion's peak [g]: a line per (motion,
    polarity, parameter set) across the factors, a marker per case."""
    import matplotlib.pyplot as plt

    g = float(getattr(ensemble.model, "g", STANDARD_GRAVITY))
    peak = ensemble.cases.peak_g(g)  # (n_motions, n_scales)
    largest = ensemble.max_abs_displacement.reshape(ensemble.cases.shape + (-1,))
    n_motions, _, n_polarities, n_sets = largest.shape
    labelled = n_motions * n_polarities * n_sets <= ENSEMBLE_LEGEND
    fig, ax = plt.subplots(figsize=(6.5, 4), constrained_layout=True)
    for i, name in enumerate(ensemble.cases.names):
        for p, polarity in enumerate(ensemble.cases.polarities):
            for j in range(n_sets):
                label = " ".join([name] + ([polarity] if n_polarities > 1 else []) + ([f"set {j}"] if n_sets > 1
                                                                                       else []))
                ax.plot(peak[i], largest[i, :, p, j], marker="o" if polarity == "normal" else "s", ms=4,
                        ls="-" if polarity == "normal" else "--", color=f"C{i % 10}",
                        label=label if labelled else None)
    ax.set(xlabel="peak ground acceleration of the scaled motion [g]",
           ylabel=f"max |displacement| [{ensemble.model.displacement_unit}]", title=title)
    if labelled:
        ax.legend(loc="best", fontsize="small")
    return fig
