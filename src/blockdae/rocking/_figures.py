"""Figures of a free-standing block: its rotation (or slide) and the base acceleration."""

import numpy as np

from ..core import time_grid


def rocking_figure(solution, *, n_points, title=None):
    """theta / alpha [-] (or u [m] for a sliding block) against t [s] with impacts and
    overturning marked, over the base acceleration a_x [m/s²]."""
    import matplotlib.pyplot as plt

    t = time_grid(solution, n_points)
    q = solution(t)[0]
    block = solution.block
    rocks = block is None or not block.slides
    scale = block.alpha if rocks and block is not None else 1.0
    fig, (motion, base) = plt.subplots(2, 1, sharex=True, figsize=(8, 6), constrained_layout=True,
                                       gridspec_kw=dict(height_ratios=(2, 1)))
    motion.plot(t, q / scale, color="C3", lw=1.2, label="theta / alpha" if rocks else "u")
    motion.set_ylabel("theta / alpha [-]" if rocks else "u [m]")
    impacts = solution.impact_times
    if impacts.size:
        motion.plot(impacts, 0 * impacts, ls="none", marker="|", color="k", ms=8, label="impacts")
    if solution.overturned:
        motion.axvline(solution.overturn_time, color="k", ls="--", lw=0.8, label="overturned")
    for level in (-1, 1) if rocks and block is not None else ():
        motion.axhline(level, color="0.7", lw=0.8, ls=":")
    motion.axhline(0.0, color="0.85", lw=0.8, zorder=0)
    motion.legend(loc="best", fontsize="small")
    if solution.motion is not None:
        components = getattr(solution.motion, "components", None)
        x = solution.motion if components is None else components[0]
        base.plot(t, np.asarray(x.acceleration(t)), color="0.4", lw=0.8)
    base.set(ylabel="a_x [m/s²]", xlabel="t [s]")
    if title:
        fig.suptitle(title)
    return fig
