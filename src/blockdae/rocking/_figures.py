"""Figures of a free-standing block: its rotation (or slide) and the base acceleration."""

import numpy as np

from ..core import time_grid


def mark_impacts_and_overturn(ax, solution):
    """The impacts as ticks on theta = 0 and the overturn as a dashed line on ``ax``."""
    impacts = solution.impact_times
    if impacts.size:
        ax.plot(impacts, 0 * impacts, ls="none", marker="|", color="k", ms=8, label="impacts")
    if solution.overturned:
        ax.axvline(solution.overturn_time, color="k", ls="--", lw=0.8, label="overturned")


def draw_base_acceleration(ax, solution, t):
    """a_x [m/s²] of the solution's motion (its x component) at ``t`` [s] on ``ax``, the
    bottom panel."""
    if solution.motion is not None:
        components = getattr(solution.motion, "components", None)
        x = solution.motion if components is None else components[0]
        ax.plot(t, np.asarray(x.acceleration(t)), color="0.4", lw=0.8)
    ax.set(ylabel="a_x [m/s²]", xlabel="t [s]")


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
    mark_impacts_and_overturn(motion, solution)
    for level in (-1, 1) if rocks and block is not None else ():
        motion.axhline(level, color="0.7", lw=0.8, ls=":")
    motion.axhline(0.0, color="0.85", lw=0.8, zorder=0)
    motion.legend(loc="best", fontsize="small")
    draw_base_acceleration(base, solution, t)
    if title:
        fig.suptitle(title)
    return fig


#: the regions' colours, indexed by the mode codes (rest, slide, rock, slide-rock, flight)
_MODE_COLOURS = ("0.88", "#6baed6", "#fb6a4a", "#fdae6b", "#74c476")


