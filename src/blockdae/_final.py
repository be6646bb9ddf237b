"""Final numbers only, for large studies: many motions × parameter sets in one call."""

from typing import NamedTuple

import numpy as np

from .backends import Horizon, make_backend
from .excitation import AbstractExcitation
from .model import SlidingBlock


class FinalNumbers(NamedTuple):
    """The final numbers of many analyses; each of shape (n_motions,) + block.batch_shape."""

    displacement: np.ndarray  # u(t_end) [m]
    max_abs_displacement: np.ndarray  # max |u(t)| [m]
    n_events: np.ndarray  # located mode changes
    t_end: np.ndarray  # final time [s]


def simulate_final(block: SlidingBlock, motions, t_end: float | None = None, **options) -> FinalNumbers:
    """Slide ``block`` on each of ``motions``; the final numbers only, no events or knots.

    Every (motion, parameter set) pair runs in one call of the exact backend's compiled
    engine, in parallel over the cores: the path for studies of many analyses. The
    numbers equal those of ``simulate(block, motion)`` for each motion.

    Args:
        block: the block; a batch of parameter sets if its parameters are 1-D arrays.
        motions: a sequence of excitations (or one).
        t_end: final time [s] of every motion; None: until the block has come to rest
            after each (finite) motion.
        **options: settings of the exact backend (``window``).
    """
    if not isinstance(block, SlidingBlock):
        raise TypeError(f"block must be a SlidingBlock, got {type(block).__name__}")
    motions = [motions] if isinstance(motions, AbstractExcitation) else list(motions)
    for i, motion in enumerate(motions):
        if not isinstance(motion, AbstractExcitation):
            raise TypeError(f"motions[{i}] must be an excitation (Harmonic, Record, ...), got {type(motion).__name__}")
    horizons = [Horizon.resolve(motion, t_end) for motion in motions]
    out = make_backend("exact", **options).solve_final(block, motions, horizons)
    shape = (len(motions),) + block.batch_shape
    pick = lambda column: out[:, :, column].reshape(shape)
    return FinalNumbers(displacement=pick(0), max_abs_displacement=pick(3), n_events=pick(4).astype(int),
                        t_end=pick(5))
