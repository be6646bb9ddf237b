"""Figures of a solution, in the layout of seed 000 Figures 3-5, of a planar solution
(seed 001: the path in the plane and its components) and of a flight history (seed 004);
matplotlib on demand."""

import math

import numpy as np

from .sliding._solution import BatchSolution, Solution
from .planar._solution import PlanarSolution
from .upthrow._solution import UpthrowSolution
from .excitation import AbstractExcitation
from .sliding._model import SlidingBlock
from .motions import RelativeMotion, ResponseSpectrum, plot_relative_motion, plot_spectrum

_BASE = dict(color="0.3", lw=1.2, label="base")
_BLOCK = dict(color="C3", lw=1.2, ls="--", label="block")
_EVENTS = dict(ls="none", marker="o", ms=4, mfc="none", color="C0", label="events")


def plot(solution: Solution | BatchSolution | PlanarSolution | UpthrowSolution | ResponseSpectrum | RelativeMotion,
         excitation: AbstractExcitation | None = None, block: SlidingBlock | None = None, *,
         n_points: int = 2000, title: str | None = None):
    """Draw a solution: absolute and relative motion, and the phase plane.

    A :class:`ResponseSpectrum` is drawn as PSa [m/s²] against the period (log-log; see
    :func:`blockdae.motions.plot_spectrum` for the other quantities), a
    :class:`RelativeMotion` as R(tau) with the seed-003 estimates. A
    :class:`BatchSolution` is drawn as u(t_end) and max |u| [m] against the one
    parameter that varies across its grid (mu_kinetic counts only when the grid sets
    it), or against the parameter-set index when none or several vary (the x label
    then names those that vary). A :class:`PlanarSolution` is drawn as the path
    (u_x, u_y) [m] of the block relative to the base, u_x and u_y [m] and the relative
    speed |v| [m/s] against time, events marked (``excitation`` and ``block`` unused);
    an :class:`UpthrowSolution` as its flight history (ground and mass, gap, support
    force; liftoffs and landings marked).

    Left column (only with ``excitation``): base (solid) and block (dashed)
    acceleration [m/s²], velocity [m/s] and displacement [m]; the block's
    acceleration needs ``block`` (its flow gives it). Right column: relative
    velocity v [m/s], relative displacement u [m] and the phase plane (u, v).
    Located events are marked with circles on every panel.

    Args:
        solution: a single run, or a batch (``excitation``, ``block``, ``n_points``
            are then unused).
        excitation: the base motion the solution was computed for.
        block: the block, for the block-acceleration curve.
        n_points: samples of the time grid; the solution's knots are added to it.
        title: figure title.

    Returns:
        The matplotlib Figure.
    """
    import matplotlib.pyplot as plt

    if isinstance(solution, BatchSolution):
        return _plot_batch(solution, title=title)
    if isinstance(solution, ResponseSpectrum):
        return plot_spectrum(solution, title=title)
    if isinstance(solution, RelativeMotion):
        return plot_relative_motion(solution, title=title)
    if not isinstance(solution, (Solution, PlanarSolution, UpthrowSolution)):
        raise TypeError("solution must be a Solution, BatchSolution, PlanarSolution, UpthrowSolution, "
                        f"ResponseSpectrum or RelativeMotion, got {type(solution).__name__}")
    if not (isinstance(n_points, int) and n_points >= 2):
        raise ValueError(f"n_points must be an integer >= 2, got {n_points!r}")
    if isinstance(solution, UpthrowSolution):  # seed 004: a flight history
        return _plot_upthrow(solution, n_points=n_points, title=title)
    if isinstance(solution, PlanarSolution):
        return _plot_planar(solution, n_points=n_points, title=title)
    t = np.union1d(np.linspace(solution.t[0], solution.t_end, n_points), solution.t)
    u, v = solution(t)
    t_ev = solution.t_events
    u_ev, v_ev = np.array([e.u for e in solution.events]), np.array([e.v for e in solution.events])

    with_base = excitation is not None
    fig, axes = plt.subplots(3, 2 if with_base else 1, figsize=(11 if with_base else 6, 8),
                             squeeze=False, constrained_layout=True)
    rel_v, rel_u, phase = axes[:, -1]
    _curve(rel_v, t, v, t_ev, v_ev, "relative velocity v [m/s]")
    _curve(rel_u, t, u, t_ev, u_ev, "relative displacement u [m]")
    rel_u.set_xlabel("t [s]")
    phase.plot(u, v, color="C3", lw=1.2)
    phase.plot(u_ev, v_ev, **_EVENTS)
    phase.set(xlabel="u [m]", ylabel="v [m/s]", title="phase plane")
    phase.axhline(0.0, color="0.8", lw=0.8, zorder=0)

    if with_base:
        acc, vel, disp = axes[:, 0]
        a_base, v_base, x_base = (excitation.acceleration(t), excitation.velocity(t),
                                  excitation.displacement(t))
        at_ev = np.searchsorted(t, t_ev)
        _curve(acc, t, a_base, t_ev, a_base[at_ev], "acceleration [m/s²]", style=_BASE)
        if block is not None:
            mode = solution.mode[np.searchsorted(solution.t, t, side="right") - 1]
            dv = block.flow(mode, t, np.stack([u, v]), excitation)[1]
            acc.plot(t, a_base + dv, **_BLOCK)
        _curve(vel, t, v_base, None, None, "velocity [m/s]", style=_BASE)
        _curve(vel, t, v_base + v, t_ev, v_base[at_ev] + v_ev, None, style=_BLOCK)
        _curve(disp, t, x_base, None, None, "displacement [m]", style=_BASE)
        _curve(disp, t, x_base + u, t_ev, x_base[at_ev] + u_ev, None, style=_BLOCK)
        disp.set_xlabel("t [s]")
        acc.legend(loc="upper right", fontsize="small")
    rel_v.legend(loc="best", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig


def _curve(ax, t, y, t_ev, y_ev, ylabel, style=None):
    ax.plot(t, y, **(style or dict(color="C3", lw=1.2, label="block - base")))
    if t_ev is not None:
        ax.plot(t_ev, y_ev, **_EVENTS)
    if ylabel:
        ax.set_ylabel(ylabel)
    ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)


