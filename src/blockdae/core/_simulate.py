"""The one entry point: ``simulate``, one run or many (motions x factors x polarities x
parameter sets) into one :class:`Ensemble`."""

import functools
import math

import numpy as np

from ..excitation import AbstractExcitation, check_finite_result
from ..units import STANDARD_GRAVITY
from ._cases import cases, is_many
from ._ensemble import Ensemble, Finals
from ._progress import progress_bar
from ._registry import AbstractBackend, Horizon, available, make_backend
from ._solution import of_run
from .contract import AbstractHybridModel


def simulate(model: AbstractHybridModel, motion, t_end: float | None = None,
             backend: str | AbstractBackend | None = None, *, scale=None, pga=None, polarity: str = "normal",
             final_only: bool = False, pga_rounding: str = "exact", check_peak: bool = True, executor=None,
             progress=None, **options):
    """Run ``model`` on a base moving with ``motion``, or on many motions at many amplitudes.

    Args:
        model: any model: a :class:`SlidingBlock`, :class:`PlanarBlock`,
            :class:`SpringSupportedMass` (``motion`` is then its vertical ground
            acceleration), :class:`FlexibleSlidingMass`, :class:`RockingBlock` or a user's
            :class:`AbstractHybridModel`; a batch of parameter sets where the model takes
            arrays (a :class:`~blockdae.core.contract.BatchedModel` with 1-D array
            parameters: the 1-D block's mu, the plane's, the spring's frequency and
            damping, the flexible mass's ky, the free-standing block's b, h, mu, ...).
        motion: the base excitation [m/s²] (a :class:`Record`, :class:`Harmonic`, ...; for
            a PlanarBlock also a :class:`BaseMotion` of x, y, z components); or many: a
            sequence of them, a mapping name -> excitation, a :class:`RecordSet` (its
            metadata carried into the table), or a path to a record file or a folder of
            them (read by :func:`blockdae.read_record` with the units their files state).
        t_end: final time [s]; "motion": each motion's own end (its last sample: for
            models that never come to rest, over motions of different lengths); None:
            until the model has come to rest after a finite excitation ends.
        backend: a backend object configured already, e.g. ``bd.CVODE(rtol=1e-12)``, or
            its name from ``blockdae.backends.available()`` ("exact", "exact-jax", "cvode",
            "ida", "jax", "compiled"; :func:`blockdae.backends.register_backend` adds
            names) with its options in ``**options``; None: the model's
            ``default_backend`` with its defaults.
        scale: factor(s) on a(t) [-], a number or a 1-D sequence (default 1).
        pga: instead of ``scale``, target peak ground acceleration(s) [g], a number or a
            1-D sequence: each motion is scaled so that its peak |a| is each value times
            the model's g (:func:`blockdae.excitation.pga_factor`). A value above 2 g is
            refused (likely m/s²: 2.94 is 0.3 g in m/s²) unless ``check_peak=False``.
        polarity: "normal" (the motion as given, default), "inverse" (a(t) times -1) or
            "both".
        final_only: keep the final numbers of each case only (no events or dense output:
            the path for large studies); on the exact backend of a :class:`SlidingBlock`
            and the compiled backend of a :class:`PlanarBlock` every case then runs in one
            compiled call, in parallel over cores, each ``scale`` a factor inside the
            engine (equal to running a scaled copy, to the rounding of a(t) times the
            factor). ``ensemble[i]`` still gives a case's full solution (it runs that case
            again).
        pga_rounding: "exact" (default) or "slammer": each motion's own peak rounded to
            0.001 g before scaling, as SLAMMER scales (to reproduce its tables).
        check_peak: False accepts a ``pga`` above 2 g.
        executor: where the cases of many run: None (here, one after the other; the
            compiled engines use every core themselves), or a
            ``concurrent.futures.Executor`` or ``dask.distributed.Client`` (anything with
            ``submit``): one task per case (a ProcessPoolExecutor needs
            ``mp_context=multiprocessing.get_context("spawn")``).
        progress: over many cases, a tqdm bar on stderr; None: only when stderr is a terminal.
        **options: settings of the backend named by ``backend``, as its class takes
            them: :class:`Exact`, :class:`ExactJax`, :class:`CVODE`, :class:`IDA`,
            :class:`JaxTwin`, :class:`Compiled` (each lists its options with defaults and
            units); none beside a backend object.

    Returns:
        The model's solution where one motion runs at one scale in one polarity
        (:class:`Solution` for a SlidingBlock, :class:`PlanarSolution`,
        :class:`UpthrowSolution`, :class:`FlexibleSolution`, a :class:`DriverSolution` for
        a user's model), or a :class:`BatchSolution` for a batch of parameter sets; each
        keeps ``block`` and ``motion``. An :class:`Ensemble` where many motions, scales or
        polarities run (or ``final_only``), one row per case in ``.to_dataframe()``.
    """
    if not isinstance(model, AbstractHybridModel):
        raise TypeError(f"model must be a model (SlidingBlock, PlanarBlock, SpringSupportedMass, FlexibleSlidingMass "
                        f"or an AbstractHybridModel), got {type(model).__name__}")
    as_given = scale is None and pga is None and polarity == "normal" and not final_only  # the hot path: no np.ndim
    one = (isinstance(motion, AbstractExcitation) or not is_many(motion)) and \
        (as_given or (np.ndim(scale) == 0 and np.ndim(pga) == 0 and polarity != "both" and not final_only))
    if one:
        model.check_motion(motion)  # before scaling: the model's own words for what it refuses
    solver = make_backend(model.default_backend if backend is None else backend, **options)
    if not solver.runs(model):
        raise ValueError(f"backend={solver.name!r} does not run a {type(model).__name__}; choose one of "
                         f"{list(available(model))}")
    if one and as_given:
        return solve(model, motion, t_end, solver)
    runs = cases(motion, scale=scale, pga=pga, polarity=polarity, g=float(getattr(model, "g", STANDARD_GRAVITY)),
                 pga_rounding=pga_rounding, check_peak=check_peak)
    if one:
        return solve(model, runs.motion(0, 0, 0), t_end, solver)
    return _ensemble(model, runs, t_end, solver, final_only, executor, progress)


def _ensemble(model, runs, t_end, solver, final_only, executor, progress) -> Ensemble:
    """Every case of ``runs``: in one compiled call where only final numbers are kept and
    the model's engine has one, else one run per case (here, or on ``executor``)."""
    runs.check(lambda motion: (model.check_motion(motion), Horizon.resolve(motion, _end(motion, t_end))))
    run = functools.partial(solve, t_end=t_end, solver=solver)
    if final_only and _finals_in_one_call(model, solver):
        return Ensemble(model, runs, _compiled_finals(model, runs, t_end, solver), run=run)
    solutions = _each_case(model, runs, t_end, solver, executor, progress)
    finals = tuple(tuple(tuple(Finals.of(s) for s in row) for row in motion) for motion in solutions)
    keep = not final_only and not model.batch_shape
    return Ensemble(model, runs, finals, solutions if keep else None, run=run)


def solve(model, motion, t_end, solver):
    """The solution of ``model`` (one parameter set or a batch) under ``motion`` (checked by
    the model already) to ``t_end`` [s] (None: until rest) on the backend object ``solver``,
    checked by the model (its ``check_solution``)."""
    horizon = Horizon.resolve(motion, _end(motion, t_end))
    try:
        result = (solver.solve_batch(model, motion, horizon) if model.batch_shape
                  else solver.solve(model, motion, horizon))
    except OverflowError as error:  # Python floats raise where arrays would give inf
        raise ValueError(f"bd.simulate: the run of {model} under {_label(motion)} overflowed (a value beyond "
                         f"1.8e308: {error}); check the motion's units and scale") from error
    solution = of_run(result, model, motion)
    if not _finite(solution.displacement):  # the end alone (an overflow stays there)
        check_finite_finals(model, Finals.of(solution), _label(motion))
    model.check_solution(solution)
    return solution


def check_finite_finals(model, finals, motion):
    """ValueError if a final number of ``finals`` (a :class:`Finals` of ``model``) is not
    finite, naming the quantity, the parameter set, ``model`` and ``motion`` (its label):
    a run that overflowed (a motion scaled far out of range, say) is never returned."""
    values = np.column_stack([finals.displacement, finals.max_abs_displacement])
    names = [model.state_names[s] for s in model.displacement_states]
    unit = model.displacement_unit

    def describe(index):
        j, column = index
        what = f"{names[column]} at the end [{unit}]" if column < len(names) else f"max |displacement| [{unit}]"
        one = model.item(j) if model.batch_shape else model
        return f"bd.simulate: {what} of {one} under {motion}"

    check_finite_result(values, describe)


def _finite(values) -> bool:
    """Whether ``values`` (a float, or an array) are all finite: a float's in 0.1 µs."""
    return math.isfinite(values) if isinstance(values, float) else bool(np.isfinite(values).all())


def _label(motion) -> str:
    """How an error names ``motion``: its name where it has one, else its type."""
    name = getattr(motion, "name", "")
    return repr(name) if name else f"a {type(motion).__name__}"


def _end(motion, t_end):
    """``t_end`` [s] or None, where "motion" is ``motion``'s own duration [s]."""
    if isinstance(t_end, str):
        if t_end != "motion":
            raise ValueError(f"t_end must be a time [s], \"motion\" (each motion's own end) or None, got {t_end!r}")
        return motion.duration
    return t_end


def _each_case(model, runs, t_end, solver, executor, progress):
    """The solution of every case, nested (motion, factor, polarity)."""
    n_motions, n_scales, n_polarities = runs.shape
    keys = [(i, k, p) for i in range(n_motions) for k in range(n_scales) for p in range(n_polarities)]
    done = {}
    with progress_bar(len(keys), "simulate", "case", progress) as bar:
        futures = {} if executor is None else \
            {key: executor.submit(solve, model, runs.motion(*key), t_end, solver) for key in keys}
        for key in keys:
            try:
                done[key] = futures[key].result() if futures else solve(model, runs.motion(*key), t_end, solver)
            except Exception as err:
                i, k, p = key
                err.add_note(f"in the case {runs.names[i]} at {runs.by} {runs.targets[k]:g}, {runs.polarities[p]} "
                             "polarity")
                raise
            bar.update()
    return tuple(tuple(tuple(done[i, k, p] for p in range(n_polarities)) for k in range(n_scales))
                 for i in range(n_motions))


def _finals_in_one_call(model, solver) -> bool:
    """Whether the model's engine on ``solver`` runs many motions' final numbers in one call."""
    engine = getattr(model, "engines", {}).get(solver.name)
    return hasattr(solver, "solve_final") and engine not in (None, "linear") and hasattr(engine, "final_numbers")


def _compiled_finals(model, runs, t_end, solver):
    """Every case's final numbers from one call of the model's engine, the polarities as its
    factors on a(t) (-1 negates exactly). Scales common to every motion are factors too
    (no scaled copy: equal to a scaled copy's run to the rounding of the product); target
    PGAs scale a copy of each motion."""
    n_motions, n_scales, n_polarities = runs.shape
    signs = [1.0 if polarity == "normal" else -1.0 for polarity in runs.polarities]
    in_engine = runs.by == "scale"
    if in_engine:
        motions, factors = list(runs.motions), [k * sign for k in runs.targets for sign in signs]
    else:
        motions, factors = [runs.scaled(i, k) for i in range(n_motions) for k in range(n_scales)], signs
    out = solver.solve_final(model, motions, [Horizon.resolve(m, _end(m, t_end)) for m in motions], tuple(factors))
    engine, stride = model.engines[solver.name], len(factors)

    def finals(i, k, p):
        row, column = (i, k * n_polarities + p) if in_engine else (i * n_scales + k, p)
        numbers = Finals(*engine.final_numbers(out[row, column::stride]))
        if not (np.isfinite(numbers.displacement).all() and np.isfinite(numbers.max_abs_displacement).all()):
            check_finite_finals(model, numbers, f"{runs.names[i]!r} at {runs.by} {runs.targets[k]:g}, "
                                                f"{runs.polarities[p]} polarity")
        return numbers

    return tuple(tuple(tuple(finals(i, k, p) for p in range(n_polarities)) for k in range(n_scales))
                 for i in range(n_motions))
