"""Studies of records × friction (or yield acceleration) × intensity × location (seed
002), as one tidy table.

A study slides a one-way block (by default in both polarities of each record, as
``bd.newmark``) on the ground and on floors of shear frames under every record, at every
friction coefficient μ (or yield acceleration ky [g]) and every intensity; another model
sweeps the parameter it declares (``study_parameter``: the flexible mass's ky [g]), or the
keyword it is given, one model per value run by ``bd.simulate`` (:mod:`._hooks`). The work is
split into tasks of whole records: a task computes the ground and floor motions of its
records once (one frame response per record and frame), normalises each motion to a
peak of 1 g (``pga``) and runs every (motion, μ, intensity) in one call of the compiled
engine, the intensity being the engine's factor on a(t) (no scaled copy of any motion).
Memory is O(records of a task × samples), never O(analyses × samples); tasks run one
after the other here (the engine uses every core) or on an executor (Dask). With a
checkpoint folder each finished task is saved as it completes and a rerun skips the
saved ones (:mod:`._checkpoint`).
"""

import concurrent.futures
import dataclasses
import math
import numbers
import os
import queue
import time

import numpy as np

from ..sliding import AdjustmentFactor, SlidingBlock, newmark_rd_sd
from ..core.contract import AbstractHybridModel
from ..core import progress_bar
from ..units import STANDARD_GRAVITY
from ..excitation import BaseMotion, Record, RecordSet, check_horizontal, check_pga, with_metadata
from ..motions import response_spectrum
from ..structures import Floor
from ._checkpoint import Checkpoint, motion_name as _name
from ._hooks import study_batch, study_parameter

#: analyses per task aimed at (Dask: each task costs 0.2-1 ms of overhead; aim at 10³-10⁴)
TASK_ANALYSES = 2000
#: bytes per row of the result table, with room for building it (measured ~150)
ROW_BYTES = 400
#: longest wait [s] for a finished Dask task before the workers are counted again
WORKER_POLL = 1.0


class NoWorkerError(RuntimeError):
    """No Dask worker was alive for ``no_worker_timeout`` [s] while tasks of a study were unfinished."""


@dataclasses.dataclass(frozen=True)
class _Grid:
    """What every task shares: the grid and the settings (small, sent with each task)."""

    parameter: str  # the model's swept parameter: its keyword ("mu", "ky") ...
    column: str  # ... and its column in the table ("mu", "ky_g")
    values: np.ndarray  # its values (its column in the table)
    sweep: object  # what the model's study_batch takes: ``values``, or the model's own (the flexible mass's ky tables)
    factors: np.ndarray  # pga [g] ("pga") or factors on a(t) [-] ("scale")
    by: str  # "pga" or "scale"
    where: tuple
    direction: str | None
    polarities: tuple  # the 1-D block's: ("normal", "inverse"), ("normal",); other models: ()
    refine: int
    sd_period: float
    damping: float
    t_end: float | None
    g: float
    block: object  # the model at one value: its study_batch(values).study_columns(...) runs a task's analyses
    rtol: float | None

    @property
    def rows_per_record(self) -> int:
        """Rows of the table per record: locations x polarities x swept values x intensities."""
        return len(self.where) * max(1, len(self.polarities)) * self.values.size * self.factors.size