def _plot_batch(batch: BatchSolution, *, title: str | None = None):
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


def _plot_planar(solution: PlanarSolution, *, n_points: int, title: str | None = None):
    """Path (u_x, u_y) [m] in the plane; u_x, u_y [m] and |v| [m/s] against time; events marked."""
    import matplotlib.pyplot as plt

    t = np.union1d(np.linspace(solution.t[0], solution.t_end, n_points), solution.t)
    u_x, u_y, v_x, v_y, _ = solution(t)
    events = solution.events
    t_ev = solution.t_events
    ux_ev, uy_ev = np.array([e.u_x for e in events]), np.array([e.u_y for e in events])
    speed_ev = np.array([math.hypot(e.v_x, e.v_y) for e in events])

    fig, (path, disp, speed) = plt.subplots(1, 3, figsize=(15, 4.5), constrained_layout=True)
    path.plot(u_x, u_y, color="C3", lw=1.2, label="block - base")
    path.plot(ux_ev, uy_ev, **_EVENTS)
    path.set(xlabel="u_x [m]", ylabel="u_y [m]", title="path relative to the base")
    path.set_aspect("equal", adjustable="datalim")
    path.legend(loc="best", fontsize="small")
    disp.plot(t, u_x, color="C3", lw=1.2, label="u_x")
    disp.plot(t, u_y, color="C0", lw=1.2, ls="--", label="u_y")
    disp.plot(np.concatenate([t_ev, t_ev]), np.concatenate([ux_ev, uy_ev]), **_EVENTS)
    disp.set(xlabel="t [s]", ylabel="relative displacement [m]")
    disp.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    disp.legend(loc="best", fontsize="small")
    _curve(speed, t, np.hypot(v_x, v_y), t_ev, speed_ev, "relative speed |v| [m/s]")
    speed.set_xlabel("t [s]")
    if title:
        fig.suptitle(title)
    return fig


# ---- a spring-supported mass (seed 004) --------------------------------------------
def _plot_upthrow(solution: UpthrowSolution, *, n_points: int, title: str | None = None):
    """A flight history: the ground y and the mass y + u [m] (absolute, from the static
    position), the gap u - u0 above the unloaded support [m], and the support force per
    unit mass n [m/s²]; liftoffs (triangles up) and landings (down) marked."""
    import matplotlib.pyplot as plt

    t = np.union1d(np.linspace(solution.t[0], solution.t_end, n_points), solution.t)
    u, _, gap, force = solution(t)
    ground = solution.motion.displacement(t) - solution.motion.displacement(0.0) if solution.motion else 0 * t
    fig, (position, lift, support) = plt.subplots(3, 1, sharex=True, figsize=(8, 7), constrained_layout=True)
    position.plot(t, ground, **_BASE)
    position.plot(t, ground + u, color="C3", lw=1.2, label="mass")
    position.set_ylabel("displacement [m]")
    lift.plot(t, gap, color="C3", lw=1.2)
    lift.set_ylabel("gap u - u0 [m]")
    support.plot(t, force, color="C0", lw=1.2)
    support.set(ylabel="support force n [m/s²]", xlabel="t [s]")
    for kind, marker in (("liftoff", "^"), ("landing", "v")):
        times = np.array([e.t for e in solution.events_of(kind)])
        if times.size:
            at = np.interp(times, t, ground)
            position.plot(times, at + solution(times)[0], ls="none", marker=marker, color="k", ms=5, label=kind)
            lift.plot(times, 0 * times, ls="none", marker=marker, color="k", ms=5)
    for ax in (position, lift, support):
        ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    position.legend(loc="best", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig
