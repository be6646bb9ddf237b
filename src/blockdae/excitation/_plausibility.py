"""The plausibility rules, written once for the readers, the models' functions, the command
line and the app: an error where a value is impossible (or so far out that a unit mix-up
is all but certain), a :class:`UnitsWarning` naming the likely unit where it is only
implausible.

- the peak acceleration of a record [g] (:func:`check_peak_acceleration`),
- a target peak ground acceleration [g] (:func:`check_pga`),
- a yield acceleration ky [g] against the peak that drives the sliding (:func:`ky_not_reached`,
  :func:`warn_not_sliding`),
- a sliding mass's column: height [m], shear-wave velocities [m/s], damping ratio [-]
  (:func:`check_column`),
- a result: finite, or an error naming it (:func:`check_finite_result`).
"""

import math
import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ._record_checks import outside_blockdae
from ._units import _SYMBOLS, canonical_units, unit_factor

#: plausible peak acceleration of a record [g]: from about an accelerometer's noise to the
#: largest peaks recorded (3.9 g, one component); outside it the units are likely wrong (refused)
PLAUSIBLE_PEAK_G = (1e-4, 4.0)
#: target peak ground accelerations [g] above this are refused unless confirmed (likely m/s²
#: given as g); a record's peak above it is warned about (rarer than a unit mix-up)
MAX_PGA_G = 2.0
#: samples given without units (read as m/s²) whose peak |a| is at most this number read as
#: a plausible peak in g too (2 m/s² = 0.204 g, or 2 g): warned about until units= states them
AMBIGUOUS_PEAK = 2.0
#: how a caller confirms a peak outside the plausible range (Python; the command line's flag)
CONFIRM_PEAK = "check_peak=False (command line: --accept-peak)"
#: a yield acceleration [g] above this that the peak driving the sliding does not reach is
#: refused: likely m/s²
MAX_KY_G = 1.0
#: plausible height H of a sliding mass [m] (a cover veneer to a high dam); outside: warned about
PLAUSIBLE_HEIGHT_M = (0.5, 500.0)
#: plausible shear-wave velocity of a sliding mass or the ground below it [m/s] (peat to hard
#: rock); outside: warned about
PLAUSIBLE_VS_M_S = (30.0, 5000.0)
#: a soil damping ratio [-] above this (30 %) is warned about; one of 1 or more is refused
#: (a percentage given as a ratio)
MAX_PLAUSIBLE_DAMPING = 0.3


class UnitsWarning(UserWarning):
    """A value that a unit mix-up often gives: a yield acceleration at or above the motion's
    peak (D = 0), a record's peak above 2 g, samples without units whose peak reads as g
    too, a column's height or shear-wave velocity out of the range of slopes: check the
    value and its units."""


# --- peak accelerations ------------------------------------------------------------------

def check_peak_acceleration(samples, units: str, g: float = STANDARD_GRAVITY, source: str = "record",
                            units_from: str | None = None, stated: bool = True):
    """The peak rule: raise ValueError if the peak of ``samples`` (in ``units``; one g is
    ``g`` [m/s²]) is outside :data:`PLAUSIBLE_PEAK_G` in standard g, naming the peak, the
    likely unit and how to confirm it (:data:`CONFIRM_PEAK`); a :class:`UnitsWarning`
    naming the likely unit if it is above :data:`MAX_PGA_G`, or if the units are not
    ``stated`` (samples from Python, read as m/s²) and the peak is at most
    :data:`AMBIGUOUS_PEAK` (a record in g reads as one in m/s², 9.8 times too weak).

    ``units_from`` says where ``units`` came from (e.g. a file's header line), if not the caller.
    """
    units = canonical_units(units)
    peak = float(np.max(np.abs(samples), initial=0.0))
    peak_g = peak * unit_factor(units, g) / STANDARD_GRAVITY
    low, high = PLAUSIBLE_PEAK_G
    in_g = "" if units == "g" else f" = {peak_g:.4g} g"
    shown = f"{source}: peak acceleration {peak:.4g} {_SYMBOLS[units]}{in_g}"
    mix_up = _likely_units(peak, units)
    fix = f"correct the file ({units_from} sets the units)" if units_from else f"pass units={mix_up!r}"
    if not low <= peak_g <= high:
        hint = (f"looks like {_SYMBOLS[mix_up]} read as {_SYMBOLS[units]}: {fix}" if mix_up
                else "check the values and their units")
        side = "above the largest peaks recorded" if peak_g > high else "below an accelerometer's noise"
        raise ValueError(f"{shown} is implausible ({side}; plausible: {low:g} g to {high:g} g); {hint}, "
                         f"or {CONFIRM_PEAK} to accept it")
    if peak_g > MAX_PGA_G:
        hint = (f"it looks like {_SYMBOLS[mix_up]} read as {_SYMBOLS[units]} ({peak:.4g} {_SYMBOLS[mix_up]} = "
                f"{peak * unit_factor(mix_up) / STANDARD_GRAVITY:.4g} g): {fix}" if mix_up
                else "check the values and their units")
        warnings.warn(f"{shown} is above {MAX_PGA_G:g} g, rarer than a unit mix-up: {hint}; {CONFIRM_PEAK} "
                      "accepts it without this warning", UnitsWarning, stacklevel=outside_blockdae())
    elif not stated and peak <= AMBIGUOUS_PEAK:
        warnings.warn(f"{source}: no units given, the samples are read as m/s²: a peak of {peak:.4g} m/s² = "
                      f"{peak_g:.4g} g; if they are in g (a peak of {peak:.4g} g), pass units='g'; pass "
                      f"units='m/s2' to state m/s² (or {CONFIRM_PEAK})", UnitsWarning, stacklevel=outside_blockdae())


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
    """The other units that make ``peak`` plausible (within :data:`PLAUSIBLE_PEAK_G`, at most
    :data:`MAX_PGA_G`), nearest 0.3 g; None if none do."""
    low = PLAUSIBLE_PEAK_G[0]
    in_g = {u: peak * unit_factor(u) / STANDARD_GRAVITY for u in _SYMBOLS if u != units}
    plausible = [u for u, p in in_g.items() if low <= p <= MAX_PGA_G]
    return min(plausible, key=lambda u: abs(np.log(in_g[u] / 0.3)), default=None)


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


