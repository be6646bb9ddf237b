"""The one entry point: ``simulate``."""

import dataclasses

from ._solution import BatchSolution, Solution
from .backends import Horizon, make_backend
from .excitation import AbstractExcitation
from .model import SlidingBlock


def simulate(block: SlidingBlock, motion: AbstractExcitation, t_end: float | None = None,
             backend: str = "exact", **options) -> Solution | BatchSolution:
    """Slide ``block`` on a base moving with ``motion``.

    Args:
        block: the block; a batch of parameter sets if its parameters are arrays.
        motion: base excitation.
        t_end: final time [s]. None: until the block has come to rest after a finite
            excitation ends.
        backend: "exact" (closed form), or another name from
            ``blockdae.backends.available()``.
        **options: settings of the backend (e.g. ``rtol`` for the ODE solvers).

    Returns:
        A :class:`Solution`, or a :class:`BatchSolution` for a batch.
    """
    if not isinstance(block, SlidingBlock):
        raise TypeError(f"block must be a SlidingBlock, got {type(block).__name__}")
    if not isinstance(motion, AbstractExcitation):
        raise TypeError(f"motion must be an excitation (Harmonic, Record, ...), got {type(motion).__name__}")
    horizon = Horizon.resolve(motion, t_end)
    solver = make_backend(backend, **options)
    result = solver.solve_batch(block, motion, horizon) if block.batch_shape else solver.solve(block, motion, horizon)
    return dataclasses.replace(result, block=block, motion=motion)
