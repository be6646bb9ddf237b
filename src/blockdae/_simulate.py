"""The one entry point: ``simulate``."""

import dataclasses

from ._solution import BatchSolution, Solution
from .backends import Horizon, available, make_backend
from ._solution_planar import PlanarSolution
from .excitation import AbstractExcitation, BaseMotion
from ._solution_upthrow import UpthrowSolution
from .model import PlanarBlock, SlidingBlock, SpringSupportedMass

#: the backend each model runs on unless told otherwise
DEFAULT_BACKEND = {SlidingBlock: "exact", PlanarBlock: "ida", SpringSupportedMass: "exact"}


def simulate(block: SlidingBlock | PlanarBlock | SpringSupportedMass, motion: AbstractExcitation | BaseMotion,
             t_end: float | None = None, backend: str | None = None,
             **options) -> Solution | BatchSolution | PlanarSolution | UpthrowSolution:
    """Slide ``block`` on a base moving with ``motion``.

    Args:
        block: a :class:`SlidingBlock` or a :class:`PlanarBlock` (a batch of
            parameter sets if its parameters are 1-D arrays), or a
            :class:`SpringSupportedMass` (``motion`` is then its vertical ground
            acceleration; give ``t_end``).
        motion: base excitation; for a PlanarBlock also a :class:`BaseMotion` (x, y, z
            components; a 1-D excitation is its x component).
        t_end: final time [s]. None: until the block has come to rest after a finite
            excitation ends.
        backend: a name from ``blockdae.backends.available()``; None: "exact" (closed
            form) for a SlidingBlock and a SpringSupportedMass, "ida" for a PlanarBlock.
        **options: settings of the backend, name=default: meaning [unit]
            (tests check this list against the backends' fields)

            backend="exact" and backend="exact-jax" (closed forms compiled with numba,
            batches parallel over cores; or with JAX, what ``sensitivities``
            differentiates):
                window=64: pieces of a(t) per block of the onset search [-]; changes
                    speed, never results.
            backend="cvode" (ODE in u, v) and backend="ida" (DAE, with the friction
            force per unit mass F, for a PlanarBlock (F_x, F_y), as algebraic variables):
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
                solver=None: diffrax solver [-]: "tsit5", "dopri5", "dopri8"
                    (explicit) or "kvaerno5" (implicit); None: "tsit5" for a
                    SlidingBlock, "dopri8" for a PlanarBlock.
                max_segments=8: most segments (events + 1) in one piece of a(t) [-]
                    (SlidingBlock).
                max_steps=4096: most solver steps per segment [-].
                max_events_at_one_instant=5: most events at one instant [-]
                    (PlanarBlock; more: chatter, an error).
                event_resolution=1e-9: events closer are one instant [s] (PlanarBlock).

    Returns:
        A :class:`Solution` (SlidingBlock), :class:`PlanarSolution` or
        :class:`UpthrowSolution` (SpringSupportedMass), or a :class:`BatchSolution` for
        a batch; each keeps ``block`` and ``motion``. For several motions or scales: :func:`simulate_many`.
    """
    if not isinstance(block, tuple(DEFAULT_BACKEND)):
        raise TypeError(f"block must be a SlidingBlock, a PlanarBlock or a SpringSupportedMass, "
                        f"got {type(block).__name__}")
    planar = isinstance(block, PlanarBlock)
    if not isinstance(motion, (AbstractExcitation, BaseMotion) if planar else AbstractExcitation):
        kinds = "an excitation (Harmonic, Record, ...)" + (" or a BaseMotion" if planar else "")
        raise TypeError(f"motion must be {kinds}, got {type(motion).__name__}")
    horizon = Horizon.resolve(motion, t_end)
    backend = DEFAULT_BACKEND[type(block)] if backend is None else backend
    solver = make_backend(backend, **options)
    if not isinstance(block, solver.models):
        raise ValueError(f"backend={backend!r} does not run a {type(block).__name__}; choose one of "
                         f"{[name for name in available() if isinstance(block, make_backend(name).models)]}")
    result = solver.solve_batch(block, motion, horizon) if block.batch_shape else solver.solve(block, motion, horizon)
    return dataclasses.replace(result, block=block, motion=motion)
