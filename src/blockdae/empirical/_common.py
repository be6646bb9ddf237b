"""What every empirical model shares: its result, input checks and the range warning."""

import math
import typing
import warnings

import numpy as np

#: one centimetre [m]: the regressions give D in cm
CM = 0.01
LN10 = math.log(10.0)


class ValidityWarning(UserWarning):
    """An argument lies outside the range of the data a regression was fitted to."""


class EmpiricalDisplacement(typing.NamedTuple):
    """A regression's prediction, arrays broadcast over its arguments.

    Attributes:
        median_m: median displacement where D is not negligible [m] (0 where ky >= PGA
            for the rigid-block models).
        sigma_ln: standard deviation of ln D [-].
        p_negligible: probability that D is negligible [-] (Bray & Travasarou: D < 1 cm;
            Bray & Macedo: D < 0.5 cm; the rigid-block models: 1 where ky >= PGA, else 0).
    """

    median_m: np.ndarray
    sigma_ln: np.ndarray
    p_negligible: np.ndarray

    def exceedance(self, d_m):
        """P(D > d) = (1 - p_negligible) (1 - Φ((ln d - ln median) / σ)) for d [m] > 0
        (shape: the prediction's broadcast with ``d_m``)."""
        from scipy.stats import norm  # on use: importing scipy.stats takes about a second

        d = positive("d_m", d_m, "m")
        with np.errstate(divide="ignore"):
            z = (np.log(d) - np.log(self.median_m)) / self.sigma_ln
        return (1.0 - self.p_negligible) * norm.sf(z)


def positive(name, value, unit):
    """``value`` as a float array, every entry finite and > 0, else a ValueError naming it."""
    x = np.asarray(value, dtype=float)
    bad = ~(np.isfinite(x) & (x > 0))
    if np.any(bad):
        raise ValueError(f"{name} must be positive and finite [{unit}], got {float(x[bad].flat[0])!r}")
    return x


def finite(name, value, unit, minimum=-math.inf):
    """``value`` as a float array, finite and >= ``minimum``, else a ValueError naming it."""
    x = np.asarray(value, dtype=float)
    bad = ~(np.isfinite(x) & (x >= minimum))
    if np.any(bad):
        what = "finite" if minimum == -math.inf else f"finite and >= {minimum:g}"
        raise ValueError(f"{name} must be {what} [{unit}], got {float(x[bad].flat[0])!r}")
    return x


def warn_outside(model, name, x, low, high, unit):
    """A :class:`ValidityWarning` if any of ``x`` lies outside [low, high]."""
    out = (x < low) | (x > high)
    if np.any(out):
        warnings.warn(f"{model}: {name}={float(x[out].flat[0]):g} {unit} lies outside the model's range "
                      f"[{low:g}, {high:g}] {unit}: an extrapolation", ValidityWarning, stacklevel=3)


def result(median_cm, sigma_ln, p_negligible):
    """An :class:`EmpiricalDisplacement` from D [cm], broadcast to one shape."""
    median, sigma, p = np.broadcast_arrays(np.asarray(median_cm) * CM, sigma_ln, p_negligible)
    return EmpiricalDisplacement(median.copy(), sigma.astype(float), p.astype(float))


def ratio_model(ky_g, pga_g, ln_d_cm):
    """A rigid-block model in r = ky/PGA: ``ln_d_cm(r)`` where r < 1, D = 0 (negligible
    for sure) where ky >= PGA. Returns (r, median [cm], p_negligible)."""
    r = ky_g / pga_g
    slides = r < 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        median = np.where(slides, np.exp(ln_d_cm(np.where(slides, r, 0.5))), 0.0)
    return r, median, np.where(slides, 0.0, 1.0)
