"""Units of acceleration samples: names, factors to m/s², the units a file's header names,
the peak plausibility rule (one for files, arrays and the command line), the rule on
target peak ground accelerations [g] and the factor that scales a motion to one."""

import re
import warnings

import numpy as np

from ..units import STANDARD_GRAVITY

#: plausible peak acceleration of a record [g]: from about an accelerometer's noise to the
#: largest peaks recorded (3.9 g, one component); outside it the units are likely wrong
PLAUSIBLE_PEAK_G = (1e-4, 4.0)
#: target peak ground accelerations [g] above this are refused unless confirmed: likely m/s² given as g
MAX_PGA_G = 2.0
#: how a caller confirms a peak outside the plausible range (Python; the command line's flag)
CONFIRM_PEAK = "check_peak=False (command line: --accept-peak)"

_UNITS = {"g": "g", "m/s2": "m/s2", "m/s^2": "m/s2", "m/s²": "m/s2",
          "cm/s2": "cm/s2", "cm/s^2": "cm/s2", "cm/s²": "cm/s2", "gal": "cm/s2"}
_FACTORS = {"m/s2": 1.0, "cm/s2": 0.01}
_SYMBOLS = {"g": "g", "m/s2": "m/s²", "cm/s2": "cm/s²"}
# units in a header's words: m/s2, m/s^2, m/s**2, m/s², m/sec2, m/s/s, cm/..., gal(s); g only where
# it cannot be a letter of a name: "(g)", "[g's]", "in g", "units: g", "acc_g"
_NO_LETTER_BEFORE, _NO_LETTER_AFTER = r"(?<![a-z0-9])", r"(?![a-z0-9/*^²])"
_PER_SECOND_SQUARED = r"\s*/\s*s(?:ec)?\s*(?:\^\s*2|\*\*\s*2|²|2|/\s*s(?:ec)?)"
_HEADER_UNIT_WORDS = (
    ("cm/s2", re.compile(_NO_LETTER_BEFORE + r"cm" + _PER_SECOND_SQUARED + _NO_LETTER_AFTER, re.I)),
    ("m/s2", re.compile(_NO_LETTER_BEFORE + r"m" + _PER_SECOND_SQUARED + _NO_LETTER_AFTER, re.I)),
    ("cm/s2", re.compile(_NO_LETTER_BEFORE + r"gals?" + _NO_LETTER_AFTER, re.I)),
    ("g", re.compile(r"(?:[(\[]\s*g(?:'?s)?\s*[)\]]"  # (g), [g's]
                     r"|(?:\bin\s|\bunits?\s*(?:of\s|:|=)?|_)\s*g(?:'?s)?(?![a-z0-9/]))", re.I)))  # in g, units: g, acc_g
_BRACKETED_RATIO = re.compile(r"[(\[]\s*([^()\[\]]*/[^()\[\]]*?)\s*[)\]]")  # "(m/s)", "[cm/s2]"


class UnitsWarning(UserWarning):
    """A value that gives a trivial result a unit mix-up often causes (a yield acceleration
    at or above the motion's peak: D = 0): check the value and its units."""


def canonical_units(units: str) -> str:
    """The name "g", "m/s2" or "cm/s2" of ``units`` (also "gal", "m/s^2", "cm/s²", ...)."""
    key = str(units).strip().lower()
    if key not in _UNITS:
        raise ValueError(f"units={units!r} is unknown; use one of {sorted(_UNITS)}")
    return _UNITS[key]


def unit_factor(units: str, g: float = STANDARD_GRAVITY) -> float:
    """Factor converting ``units`` to m/s² ("g", "m/s2", "cm/s2" or "gal"); one g is ``g`` [m/s²]."""
    return _FACTORS.get(canonical_units(units), g)


def units_named(text: str) -> tuple[list, list]:
    """(the canonical units "g", "m/s2", "cm/s2" that ``text``, a header line, names in words,
    e.g. ``time (s), acceleration (m/s2)``, ``Acceleration in m/s2``, ``acc [cm/sec2]``,
    ``(gal)``, ``(g's)``, in the order they appear; the bracketed ratios in it that are no
    acceleration unit, e.g. "m/s")."""
    found = {}
    for units, pattern in _HEADER_UNIT_WORDS:
        for match in pattern.finditer(text):
            found.setdefault(units, match.start())
        text = pattern.sub(lambda match: " " * len(match.group()), text)  # "cm/s2" not read again as "m/s2"
    others = [ratio for ratio in _BRACKETED_RATIO.findall(text) if ratio.strip()]
    return sorted(found, key=found.get), others


