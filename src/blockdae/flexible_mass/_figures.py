"""The figure of a flexible sliding mass: HEA against ±ky g, sliding velocity and
displacement, episodes marked (the figure SLAMMER and pySLAMMER users know)."""

import numpy as np

from ..core import time_grid


def sliding_figure(solution, *, n_points, title=None):
    """Three panels against t [s]: HEA and ±ky g [g]; the sliding velocity w [m/s]; the
    downslope sliding displacement D = s >= 0 [m] (the tables' normal_m / inverse_m); each
    episode shaded from onset to stop."""
    import matplotlib.pyplot as plt

    block = solution.block
    t = time_grid(solution, n_points)
    t = t[t < solution.t_end]  # a(t) is the record's before its last sample
    states = solution(t)
    s, w = states[2], states[3]
    ky = block.ky_at(s)  # [g]; a table's ky follows s
    fig, (hea, velocity, displacement) = plt.subplots(3, 1, sharex=True, figsize=(8, 7), constrained_layout=True)
    hea.plot(t, solution.hea(t) / block.g, color="C0", lw=1.0, label="HEA")
    for sign in (1, -1):
        hea.plot(t, sign * ky, color="C3", lw=0.9, ls="--", label="±ky" if sign > 0 else None)
    hea.set_ylabel("horizontal equivalent\nacceleration HEA [g]")
    velocity.plot(t, w, color="C3", lw=1.2)
    velocity.set_ylabel("downslope sliding\nvelocity w [m/s]")
    displacement.plot(t, s, color="C3", lw=1.2)
    displacement.set(ylabel="downslope\ndisplacement D [m]", xlabel="time t [s]")
    for episode in solution.episodes:
        stop = solution.t_end if np.isnan(episode.stop) else episode.stop
        for ax in (hea, velocity, displacement):
            ax.axvspan(episode.onset, stop, color="0.9", zorder=0)
    hea.legend(loc="upper right", fontsize="small")
    fig.suptitle(title or f"{block.method} flexible sliding mass, ky = {_ky_label(block)}: "
                          f"{len(solution.episodes)} episodes, D = {solution.sliding_displacement:.4g} m")
    return fig


def _ky_label(block):
    """ky [g] for the title: a table by its first and last values."""
    if block.table is None:
        return f"{block.ky:g} g"
    return f"{block.ky.ky_g[0]:g} to {block.ky.ky_g[-1]:g} g (a table of s)"
