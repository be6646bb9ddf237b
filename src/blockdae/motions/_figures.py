"""Figures of response spectra and of the two-point relative motion (matplotlib on demand)."""

import numpy as np


def plot_spectrum(spectrum, *, quantity="psa", ax=None, title=None, label=None):
    """Log-log spectrum curves against the period [s].

    Args:
        spectrum: a :class:`ResponseSpectrum` (any batch/damping shape; every curve drawn).
        quantity: "sd" [m], "sv" [m/s], "sa" [m/s²], "psv" [m/s], "psa" [m/s²] or "sd_abs" [m].
        ax: matplotlib Axes to draw on (a new figure otherwise).
        label: legend label prefix (default the motion names and damping values).

    Returns:
        The matplotlib Figure.
    """
    import matplotlib.pyplot as plt

    units = {"sd": "m", "sv": "m/s", "sa": "m/s²", "psv": "m/s", "psa": "m/s²", "sd_abs": "m"}
    if quantity not in units:
        raise ValueError(f"quantity = {quantity!r}; quantity must be one of {sorted(units)}")
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
    if curves.shape[0] <= 8:
        ax.legend(fontsize=8)
    if title:
        ax.set_title(title)
    return fig


def plot_relative_motion(rm, *, ax=None, title=None, estimates=True):
    """R(τ) against the lag on log-log axes with the seed's estimates (seed 003 Figs 4-7).

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
