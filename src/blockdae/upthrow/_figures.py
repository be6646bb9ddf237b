"""Figures of a spring-supported mass (Newmark 1969): a flight history."""

import numpy as np

from ..core import BASE, time_grid


def flight_figure(solution, *, n_points, title=None):
    """A flight history: the ground y and the mass y + u [m] (absolute, from the static
    position), the gap u - u0 above the unloaded support [m], and the support force per
    unit mass n [m/s²]; liftoffs (triangles up) and landings (down) marked."""
    import matplotlib.pyplot as plt

    t = time_grid(solution, n_points)
    u, _, gap, force = solution(t)
    ground = solution.motion.displacement(t) - solution.motion.displacement(0.0) if solution.motion else 0 * t
    fig, (position, lift, support) = plt.subplots(3, 1, sharex=True, figsize=(8, 7), constrained_layout=True)
    position.plot(t, ground, **BASE)
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