def study(records, mu=None, pga=None, scale=None, where=("ground",), direction=None, *, ky=None,
          executor=None, no_worker_timeout=60.0, checkpoint=None, progress=None, refine=4, sd_period=10.0,
          damping=0.05, t_end=None, g=STANDARD_GRAVITY, block=None, rtol=None, check_peak=True):
    """Slide a block under every record, μ (or ky), intensity and location: one tidy table.

    Args:
        records: ground accelerograms (:class:`bd.Record` [m/s²], distinct names), or a
            :class:`bd.RecordSet`: its :attr:`~bd.RecordSet.metadata` columns (magnitude,
            epicentral_distance_km, vs30_m_s, ...) follow ``record`` in the table, to group by.
        mu: friction coefficients μ > 0 [-], the swept parameter of a block (the 1-D
            block, ``bd.PlanarBlock``).
        ky: instead of ``mu``, yield accelerations ky > 0 [g] (column ky_g): of the 1-D
            block without bias (Newmark's rigid block: μ = ky), or of a model that
            declares ky (``bd.FlexibleSlidingMass``; also a ``bd.KyTable`` of
            ky against the sliding displacement, or a sequence of them: column ky_g is
            then each table's ky at zero displacement). The model's
            ``study_parameter`` says which of the two it takes; the other is refused.
        pga: target peak accelerations A > 0 [g]: the motion at each location (ground
            or floor) is scaled so that its peak |a| is A g (the SMiRT paper on Newmark's formula). A value above 2 g
            is refused (likely m/s²: 2.94 is 0.3 g in m/s²) unless ``check_peak=False``.
        scale: instead of ``pga``, factors > 0 [-] on the motion at each location.
        where: locations: "ground" and/or floors (``bd.ShearFrame(...).floor(i)``).
        direction: of the 1-D block: None (default) runs Newmark's one-way block in both
            polarities, as :func:`bd.newmark` does (column polarity: "normal", the record
            as given, and "inverse", the record times -1; the block slides downslope,
            u < 0, column D_m = -u >= 0); "negative" runs the record as given only;
            "positive" or "both" (two-way) too, with the signed u (column u_end_m).
        executor: None (run here, on every core), a ``dask.distributed.Client`` or a
            ``concurrent.futures.Executor``: tasks of whole records are submitted to it
            (a ProcessPoolExecutor with ``mp_context=multiprocessing.get_context("spawn")``:
            forking a process that ran the engine's OpenMP threads aborts it).
        no_worker_timeout: with a Dask client, the longest time [s] with no worker alive
            (all lost, or the cluster scaled to 0) while tasks are unfinished; then
            :class:`NoWorkerError` (how many tasks finished). None: wait for workers forever.
            Not used by a ``concurrent.futures`` executor (a broken process pool raises
            ``BrokenProcessPool`` by itself) nor by the local run.
        checkpoint: a folder (new or empty, or the checkpoint of this same study): each
            finished task is saved there as it completes (a CSV table, atomically, here
            in the calling process also when the tasks run on an executor), and a rerun
            with the same arguments runs only the tasks not saved yet; its table is
            bit-identical to an uninterrupted run's. The folder's ``manifest.json``
            holds the grid, the settings and the records' names and SHA-256 of their
            samples: another study is refused (ValueError naming the folder and what
            differs). None: nothing is saved.
        progress: a tqdm bar over the tasks; None: only when stderr is a terminal.
        refine: floor motions sampled at dt/refine [s] (:meth:`bd.ShearFrame.floor_motions`).
        sd_period, damping: period [s] and damping ratio [-] of the oscillator whose
            displacement spectrum gives Sd (see ``sd_m``).
        t_end: final time [s]; None: until the block rests after each motion.
        g: the value of one g [m/s²] (a ``block`` given brings its own where it has a g).
        block: the model to slide, any μ or ky (the study sets it): every model. One that
            declares ``study_parameter`` ((keyword, table column, unit), e.g. ("mu", "mu",
            "-")) sweeps that; ``study_batch(values)``, the model at every value, whose
            ``study_columns(motions, t_end, scale, rtol)`` gives its table columns (one
            row per motion x value x factor), runs them (both optional: see
            :class:`bd.core.contract.StudyModel`; by default the keyword given is the
            model's parameter of that name, each value a model of its own through its
            ``replace``, each motion x factor run by ``bd.simulate`` on the model's
            default backend, with an ensemble's columns: ``u_end_m``,
            ``max_abs_displacement_m``, n_events, t_end_s for a model whose state u is in
            m). E.g. ``bd.PlanarBlock(mu=0.1, bias=(-0.02,
            0))`` on three-component records (``bd.BaseMotion``, named by their
            components; ``pga`` scales the largest horizontal peak; ground only), or
            ``bd.FlexibleSlidingMass(bd.ShearColumn(height, vs), ky=0.1)`` with ``ky=``
            (both polarities, linear-elastic: the equivalent-linear iteration is not run
            in studies; ``t_end`` None: each record's last sample). None: the 1-D
            ``bd.SlidingBlock(direction=direction, g=g)``.
        rtol: relative tolerance [-] of a model that integrates (None: the model's
            study default, 1e-10 for the block on a plane); the engines of the 1-D block
            and of the flexible mass are exact.
        check_peak: False accepts a ``pga`` above 2 g.

    Returns:
        A DataFrame, one row per record × location × polarity × μ × intensity (in that
        order): record; location ("ground" or "T1=0.3s n=5 zeta=0.05 floor 1"); floor (0:
        ground); frame_period_s (T_1 of the frame [s], NaN on the ground); polarity (the
        1-D block: "normal" or "inverse", see ``direction``); mu [-] (ky_g [g]); pga_g (peak
        |a| of the motion used [g]); scale (its factor on the location's motion [-]);
        pga_m_s2 [m/s²]; pgv_m_s (peak |v| of the motion used, exact for linear pieces
        [m/s]); sd_m (Sd [m]: the paper's "absolute displacement spectrum at the low
        frequency end", which it identifies with the largest base displacement; the
        displacement u + x_g of a long-period oscillator tends to 0, its displacement u
        relative to the base to max |x_g|, so Sd = max |u| at ``sd_period``, exact);
        D_m (the downslope displacement at the end, -u >= 0 [m], one-way downslope
        studies) or u_end_m (the signed u at the end [m], directions "positive" and
        "both"); max_abs_displacement_m (R_c, max |u| [m]);
        n_events (mode changes); n_slips (slip episodes = slip onsets, one-way
        studies only: there stick and slip alternate, so n_slips = ⌈n_events / 2⌉);
        t_end_s (final time [s]). A ``block``'s own columns replace D_m ...
        t_end_s (the block on a plane: displacement_x_m, displacement_y_m, displacement_m
        = |u|, max_abs_displacement_m, slide_distance_m, n_events, n_flights, t_end_s;
        the flexible mass: ``bd.flexible``'s height_m, vs_m_s, normal_m, inverse_m,
        kmax_g, kmax_sup_g, vs_final_m_s, damping_final, episodes_normal,
        episodes_inverse), and its swept column (ky_g [g]) replaces mu.

    Every check runs before any work (:class:`ValueError`): no records, a record that
    is not a finite :class:`bd.Record`, μ (ky) or an intensity <= 0, ``mu`` given to a
    model that sweeps ky or ``ky`` to one that sweeps μ, ``no_worker_timeout`` not
    a positive finite number [s] or None, a result table larger than the free memory,
    a checkpoint of another study. A task that raises on an executor lets the others
    finish (and be saved) before its error is raised. The flexible mass refuses a motion
    that is not a :class:`bd.Record` or ends before ``t_end``, also before any work.
    Rows equal ``bd.simulate(bd.SlidingBlock(mu=mu, direction="negative"),
    motion.scaled(scale))`` of the location's motion to rounding (the inverse polarity:
    ``motion.scaled(-scale)``).
    """
    metadata = records.metadata if isinstance(records, RecordSet) else None
    records, grid = _checked(records, dict(mu=mu, ky=ky), pga, scale, where, direction, refine, sd_period, damping,
                             t_end, g, block, rtol, check_peak)
    no_worker_timeout = _timeout(no_worker_timeout)
    tasks = _tasks(records, grid.rows_per_record)
    store = None if checkpoint is None else Checkpoint.open(checkpoint, records, grid, tasks)
    parts = {} if store is None else store.finished()
    bar = progress_bar(len(tasks), "study", "task", progress)
    bar.update(len(parts))

    def finish(index, part):
        if store is not None:
            store.save(index, part)
        parts[index] = part
        bar.update()

    todo = {i: chunk for i, chunk in enumerate(tasks) if i not in parts}
    try:
        if executor is None:
            for i, chunk in todo.items():
                finish(i, run_task(chunk, grid))
        else:
            _on_executor(executor, todo, grid, finish, no_worker_timeout)
    finally:
        bar.close()
    return with_metadata(_table([parts[i] for i in range(len(tasks))], grid), metadata)