def check_peak_acceleration(samples, units: str, g: float = STANDARD_GRAVITY, source: str = "record",
                            units_from: str | None = None):
    """The peak plausibility rule: raise ValueError if the peak of ``samples`` (in ``units``;
    one g is ``g`` [m/s²]) is outside :data:`PLAUSIBLE_PEAK_G` in standard g,
    naming the peak, the likely unit and how to confirm it (:data:`CONFIRM_PEAK`).

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
            else "check the values and their units")
    side = "above the largest peaks recorded" if peak_g > high else "below an accelerometer's noise"
    raise ValueError(f"{source}: peak acceleration {peak:.4g} {_SYMBOLS[units]}{in_g} is implausible ({side}; "
                     f"plausible: {low:g} g to {high:g} g); {hint}, or {CONFIRM_PEAK} to accept it")


def unstated_units_error(source: str, samples) -> ValueError:
    """The error for samples whose units nothing states: it names ``source`` and the peak
    each unit would give, the plausible ones marked, so that the choice takes a second."""
    peak = float(np.max(np.abs(samples), initial=0.0))
    low, high = PLAUSIBLE_PEAK_G
    readings = []
    for units, symbol in _SYMBOLS.items():
        peak_g = peak * unit_factor(units) / STANDARD_GRAVITY
        shown = f"{peak:.4g} {symbol}" + ("" if units == "g" else f" = {peak_g:.3g} g")
        readings.append(shown + ("" if low <= peak_g <= high else " (implausible)"))
    return ValueError(f"{source}: the units of the accelerations are not stated (no header such as "
                      "'time (s), acceleration (m/s2)'); pass units= (command line: --units) g, m/s2 or cm/s2. "
                      f"Its peak {peak:.4g} would be {'; '.join(readings)}")


def _likely_units(peak, units):
    """The other units that make ``peak`` plausible, nearest 0.3 g; None if none do."""
    low, high = PLAUSIBLE_PEAK_G
    in_g = {u: peak * unit_factor(u) / STANDARD_GRAVITY for u in _SYMBOLS if u != units}
    plausible = [u for u, p in in_g.items() if low <= p <= high]
    return min(plausible, key=lambda u: abs(np.log(in_g[u] / 0.3)), default=None)


#: how :func:`pga_factor` takes a motion's own peak: "exact", or "slammer" (rounded to 0.001 g)
PGA_ROUNDINGS = ("exact", "slammer")


def check_pga(pga, name: str = "pga", check_peak: bool = True) -> np.ndarray:
    """The rule on target peak ground accelerations: ``pga`` [g] as a 1-D array of positive
    finite values; ValueError naming ``name`` and the value if one is not, or if one is above
    :data:`MAX_PGA_G` (likely m/s² given where g is meant) unless ``check_peak`` is False."""
    values = np.atleast_1d(np.asarray(pga, dtype=float))
    if values.ndim != 1 or values.size == 0:
        raise ValueError(f"{name} must be a number or a non-empty 1-D sequence of peaks [g], got {pga!r}")
    for value in values:
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name}={value!r} must be a positive finite peak ground acceleration [g]")
        if check_peak and value > MAX_PGA_G:
            raise ValueError(f"{name}={value:g} g is implausible for a peak ground acceleration (above "
                             f"{MAX_PGA_G:g} g); it looks like m/s² ({value:g} m/s² = "
                             f"{value / STANDARD_GRAVITY:.4g} g): give {name} in g, or {CONFIRM_PEAK} to accept it")
    return values


def pga_keyword(function: str, pga, target_pga):
    """The target peak ground acceleration(s) [g] a call to ``function`` gave: ``pga``, or
    ``target_pga``, its deprecated name, with a DeprecationWarning naming ``pga``; a
    ValueError where both are given."""
    if target_pga is None:
        return pga
    if pga is not None:
        raise ValueError(f"{function}: pga={pga!r} and target_pga={target_pga!r} name the same target peak [g]; "
                         "give pga only (target_pga is its deprecated name)")
    warnings.warn(f"{function}(..., target_pga=...) is deprecated; use {function}(..., pga=...), the same target "
                  "peak ground acceleration [g]", DeprecationWarning, stacklevel=3)
    return target_pga


def check_pga_rounding(rounding):
    """ValueError unless ``rounding`` is one of :data:`PGA_ROUNDINGS`."""
    if rounding not in PGA_ROUNDINGS:
        raise ValueError(f"pga_rounding must be one of {PGA_ROUNDINGS}, got {rounding!r}")


def pga_factor(peak, pga, g: float = STANDARD_GRAVITY, rounding: str = "exact", name: str = "pga",
               check_peak: bool = True):
    """Factor(s) [-] on a motion of peak |a| ``peak`` [m/s²] that scale it to ``pga`` [g]
    (a number or 1-D sequence; one g is ``g`` [m/s²]): ``pga g / peak``.

    ``rounding``: "exact" (default) or "slammer", SLAMMER's convention for reproducing its
    tables: the record's own peak in g rounded to 0.001 g, ``pga / round(peak / g, 3)``.
    ``check_peak``: False accepts a ``pga`` above :data:`MAX_PGA_G` (see :func:`check_pga`).
    Returns an array shaped like ``pga`` (a float for a number).
    """
    check_pga_rounding(rounding)
    targets = check_pga(pga, name, check_peak)
    own = round(float(peak) / g, 3) if rounding == "slammer" else float(peak)
    if not own > 0:
        raise ValueError(f"{name} needs a motion with a nonzero peak; this one's is {float(peak):.4g} m/s² "
                         f"(= {float(peak) / g:.4g} g{', 0 to 0.001 g' if rounding == 'slammer' else ''})")
    factors = targets / own if rounding == "slammer" else targets * g / own
    return float(factors[0]) if np.ndim(pga) == 0 else factors
