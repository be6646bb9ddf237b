"""Figures of the block on a plane (Elms 2000): the path in the plane and its components."""

import math

import numpy as np

from ..core import EVENTS, curve, time_grid


def planar_figure(solution, *, n_points, title=None):
    """Path (u_x, u_y) [m] in the plane; u_x, u_y [m] and |v| [m/s] against time; events
    marked, in the block's ``state_units`` (a block with g = 1, dimensionless: lengths in
    g s² and speeds in g s)."""
    import matplotlib.pyplot as plt

    length, speed_unit = (solution.block.state_units[0], solution.block.state_units[2]) if solution.block is not None \
        else ("m", "m/s")  # the block's state_units: of u_x and of the speed s
    t = time_grid(solution, n_points)
    u_x, u_y, v_x, v_y, _ = solution(t)
    events = solution.events
    t_ev = solution.t_events
    ux_ev, uy_ev = np.array([e.u_x for e in events]), np.array([e.u_y for e in events])
    speed_ev = np.array([math.hypot(e.v_x, e.v_y) for e in events])

    fig, (path, disp, speed) = plt.subplots(1, 3, figsize=(15, 4.5), constrained_layout=True)
    path.plot(u_x, u_y, color="C3", lw=1.2, label="block - base")
    path.plot(ux_ev, uy_ev, **EVENTS)
    path.set(xlabel=f"u_x [{length}]", ylabel=f"u_y [{length}]", title="path relative to the base")
    path.set_aspect("equal", adjustable="datalim")
    path.legend(loc="best", fontsize="small")
    disp.plot(t, u_x, color="C3", lw=1.2, label="u_x")
    disp.plot(t, u_y, color="C0", lw=1.2, ls="--", label="u_y")
    disp.plot(np.concatenate([t_ev, t_ev]), np.concatenate([ux_ev, uy_ev]), **EVENTS)
    disp.set(xlabel="t [s]", ylabel=f"relative displacement [{length}]")
    disp.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    disp.legend(loc="best", fontsize="small")
    curve(speed, t, np.hypot(v_x, v_y), t_ev, speed_ev, f"relative speed |v| [{speed_unit}]")
    speed.set_xlabel("t [s]")
    if title:
        fig.suptitle(title)
    return fig