def summary(table, adjustment: AdjustmentFactor = AdjustmentFactor()):
    """The paper's summaries of a study normalised by ``pga``: means over the records.

    Args:
        table: the result of :func:`study` (or :func:`load_study`).
        adjustment: the factor of the SMiRT paper's eq. 4.

    Returns:
        One row per location × polarity × μ (or ky_g) × pga_g: location, floor,
        frame_period_s, polarity (where the study has it), mu (ky_g), pga_g, n_records,
        rc_m (mean R_c = mean max |u| [m]), sd_m (mean Sd [m]), rd_m (eq. 3 with the mean
        Sd [m]), adjustment (eq. 4 [-]) and rd_adjusted_m (its product with rd_m [m]).
    """
    swept = "ky_g" if "ky_g" in table and "mu" not in table else "mu"
    missing = [c for c in (swept, "max_abs_displacement_m", "sd_m") if c not in table]
    if missing:
        raise ValueError(f"summary takes a study of a block over mu or ky_g (the paper's Newmark summaries); "
                         f"the table has no {missing} columns (a flexible mass's study: group it yourself, or fit "
                         "bd.hazard.fit_fragility to it)")
    keys = ["location", "floor", "frame_period_s", *(["polarity"] if "polarity" in table else []), swept, "pga_g"]
    out = (table.groupby(keys, sort=False, dropna=False)
           .agg(n_records=("record", "size"), rc_m=("max_abs_displacement_m", "mean"), sd_m=("sd_m", "mean"))
           .reset_index())
    out["rd_m"] = newmark_rd_sd(out["sd_m"].to_numpy(), out["pga_g"].to_numpy(), out[swept].to_numpy())
    out["adjustment"] = adjustment(out["pga_g"].to_numpy(), out[swept].to_numpy())
    out["rd_adjusted_m"] = out["adjustment"] * out["rd_m"]
    return out


