"""The contract every base excitation fulfils."""

import abc

import numpy as np

from .pieces import Pieces, evaluate


class AbstractExcitation(abc.ABC):
    """Base acceleration a(t) [m/s²] for t >= 0, with its velocity and displacement.

    A concrete excitation defines ``duration`` [s] (``inf`` if it never ends), the
    monotone closed-form pieces of a(t) on [0, duration] and the base velocity at
    t = 0. Past ``duration`` the base acceleration is zero.
    """

    #: time after which a(t) = 0 [s]; ``inf`` for an unending excitation
    duration: float

    @property
    @abc.abstractmethod
    def peak_acceleration(self) -> float:
        """max |a(t)| [m/s²]."""

    @abc.abstractmethod
    def _pieces_until(self, t_end: float) -> Pieces:
        """Monotone pieces covering [0, t_end], for 0 < t_end <= duration."""

    @abc.abstractmethod
    def scaled(self, factor: float) -> "AbstractExcitation":
        """The same excitation with a(t) multiplied by ``factor`` [-]."""

    @property
    def initial_velocity(self) -> float:
        """Base velocity at t = 0 [m/s]; the block starts moving with the base."""
        return 0.0

    def inverted(self) -> "AbstractExcitation":
        """The excitation with a(t) of opposite sign."""
        return self.scaled(-1.0)

    def pieces(self, t_end: float) -> Pieces:
        """Monotone pieces of a(t) covering exactly [0, t_end] [s]."""
        if not (np.isfinite(t_end) and t_end > 0):
            raise ValueError(f"t_end must be a positive finite time [s], got {t_end!r}")
        if t_end <= self.duration:
            return self._pieces_until(t_end)
        rest = Pieces.linear([self.duration], [t_end - self.duration], [0.0], [0.0])
        return Pieces.concatenate([self._pieces_until(self.duration), rest])

    @property
    def breakpoints(self) -> np.ndarray:
        """Times where a(t) or its slope may jump [s] (ends of finite excitations)."""
        t_end = self.duration if np.isfinite(self.duration) else 0.0
        p = self._pieces_until(t_end) if t_end > 0 else None
        return np.array([0.0]) if p is None else np.append(p.t0, p.t_end)

    def _evaluate(self, t):
        t = np.asarray(t, dtype=float)
        horizon = float(np.max(t, initial=0.0))
        if np.isfinite(self.duration):
            horizon = max(horizon, self.duration)
        else:  # cover the last time inside a piece, not at the pieces' end
            horizon = horizon * (1 + 1e-12) + 1e-12
        return evaluate(self.pieces(horizon), t, v0=self.initial_velocity)

    def acceleration(self, t):
        """a(t) [m/s²], right-continuous at jumps."""
        return self._evaluate(t)[0]

    def acceleration_rate(self, t):
        """da/dt just after t [m/s³]."""
        return self._evaluate(t)[1]

    def velocity(self, t):
        """Base velocity v(t) [m/s]."""
        return self._evaluate(t)[2]

    def displacement(self, t):
        """Base displacement x(t) [m], with x(0) = 0."""
        return self._evaluate(t)[3]


def check_positive(name, value, unit):
    value = float(value)
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be a positive finite number [{unit}], got {value!r}")
    return value


def check_finite(name, value, unit):
    value = float(value)
    if not np.isfinite(value):
        raise ValueError(f"{name} must be finite [{unit}], got {value!r}")
    return value
