"""Figures of fragilities and displacement hazard curves (matplotlib imported here only);
displacements in m, as the tables and the functions take them."""

import numpy as np

#: axis labels of the intensity columns of the study tables and the regressions
INTENSITY_LABELS = {"pga_g": "Peak ground acceleration [g]", "pga_m_s2": "Peak ground acceleration [m/s²]",
                    "pgv_m_s": "Peak ground velocity [m/s]", "sa_g": "Spectral acceleration Sa [g]",
                    "sd_m": "Spectral displacement Sd [m]", "kmax_g": "Seismic coefficient kmax [g]",
                    "kmax_sup_g": "Seismic coefficient kmax (supremum) [g]", "scale": "Scale factor [-]"}
_UNITS = {"_g": "g", "_m_s2": "m/s²", "_m_s": "m/s", "_m": "m", "_s": "s"}


def intensity_label(column: str) -> str:
    """An axis label in words with its unit for an intensity column ("pga_g": "Peak ground
    acceleration [g]"); another column: its name with the unit its suffix names."""
    if column in INTENSITY_LABELS:
        return INTENSITY_LABELS[column]
    for suffix, unit in sorted(_UNITS.items(), key=lambda item: -len(item[0])):
        if column.endswith(suffix):
            return f"{column[:-len(suffix)].replace('_', ' ')} [{unit}]"
    return column.replace("_", " ")


def plot_fragility(fragility, d_m, im, *, others=None, level=0.90, ax=None):
    """P(D > d | im) of a fitted :class:`Fragility` with its bootstrap band, and of
    ``others`` ({label: EmpiricalFragility}) for comparison, over intensities ``im`` (in
    the fit's column's unit), at the displacement ``d_m`` [m]. Returns the matplotlib Axes."""
    import matplotlib.pyplot as plt

    ax = ax or plt.subplots(figsize=(6, 4), constrained_layout=True)[1]
    im = np.asarray(im, dtype=float)
    line, = ax.plot(im, fragility.exceedance(d_m, im), lw=2, label=f"time histories (MLE, {fragility.n_records} records)")
    if fragility.boot.size:
        low, high = fragility.band(d_m, im, level)
        ax.fill_between(im, low, high, color=line.get_color(), alpha=0.25, label=f"{level:.0%} bootstrap band")
    for label, other in (others or {}).items():
        ax.plot(im, other.exceedance(d_m, im), ls="--", label=label)
    ax.set(xlabel=intensity_label(fragility.im), ylabel=f"probability of D > {d_m:g} m [-]", ylim=(0, 1))
    ax.legend(fontsize="small")
    return ax


def plot_displacement_hazard(d_m, curves, *, ax=None):
    """Displacement hazard curves λ(D > d) [1/yr] over d [m] (log-log, d drawn in m):
    ``curves`` {label: rates}. Returns the matplotlib Axes."""
    import matplotlib.pyplot as plt

    ax = ax or plt.subplots(figsize=(6, 4), constrained_layout=True)[1]
    for label, rate in curves.items():
        ax.loglog(np.asarray(d_m, dtype=float), rate, label=label)
    ax.set(xlabel="downslope displacement d [m]", ylabel="annual rate of D > d [1/yr]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    return ax