def run_task(records, grid: _Grid) -> dict:
    """One task: every location, swept value (μ, ky) and intensity under ``records``; columns as arrays."""
    motions, places = [], []
    for record in records:
        floors = {}
        for place in grid.where:
            if place == "ground":
                motions.append(record)
            else:
                if place.frame not in floors:  # one frame response per record and frame
                    floors[place.frame] = place.frame.floor_motions(record, refine=grid.refine)
                motions.append(floors[place.frame][place.level - 1])
            places.append(place)
    leading = [_leading(m) for m in motions]  # the component whose peak is the motion's
    peak = np.array([m.peak_acceleration for m in leading])
    polarities = grid.polarities or ("normal",)
    sign = {"normal": 1.0, "inverse": -1.0}  # the inverse polarity: the motion times -1
    unit = grid.g / peak if grid.by == "pga" else np.ones(len(motions))
    engine_motions = [m if sign[p] * k == 1.0 else _normalised(m, sign[p] * k)
                      for m, k in zip(motions, unit) for p in polarities]
    batch = study_batch(grid.block, grid.parameter, grid.sweep)
    columns = batch.study_columns(engine_motions, grid.t_end, grid.factors, grid.rtol)
    sd = response_spectrum(leading, grid.sd_period, grid.damping).sd
    pgv = np.array([_peak_velocity(m) for m in leading])
    n_p, n_v, n_f = len(polarities), grid.values.size, grid.factors.size
    each = lambda x: np.repeat(np.asarray(x), n_p * n_v * n_f)  # per motion -> per row
    factors = np.tile(grid.factors, len(motions) * n_p * n_v)
    scale = factors * np.repeat(grid.g / peak, n_p * n_v * n_f) if grid.by == "pga" else factors
    polarity = dict(polarity=np.tile(np.repeat(polarities, n_v * n_f), len(motions))) if grid.polarities else {}
    return dict(record=each([_name(m) for m in records for _ in grid.where]),
                place=each([grid.where.index(p) for p in places]), **polarity,
                **{grid.column: np.tile(np.repeat(grid.values, n_f), len(motions) * n_p)},
                scale=scale, pga_m_s2=scale * each(peak), pgv_m_s=scale * each(pgv), sd_m=scale * each(sd), **columns)


