"""The one entry point: ``simulate``."""

import dataclasses

from ..backends import Horizon, available, make_backend
from .contract import AbstractHybridModel


def simulate(block: AbstractHybridModel, motion, t_end: float | None = None, backend: str | None = None,
             **options):
    """Slide ``block`` on a base moving with ``motion``.

    Args:
        block: a :class:`SlidingBlock` or a :class:`PlanarBlock` (a batch of
            parameter sets if its parameters are 1-D arrays), a
            :class:`SpringSupportedMass` (``motion`` is then its vertical ground
            acceleration; give ``t_end``), or any :class:`AbstractHybridModel`.
        motion: base excitation; for a PlanarBlock also a :class:`BaseMotion` (x, y, z
            components; a 1-D excitation is its x component).
        t_end: final time [s]. None: until the block has come to rest after a finite
            excitation ends.
        backend: a name from ``blockdae.backends.available()``; None: the model's
            ``default_backend`` ("exact" (closed form) for a SlidingBlock and a
            SpringSupportedMass, "ida" for a PlanarBlock, "cvode" for other models).
        **options: settings of the backend, name=default: meaning [unit]
            (tests check this list against the backends' fields)

            backend="exact" and backend="exact-jax" (closed forms compiled with numba,
            batches parallel over cores; or with JAX, what ``sensitivities``
            differentiates):
                window=64: pieces of a(t) per block of the onset search [-]; changes
                    speed, never results.
            backend="exact" for a model on its "linear" engine (a SpringSupportedMass):
                linear="compiled": its path [-]: "compiled" (numba, records) or "python"
                    (closed-form steps on the driver, the reference; sine excitations).
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
            backend="compiled" (the compiled planar engine, numba: a PlanarBlock on a
            rigid support; stick and flight in closed form, slip by DOP853):
                rtol=1e-12: relative tolerance of the slip's steps [-], in [1e-14, 1e-2].
                atol=1e-14: absolute tolerance [m, m/s].
                max_events_at_one_instant=5: most consecutive events at one instant [-];
                    more (chatter) raises an error.
                event_resolution=1e-9: events closer than this are one instant [s].

    Returns:
        The model's solution (:class:`Solution` for a SlidingBlock,
        :class:`PlanarSolution`, :class:`UpthrowSolution` for a SpringSupportedMass, a
        :class:`DriverSolution` by default), or a :class:`BatchSolution` for a batch;
        each keeps ``block`` and ``motion``. For several motions or scales: :func:`simulate_many`.
    """
    if not isinstance(block, AbstractHybridModel):
        raise TypeError(f"block must be a model (SlidingBlock, PlanarBlock, SpringSupportedMass or an "
                        f"AbstractHybridModel), got {type(block).__name__}")
    block.check_motion(motion)
    horizon = Horizon.resolve(motion, t_end)
    backend = block.default_backend if backend is None else backend
    solver = make_backend(backend, **options)
    if not solver.runs(block):
        raise ValueError(f"backend={backend!r} does not run a {type(block).__name__}; choose one of "
                         f"{list(available(block))}")
    result = solver.solve_batch(block, motion, horizon) if block.batch_shape else solver.solve(block, motion, horizon)
    return dataclasses.replace(result, block=block, motion=motion)