# --- yield accelerations -----------------------------------------------------------------

def ky_not_reached(ky, peak_g, where="", peak_name="the motion's peak"):
    """The yield accelerations among ``ky`` [g] at or above ``peak_g`` [g], the peak that
    drives the sliding (no sliding: D = 0), as text ("0.4, 0.5"), or "" if none; ValueError
    for one also above :data:`MAX_KY_G` (it reads as m/s²), the message starting with
    ``where`` and naming the peak as ``peak_name``."""
    ky = np.atleast_1d(np.asarray(ky, dtype=float))
    still = ky[ky >= peak_g]
    high = still[still > MAX_KY_G]
    if high.size:
        k = float(high[0])
        raise ValueError(f"{where}ky={k:g} g is above {MAX_KY_G:g} g and {peak_name} ({peak_g:.4g} g): it looks "
                         f"like m/s² ({k:g} m/s² = {k / STANDARD_GRAVITY:.4g} g); give ky in g")
    return ", ".join(f"{k:g}" for k in still)


#: cases named in the warning of a sweep where some ky is not reached
_CASES_SHOWN = 5


def warn_not_sliding(cases, total, peak_name="PGA", body="block", kind="(record, PGA) cases",
                     peak_words="the motion's peak"):
    """Refuse a ky [g] above :data:`MAX_KY_G` that its case's peak does not reach, and warn
    (a :class:`UnitsWarning`) about every case whose ky [g] its peak does not reach (D = 0).

    ``cases``: (name, peak [g], the ky [g] of the case) of each case, e.g. (record, PGA) of a
    rigid block or (record, kmax) of a sliding mass; ``total``: the number of cases run;
    ``peak_name``: the peak's name in the warning, ``peak_words`` in the error; ``body``: what
    does not slide; ``kind``: what the cases are, in the warning."""
    still = []
    for name, peak, ky in cases:
        if shown := ky_not_reached(ky, peak, f"{name}: " if total > 1 else "", peak_words):
            still.append((name, peak, shown))
    if len(still) == 1 and total == 1:
        _, peak, shown = still[0]
        warnings.warn(f"ky={shown} g >= {peak_name} = {peak:.4g} g: the {body} does not slide, D = 0 m", UnitsWarning,
                      stacklevel=outside_blockdae())
    elif still:
        shown = [f"{name} ({peak_name} {peak:.4g} g): ky={ky} g" for name, peak, ky in still]
        more = f"; and {len(still) - _CASES_SHOWN} more" if len(still) > _CASES_SHOWN else ""
        warnings.warn(f"ky >= {peak_name} in {len(still)} of {total} {kind}: the {body} does not slide there, D = 0 m: "
                      f"{'; '.join(shown[:_CASES_SHOWN])}{more}", UnitsWarning, stacklevel=outside_blockdae())


# --- a sliding mass's column -------------------------------------------------------------