def plot_mode_map(b_over_h, *, mu_k_ratio=1.0, av_over_g=0.0, a_max=None, mu_max=None, n=400, ax=None):
    """The rest -> mode map of a block of aspect ratio ``b_over_h`` = b/h [-] (Shenton 1996):
    static friction mu_s [-] against the horizontal base acceleration a_x / g [-], the
    regions (:func:`~blockdae.rocking.mode_map`) shaded on an ``n`` x ``n`` grid and their
    exact boundaries drawn (a_x = mu_s g_e, a_x = g_e b/h, Shenton's critical friction,
    mu_k = b/h). ``mu_k_ratio`` = mu_k / mu_s [-], ``av_over_g`` = a_z / g [-]; the axes
    reach ``a_max`` and ``mu_max`` (default: 2.5 b/h, at least 1). A matplotlib Figure."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from . import _slide_rock_laws as laws
    from ._mode_map import MODE_NAMES, mode_codes

    if not 0.0 <= mu_k_ratio <= 1.0:
        raise ValueError(f"mu_k_ratio = mu_k / mu_s must be in [0, 1], got {mu_k_ratio!r}")
    if n < 2:
        raise ValueError(f"n (grid points per axis) must be >= 2, got {n!r}")
    lam, ge = float(b_over_h), 1.0 + av_over_g
    a_max = max(1.0, 2.5 * lam) if a_max is None else a_max
    mu_max = max(1.0, 2.5 * lam) if mu_max is None else mu_max
    a, mu = (np.linspace(0.0, top, n) for top in (a_max, mu_max))
    codes = mode_codes(lam, mu[:, None], a[None, :], mu_k_ratio * mu[:, None], av_over_g)
    fig = plt.figure(figsize=(6, 4.5), constrained_layout=True) if ax is None else ax.figure
    ax = ax or fig.add_subplot()
    ax.imshow(codes, origin="lower", extent=(0.0, a_max, 0.0, mu_max), aspect="auto", interpolation="nearest",
              cmap=ListedColormap(_MODE_COLOURS), vmin=-0.5, vmax=len(MODE_NAMES) - 0.5)
    if ge > 0:
        line = dict(color="k", lw=1.0)
        ax.plot([0.0, lam * ge], [0.0, lam], **line)  # a_x = mu_s g_e while mu_s <= b/h
        ax.plot([lam * ge, lam * ge], [lam, mu_max], **line)  # a_x = g_e b/h
        demand = np.linspace(lam * ge, a_max, 200)
        ax.plot(demand, laws.critical_friction(demand, ge, lam), **line)  # rock above, slips below
        if mu_k_ratio > 0 and lam / mu_k_ratio < mu_max:  # slide-rock above mu_k = b/h, slide below
            start = np.interp(lam / mu_k_ratio, laws.critical_friction(demand, ge, lam), demand)
            ax.plot([start, a_max], [lam / mu_k_ratio] * 2, **line)
    present = np.unique(codes)
    ax.legend(handles=[Patch(color=_MODE_COLOURS[k], label=MODE_NAMES[k]) for k in present], loc="upper left",
              fontsize="small", framealpha=0.9)
    ax.set(xlim=(0.0, a_max), ylim=(0.0, mu_max), xlabel="a_x / g [-]", ylabel="static friction mu_s [-]",
           title=f"rest -> mode map, b/h = {lam:g}, mu_k/mu_s = {mu_k_ratio:g}, a_z/g = {av_over_g:g}")
    return fig


#: the complete block's shaded motions: label -> (colour, the mode kinds it spans)
#: (:func:`._free_modes.kind_of`; a Zeno tail of rocking impacts counts as rock)
MOTION_SPANS = {"slide": ("#6baed6", (1,)), "rock": ("#fb6a4a", (2, 3, 4, 5)),
                "slide-rock": ("#fdae6b", (7, 8)), "flight": ("#74c476", (9,))}


def motion_spans(solution):
    """The spans of each shaded motion of a complete block's run: label -> [(t_start,
    t_end) [s], ...] (:data:`MOTION_SPANS`), from the mode after each knot; rest and
    overturned are not shaded."""
    from ._free_modes import kind_of

    label_of = {kind: label for label, (_, kinds) in MOTION_SPANS.items() for kind in kinds}
    labels = [label_of.get(kind_of(mode)) for mode in solution.mode[:-1]]
    spans = {label: [] for label in MOTION_SPANS}
    start = 0
    for i in range(1, len(labels) + 1):
        if i == len(labels) or labels[i] != labels[start]:
            if labels[start] is not None and solution.t[i] > solution.t[start]:
                spans[labels[start]].append((float(solution.t[start]), float(solution.t[i])))
            start = i
    return spans


def free_standing_figure(solution, *, n_points, title=None):
    """A complete block's run against t [s]: theta [rad] (impacts and overturning marked),
    the base's slip [m] (:func:`._slide_rock_laws.base_slip`), the corners' heights above the
    base [m] and a_x [m/s²], each panel shaded by the motion (:data:`MOTION_SPANS`:
    slide, rock, slide-rock, flight) with a legend."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    from . import _slide_rock_laws as laws

    block = solution.block
    t = time_grid(solution, n_points)
    y = np.asarray(solution(t))
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 8), constrained_layout=True,
                             gridspec_kw=dict(height_ratios=(2, 1.5, 1.5, 1)))
    theta, slip, heights, base = axes
    spans = motion_spans(solution)
    for ax in axes:
        for label, (colour, _) in MOTION_SPANS.items():
            for start, end in spans[label]:
                ax.axvspan(start, end, color=colour, alpha=0.35, lw=0, zorder=0, gid=label)
        ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    theta.plot(t, y[2], color="k", lw=1.1, label="theta")
    for level in (-block.alpha, block.alpha):
        theta.axhline(level, color="0.6", lw=0.8, ls=":")
    mark_impacts_and_overturn(theta, solution)
    theta.set_ylabel("theta [rad]")
    slip.plot(t, laws.base_slip(y[0], y[2], block.b, block.h, np), color="C0", lw=1.1, label="slip")
    slip.set_ylabel("slip [m]")
    for c, colour in ((1, "C3"), (-1, "C2")):  # z + r_cz of each corner
        heights.plot(t, y[1] + laws.corner_offset(c, y[2], block.b, block.h, np)[1], color=colour, lw=1.0,
                     label=f"corner {'+' if c > 0 else '-'}b")
    heights.set_ylabel("corner heights [m]")
    heights.legend(loc="upper right", fontsize="small")
    draw_base_acceleration(base, solution, t)
    handles = [Patch(color=MOTION_SPANS[label][0], alpha=0.35, label=label) for label in MOTION_SPANS if spans[label]]
    theta.legend(handles=theta.get_legend_handles_labels()[0] + handles, loc="best", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig
