"""Final numbers only, for large studies: many motions × parameter sets in one call."""

import warnings
from typing import NamedTuple

import numpy as np

from ..core import Horizon, compact_repr, make_backend
from ..excitation import AbstractExcitation
from ._model import SlidingBlock


class FinalNumbers(NamedTuple):
    """The final numbers of many analyses; each of shape (n_motions,) + block.batch_shape
    (+ (n_scales,) when ``scale`` is given)."""

    def __repr__(self):
        return compact_repr(self)

    displacement: np.ndarray  # u(t_end) [m]
    max_abs_displacement: np.ndarray  # max |u(t)| [m]
    n_events: np.ndarray  # located mode changes
    t_end: np.ndarray  # final time [s]


def simulate_final(block: SlidingBlock, motions, t_end: float | None = None, *, scale=None,
                   **options) -> FinalNumbers:
    """Slide ``block`` on each of ``motions``; the final numbers only, no events or knots.

    Every (motion, parameter set) pair runs in one call of the exact backend's compiled
    engine, in parallel over the cores: the path for studies of many analyses. The
    numbers equal those of ``simulate(block, motion)`` for each motion.

    Args:
        block: the block; a batch of parameter sets if its parameters are 1-D arrays.
        motions: a sequence of excitations (or one).
        t_end: final time [s] of every motion; None: until the block has come to rest
            after each (finite) motion.
        scale: None, or a 1-D sequence of factors on every motion's a(t) [-]: a last
            axis of the results, each factor equal to sliding on ``motion.scaled(k)``
            (to rounding of the product) without a scaled copy of any motion.
        **options: settings of the exact backend (``window``).

    Deprecated: ``bd.simulate(block, motions, scale=..., final_only=True)`` runs the same
    compiled call for every model with such an engine into one :class:`blockdae.Ensemble`.
    """
    warnings.warn("blockdae.sliding.simulate_final is deprecated; use bd.simulate(block, motions, scale=..., "
                  "final_only=True), the same compiled call, which returns a bd.Ensemble", DeprecationWarning,
                  stacklevel=2)
    if not isinstance(block, SlidingBlock):
        raise TypeError(f"block must be a SlidingBlock, got {type(block).__name__}")
    motions = [motions] if isinstance(motions, AbstractExcitation) else list(motions)
    for i, motion in enumerate(motions):
        if not isinstance(motion, AbstractExcitation):
            raise TypeError(f"motions[{i}] must be an excitation (Harmonic, Record, ...), got {type(motion).__name__}")
    factors = (1.0,) if scale is None else np.asarray(scale, dtype=float)
    if np.ndim(factors) != 1 or np.size(factors) == 0 or not np.all(np.isfinite(factors)):
        raise ValueError(f"scale must be a non-empty 1-D sequence of finite factors [-], got {scale!r}")
    horizons = [Horizon.resolve(motion, t_end) for motion in motions]
    out = make_backend("exact", **options).solve_final(block, motions, horizons, factors)
    shape = (len(motions),) + block.batch_shape + (() if scale is None else (len(factors),))
    pick = lambda column: out[:, :, column].reshape(shape)
    return FinalNumbers(displacement=pick(0), max_abs_displacement=pick(3), n_events=pick(4).astype(int),
                        t_end=pick(5))
