"""Three-component base motion: two horizontal components and a vertical one."""

import dataclasses

import numpy as np

from ..units import STANDARD_GRAVITY
from ._base import AbstractExcitation
from .pieces import Pieces, rebase
from ._record import Record

_NAMES = ("x", "y", "z")
# breakpoints of different components closer than this times t_end are one (rounding of k dt, k T/2)
_SAME_TIME = 1e-12
# Record steps closer than this, relative, are one step
_SAME_DT = 1e-9


@dataclasses.dataclass(frozen=True, eq=False)
class BaseMotion:
    """Base acceleration (a_x, a_y, a_z)(t) [m/s²]; z is vertical, upward positive.

    Args:
        x: horizontal component along x (any excitation).
        y, z: second horizontal and vertical components; None: zero.

    Components of any kinds mix; Records must share one ``dt`` (lengths may differ;
    :func:`blockdae.excitation.resample` brings records of mixed steps to one).
    Past its own duration a component is zero, as a 1-D record is.
    """

    x: AbstractExcitation
    y: AbstractExcitation | None = None
    z: AbstractExcitation | None = None

    def __post_init__(self):
        for name in _NAMES:
            value = getattr(self, name)
            if not (value is None and name != "x") and not isinstance(value, AbstractExcitation):
                raise TypeError(f"{name} must be an excitation (Harmonic, Record, ...), got {type(value).__name__}")
        records = [(name, c) for name, c in zip(_NAMES, self.components) if isinstance(c, Record)]
        for name, record in records[1:]:
            first, other = records[0]
            if not np.isclose(record.dt, other.dt, rtol=_SAME_DT, atol=0.0):
                raise ValueError(f"components {_label(first, other)} and {_label(name, record)} are Records "
                                 f"with different dt ({first}: dt={other.dt:g} s, {name}: dt={record.dt:g} s); "
                                 "resample them to one sample step first: blockdae.excitation.resample(record, dt) "
                                 "on each in Python, --resample DT on the command line")

    @classmethod
    def from_samples(cls, ax, ay=None, az=None, *, dt: float, name: str = "", units=None, g=STANDARD_GRAVITY,
                     check_peak=True) -> "BaseMotion":
        """Records of samples ``ax``, ``ay``, ``az`` (in ``units``; m/s² by default) at step
        ``dt`` [s], named "<name> x", "<name> y", "<name> z"; a missing component stays None.
        ``units``, ``g``, ``check_peak``: as for :class:`Record`, for each component."""
        return cls(*(None if a is None else Record(a, dt, f"{name} {axis}".lstrip(), units=units, g=g,
                                                   check_peak=check_peak)
                     for a, axis in zip((ax, ay, az), _NAMES)))

    @property
    def components(self) -> tuple:
        """(x, y, z); a missing component is None."""
        return self.x, self.y, self.z

    @property
    def duration(self) -> float:
        """Time after which every component is zero [s]."""
        return max(c.duration for c in self.components if c is not None)

    @property
    def peak_acceleration(self) -> tuple[float, float, float]:
        """max |a| of each component [m/s²]; 0 for a missing one."""
        return tuple(0.0 if c is None else float(c.peak_acceleration) for c in self.components)

    @property
    def initial_velocity(self) -> tuple[float, float, float]:
        """Base velocity of each component at t = 0 [m/s]; 0 for a missing one."""
        return tuple(0.0 if c is None else float(c.initial_velocity) for c in self.components)

    @property
    def breakpoints(self) -> np.ndarray:
        """Times where a component or its slope may jump [s]: the union, sorted, unique."""
        return np.unique(np.concatenate([c.breakpoints for c in self.components if c is not None]))

    def scaled(self, factor: float) -> "BaseMotion":
        """Every component multiplied by ``factor`` [-]."""
        return self.scaled_components(factor, factor, factor)

    def inverted(self) -> "BaseMotion":
        """Every component of opposite sign."""
        return self.scaled(-1.0)

    def scaled_components(self, x: float = 1.0, y: float = 1.0, z: float = 1.0) -> "BaseMotion":
        """Each component multiplied by its own factor [-]; a missing component stays None."""
        return BaseMotion(*(None if c is None else c.scaled(k) for c, k in zip(self.components, (x, y, z))))

    def acceleration(self, t) -> np.ndarray:
        """(a_x, a_y, a_z)(t) [m/s²], shape (3,) + t.shape."""
        return self._stack("acceleration", t)

    def velocity(self, t) -> np.ndarray:
        """Base velocity (v_x, v_y, v_z)(t) [m/s], shape (3,) + t.shape."""
        return self._stack("velocity", t)

    def displacement(self, t) -> np.ndarray:
        """Base displacement (x, y, z)(t) [m], zero at t = 0, shape (3,) + t.shape."""
        return self._stack("displacement", t)

    def _stack(self, quantity, t):
        t = np.asarray(t, dtype=float)
        return np.stack([np.zeros(t.shape) if c is None else np.asarray(getattr(c, quantity)(t), dtype=float)
                         for c in self.components])

    def aligned_pieces(self, t_end: float) -> tuple[Pieces, Pieces, Pieces]:
        """Pieces of a_x, a_y, a_z on [0, t_end] [s] on one common partition (the union
        of the components' breakpoints): same ``t0`` and ``h``, each monotone."""
        parts = [None if c is None else c.pieces(t_end) for c in self.components]
        tol = _SAME_TIME * t_end
        starts = np.unique(np.concatenate([p.t0 for p in parts if p is not None]))
        starts = starts[np.concatenate([[True], np.diff(starts) > tol])]
        t0 = starts[starts < t_end - tol]
        h = np.diff(np.append(t0, t_end))
        return tuple(_restrict(p, t0, h, tol) for p in parts)

    def __repr__(self):
        return f"BaseMotion(x={self.x!r}, y={self.y!r}, z={self.z!r})"


def _label(axis, record):
    return f"{axis} ({record.name!r})" if record.name else axis


def _restrict(pieces: Pieces | None, t0: np.ndarray, h: np.ndarray, tol: float) -> Pieces:
    """``pieces`` re-cut on the finer partition (t0, h) that contains its breakpoints
    (each to within ``tol`` [s])."""
    if pieces is None:
        return Pieces.linear(t0, h, 0.0, 0.0)
    k = np.clip(np.searchsorted(pieces.t0, t0 + tol, side="right") - 1, 0, len(pieces.t0) - 1)
    p0, p1, s, w, phi = rebase(pieces.p0[k], pieces.p1[k], pieces.s[k], pieces.w[k], pieces.phi[k],
                               t0 - pieces.t0[k])
    return Pieces(t0, h, p0, p1, s, w, phi)
