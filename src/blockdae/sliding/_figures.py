"""Figures of the 1-D block: Sawicki & Chybicki 2005 Figures 3-5 (absolute and relative motion, the
phase plane) and a batch's displacements against its parameters."""

import numpy as np

from ..core import BASE, BLOCK, EVENTS, curve, time_grid

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
            _thresholds(acc, block)
        curve(vel, t, v_base, None, None, "velocity [m/s]", style=BASE)
        curve(vel, t, v_base + v, t_ev, v_base[at_ev] + v_ev, None, style=BLOCK)
        curve(disp, t, x_base, None, None, "displacement [m]", style=BASE)
        curve(disp, t, x_base + u, t_ev, x_base[at_ev] + u_ev, None, style=BLOCK)
        disp.set_xlabel("t [s]")
        acc.legend(loc="lower right", fontsize="x-small", ncol=2)
    rel_v.legend(loc="best", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig



def _thresholds(ax, block):
    """The base accelerations at which a block at rest starts to slide, (bias ± mu) g
    [m/s²] (+: toward u < 0, -: toward u > 0), on the sides its direction allows (a batch
    of blocks: none)."""
    if np.ndim(block.mu) or np.ndim(block.bias):
        return
    for sign, towards, allowed, style in ((1.0, "u < 0", block.allow_negative, "--"),
                                          (-1.0, "u > 0", block.allow_positive, ":")):
        if allowed:
            level = (block.bias + sign * block.mu) * block.g
            ax.axhline(level, color="C1", ls=style, lw=1.0, label=f"threshold, to {towards}")


def newmark_figure(ky, curves, *, key="record", pga=None, polarity=None, title=None):
    """Newmark's D [m] against k_y [g]: a colour per entry of ``curves`` ((label, D of shape
    (n_pga, n_ky) [m]) pairs), a line style per target PGA (``pga`` [g]; None: the records
    as given); a legend titled ``key`` (a colour scale beyond :data:`_LEGEND_ENTRIES`
    curves); log axes where the values span a decade or more (D = 0 is then not drawn);
    ``polarity``, if given, says which D is drawn."""
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FormatStrFormatter, FuncFormatter, NullFormatter

    fig, ax = plt.subplots(figsize=(8.5, 5), constrained_layout=True)
    many = len(curves) > _LEGEND_ENTRIES
    colours = plt.get_cmap("viridis")(np.linspace(0, 1, len(curves))) if many else \
        [f"C{i}" for i in range(len(curves))] if len(curves) <= 10 else plt.get_cmap("tab20").colors
    order = np.argsort(ky, kind="stable")  # each line drawn along increasing ky, whatever order ky came in
    for colour, (label, d) in zip(colours, curves):
        for j, row in enumerate(np.atleast_2d(d)):
            ax.plot(np.asarray(ky)[order], np.asarray(row)[order], color=colour, ls=_STYLES[j % len(_STYLES)], marker=_MARKERS[j % len(_MARKERS)], ms=3.5,
                    lw=1.2, label=label if j == 0 else None)
    values = np.concatenate([np.ravel(d) for _, d in curves])
    positive = values[values > 0]
    log_d = positive.size > 0 and positive.max() >= 10 * positive.min()
    if log_d:
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))
        short = positive.max() < 100 * positive.min()  # under two decades: 2 and 5 x 10^n labelled too
        ax.yaxis.set_minor_formatter(FuncFormatter(_two_and_five) if short else NullFormatter())
        if np.any(values == 0):
            ax.text(0.99, 0.99, "D = 0 (no sliding) not drawn", transform=ax.transAxes, fontsize="small",
                    color="0.4", ha="right", va="top")
    else:
        ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    if np.max(ky) >= 10 * np.min(ky):
        ax.set_xscale("log")
        ax.set_xticks([x for x in _KY_TICKS if np.min(ky) <= x <= np.max(ky)])
        ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.xaxis.set_minor_formatter(NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    ax.set(xlabel="yield acceleration k_y [g]",
           ylabel="downslope displacement D [m]" + (f" ({polarity})" if polarity else ""), title=title)
    if many:
        bar = fig.colorbar(plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(1, len(curves))), ax=ax)
        bar.set_label(f"{key} number (1 to {len(curves)}, in the table's order)")
    else:
        fig.legend(loc="outside right upper", fontsize="small", title=key)
    if pga is not None and len(pga) > 1:
        handles = [Line2D([], [], color="0.3", ls=_STYLES[j % len(_STYLES)], marker=_MARKERS[j % len(_MARKERS)],
                          ms=3.5) for j in range(len(pga))]
        ax.legend(handles, [f"{p:g} g" for p in pga], loc="lower left", fontsize="small", title="target PGA")
    return fig


def _two_and_five(value, _position):
    """A minor tick's label on a log axis: "0.2", "50", ... at 2 and 5 x 10^n, else none."""
    leading = value / 10 ** np.floor(np.log10(value))
    return f"{value:g}" if np.isclose(leading, 2) or np.isclose(leading, 5) else ""


def newmark_history_figure(solution, motion, ky, g, *, polarity, n_points, title=None):
    """One Newmark analysis as practitioners draw it, against t [s]: the ground
    acceleration [g] of the polarity run with the yield acceleration k_y marked; the
    downslope sliding velocity -v [m/s]; the downslope displacement D = -u >= 0 [m];
    slip episodes shaded. ``solution`` is of the one-way block (u <= 0) under ``motion``."""
    import matplotlib.pyplot as plt

    t = time_grid(solution, n_points)
    u, v = solution(t)
    fig, (acc, vel, disp) = plt.subplots(3, 1, sharex=True, figsize=(8, 8.5), constrained_layout=True)
    acc.plot(t, motion.acceleration(t) / g, color="0.3", lw=1.0, label=f"ground ({polarity} polarity)")
    acc.axhline(ky, color="C3", ls="--", lw=1.0, label=f"k_y = {ky:g} g")
    acc.set_ylabel("ground acceleration [g]")
    vel.plot(t, 0.0 - v, color="C3", lw=1.2)
    vel.set_ylabel("downslope velocity [m/s]")
    disp.plot(t, 0.0 - u, color="C3", lw=1.2)
    disp.set(ylabel="downslope displacement D [m]", xlabel="time t [s]")
    sliding = solution.mode[np.searchsorted(solution.t, t, side="right") - 1] != 0
    for ax in (acc, vel, disp):
        ax.fill_between(t, 0, 1, where=sliding, transform=ax.get_xaxis_transform(), color="0.9", zorder=0,
                        label="sliding" if ax is acc else None)
        ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    acc.legend(loc="upper right", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig


_KY_TICKS = (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0)  # [g]
_STYLES = ("-", "--", ":", "-.")
_MARKERS = ("o", "s", "^", "v", "D")
