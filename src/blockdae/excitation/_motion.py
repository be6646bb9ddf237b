"""Three-component base motion: two horizontal components and a vertical one."""

import dataclasses

import numpy as np

from ._base import AbstractExcitation
from ._pieces import Pieces, rebase

_NAMES = ("x", "y", "z")


@dataclasses.dataclass(frozen=True, eq=False)
class BaseMotion:
    """Base acceleration (a_x, a_y, a_z)(t) [m/s²]; z is vertical, upward positive.

    Args:
        x: horizontal component along x (any excitation).
        y, z: second horizontal and vertical components; None: zero.

    The breakpoints are the union of the components'; past its own duration a
    component is zero, as a 1-D record is.
    """

    x: AbstractExcitation
    y: AbstractExcitation | None = None
    z: AbstractExcitation | None = None

    def __post_init__(self):
        for name in _NAMES:
            value = getattr(self, name)
            if not (value is None and name != "x") and not isinstance(value, AbstractExcitation):
                raise TypeError(f"{name} must be an excitation (Harmonic, Record, ...), got {type(value).__name__}")

    @property
    def components(self) -> tuple:
        """(x, y, z); a missing component is None."""
        return self.x, self.y, self.z

    @property
    def duration(self) -> float:
        """Time after which every component is zero [s]."""
        return max(c.duration for c in self.components if c is not None)

    def aligned_pieces(self, t_end: float) -> tuple[Pieces, Pieces, Pieces]:
        """Pieces of a_x, a_y, a_z on [0, t_end] [s] on one common partition (the union
        of the components' breakpoints): same ``t0`` and ``h``, each monotone."""
        parts = [None if c is None else c.pieces(t_end) for c in self.components]
        edges = np.unique(np.concatenate([np.append(p.t0, p.t_end) for p in parts if p is not None]))
        edges = edges[edges <= t_end]
        t0, h = edges[:-1], np.diff(edges)
        return tuple(_restrict(p, t0, h) for p in parts)


def _restrict(pieces: Pieces | None, t0: np.ndarray, h: np.ndarray) -> Pieces:
    """``pieces`` re-cut on the finer partition (t0, h) that contains its breakpoints."""
    if pieces is None:
        return Pieces.linear(t0, h, 0.0, 0.0)
    k = np.clip(np.searchsorted(pieces.t0, t0, side="right") - 1, 0, len(pieces.t0) - 1)
    p0, p1, s, w, phi = rebase(pieces.p0[k], pieces.p1[k], pieces.s[k], pieces.w[k], pieces.phi[k],
                               t0 - pieces.t0[k])
    return Pieces(t0, h, p0, p1, s, w, phi)
