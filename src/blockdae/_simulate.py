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
        **options: settings of the backend, name=default: meaning [unit]
            (tests check this list against the backends' fields)

            backend="exact" and backend="exact-jax" (closed forms compiled with numba,
            batches parallel over cores; or with JAX, what ``sensitivities``
            differentiates):
                window=64: pieces of a(t) per block of the onset search [-]; changes
                    speed, never results.
            backend="cvode" (ODE in u, v) and backend="ida" (DAE, with the friction
            force per unit mass F as algebraic variable):
                rtol=1e-10: relative tolerance [-], in [1e-14, 1e-2].
                atol=1e-14: absolute tolerance [m, m/s]; IDA's on F [m/s²] is at
                    least rtol mu g.
                max_step=None: largest internal step [s]; None: no bound besides
                    the stops at every piece of a(t) and every turning point of v.
                max_num_steps=5000: most internal steps between two stops [-].
                max_events_at_one_instant=5: most consecutive events at one instant [-];
                    more (chatter) raises an error.
                event_resolution=1e-9: events closer than this are one instant [s].
            backend="jax" (diffrax twin, forward-mode differentiable):
                rtol=1e-10: relative tolerance of the step-size controller [-].
                atol=1e-12: absolute tolerance [m, m/s].
                solver="tsit5": diffrax solver [-]: "tsit5", "dopri5", "dopri8"
                    (explicit) or "kvaerno5" (implicit).
                max_segments=8: most segments (events + 1) in one piece of a(t) [-].
                max_steps=4096: most solver steps per segment [-].

    Returns:
        A :class:`Solution`, or a :class:`BatchSolution` for a batch; either keeps
        ``block`` and ``motion``. For several motions or scales: :func:`simulate_many`.
    """
    if not isinstance(block, SlidingBlock):
        raise TypeError(f"block must be a SlidingBlock, got {type(block).__name__}")
    if not isinstance(motion, AbstractExcitation):
        raise TypeError(f"motion must be an excitation (Harmonic, Record, ...), got {type(motion).__name__}")
    horizon = Horizon.resolve(motion, t_end)
    solver = make_backend(backend, **options)
    result = solver.solve_batch(block, motion, horizon) if block.batch_shape else solver.solve(block, motion, horizon)
    return dataclasses.replace(result, block=block, motion=motion)
