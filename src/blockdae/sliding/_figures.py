"""Figures of the 1-D block: seed 000 Figures 3-5 (absolute and relative motion, the
phase plane) and a batch's displacements against its parameters."""

import numpy as np

from ..core._figures import BASE, BLOCK, EVENTS, curve, time_grid

_LEGEND_ENTRIES = 12  # Newmark's figure has a legend for at most this many curves


def solution_figure(solution, excitation=None, block=None, *, n_points, title=None):
    """Left column (only with ``excitation``): base (solid) and block (dashed)
    acceleration [m/s²], velocity [m/s] and displacement [m] (the block's acceleration
    needs ``block``); right column: v [m/s], u [m] and the phase plane; events marked."""
    import matplotlib.pyplot as plt

    t = time_grid(solution, n_points)
    u, v = solution(t)
    t_ev = solution.t_events
    u_ev, v_ev = np.array([e.u for e in solution.events]), np.array([e.v for e in solution.events])

    with_base = excitation is not None
    fig, axes = plt.subplots(3, 2 if with_base else 1, figsize=(11 if with_base else 6, 8),
                             squeeze=False, constrained_layout=True)
    rel_v, rel_u, phase = axes[:, -1]
    curve(rel_v, t, v, t_ev, v_ev, "relative velocity v [m/s]")
    curve(rel_u, t, u, t_ev, u_ev, "relative displacement u [m]")
    rel_u.set_xlabel("t [s]")
    phase.plot(u, v, color="C3", lw=1.2)
    phase.plot(u_ev, v_ev, **EVENTS)
    phase.set(xlabel="u [m]", ylabel="v [m/s]", title="phase plane")
    phase.axhline(0.0, color="0.8", lw=0.8, zorder=0)

    if with_base:
        acc, vel, disp = axes[:, 0]
        a_base, v_base, x_base = (excitation.acceleration(t), excitation.velocity(t),
                                  excitation.displacement(t))
        at_ev = np.searchsorted(t, t_ev)
        curve(acc, t, a_base, t_ev, a_base[at_ev], "acceleration [m/s²]", style=BASE)
        if block is not None:
            mode = solution.mode[np.searchsorted(solution.t, t, side="right") - 1]
            dv = block.flow(mode, t, np.stack([u, v]), excitation)[1]
            acc.plot(t, a_base + dv, **BLOCK)
        curve(vel, t, v_base, None, None, "velocity [m/s]", style=BASE)
        curve(vel, t, v_base + v, t_ev, v_base[at_ev] + v_ev, None, style=BLOCK)
        curve(disp, t, x_base, None, None, "displacement [m]", style=BASE)
        curve(disp, t, x_base + u, t_ev, x_base[at_ev] + u_ev, None, style=BLOCK)
        disp.set_xlabel("t [s]")
        acc.legend(loc="upper right", fontsize="small")
    rel_v.legend(loc="best", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig



def batch_figure(batch, *, title=None):
    """u(t_end) and max |u| [m] of each parameter set against the parameter that varies."""
    import matplotlib.pyplot as plt

    grid = batch.parameters()
    if batch.block is not None and batch.block.mu_kinetic is None:
        del grid["mu_kinetic"]
    varied = [name for name, values in grid.items() if np.unique(values).size > 1]
    if len(varied) == 1:
        x, xlabel = grid[varied[0]], f"{varied[0]} [-]"
    else:
        x = np.arange(len(batch))
        xlabel = "parameter set" + (f" ({', '.join(varied)} vary)" if varied else "")
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    ax.plot(x, batch.displacement, marker="o", ms=4, color="C3", label="u(t_end)")
    ax.plot(x, batch.max_abs_displacement, marker="s", ms=4, mfc="none", ls="--", color="0.3", label="max |u|")
    ax.set(xlabel=xlabel, ylabel="displacement [m]", title=title)
    ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    ax.legend(loc="best", fontsize="small")
    return fig



def newmark_figure(ky, displacement, labels, *, polarity=None, title=None):
    """Newmark's D [m] against k_y [g]: one curve per row of ``displacement`` (shape
    (n_curves, n_ky)), labelled by ``labels``; ``polarity``, if given, says which D is drawn."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.5), constrained_layout=True)
    for label, d in zip(labels, displacement):
        ax.plot(ky, d, marker="o", ms=3.5, label=label)
    ax.set(xlabel="yield acceleration k_y [g]", ylabel="downslope displacement D [m]" + (f" ({polarity})" if polarity else ""), title=title)
    ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    if len(labels) <= _LEGEND_ENTRIES:
        ax.legend(loc="best", fontsize="small")
    return fig
