"""The one entry point: ``simulate``."""

from ._registry import AbstractBackend, Horizon, available, make_backend
from .contract import AbstractHybridModel


def simulate(block: AbstractHybridModel, motion, t_end: float | None = None,
             backend: str | AbstractBackend | None = None, **options):
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
        backend: a backend object configured already, e.g. ``bd.CVODE(rtol=1e-12)``,
            or its name from ``blockdae.backends.available()`` ("exact", "exact-jax",
            "cvode", "ida", "jax", "compiled"; :func:`blockdae.backends.register_backend`
            adds names) with its options in ``**options``; None: the model's
            ``default_backend`` with its defaults.
        **options: settings of the backend named by ``backend``, as its class takes
            them: :class:`Exact`, :class:`ExactJax`, :class:`CVODE`, :class:`IDA`,
            :class:`JaxTwin`, :class:`Compiled` (each lists its options with
            defaults and units); none beside a backend object.

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
    solver = make_backend(block.default_backend if backend is None else backend, **options)
    if not solver.runs(block):
        raise ValueError(f"backend={solver.name!r} does not run a {type(block).__name__}; choose one of "
                         f"{list(available(block))}")
    result = solver.solve_batch(block, motion, horizon) if block.batch_shape else solver.solve(block, motion, horizon)
    return _of_run(result, block, motion)


def _of_run(result, block, motion):
    """``result`` (a solution: a frozen dataclass that checks nothing on construction) with
    its ``block`` and ``motion`` set: what ``dataclasses.replace`` makes, a shallow copy,
    without running ``__init__`` again."""
    copy = object.__new__(type(result))
    copy.__dict__.update(result.__dict__)
    object.__setattr__(copy, "block", block)
    object.__setattr__(copy, "motion", motion)
    return copy
