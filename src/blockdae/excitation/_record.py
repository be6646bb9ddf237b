"""Recorded accelerograms: samples joined by straight lines."""

import dataclasses

import numpy as np

from ._base import AbstractExcitation, check_finite, check_positive
from ._pieces import Pieces


@dataclasses.dataclass(frozen=True, eq=False)
class Record(AbstractExcitation):
    """Accelerogram sampled at t = k dt, linear between samples, zero after the last.

    Args:
        acceleration: samples [m/s²], shape (n,), n >= 2.
        dt: sample step [s].
        name: label used in tables and plots.
        start_time: time of the first sample on the file's own axis [s]; kept as a label.

    The excitation starts at t = 0 whatever ``start_time`` is (the base is at rest
    there): an event time t of a Solution is ``start_time + t`` on the file's axis.
    Use :func:`blockdae.read_record` to load files.
    """

    acceleration_samples: np.ndarray
    dt: float
    name: str = ""
    start_time: float = 0.0

    def __init__(self, acceleration, dt, name="", start_time=0.0):
        samples = np.array(acceleration, dtype=float)
        if samples.ndim != 1:
            raise ValueError(f"acceleration must be a 1-D array of samples, got shape {samples.shape}")
        if samples.size < 2:
            raise ValueError(f"acceleration needs at least 2 samples, got {samples.size}")
        bad = np.flatnonzero(~np.isfinite(samples))
        if bad.size:
            raise ValueError(f"acceleration sample {bad[0]} (0-based) is {float(samples[bad[0]])}; "
                             "samples must be finite")
        samples.setflags(write=False)
        object.__setattr__(self, "acceleration_samples", samples)
        object.__setattr__(self, "dt", check_positive("dt", dt, "s"))
        object.__setattr__(self, "name", str(name))
        object.__setattr__(self, "start_time", check_finite("start_time", start_time, "s"))

    @property
    def duration(self) -> float:
        return self.dt * (self.acceleration_samples.size - 1)

    @property
    def times(self) -> np.ndarray:
        """Sample times from the first sample [s], shape (n,); add ``start_time`` for the file's axis."""
        return self.dt * np.arange(self.acceleration_samples.size)

    @property
    def peak_acceleration(self) -> float:
        return float(np.max(np.abs(self.acceleration_samples)))

    def scaled(self, factor):
        return Record(self.acceleration_samples * float(factor), self.dt, self.name, self.start_time)

    def _pieces_until(self, t_end):
        a = self.acceleration_samples
        n = min(a.size - 1, int(np.ceil(t_end / self.dt - 1e-9)))
        t0 = self.dt * np.arange(n)
        h = np.minimum(self.dt, t_end - t0)
        return Pieces.linear(t0, h, a[:n], np.diff(a[: n + 1]) / self.dt)

    def __repr__(self):
        return (f"Record(name={self.name!r}, n={self.acceleration_samples.size}, dt={self.dt} s, "
                f"peak={self.peak_acceleration:.4g} m/s², start_time={self.start_time:g} s)")