#: the other units a column's values may have been given in: (name, factor to the SI unit)
_LENGTHS = (("km", 1000.0), ("cm", 0.01), ("mm", 0.001))
_VELOCITIES = (("km/s", 1000.0), ("cm/s", 0.01))


def check_column(height, vs, vr=None, damping=None):
    """The rules on a sliding mass's column (each a number or an array of them): a
    :class:`UnitsWarning` naming the likely unit for a ``height`` [m] outside
    :data:`PLAUSIBLE_HEIGHT_M` or a shear-wave velocity ``vs``, ``vr`` [m/s] outside
    :data:`PLAUSIBLE_VS_M_S`; for a soil ``damping`` ratio [-] of 1 or more a ValueError
    (a percentage), above :data:`MAX_PLAUSIBLE_DAMPING` a warning. Values that are not
    positive finite numbers are left to the model's own checks."""
    if (type(height) in _NUMBERS and type(vs) in _NUMBERS and (vr is None or type(vr) in _NUMBERS) and
            type(damping) in _NUMBERS and PLAUSIBLE_HEIGHT_M[0] <= height <= PLAUSIBLE_HEIGHT_M[1] and
            PLAUSIBLE_VS_M_S[0] <= vs <= PLAUSIBLE_VS_M_S[1] and
            (vr is None or PLAUSIBLE_VS_M_S[0] <= vr <= PLAUSIBLE_VS_M_S[1]) and damping <= MAX_PLAUSIBLE_DAMPING):
        return  # plain numbers, each plausible: no rule speaks
    _check_range("height", height, PLAUSIBLE_HEIGHT_M, "m", _LENGTHS, "a sliding mass's height")
    for name, value in (("vs", vs), ("vr", vr)):
        _check_range(name, value, PLAUSIBLE_VS_M_S, "m/s", _VELOCITIES, "a soil's or rock's shear-wave velocity")
    if damping is None:
        return
    if type(damping) in _NUMBERS:  # one number: no array
        percent = high = float(damping)
    else:  # the first value of each rule's (nan: none)
        values = np.atleast_1d(np.asarray(damping, dtype=float))
        percent, high = (float(values[test][0]) if np.any(test) else math.nan
                         for test in (values >= 1, values > MAX_PLAUSIBLE_DAMPING))
    if percent >= 1:
        value = percent
        raise ValueError(f"damping={value:g} is a damping ratio of {100 * value:g} %: give the ratio, not a "
                         f"percentage ({value:g} % is damping={value / 100:g})")
    if high > MAX_PLAUSIBLE_DAMPING:
        value = high
        warnings.warn(f"damping={value:g} is a damping ratio of {100 * value:g} %, above the "
                      f"{100 * MAX_PLAUSIBLE_DAMPING:g} % a soil reaches: if it is a percentage, give damping="
                      f"{value / 100:g}", UnitsWarning, stacklevel=outside_blockdae())


#: the types of one plain number (a bool is none: np.asarray gives it its own dtype)
_NUMBERS = (float, int)


def _check_range(name, value, plausible, unit, others, what):
    """A UnitsWarning for the first of ``value`` (in ``unit``) outside ``plausible``, naming
    the ``others`` (unit, factor to ``unit``) that would bring it in."""
    if value is None:
        return
    low, high = plausible
    if type(value) in _NUMBERS:  # one number: no array
        v = float(value)
        if not (math.isfinite(v) and v > 0 and (v < low or v > high)):
            return
    else:
        values = np.atleast_1d(np.asarray(value, dtype=float))
        out = values[np.isfinite(values) & (values > 0) & ((values < low) | (values > high))]
        if not out.size:
            return
        v = float(out[0])
    likely = [f"{v:g} {other} = {v * factor:g} {unit}" for other, factor in others if low <= v * factor <= high]
    hint = f"in other units? {' or '.join(likely)}" if likely else "check the value and its units"
    warnings.warn(f"{name}={v:g} {unit} is implausible for {what} (plausible: {low:g} {unit} to {high:g} {unit}); "
                  f"{hint}; give {name} in {unit}", UnitsWarning, stacklevel=outside_blockdae())


# --- results -----------------------------------------------------------------------------

def check_finite_result(values, describe):
    """ValueError if one of ``values`` (an array) is not finite, naming it by
    ``describe(index)`` (its index in ``values``, a tuple): a result that overflowed is
    never returned."""
    values = np.asarray(values, dtype=float)
    bad = np.argwhere(~np.isfinite(values))
    if bad.size:
        index = tuple(int(i) for i in bad[0])
        raise ValueError(f"{describe(index)} is {values[index]} (not a finite number: the computation overflowed); "
                         "check the motion's samples and the parameters' units")
