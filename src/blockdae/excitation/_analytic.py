"""Harmonic motion and single pulses (Sawicki & Chybicki 2005, Eqs. 1-3 and Examples 4-6)."""

import dataclasses

import numpy as np

from ._base import AbstractExcitation, check_finite, check_positive
from .pieces import Pieces


@dataclasses.dataclass(frozen=True)
class Harmonic(AbstractExcitation):
    """a(t) = A sin(2 pi t / T), v(t) = -(A T / 2 pi) cos(2 pi t / T) (Sawicki & Chybicki 2005, Eqs. 1-2).

    Args:
        amplitude: A [m/s²].
        period: T [s].
        cycles: n [-], a positive number (0.5, 1, 2.25, ...): a(t) ends after n
            periods (duration n T [s], a = 0 after, the base keeps v(n T)); None: never ends.
    """

    amplitude: float
    period: float
    cycles: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "amplitude", check_finite("amplitude", self.amplitude, "m/s²"))
        object.__setattr__(self, "period", check_positive("period", self.period, "s"))
        if self.cycles is not None:
            object.__setattr__(self, "cycles", check_positive("cycles", self.cycles, "-"))

    @property
    def duration(self) -> float:
        return np.inf if self.cycles is None else self.cycles * self.period

    @property
    def peak_acceleration(self) -> float:
        return abs(self.amplitude)

    @property
    def initial_velocity(self) -> float:
        return -self.amplitude * self.period / (2 * np.pi)

    def scaled(self, factor):
        return dataclasses.replace(self, amplitude=self.amplitude * factor)

    def _pieces_until(self, t_end):
        w = 2 * np.pi / self.period
        # split at the extrema, t = T/4 + k T/2, so that a is monotone on each piece
        extrema = np.arange(self.period / 4, t_end, self.period / 2)
        edges = np.concatenate([[0.0], extrema[extrema < t_end], [t_end]])
        t0, h = edges[:-1], np.diff(edges)
        zeros = np.zeros_like(t0)
        return Pieces(t0, h, zeros, zeros, zeros + self.amplitude, zeros + w, np.mod(w * t0, 2 * np.pi))

    def __repr__(self):
        cycles = "" if self.cycles is None else f", cycles={self.cycles!r}"
        return f"Harmonic(amplitude={self.amplitude!r}, period={self.period!r}{cycles})"


@dataclasses.dataclass(frozen=True)
class _Pulse(AbstractExcitation):
    amplitude: float
    duration: float

    def __post_init__(self):
        object.__setattr__(self, "amplitude", check_finite("amplitude", self.amplitude, "m/s²"))
        object.__setattr__(self, "duration", check_positive("duration", self.duration, "s"))

    @property
    def peak_acceleration(self) -> float:
        return abs(self.amplitude)

    def scaled(self, factor):
        return dataclasses.replace(self, amplitude=self.amplitude * factor)

    def _pieces_until(self, t_end):
        full = self._pieces()
        keep = full.t0 < t_end
        cut = full._replace(**{f: getattr(full, f)[keep] for f in Pieces._fields})
        return cut._replace(h=np.minimum(cut.h, t_end - cut.t0))


@dataclasses.dataclass(frozen=True)
class RectangularPulse(_Pulse):
    """a(t) = A on [0, duration), zero after; base at rest at t = 0 (Sawicki & Chybicki 2005, Ex. 4).

    Args:
        amplitude: A [m/s²].
        duration: t0 [s].
    """

    def _pieces(self):
        return Pieces.linear([0.0], [self.duration], [self.amplitude], [0.0])


@dataclasses.dataclass(frozen=True)
class TriangularPulse(_Pulse):
    """Triangle rising to A at duration/2, back to zero at duration (Sawicki & Chybicki 2005, Ex. 5).

    Args:
        amplitude: peak A [m/s²].
        duration: t0 [s].
    """

    def _pieces(self):
        half, slope = self.duration / 2, 2 * self.amplitude / self.duration
        return Pieces.linear([0.0, half], [half, half], [0.0, self.amplitude], [slope, -slope])


@dataclasses.dataclass(frozen=True)
class SinePulse(_Pulse):
    """a(t) = A sin(pi t / duration) on [0, duration], zero after (Sawicki & Chybicki 2005, Ex. 6).

    Args:
        amplitude: A [m/s²].
        duration: t0 [s].
    """

    def _pieces(self):
        half, w = self.duration / 2, np.pi / self.duration
        return Pieces(np.array([0.0, half]), np.array([half, half]), np.zeros(2), np.zeros(2),
                      np.full(2, self.amplitude), np.full(2, w), np.array([0.0, np.pi / 2]))
