"""Units of acceleration samples: names, factors to m/s², the peak plausibility check
and the factor that scales a motion to a target peak ground acceleration [g]."""

import numpy as np

from ..core._units import STANDARD_GRAVITY

#: plausible peak acceleration of a record [g]; outside it the units are likely wrong
PLAUSIBLE_PEAK_G = (1e-4, 10.0)

#: peaks [m/s²] that samples given without units may have silently: 0.2 g to 2 g. Below,
#: the numbers read as g (under 2 g) are as plausible as m/s² (an array in g passed as m/s²);
#: above, as cm/s² (under 0.02 g) they are (an array in cm/s² passed as m/s²): Record warns
UNSTATED_PEAK_M_S2 = (2.0, 2.0 * STANDARD_GRAVITY)
#: target peak ground accelerations [g] above this are refused: likely m/s² given as g
MAX_PGA_G = 5.0

_UNITS = {"g": "g", "m/s2": "m/s2", "m/s^2": "m/s2", "m/s²": "m/s2",
          "cm/s2": "cm/s2", "cm/s^2": "cm/s2", "cm/s²": "cm/s2", "gal": "cm/s2"}
_FACTORS = {"m/s2": 1.0, "cm/s2": 0.01}
_SYMBOLS = {"g": "g", "m/s2": "m/s²", "cm/s2": "cm/s²"}


class UnitsWarning(UserWarning):
    """A value whose units cannot be told from it (samples given without units), or that
    gives a trivial result a unit mix-up often causes (a yield acceleration at or above the
    motion's peak: D = 0): say the units, or check the value."""


def canonical_units(units: str) -> str:
    """The name "g", "m/s2" or "cm/s2" of ``units`` (also "gal", "m/s^2", "cm/s²", ...)."""
    key = str(units).strip().lower()
    if key not in _UNITS:
        raise ValueError(f"units={units!r} is unknown; use one of {sorted(_UNITS)}")
    return _UNITS[key]


def unit_factor(units: str, g: float = STANDARD_GRAVITY) -> float:
    """Factor converting ``units`` to m/s² ("g", "m/s2", "cm/s2" or "gal"); one g is ``g`` [m/s²]."""
    return _FACTORS.get(canonical_units(units), g)


def check_peak_acceleration(samples, units: str, g: float = STANDARD_GRAVITY, source: str = "record",
                            units_from: str | None = None):
    """Raise ValueError if the peak of ``samples`` (in ``units``; one g is ``g`` [m/s²]) is
    outside :data:`PLAUSIBLE_PEAK_G` in standard g, naming the peak and the likely unit mix-up.

    ``units_from`` says where ``units`` came from (e.g. a file's header line), if not the caller.
    """
    units = canonical_units(units)
    peak = float(np.max(np.abs(samples), initial=0.0))
    peak_g = peak * unit_factor(units, g) / STANDARD_GRAVITY
    low, high = PLAUSIBLE_PEAK_G
    if low <= peak_g <= high:
        return
    in_g = "" if units == "g" else f" = {peak_g:.4g} g"
    mix_up = _likely_units(peak, units)
    fix = f"correct the file ({units_from} sets the units)" if units_from else f"pass units={mix_up!r}"
    hint = (f"looks like {_SYMBOLS[mix_up]} read as {_SYMBOLS[units]}: {fix}" if mix_up
            else "check the file's values and units")
    raise ValueError(f"{source}: peak acceleration {peak:.4g} {_SYMBOLS[units]}{in_g} is implausible "
                     f"(outside {low:g} g to {high:g} g); {hint}, or check_peak=False to accept it")


def _likely_units(peak, units):
    """The other units that make ``peak`` plausible, nearest 0.3 g; None if none do."""
    low, high = PLAUSIBLE_PEAK_G
    in_g = {u: peak * unit_factor(u) / STANDARD_GRAVITY for u in _SYMBOLS if u != units}
    plausible = [u for u, p in in_g.items() if low <= p <= high]
    return min(plausible, key=lambda u: abs(np.log(in_g[u] / 0.3)), default=None)


#: how :func:`pga_factor` takes a motion's own peak: "exact", or "slammer" (rounded to 0.001 g)
PGA_ROUNDINGS = ("exact", "slammer")


def check_pga(pga, name: str = "pga") -> np.ndarray:
    """``pga``, target peak ground acceleration(s) [g], as a 1-D array of positive finite
    values; ValueError naming ``name`` and the value if one is not, or is above
    :data:`MAX_PGA_G` (then likely m/s² given where g is meant)."""
    values = np.atleast_1d(np.asarray(pga, dtype=float))
    if values.ndim != 1 or values.size == 0:
        raise ValueError(f"{name} must be a number or a non-empty 1-D sequence of peaks [g], got {pga!r}")
    for value in values:
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name}={value!r} must be a positive finite peak ground acceleration [g]")
        if value > MAX_PGA_G:
            raise ValueError(f"{name}={value:g} g is implausible for a peak ground acceleration [g] (above "
                             f"{MAX_PGA_G:g} g); it looks like m/s² ({value:g} m/s² = "
                             f"{value / STANDARD_GRAVITY:.4g} g): give {name} in g")
    return values


def check_pga_rounding(rounding):
    """ValueError unless ``rounding`` is one of :data:`PGA_ROUNDINGS`."""
    if rounding not in PGA_ROUNDINGS:
        raise ValueError(f"pga_rounding must be one of {PGA_ROUNDINGS}, got {rounding!r}")


def pga_factor(peak, pga, g: float = STANDARD_GRAVITY, rounding: str = "exact", name: str = "pga"):
    """Factor(s) [-] on a motion of peak |a| ``peak`` [m/s²] that scale it to ``pga`` [g]
    (a number or 1-D sequence; one g is ``g`` [m/s²]): ``pga g / peak``.

    ``rounding``: "exact" (default) or "slammer", SLAMMER's convention for reproducing its
    tables: the record's own peak in g rounded to 0.001 g, ``pga / round(peak / g, 3)``.
    Returns an array shaped like ``pga`` (a float for a number).
    """
    check_pga_rounding(rounding)
    targets = check_pga(pga, name)
    own = round(float(peak) / g, 3) if rounding == "slammer" else float(peak)
    if not own > 0:
        raise ValueError(f"{name} needs a motion with a nonzero peak; this one's is {float(peak):.4g} m/s² "
                         f"(= {float(peak) / g:.4g} g{', 0 to 0.001 g' if rounding == 'slammer' else ''})")
    factors = targets / own if rounding == "slammer" else targets * g / own
    return float(factors[0]) if np.ndim(pga) == 0 else factors
