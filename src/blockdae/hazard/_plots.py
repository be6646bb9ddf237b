"""Figures of fragilities and displacement hazard curves (matplotlib imported here only)."""

import numpy as np


def plot_fragility(fragility, d_m, im, *, others=None, level=0.90, ax=None):
    """P(D > d | im) of a fitted :class:`Fragility` with its bootstrap band, and of
    ``others`` ({label: EmpiricalFragility}) for comparison, over intensities ``im``.
    Returns the matplotlib Axes."""
    import matplotlib.pyplot as plt

    ax = ax or plt.subplots(figsize=(6, 4))[1]
    im = np.asarray(im, dtype=float)
    line, = ax.plot(im, fragility.exceedance(d_m, im), lw=2, label=f"time histories (MLE, {fragility.n_records} records)")
    if fragility.boot.size:
        low, high = fragility.band(d_m, im, level)
        ax.fill_between(im, low, high, color=line.get_color(), alpha=0.25, label=f"{level:.0%} bootstrap band")
    for label, other in (others or {}).items():
        ax.plot(im, other.exceedance(d_m, im), ls="--", label=label)
    ax.set(xlabel=fragility.im, ylabel=f"P(D > {d_m * 100:g} cm | {fragility.im})", ylim=(0, 1))
    ax.legend(fontsize="small")
    return ax


def plot_displacement_hazard(d_m, curves, *, ax=None):
    """Displacement hazard curves λ(D > d) [1/yr] over d [m]: ``curves`` {label: rates}.
    Returns the matplotlib Axes."""
    import matplotlib.pyplot as plt

    ax = ax or plt.subplots(figsize=(6, 4))[1]
    for label, rate in curves.items():
        ax.loglog(np.asarray(d_m) * 100, rate, label=label)
    ax.set(xlabel="displacement d [cm]", ylabel="annual rate of D > d [1/yr]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    return ax
