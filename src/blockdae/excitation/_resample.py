"""Resampling a record (or the Records of a base motion) to another sample step."""

import numpy as np

from ._motion import BaseMotion
from ._record import Record

# a new sample within this fraction of a new step past the record's end still counts as inside
_END_TOLERANCE = 1e-9


def resample(record, dt):
    """The record's piecewise-linear a(t) sampled every ``dt`` [s].

    Args:
        record: a :class:`Record`, or a :class:`BaseMotion` whose Record components are
            each resampled (other components are kept as they are). Records of mixed
            steps (e.g. 0.005, 0.01 and 0.02 s) make one BaseMotion once each is resampled
            to one step: ``BaseMotion(resample(x, dt), resample(y, dt))``.
        dt: the new sample step [s], finite and > 0.

    Returns:
        A Record (or BaseMotion) with the same name, ``start_time`` and ``metadata``, samples in m/s²
        at t = k ``dt`` for every k with k ``dt`` <= the record's duration. Each new
        sample is exact: the old record's a(t) (linear between old samples) at that time.
        Between new samples the result is linear in the *new* samples, so it is not the
        old a(t) there: an old sample (a peak) that falls between two new ones is cut,
        and ``peak_acceleration`` can drop when ``dt`` is larger than the old step.
        A tail shorter than ``dt`` after the last new sample is dropped. With ``dt`` a
        divisor of the old step, the result is a(t) itself, exactly.

    Raises:
        ValueError: ``dt`` not finite or <= 0, or too large to leave two samples.
        TypeError: ``record`` neither a Record nor a BaseMotion.
    """
    if isinstance(record, BaseMotion):
        return BaseMotion(*(_resampled_component(c, dt) for c in record.components))
    if not isinstance(record, Record):
        raise TypeError(f"record must be a Record or a BaseMotion, got {type(record).__name__}")
    new_dt = _checked_step(dt)
    times = new_dt * np.arange(_sample_count(record, new_dt))
    samples = np.interp(times, record.times, record.acceleration_samples)
    return Record(samples, new_dt, record.name, record.start_time, units="m/s2", check_peak=False,
                  metadata=record.metadata)


def _resampled_component(component, dt):
    """A Record component resampled; None or another excitation kept as it is."""
    return resample(component, dt) if isinstance(component, Record) else component


def _checked_step(dt) -> float:
    """``dt`` [s] as a float, or ValueError naming it if it is not finite and > 0."""
    try:
        value = float(dt)
    except (TypeError, ValueError):
        raise ValueError(f"dt must be a finite sample step > 0 [s], got {dt!r}") from None
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"dt must be a finite sample step > 0 [s], got {dt!r}")
    return value


def _sample_count(record, dt) -> int:
    """How many new samples k dt [s] lie within the record's duration; at least 2."""
    count = int(np.floor(record.duration / dt + _END_TOLERANCE)) + 1
    if count < 2:
        raise ValueError(f"dt = {dt!r} s leaves fewer than 2 samples of record {record.name!r} "
                         f"(duration {record.duration:g} s); choose dt <= {record.duration:g} s")
    return count
