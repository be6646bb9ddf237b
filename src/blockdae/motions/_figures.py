"""Figures of response spectra and of the two-point relative motion (matplotlib on demand)."""

import numpy as np

from ..units import STANDARD_GRAVITY


def plot_spectrum(spectrum, *, quantity="psa", ax=None, title=None, label=None, tripartite=False,
                  psa_unit="g", g=STANDARD_GRAVITY):
    """Log-log spectrum curves against the period [s].

    Args:
        spectrum: a :class:`ResponseSpectrum` (any batch/damping shape; every curve drawn).
        quantity: "sd" [m], "sv" [m/s], "sa" [m/s²], "psv" [m/s], "psa" [m/s²] or "sd_abs" [m].
        ax: matplotlib Axes to draw on (a new figure otherwise).
        label: legend label prefix (default the motion names and damping values).
        tripartite: with quantity "psv", add the diagonals of constant Sd = PSv T/(2π) [m]
            (slope -1) and of constant PSa = 2π PSv/T (slope +1), labelled.
        psa_unit: unit of the PSa diagonals, "g" or "m/s²".
        g: the unit "g" [m/s²].

    Returns:
        The matplotlib Figure.
    """
    import matplotlib.pyplot as plt

    units = {"sd": "m", "sv": "m/s", "sa": "m/s²", "psv": "m/s", "psa": "m/s²", "sd_abs": "m"}
    if quantity not in units:
        raise ValueError(f"quantity = {quantity!r}; quantity must be one of {sorted(units)}")
    if tripartite and quantity != "psv":
        raise ValueError(f"tripartite axes need quantity = 'psv', got {quantity!r}")
    if psa_unit not in ("g", "m/s²"):
        raise ValueError(f"psa_unit = {psa_unit!r}; psa_unit must be 'g' or 'm/s²'")
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4.5), constrained_layout=True)
    fig = ax.figure
    T = np.atleast_1d(spectrum.periods)
    values = np.asarray(getattr(spectrum, quantity))
    curves = values.reshape(-1, T.size)
    names = np.atleast_1d(spectrum.names)
    zetas = np.atleast_1d(spectrum.damping)
    for i, curve in enumerate(curves):
        name = names[i // zetas.size] if names.size > 1 else names[0]
        text = label or f"{name} ζ = {zetas[i % zetas.size]:g}"
        ax.loglog(T, curve, lw=1.2, label=text)
    ax.set_xlabel("period T [s]")
    ax.set_ylabel(f"{quantity.upper()} [{units[quantity]}]")
    ax.grid(True, which="both", lw=0.3)
    if tripartite:
        _tripartite_grid(ax, 1.0 if psa_unit == "m/s²" else g, psa_unit)
    if curves.shape[0] <= 8:
        ax.legend(fontsize=8)
    if title:
        ax.set_title(title)
    return fig


def _decades(lo, hi):
    """The powers of ten in [lo, hi]."""
    return 10.0 ** np.arange(np.ceil(np.log10(lo) - 1e-9), np.floor(np.log10(hi) + 1e-9) + 1)


def _tripartite_grid(ax, unit, unit_name):
    """Diagonals of constant Sd [m] and PSa [``unit`` m/s²] on PSv [m/s]-T [s] log axes, one
    per decade of each, drawn across the current limits (kept) and labelled at their middle."""
    (t0, t1), (v0, v1) = ax.get_xlim(), ax.get_ylim()
    T = np.geomspace(t0, t1, 2)
    style = dict(color="0.55", lw=0.6, zorder=0.5)
    text = dict(fontsize=7, color="0.35", ha="center", va="center",
                bbox=dict(fc="white", ec="none", alpha=0.7, pad=0.5))
    for sd in _decades(v0 * t0 / (2 * np.pi), v1 * t1 / (2 * np.pi)):  # PSv = 2π Sd / T
        ax.plot(T, 2 * np.pi * sd / T, ls="--", gid=f"sd {sd:g} m", **style)
        lo, hi = max(t0, 2 * np.pi * sd / v1), min(t1, 2 * np.pi * sd / v0)
        tm = np.sqrt(lo * hi)
        ax.text(tm, 2 * np.pi * sd / tm, f"Sd {sd:g} m", **text)
    for psa in _decades(2 * np.pi * v0 / (t1 * unit), 2 * np.pi * v1 / (t0 * unit)):  # PSv = PSa T / 2π
        a = psa * unit
        ax.plot(T, a * T / (2 * np.pi), ls=":", gid=f"psa {psa:g} {unit_name}", **style)
        lo, hi = max(t0, 2 * np.pi * v0 / a), min(t1, 2 * np.pi * v1 / a)
        tm = np.sqrt(lo * hi)
        ax.text(tm, a * tm / (2 * np.pi), f"PSa {psa:g} {unit_name}", **text)
    ax.set_xlim(t0, t1)
    ax.set_ylim(v0, v1)


def plot_relative_motion(rm, *, ax=None, title=None, estimates=True):
    """R(τ) against the lag on log-log axes with the paper's estimates (Christian 1973 Figs 4-7).

    Args:
        rm: a :class:`RelativeMotion`.
        estimates: draw 2 d_m, Newmark's bound, 2 x Fourier amplitude, 2 Sd(2τ) and the
            envelope min(v_m τ, d_m) beside the exact R.

    Returns:
        The matplotlib Figure.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4.5), constrained_layout=True)
    fig = ax.figure
    lags = np.atleast_1d(rm.lags)
    keep = lags > 0
    lags = lags[keep]
    ax.loglog(lags, np.atleast_1d(rm.r)[keep], "o-", color="k", ms=4, label="R exact")
    if estimates:
        ax.loglog(lags, np.atleast_1d(rm.twice_pgd)[keep], "--", label="(a) 2 d_m")
        ax.loglog(lags, np.atleast_1d(rm.newmark)[keep], "--", label="(b) d_max - d_min")
        if np.any(np.atleast_1d(rm.fourier)[keep] > 0):
            ax.loglog(lags, np.atleast_1d(rm.fourier)[keep], ":", label="(d) 2 x Fourier ampl. at T = 2τ")
            ax.loglog(lags, np.atleast_1d(rm.spectral)[keep], ":", label=f"(d) 2 Sd(2τ, {rm.damping:g})")
        ax.loglog(lags, np.atleast_1d(rm.envelope)[keep], "-", color="C3", lw=2, alpha=0.5,
                  label="min(v_m τ, d_m)")
    ax.set_xlabel("lag τ = b/c [s]")
    ax.set_ylabel("max relative displacement R [m]")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or rm.name)
    return fig