def _leading(motion) -> Record:
    """The record whose peak is the motion's: itself, or a BaseMotion's horizontal
    component of the larger peak |a|."""
    if isinstance(motion, BaseMotion):
        return motion.x if motion.y is None or motion.x.peak_acceleration >= motion.y.peak_acceleration else motion.y
    return motion


def _normalised(motion, factor):
    """``motion`` times ``factor`` [-] (a Record with its samples multiplied, unchecked)."""
    if isinstance(motion, BaseMotion):
        return motion.scaled(factor)
    return Record(motion.acceleration_samples * factor, motion.dt, motion.name, units="m/s2", check_peak=False)


def _peak_velocity(record: Record) -> float:
    """max |v(t)| [m/s] of a record (linear between samples, starting at rest): at the
    samples and where a(t) crosses zero inside a piece."""
    a, dt = record.acceleration_samples, record.dt
    v = np.concatenate([[0.0], np.cumsum(0.5 * dt * (a[:-1] + a[1:]))])
    cross = a[:-1] * a[1:] < 0
    slope = np.diff(a)[cross] / dt
    inside = v[:-1][cross] - a[:-1][cross] ** 2 / (2 * slope)
    return float(max(np.max(np.abs(v)), np.max(np.abs(inside), initial=0.0)))


def _checked(records, swept, pga, scale, where, direction, refine, sd_period, damping, t_end, g, block, rtol,
             check_peak=True):
    if isinstance(records, (Record, BaseMotion)):
        records = [records]
    records = list(records)
    if not records:
        raise ValueError("records is empty: give at least one bd.Record")
    for i, record in enumerate(records):
        parts = record.components if isinstance(record, BaseMotion) else (record,)
        if not all(isinstance(c, Record) for c in parts if c is not None):
            raise TypeError(f"records[{i}] must be a bd.Record or a bd.BaseMotion of Records, got {record!r:.80}")
        for horizontal in parts[:2]:
            if horizontal is not None:
                check_horizontal(horizontal)
        if not all(np.all(np.isfinite(c.acceleration_samples)) for c in parts if c is not None):
            raise ValueError(f"records[{i}] ({_name(record)!r}) has samples that are not finite (NaN or inf)")
    names = [_name(r) for r in records]
    if len(set(names)) < len(names):
        raise ValueError(f"record names must be distinct (they label the rows); repeated: "
                         f"{sorted({n for n in names if names.count(n) > 1})}")
    if (pga is None) == (scale is None):
        raise ValueError("give pga (target peaks [g]) or scale (factors [-]), one of the two")
    by = "pga" if pga is not None else "scale"
    factors = _values(by, pga if pga is not None else scale, "g" if by == "pga" else "-")
    if by == "pga":
        check_pga(factors, "pga", check_peak)  # above 2 g: likely m/s²
    where = tuple([where] if isinstance(where, (str, Floor)) else where)
    if not where:
        raise ValueError('where is empty: give "ground" and/or floors (frame.floor(i))')
    for place in where:
        if not (place == "ground" or isinstance(place, Floor)):
            raise ValueError(f'where must hold "ground" or bd.structures.Floor objects, got {place!r}')
    if len(set(where)) < len(where):
        raise ValueError(f"where repeats a location: {where!r}")
    if block is None:
        block = SlidingBlock(mu=1.0, direction=direction or "negative", g=g)  # checks direction and g
        polarities = ("normal", "inverse") if direction is None else block.study_polarities
    else:
        polarities = getattr(block, "study_polarities", ())  # none declared: the motions as given
    parameter, column, values, sweep = _swept(block, swept)
    batch = study_batch(block, parameter, sweep)  # checks the values against the model's other parameters
    if any(isinstance(r, BaseMotion) for r in records) and where != ("ground",):
        raise ValueError("three-component motions (bd.BaseMotion) are studied on the ground only")
    _values("sd_period", sd_period, "s")
    if not (np.isfinite(damping) and 0 <= damping < 1):
        raise ValueError(f"damping must lie in [0, 1) [-], got {damping!r}")
    if isinstance(refine, bool) or not isinstance(refine, (int, np.integer)) or refine < 1:
        raise ValueError(f"refine must be an integer >= 1 (floor samples per record step), got {refine!r}")
    if t_end is not None:
        _values("t_end", t_end, "s")
    batch.check_motions(records, t_end)  # a model that takes only some motions (the flexible mass) refuses them
    if by == "pga" and any(_leading(r).peak_acceleration == 0 for r in records):
        zero = next(_name(r) for r in records if _leading(r).peak_acceleration == 0)
        raise ValueError(f"pga cannot normalise a record of zeros: {zero!r}")
    rows = len(records) * len(where) * max(1, len(polarities)) * values.size * factors.size
    free = os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    if rows * ROW_BYTES > free:
        raise ValueError(f"the result table would have {rows:,} rows (~{rows * ROW_BYTES / 2**30:.1f} GiB), more "
                         f"than the free memory ({free / 2**30:.1f} GiB): split the study or shrink the grid")
    grid = _Grid(parameter=parameter, column=column, values=values, sweep=sweep, factors=factors, by=by, where=where,
                 direction=direction, polarities=polarities, refine=refine, sd_period=float(sd_period),
                 damping=float(damping), t_end=t_end, g=float(getattr(block, "g", g)), block=block, rtol=rtol)
    return records, grid


def _swept(block, swept):
    """(keyword, table column, values, sweep) of the parameter ``block`` sweeps, from
    ``swept`` (keyword -> the values given to :func:`study`, None where not given),
    checked: the model is a model, and only its keyword is given. ``values`` are numbers
    for the table; ``sweep`` is what the batch takes: the same numbers, or what the model's
    ``study_sweep(given)`` makes of what it takes besides numbers (the flexible mass's ky
    tables; None: numbers)."""
    if not isinstance(block, AbstractHybridModel):
        raise TypeError(f"block must be a model (a bd.core.contract.AbstractHybridModel), got {type(block).__name__}")
    parameter, column, unit = study_parameter(block, swept)
    model = type(block).__name__
    for other, given in swept.items():
        if other != parameter and given is not None:
            raise ValueError(f"{other}={given!r}: {model} sweeps {parameter} [{unit}], not {other}; give "
                             f"{parameter}= instead")
    if swept.get(parameter) is None:
        raise ValueError(f"give {parameter}= ({model}'s swept parameter [{unit}], a number or a 1-D sequence)")
    own = getattr(block, "study_sweep", lambda given: None)(swept[parameter])
    if own is not None:
        return parameter, column, *own
    values = _values(parameter, swept[parameter], unit)
    return parameter, column, values, values


def _values(name, values, unit):
    x = np.atleast_1d(np.asarray(values, dtype=float))
    if x.ndim != 1 or x.size == 0:
        raise ValueError(f"{name} must be a number or a non-empty 1-D sequence [{unit}], got {values!r}")
    bad = ~(np.isfinite(x) & (x > 0))
    if np.any(bad):
        raise ValueError(f"{name} must be positive and finite [{unit}], got {float(x[bad][0])!r}")
    return x


