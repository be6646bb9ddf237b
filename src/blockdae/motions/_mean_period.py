"""The mean period of a record (Rathje, Abrahamson & Bray 1998), the period the
flexible sliding mass is compared with (T_s / T_m)."""

import numpy as np

from ..excitation import Record
from . import _checks

#: the frequency band of the definition [Hz]
MEAN_PERIOD_BAND = (0.25, 20.0)


def mean_period(record: Record, band=MEAN_PERIOD_BAND) -> float:
    """T_m = sum(C_i² / f_i) / sum(C_i²) [s] over the record's discrete Fourier
    frequencies f_i = i / (N dt) within ``band`` [Hz], C_i the Fourier amplitudes of its
    acceleration samples (no padding, no window, as in the definition).

    Args:
        record: a sampled record (``bd.Record``).
        band: (low, high) frequencies [Hz], both ends included; default 0.25-20 Hz.

    Raises:
        ValueError: a band not increasing and positive, or one holding no Fourier
            frequency of the record or only zero amplitudes.
    """
    if not isinstance(record, Record):
        raise TypeError(f"mean_period needs a sampled record (bd.Record), got {type(record).__name__}")
    limits = _checks.array("band", band, "Hz", low=0.0, low_open=True)
    if limits.shape != (2,) or not limits[0] < limits[1]:
        raise ValueError(f"band = {band!r} Hz; band must be two increasing frequencies > 0")
    low, high = float(limits[0]), float(limits[1])
    samples = record.acceleration_m_s2
    frequencies = np.fft.rfftfreq(samples.size, record.dt)
    power = np.abs(np.fft.rfft(samples)) ** 2
    inside = (frequencies >= low) & (frequencies <= high)
    if not np.any(inside):
        raise ValueError(f"band = ({low!r}, {high!r}) Hz holds no Fourier frequency of record {record.name!r} "
                         f"(its frequency step is {frequencies[1]!r} Hz): no mean period")
    if not np.any(power[inside] > 0):
        raise ValueError(f"record {record.name!r} has zero Fourier amplitude in band = ({low!r}, {high!r}) Hz: "
                         "no mean period")
    return float(np.sum(power[inside] / frequencies[inside]) / np.sum(power[inside]))
