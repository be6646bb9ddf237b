"""Recorded accelerograms: samples joined by straight lines."""

import dataclasses
import functools
import types
import typing

import numpy as np

from ..units import STANDARD_GRAVITY
from ._base import AbstractExcitation, check_finite, check_positive
from .pieces import Pieces
from ._plausibility import check_peak_acceleration
from ._units import unit_factor


@dataclasses.dataclass(frozen=True, eq=False)
class Record(AbstractExcitation):
    """Accelerogram sampled at t = k dt, linear between samples, zero after the last.

    Args:
        acceleration: samples in ``units``, shape (n,), n >= 2; kept in m/s²
            (``acceleration_samples``, also named ``acceleration_m_s2``; in g:
            ``acceleration_g``; their times: ``sample_times`` [s]).
        dt: sample step [s].
        name: label used in tables and plots.
        start_time: time of the first sample on the file's own axis [s]; kept as a label.
        units: units of ``acceleration``: "m/s2", "g", "cm/s2" or "gal"; None (default):
            m/s², as every number blockdae takes from Python.
        g: the value of one "g" [m/s²], for ``units="g"``.
        check_peak: the peak rule (:func:`check_peak_acceleration`): ValueError if a nonzero
            peak is implausible in ``units`` (outside :data:`PLAUSIBLE_PEAK_G`, 1e-4 g to 4 g:
            an array in g or cm/s² given as m/s², ...), naming the likely units; a
            :class:`UnitsWarning` if it is above 2 g, or if ``units`` is None and the peak is
            at most 2 (an array in g read as m/s²: state ``units``); False accepts any peak.
        metadata: what a reader found in the file's header (format, units as read,
            station, component, event, ...), kept read-only; empty by default.

    The excitation starts at t = 0 whatever ``start_time`` is (the base is at rest
    there): an event time t of a Solution is ``start_time + t`` on the file's axis.
    Use :func:`blockdae.read_record` to load files.
    """

    acceleration_samples: np.ndarray
    dt: float
    name: str = ""
    start_time: float = 0.0
    metadata: typing.Mapping = dataclasses.field(default_factory=dict, repr=False)

    def __init__(self, acceleration, dt, name="", start_time=0.0, *, units=None, g=STANDARD_GRAVITY,
                 check_peak=True, metadata=None):
        samples = np.array(acceleration, dtype=float)
        if samples.ndim != 1:
            raise ValueError(f"acceleration must be a 1-D array of samples, got shape {samples.shape}")
        if samples.size < 2:
            raise ValueError(f"acceleration needs at least 2 samples, got {samples.size}")
        bad = np.flatnonzero(~np.isfinite(samples))
        if bad.size:
            raise ValueError(f"acceleration sample {bad[0]} (0-based) is {float(samples[bad[0]])}; "
                             "samples must be finite")
        object.__setattr__(self, "dt", check_positive("dt", dt, "s"))
        object.__setattr__(self, "name", str(name))
        object.__setattr__(self, "start_time", check_finite("start_time", start_time, "s"))
        object.__setattr__(self, "metadata", types.MappingProxyType(dict(metadata or {})))
        if check_peak and np.any(samples):  # a record of zeros: no units to get wrong
            check_peak_acceleration(samples, "m/s2" if units is None else units, g,
                                    f"Record {self.name!r}" if self.name else "Record", stated=units is not None)
        if units is not None:
            samples = samples * unit_factor(units, g)
        samples.setflags(write=False)
        object.__setattr__(self, "acceleration_samples", samples)

    def __getstate__(self):
        """What pickle keeps (a process pool's workers, Dask): the metadata as a plain dict."""
        return {**self.__dict__, "metadata": dict(self.metadata)}

    def __setstate__(self, state):
        state = {**state, "metadata": types.MappingProxyType(dict(state["metadata"]))}
        samples = np.array(state["acceleration_samples"], dtype=float)
        samples.setflags(write=False)
        self.__dict__.update(state, acceleration_samples=samples)

    @property
    def duration(self) -> float:
        return self.dt * (self.acceleration_samples.size - 1)

    @property
    def times(self) -> np.ndarray:
        """Sample times from the first sample [s], shape (n,); add ``start_time`` for the file's axis."""
        return self.dt * np.arange(self.acceleration_samples.size)

    @property
    def sample_times(self) -> np.ndarray:
        """Sample times from the first sample [s], shape (n,): the same as :attr:`times`."""
        return self.times

    @property
    def acceleration_m_s2(self) -> np.ndarray:
        """The samples [m/s²], shape (n,): :attr:`acceleration_samples` (read-only);
        ``acceleration(t)`` is a(t) between them."""
        return self.acceleration_samples

    @property
    def acceleration_g(self) -> np.ndarray:
        """The samples in units of standard gravity (9.80665 m/s²) [g], shape (n,)."""
        return self.acceleration_samples / STANDARD_GRAVITY

    @functools.cached_property
    def peak_acceleration(self) -> float:
        """max |a| over the samples [m/s²] (computed once: the samples are read-only)."""
        return float(np.max(np.abs(self.acceleration_samples)))

    def as_horizontal(self) -> "Record":
        """This record with its header's vertical flag cleared: a vertical component run on
        purpose as horizontal motion (the sliding models refuse one otherwise)."""
        return Record(self.acceleration_samples, self.dt, self.name, self.start_time, units="m/s2",
                      check_peak=False, metadata={**self.metadata, "vertical": False})

    def scaled(self, factor):
        return Record(self.acceleration_samples * float(factor), self.dt, self.name, self.start_time,
                      units="m/s2", check_peak=False, metadata=self.metadata)

    def _pieces_until(self, t_end):
        a = self.acceleration_samples
        n = min(a.size - 1, int(np.ceil(t_end / self.dt - 1e-9)))
        t0 = self.dt * np.arange(n)
        h = np.minimum(self.dt, t_end - t0)
        return Pieces.linear(t0, h, a[:n], np.diff(a[: n + 1]) / self.dt)

    def __repr__(self):
        return (f"Record(name={self.name!r}, n={self.acceleration_samples.size}, dt={self.dt} s, "
                f"peak={self.peak_acceleration:.4g} m/s², start_time={self.start_time:g} s)")


def check_horizontal(motion) -> None:
    """ValueError if ``motion`` is a record whose header says it is a vertical component: a
    sliding block or mass is shaken along its base, by a horizontal component."""
    metadata = getattr(motion, "metadata", None) or {}
    if metadata.get("vertical"):
        raise ValueError(f"{getattr(motion, 'name', '') or 'the record'}: a vertical component (its header says "
                         f"{metadata.get('component', 'vertical')!r}), refused as horizontal motion: use a horizontal "
                         "component of the station, or record.as_horizontal() (command line: --as-horizontal) to run "
                         "it as horizontal motion on purpose")