def _timeout(value):
    """``no_worker_timeout`` checked: a positive finite float [s], or None (wait forever)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (math.isfinite(value) and value > 0):
        raise ValueError(f"no_worker_timeout must be a positive finite number of seconds [s] or None "
                         f"(wait forever), got {value!r}")
    return float(value)


def _tasks(records, analyses_per_record):
    """Consecutive records in groups of about :data:`TASK_ANALYSES` analyses (at least one record)."""
    size = max(1, TASK_ANALYSES // analyses_per_record)
    return [records[i:i + size] for i in range(0, len(records), size)]


def _on_executor(executor, tasks, grid, finish, no_worker_timeout):
    """Submit the tasks (index -> records) and call ``finish(index, columns)`` for each as
    it succeeds (Dask: see :func:`_wait_on_dask`); then raise the error of the first
    failed task, in task order, if any."""
    futures = {executor.submit(run_task, chunk, grid): i for i, chunk in tasks.items()}

    def done(future, timeout=None):  # TimeoutError: no result within timeout [s]
        if future.exception(timeout) is None:
            finish(futures[future], future.result(timeout))

    if hasattr(executor, "gather"):  # dask.distributed.Client
        _wait_on_dask(executor, list(futures), done, no_worker_timeout)
    else:
        for future in concurrent.futures.as_completed(futures):
            done(future)
    for future in futures:
        future.result()


def _wait_on_dask(client, futures, done, no_worker_timeout):
    """Wait until every future is done, calling ``done(future, timeout)`` on each as it
    finishes (it fetches the result, within ``timeout`` [s] or TimeoutError).

    Blocks on a queue fed by the futures' callbacks for at most :data:`WORKER_POLL` [s]
    (a quarter of ``no_worker_timeout`` [s] if shorter) at a time, and as long on the
    result of a finished task (whose worker may have died since: then the scheduler
    computes it again and the future is waited for again); only when no result came in
    that time is the scheduler asked for its workers. None alive for
    ``no_worker_timeout`` [s]: the unfinished futures are cancelled and
    :class:`NoWorkerError` is raised.
    """
    finished = queue.SimpleQueue()
    for future in futures:
        future.add_done_callback(finished.put)
    poll = None if no_worker_timeout is None else min(WORKER_POLL, no_worker_timeout / 4)
    pending, lost_since = set(futures), None
    while pending:
        try:
            future = finished.get(timeout=poll)
            done(future, poll)
            pending.discard(future)
            lost_since = None
            continue
        except queue.Empty:
            pass
        except TimeoutError:  # its result went with its worker
            future.add_done_callback(finished.put)
        lost_since = None if client.nthreads() else (lost_since or time.monotonic())
        if lost_since is not None and time.monotonic() - lost_since >= no_worker_timeout:
            client.cancel(list(pending))
            raise _no_worker_error(len(futures) - len(pending), len(futures), time.monotonic() - lost_since,
                                   no_worker_timeout)


def _no_worker_error(n_done, n_tasks, lost_s, no_worker_timeout):
    """The :class:`NoWorkerError` of a study with ``n_done`` of ``n_tasks`` tasks finished."""
    return NoWorkerError(
        f"no Dask worker alive for {lost_s:.1f} s (no_worker_timeout={no_worker_timeout:g} s): "
        f"{n_done} of {n_tasks} tasks finished, {n_tasks - n_done} unfinished (cancelled); start or scale up "
        f"the workers, or raise no_worker_timeout [s] (None: wait forever; CLI: --no-worker-timeout SECONDS|none)")


def _table(parts, grid):
    import pandas as pd

    cols = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    labels = [_label(p) for p in grid.where]
    place = cols.pop("place")
    df = pd.DataFrame({
        "record": cols.pop("record"),
        "location": np.array(labels, dtype=object)[place],
        "floor": np.array([0 if p == "ground" else p.level for p in grid.where])[place],
        "frame_period_s": np.array([np.nan if p == "ground" else p.frame.period for p in grid.where])[place],
        **({"polarity": cols.pop("polarity")} if "polarity" in cols else {}),
        grid.column: cols.pop(grid.column),
        "pga_g": cols["pga_m_s2"] / grid.g,
    })
    if grid.by == "pga":  # exactly the grid's values, not their round trip through the peaks
        df["pga_g"] = np.tile(grid.factors, len(df) // grid.factors.size)
    for k, v in cols.items():
        df[k] = v
    return df


def _label(place) -> str:
    if place == "ground":
        return "ground"
    f = place.frame
    return f"T1={f.period:g}s n={f.storeys} zeta={f.damping:g} floor {place.level}"
