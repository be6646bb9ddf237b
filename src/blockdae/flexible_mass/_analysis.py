"""``bd.flexible``: the flexible sliding-mass analyses of SLAMMER and pySLAMMER
(decoupled and coupled, linear-elastic or equivalent-linear, both polarities), solved
exactly in continuous time (the formulation note's section 8).

As SLAMMER, the record gets a virtual zero sample at t = -dt (the system rests there
and a(t) rises linearly to a_0 at t = 0); the analysis ends at the record's last
sample. Each analysis (record, parameter set) runs the no-sliding response (kmax and,
for the equivalent-linear iteration, sup |u|) and a sliding run per polarity; the
runs of a batch go to the compiled engine in one call, parallel over cores.
"""

import dataclasses
import functools
import math
import numbers
import operator

import numpy as np

from ..units import STANDARD_GRAVITY
from ..solvers import linear_pieces
from ..excitation import (Record, RecordSet, check_column, check_finite_result, check_horizontal, pga_factor,
                          pga_keyword, warn_not_sliding, with_metadata)
from . import _engine, _fused, _table_kernel
from ._column import equivalent_linear as iterate_equivalent_linear, equivalent_linear_steps, prechecked_column
from ._damped_slip import COMPILED_RESPONSE_LIMIT, flat_table_model, slip_underdamped
from ._exact import check, engine_settings
from ._ky_table import KyTable
from ._model import METHODS, FlexibleSlidingMass
from ._slammer import slammer_flexible
from ._table_engine import response_compiled, slide_compiled, system_arrays
from ..core import compact_repr, labelled_motions, notice_numba, progress_bar, show_progress

POLARITIES = ("both", "normal", "inverse")
#: the result table's columns
COLUMNS = ("record", "ky_g", "height_m", "vs_m_s", "normal_m", "inverse_m", "kmax_g", "kmax_sup_g", "vs_final_m_s",
           "damping_final", "episodes_normal", "episodes_inverse")
#: pieces x runs above which a batch runs in parallel (~10 ms on one core); below, waking
#: the worker threads may cost more than they save
PARALLEL_WORK = 5e5
_FIELD = {name: i for i, name in enumerate(_engine.OUTCOME_FIELDS)}
_STATUS, _S, _EPISODES, _HEA_SAMPLES, _HEA_SUP = (_FIELD[name] for name in ("status", "s", "n_episodes", "hea_samples",
                                                                             "hea_sup"))
_FINISHED, _RESPONSE = _engine.FINISHED, _fused.RESPONSE


@dataclasses.dataclass(frozen=True)
class Analysis:
    """One flexible sliding-mass analysis of a batch.

    Attributes:
        record: the ground motion along the slope [m/s²], scaled (``scale`` applied).
        name: its label in the table.
        model: the sliding mass with its initial (linear-elastic) column.
        polarities: "normal" and/or "inverse".
        t_end: the end on the record's axis [s] (its last sample by default).
        reference_strain: gamma_ref of the equivalent-linear iteration (a fraction), or None.
    """

    record: Record
    name: str
    model: FlexibleSlidingMass
    polarities: tuple
    t_end: float
    reference_strain: float | None


@dataclasses.dataclass(frozen=True, eq=False, init=False)
class FlexibleResult:
    """Results of :func:`flexible`: one row per (motion, parameter set).

    Attributes:
        rows: a list of dicts with the keys :data:`COLUMNS`: record, ky_g [g] (of a
            :class:`KyTable`: ky at zero displacement), height_m
            [m], vs_m_s [m/s] (as given), normal_m and inverse_m (downslope displacement
            at the end [m], nan where that polarity was not run), kmax_g (max |HEA| / g at
            the samples of the no-sliding response, as SLAMMER reports it) and kmax_sup_g
            (its supremum over time), vs_final_m_s [m/s] and damping_final [-] (after the
            equivalent-linear iteration; the total damping), episodes_normal and
            episodes_inverse (sliding episodes).
        method, integration: as given.
    """

    def __repr__(self):
        largest = np.nanmax([[row["normal_m"], row["inverse_m"]] for row in self.rows], initial=0.0)
        return compact_repr(self, f"{len(self.rows)} rows, largest D {largest:.4g} m; .to_dataframe()")

    rows: list
    method: str
    integration: str
    pga_g: tuple = ()
    metadata: object = None

    def __init__(self, rows, method, integration, pga_g=(), metadata=None):
        # the fields at once: a frozen dataclass's own __init__ sets each through object.__setattr__
        self.__dict__.update(rows=rows, method=method, integration=integration, pga_g=pga_g, metadata=metadata)

    def to_dataframe(self):
        """The rows as a pandas DataFrame, units in the column names, in the columns of
        :func:`bd.newmark`'s tables: record, a record set's metadata columns, pga_g (the
        analysed motion's peak [g]), ky_g, height_m, vs_m_s, normal_m, inverse_m, mean_m and
        max_m (of the polarities run [m]), then kmax_g, ..., episodes_inverse."""
        import pandas as pd

        table = pd.DataFrame(self.rows, columns=list(COLUMNS))
        for name in ("episodes_normal", "episodes_inverse"):
            table[name] = table[name].astype("Int64")
        table.insert(1, "pga_g", np.asarray(self.pga_g, dtype=float))
        normal, inverse = table["normal_m"].to_numpy(), table["inverse_m"].to_numpy()
        ran = np.where(np.isnan(normal), inverse, normal), np.where(np.isnan(inverse), normal, inverse)
        at = table.columns.get_loc("inverse_m") + 1
        table.insert(at, "mean_m", 0.5 * (ran[0] + ran[1]))
        table.insert(at + 1, "max_m", np.maximum(*ran))
        return with_metadata(table, self.metadata)

    def __getitem__(self, column):
        """One column over the rows as an array (e.g. ``result["normal_m"]``)."""
        if column not in COLUMNS:
            raise KeyError(f"{column!r} is no column; columns: {COLUMNS}")
        return np.array([row[column] for row in self.rows])


def flexible(motion, ky, height, vs, vr=None, damping=0.05, method="coupled", equivalent_linear=False,
             reference_strain=None, pga=None, polarity="both", integration="exact", g=STANDARD_GRAVITY,
             t_end=None, *, check_peak=True, target_pga=None, progress=None) -> FlexibleResult:
    """Flexible sliding-mass analyses (Bray & Rathje 1998 decoupled; Rathje & Bray 1999
    coupled), downslope displacement positive, as SLAMMER runs them but exact in time.

    Args:
        motion: a :class:`Record` of the ground acceleration along the slope, or many (a
            batch): a sequence or dict (name -> record) of them, a :class:`RecordSet` (its
            metadata carried into the table), or a path to a record file or a folder of
            them (read by :func:`blockdae.read_record` with the units their files state).
        ky: yield acceleration [g], >= 0; or a :class:`KyTable` (ky [g] against the
            sliding displacement [m], linear between rows, constant beyond), also as
            pySLAMMER's pair ``(disp_values [m], ky_values [g])`` of two sequences. A ky
            in m/s² below the motion's peak cannot be told from one in g (0.49, 0.05 g in
            m/s², gives millimetres where 0.05 g gives decimetres): check that it is in g.
            A ky at or above kmax (no slide, D = 0) is warned about (a UnitsWarning), one
            also above 1 g refused (9.81 is 1 g in m/s²).
        height: height H of the sliding mass [m], > 0; outside 0.5 m to 500 m warned about.
        vs: its shear-wave velocity [m/s], > 0; outside 30 m/s to 5000 m/s warned about
            (0.3 is km/s), as is ``vr``.
        vr: shear-wave velocity below the slip surface [m/s]; None: vs.
        damping: the soil's damping ratio [-]; the impedance damping from vr/vs
            (min(0.55016 (vr/vs)^-0.9904, 0.20)) is added as SLAMMER does, the total must
            stay in (0, 1) (to leave it out, give damping minus it, or use
            :class:`FlexibleSlidingMass` with ``ShearColumn(..., impedance=False)``); 1 or
            more is refused as a percentage, above 0.3 warned about.
        method: "coupled" or "decoupled".
        equivalent_linear: run SLAMMER's equivalent-linear iteration on the exact
            no-sliding peak |u| (needs ``reference_strain``).
        reference_strain: gamma_ref, a fraction (SLAMMER's GUI takes percent).
        pga: target peak ground acceleration [g] (SLAMMER's target PGA): each motion is
            scaled so that its peak |a| is ``pga`` g; None: as given. "exact" integration
            scales by the motion's exact peak, "slammer" by its peak rounded to 0.001 g, as
            SLAMMER does. A value above 2 g is refused (likely m/s²: 2.94 is 0.3 g in m/s²)
            unless ``check_peak=False``.
        polarity: "both", "normal" (the record as given) or "inverse" (times -1).
        integration: "exact" (continuous time, events located) or "slammer" (SLAMMER
            1.1's fixed-step scheme at the record's dt, quirks included, to reproduce its
            results to the printed digits; ``kmax_sup_g`` is then nan).
        g: the value of one g [m/s²].
        t_end: end of each analysis on the record's axis [s]; None: its last sample (the
            only end "slammer" has).
        check_peak: False accepts a ``pga`` above 2 g.
        target_pga: the deprecated name of ``pga`` (a DeprecationWarning); not both.
        progress: over many motions, a tqdm bar on stderr (the motions then run a few at
            a time, each part in one compiled call); None: only when stderr is a terminal.

    ky, height, vs, vr and damping broadcast together to the parameter sets (use
    ``np.meshgrid`` for a grid); every motion runs every set.

    Returns:
        A :class:`FlexibleResult` (``.to_dataframe()``).
    """
    if target_pga is not None:
        pga = pga_keyword("bd.flexible", pga, target_pga)
    analyses, pga_g = _kept_plan(motion, ky, height, vs, vr, damping, method, equivalent_linear, reference_strain,
                                 pga, polarity, integration, g, t_end, check_peak)
    rows_of = INTEGRATIONS[integration][0]
    if analyses and analyses[0].model.table is not None:  # plan gives every model the table or none
        rows_of = table_rows
    rows = _rows_in_parts(rows_of, analyses, progress)
    _check_rows(rows, analyses)
    return FlexibleResult(rows, method, integration, pga_g,
                          motion.metadata if type(motion) is not Record and isinstance(motion, RecordSet) else None)


def _check_rows(rows, analyses):
    """The plausibility rules on the rows of :func:`flexible`: every result finite (else a
    ValueError naming it), and the ky rule (:func:`~blockdae.excitation.warn_not_sliding`)
    against kmax, the peak of the sliding mass's average acceleration that drives its slide
    (over time; at the samples for integration "slammer")."""
    check_finite_rows(rows, analyses, "bd.flexible")
    still = [row for row in rows if row["ky_g"] >= driving_peak(row)]  # the only cases the rule speaks of
    if not still:
        return
    several = len({(row["height_m"], row["vs_m_s"]) for row in rows}) > 1
    cases = [(f"{row['record']}" + (f" (H {row['height_m']:g} m, vs {row['vs_m_s']:g} m/s)" if several else ""),
              driving_peak(row), row["ky_g"]) for row in still]
    warn_not_sliding(cases, len(rows), peak_name="kmax", body="mass", kind="analyses", peak_words="kmax")


def check_finite_rows(rows, analyses, caller):
    """ValueError naming the column, the record, the model and ``caller`` (the function run)
    where a row's kmax or displacement is not finite."""
    for row, analysis in zip(rows, analyses):
        names = _FINITE_COLUMNS.get(analysis.polarities) or ("kmax_g", *(_RUN_OF[polarity][1]
                                                                         for polarity in analysis.polarities))
        total = 0.0
        for name in names:
            total += row[name]
        if math.isfinite(total):  # each is (a sum overflows only past 1e308: the check below then decides)
            continue
        check_finite_result([row[name] for name in names],
                            lambda index: f"{caller}: {names[index[0]]} of {row['record']!r} ({analysis.model})")


def driving_peak(row) -> float:
    """kmax [g] of a row: the peak of the mass's average acceleration that drives its slide,
    over time (kmax_sup_g) where it was found, else at the samples (kmax_g)."""
    return row["kmax_g"] if math.isnan(row["kmax_sup_g"]) else row["kmax_sup_g"]


def _rows_in_parts(rows_of, analyses, progress) -> list[dict]:
    """``rows_of(analyses)``: in one call, or, where a progress bar over the motions is
    shown, in :data:`PROGRESS_PARTS` parts of a few motions each, in order (the rows of an
    analysis do not depend on the others run with it)."""
    if len(analyses) < 2:
        return rows_of(analyses)
    starts = [q for q, a in enumerate(analyses) if q == 0 or a.record is not analyses[q - 1].record]
    if len(starts) < 2 or not show_progress(progress):
        return rows_of(analyses)
    size = -(-len(starts) // PROGRESS_PARTS)  # motions per part
    bounds = starts[::size] + [len(analyses)]
    rows = []
    with progress_bar(len(starts), "flexible", "record", progress) as bar:
        for k, (first, end) in enumerate(zip(bounds, bounds[1:])):
            rows += rows_of(analyses[first:end])
            bar.update(min(size, len(starts) - k * size))
    return rows


#: the parts :func:`flexible` runs many motions in where it shows its progress
PROGRESS_PARTS = 20


def plan(motion, ky, height, vs, vr, damping, method, equivalent_linear, reference_strain, pga, polarity,
         integration, g, t_end, check_peak=True) -> list[Analysis]:
    """The analyses of a :func:`flexible` call, every input checked before any work."""
    return list(_kept_plan(motion, ky, height, vs, vr, damping, method, equivalent_linear, reference_strain, pga,
                           polarity, integration, g, t_end, check_peak)[0])


def _kept_plan(*args):
    """(:func:`plan`'s analyses as a tuple, each one's motion's peak [g]). Those of one
    record and plain numbers are kept (a warm loop plans once: the record and the models
    are immutable); the column's rules, which warn, run on every call."""
    global _LAST_PLAN
    last_args, last = _LAST_PLAN
    if len(args) == len(last_args) and all(map(operator.is_, args, last_args)):  # the last call's very objects
        check_column(*args[2:6])  # height, vs, vr, damping
        return last
    types = tuple(map(type, args))
    if types[0] is not Record or args[9] is not None or not _PLAIN.issuperset(types[1:]):  # args[9]: pga
        return _with_peaks(_plan(*args))
    key = (args, types)  # True == 1 == 1.0 must not find each other's analyses
    found = _PLANS.get(key)
    if found is None:
        if len(_PLANS) >= 32:  # each holds its record
            _PLANS.clear()
        found = _PLANS[key] = _with_peaks(_plan(*args))
    else:
        check_column(*args[2:6])  # height, vs, vr, damping
    _LAST_PLAN = args, found
    return found


def _with_peaks(analyses):
    """(``analyses`` as a tuple, the peak of each one's motion [g])."""
    return tuple(analyses), tuple([a.record.peak_acceleration / a.model.g for a in analyses])


#: the types of the arguments :func:`plan` keeps the analyses of (immutable, hashable)
_PLAIN = frozenset((float, int, bool, str, type(None)))
#: :func:`_kept_plan`'s store: its arguments and their types -> what it returns
_PLANS = {}
#: the arguments of :func:`_kept_plan`'s last kept call and what it returned (a warm loop
#: passes the same objects: no key to hash)
_LAST_PLAN = ((), None)


def _plan(motion, ky, height, vs, vr, damping, method, equivalent_linear, reference_strain, pga, polarity,
          integration, g, t_end, check_peak):
    """:func:`plan`, each time."""
    if integration not in INTEGRATIONS:
        raise ValueError(f"integration={integration!r} is unknown; choose one of {tuple(INTEGRATIONS)}")
    if method not in METHODS:
        raise ValueError(f"method={method!r} is unknown; choose one of {METHODS}")
    if polarity not in POLARITIES:
        raise ValueError(f"polarity={polarity!r} is unknown; choose one of {POLARITIES}")
    if equivalent_linear and reference_strain is None:
        raise ValueError("equivalent_linear=True needs reference_strain (gamma_ref, a fraction, e.g. 0.0005)")
    if reference_strain is not None and not (isinstance(reference_strain, (int, float)) and
                                             not isinstance(reference_strain, bool) and reference_strain > 0):
        raise ValueError(f"reference_strain must be a fraction > 0, got {reference_strain!r}")
    table = as_ky_table(ky)
    if table is not None and not table.constant:
        if integration == "slammer":
            raise ValueError(f"ky={table}: integration='slammer' takes a constant ky (SLAMMER 1.1 has no ky "
                             "table); use integration='exact'")
        ky = 0.0  # a placeholder in the broadcast: every model gets the table
    elif table is not None:
        ky, table = table.ky_g[0], None
    names, records, _ = _motions(motion, g)
    for record in records:
        check_horizontal(record)
    if t_end is not None and not (isinstance(t_end, numbers.Real) and not isinstance(t_end, bool) and
                                  math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end={t_end!r} must be a positive finite time [s] (or None: each record's last sample)")
    check_column(height, vs, vr, damping)
    given = {"ky": ky, "height": height, "vs": vs, "vr": vr, "damping": damping}
    if vr is None:
        given["vr"] = np.nan  # not given: each column takes its vs
    models = [_model(float(k) if table is None else table, float(h), float(v), None if math.isnan(r) else float(r),
                     float(d), method, g)
              for k, h, v, r, d in _parameter_sets(given, checked=("vr",) if vr is None else ())]
    polarities = ("normal", "inverse") if polarity == "both" else (polarity,)
    analyses = []
    for name, record in zip(names, records):
        if pga is not None:
            rounding = INTEGRATIONS[integration][1]
            record = record.scaled(pga_factor(record.peak_acceleration, pga, g, rounding, "pga", check_peak))
        duration = record.duration
        end = duration if t_end is None else float(t_end)
        if integration == "slammer" and end != duration:
            raise ValueError(f"t_end={t_end!r}: integration='slammer' runs to the record's last sample "
                             f"({duration!r} s for {name!r}), as SLAMMER does; give t_end=None")
        if not 0 < end <= duration:
            raise ValueError(f"t_end={t_end!r} must lie in (0, {duration!r}] s (the record {name!r})")
        analyses += [Analysis(record, name, model, polarities, end, reference_strain if equivalent_linear else None)
                     for model in models]
    return analyses


def _model(ky, height, vs, vr, damping, method, g) -> FlexibleSlidingMass:
    """The sliding mass of one parameter set (validated); cached, as the models are
    immutable and a repeated call (a warm loop, a study) asks for the same ones."""
    try:
        return _cached_model(ky, height, vs, vr, damping, method, g, type(g))
    except TypeError:  # an unhashable g: validation names it
        return FlexibleSlidingMass(prechecked_column(height, vs, vr, damping), ky=ky, method=method, g=g)


@functools.lru_cache(maxsize=4096)
def _cached_model(ky, height, vs, vr, damping, method, g, g_type):
    """:func:`_model`, keyed also by the type of ``g`` (True == 1.0 must not find 1.0's)."""
    return FlexibleSlidingMass(prechecked_column(height, vs, vr, damping), ky=ky, method=method, g=g)


@functools.lru_cache(maxsize=4096)
def _settings(model):
    """:func:`engine_settings` of ``model`` (an immutable one from :func:`_model`)."""
    return engine_settings(model)


def _parameter_sets(given, checked=()):
    """(ky, height, vs, vr, damping) of each parameter set from ``given`` (name -> a
    number or a 1-D sequence), broadcast together; each checked (numbers, finite, not
    empty) but those named in ``checked``, ValueError naming it and its value."""
    values = tuple(given.values())
    if set(map(type, values)) <= {float, int}:  # one set: no arrays needed
        for name, value in given.items():
            if name not in checked and not math.isfinite(value):
                raise ValueError(f"{name}={value!r} must be a finite number [{PARAMETER_UNITS[name]}]")
        return [values]
    arrays = [_parameter_array(name, value, name in checked) for name, value in given.items()]
    try:
        sets = np.broadcast_arrays(*arrays)
    except ValueError:
        raise ValueError(f"ky, height, vs, vr and damping must broadcast together, got shapes "
                         f"{[np.shape(x) for x in arrays]}") from None
    return zip(*(np.atleast_1d(x) for x in sets))


#: the unit of each parameter of :func:`flexible`
PARAMETER_UNITS = {"ky": "g", "height": "m", "vs": "m/s", "vr": "m/s", "damping": "-"}


def _parameter_array(name, value, checked):
    """``value`` of the parameter ``name`` as a float array of at most one dimension,
    not empty, finite (unless ``checked``); else ValueError naming it and the value."""
    unit = PARAMETER_UNITS[name]
    try:
        if np.asarray(value).dtype.kind in "USb":  # text, bytes, booleans
            raise TypeError
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} must be a number or a 1-D sequence of numbers [{unit}]") from None
    if array.ndim > 1:
        raise ValueError(f"{name} must be a number or a 1-D sequence of numbers [{unit}], got shape {array.shape}")
    if array.size == 0:
        raise ValueError(f"{name}={value!r} is empty: give a number or at least one value [{unit}]")
    bad = np.flatnonzero(~np.isfinite(array.ravel()))
    if bad.size and not checked:
        where = "" if array.ndim == 0 else f"[{int(bad[0])}]"
        raise ValueError(f"{name}{where}={float(array.ravel()[bad[0]])!r} must be a finite number [{unit}]")
    return array


def as_ky_table(ky):
    """``ky`` as a :class:`KyTable` if it is one or pySLAMMER's pair of two sequences
    (displacements [m], ky [g]); None for a number or an array of them (a batch)."""
    if isinstance(ky, KyTable):
        return ky
    if isinstance(ky, tuple) and len(ky) == 2 and all(np.ndim(part) == 1 for part in ky):
        return KyTable(*ky)
    return None


def _motions(motion, g):
    """(names, records, a record set's metadata or None) of one record, a sequence or dict
    of them, a :class:`RecordSet` or a path to a record file or a folder (one g = ``g`` [m/s²])."""
    if type(motion) is Record:  # one record: labelled by its name, as labelled_motions does
        return (motion.name or "motion 0",), [motion], None
    names, records, metadata = labelled_motions(motion, g)
    for name, record in zip(names, records):
        if not isinstance(record, Record):
            raise TypeError(f"motion {name!r} must be a Record (samples at dt), got {type(record).__name__}")
    return names, records, metadata


def with_zero_sample(record) -> Record:
    """``record`` with SLAMMER's virtual zero sample at -dt: on an axis shifted by dt [s],
    at rest at 0 and rising linearly to the first sample at dt."""
    return Record(np.concatenate([[0.0], record.acceleration_samples]), record.dt, name=record.name, units="m/s2",
                  check_peak=False)


@functools.lru_cache(maxsize=64)
def _engine_input(record, t_end):
    """The pieces of ``record`` with its virtual zero sample, up to ``t_end`` [s] on the
    record's axis."""
    return linear_pieces(with_zero_sample(record), t_end + record.dt)[1]


@functools.lru_cache(maxsize=64)
def _step_slots(record, t_end):
    """:func:`._table_kernel.step_slots` of :func:`_engine_input`'s pieces."""
    t0, h, _, _ = _engine_input(record, t_end)
    return _table_kernel.step_slots(t0, h)


def analyse_exact(analysis: Analysis) -> dict:
    """One analysis (a row of the table), exact."""
    return exact_rows([analysis])[0]


def exact_rows(analyses: list[Analysis]) -> list[dict]:
    """The rows of ``analyses``, exact: equivalent-linear iterations one by one, then
    every analysis (its no-sliding response, once per record and column, and its runs)
    in one compiled call, parallel over cores for a large batch (:mod:`._fused`). A
    total damping too close to 1 for its closed forms runs on matrix exponentials
    (:func:`_near_critical_row`)."""
    prepared = _prepared(analyses)
    if prepared is None:
        near = {q for q, analysis in enumerate(analyses) if analysis.model.damping >= COMPILED_RESPONSE_LIMIT}
        others = [analysis for q, analysis in enumerate(analyses) if q not in near]
        rest = iter(exact_rows(others) if others else ())
        return [_near_critical_row(analysis) if q in near else next(rest) for q, analysis in enumerate(analyses)]
    arrays, offsets, tasks, work, response_of, templates, damped = prepared
    out = _run_kernel(arrays, offsets, tasks, work).tolist()
    rows = []
    for q, analysis in enumerate(analyses):
        response = out[response_of[q]][_RESPONSE]
        if response[_STATUS] != _FINISHED:
            check(response, f" ({analysis.name}, {analysis.model})")
        model = analysis.model
        row = templates[q].copy()
        row["kmax_g"], row["kmax_sup_g"] = response[_HEA_SAMPLES] / model.g, response[_HEA_SUP] / model.g
        for polarity in () if q in damped else analysis.polarities:
            run_row, displacement, episodes = _RUN_OF[polarity]
            run = out[q][run_row]
            if run[_STATUS] != _FINISHED:
                check(run, f" ({analysis.name}, {model})")
            row[displacement] = 0.0 + run[_S]
            row[episodes] = int(run[_EPISODES])
        rows.append(row)
    for q in damped:
        _slides_in_closed_form(analyses[q], rows[q])
    return rows


def _prepared(analyses):
    """What the compiled call of ``analyses`` takes, and how its outcomes map to rows:
    (the engine arrays and offsets of their excitations, the tasks (n, len(TASK_FIELDS)),
    their work (:func:`_kernel_input`), the analysis whose response each reads, each one's
    row before its outcome (:func:`_row`: vs [m/s] and total damping [-] after the
    equivalent-linear iteration), the analyses whose slides run in closed form after);
    None where one's total damping is too close to 1 for the compiled engine. Kept for a
    few analyses of one record without that iteration (a warm loop of :func:`plan`'s kept
    analyses prepares once; a study's batches are not held): it depends only on the
    analyses, which are immutable."""
    analyses = tuple(analyses)
    last = _LAST_PREPARED[0]
    if last[0] is analyses:
        return last[1]
    key = tuple(map(id, analyses))
    found = _PREPARED.get(key)
    if found is not None and (found[0] is analyses or found[0] == analyses):
        _LAST_PREPARED[0] = found  # the same analyses (their ids are not reused while they are kept)
        return found[1]
    if any(analysis.model.damping >= COMPILED_RESPONSE_LIMIT for analysis in analyses):
        return None
    inputs, index, input_of = [], {}, []
    for analysis in analyses:
        key_input = (id(analysis.record), analysis.t_end)
        if key_input not in index:
            index[key_input] = len(inputs)
            inputs.append(_engine_input(analysis.record, analysis.t_end))
        input_of.append(index[key_input])
    finals = _final_columns(analyses, inputs, input_of)
    tasks, response_of, templates, first_with, damped = [], [], [], {}, set()
    for q, analysis in enumerate(analyses):
        r = input_of[q]
        (omega, xi, kyg, coupled), vs_final = finals[q]
        response_of.append(first_with.setdefault((r, omega, xi), q))
        slides = slip_underdamped(xi, coupled)  # else its slides run on ._damped_slip, after
        if not slides:
            damped.add(q)
        polarities = analysis.polarities
        tasks.append((r, omega, xi, kyg, coupled and slides, slides and "normal" in polarities,
                      slides and "inverse" in polarities, False, response_of[q] == q))
        templates.append(_row(analysis, np.nan, np.nan, vs_final, xi))
    prepared = (*_kernel_input(inputs, tasks), response_of, templates, damped)
    if len(inputs) == 1 and len(analyses) <= _KEPT_ANALYSES and all(a.reference_strain is None for a in analyses):
        if len(_PREPARED) >= 32:
            _PREPARED.clear()
        _PREPARED[key] = _LAST_PREPARED[0] = (analyses, prepared)  # holds the analyses: their ids stay theirs
    return prepared


#: :func:`_prepared`'s store: the analyses' ids -> (the analyses, what they prepared)
_PREPARED = {}
#: the most analyses :func:`_prepared` keeps what they prepared of
_KEPT_ANALYSES = 64
#: the last analyses :func:`_prepared` found or kept and what they prepared
_LAST_PREPARED = [((), None)]


def _row(analysis, kmax_g, kmax_sup_g, vs_final, damping_final) -> dict:
    """The row of ``analysis`` with its no-sliding columns: kmax at the samples and over
    time [g], vs [m/s] and total damping [-] after the equivalent-linear iteration; its
    polarities' columns nan (None) until they are run."""
    model = analysis.model
    return {"record": analysis.name, "ky_g": model.ky, "height_m": model.column.height, "vs_m_s": model.column.vs,
            "normal_m": np.nan, "inverse_m": np.nan, "kmax_g": kmax_g, "kmax_sup_g": kmax_sup_g,
            "vs_final_m_s": vs_final, "damping_final": damping_final, "episodes_normal": None,
            "episodes_inverse": None}


#: polarity -> (its row of a compiled outcome, its displacement and episodes columns)
_RUN_OF = {"normal": (_fused.NORMAL, "normal_m", "episodes_normal"),
           "inverse": (_fused.INVERSE, "inverse_m", "episodes_inverse")}
#: polarities -> the columns of a row that :func:`check_finite_rows` checks
_FINITE_COLUMNS = {polarities: ("kmax_g", *(_RUN_OF[polarity][1] for polarity in polarities))
                   for polarities in (("normal",), ("inverse",), ("normal", "inverse"))}


def _near_critical_row(analysis):
    """The row of ``analysis`` whose total damping lies in [COMPILED_RESPONSE_LIMIT, 1),
    too close to 1 for the compiled no-sliding response: that response (kmax at the
    samples, its supremum over time, sup |u| for the equivalent-linear iteration) and the
    slides on matrix exponentials (:func:`response_compiled`, :func:`_slides_in_closed_form`)."""
    model, record = analysis.model, analysis.record
    column, where = model.column, f" ({analysis.name}, {model})"
    arrays, slots = _engine_input(record, analysis.t_end), _step_slots(record, analysis.t_end)

    def response(vs, xi, with_u):
        column_model = model.with_parameters({"omega": np.pi * vs / (2 * column.height), "damping": xi})
        return response_compiled(column_model, arrays, slots, with_u, where)

    vs, xi = column.vs, model.damping
    if analysis.reference_strain is not None:
        final = iterate_equivalent_linear(lambda vs, xi: response(vs, xi, True)[2], column, analysis.reference_strain)
        vs, xi = final.vs, final.damping
    samples, sup, _ = response(vs, xi, False)
    row = _row(analysis, samples / model.g, sup / model.g, vs, xi)
    _slides_in_closed_form(analysis, row)
    return row


def _run_analyses(inputs, tasks):
    """The compiled analyses (:func:`._fused._analyses`) of excitations ``inputs`` (engine
    arrays): analysis j runs ``tasks[j]`` (a tuple of TASK_FIELDS) on
    ``inputs[tasks[j][0]]``. Returns (n, 3, width) outcomes."""
    return _run_kernel(*_kernel_input(inputs, tasks))


def _kernel_input(inputs, tasks):
    """(the arrays, the offsets of each excitation in them, the tasks as an array, their
    work: the pieces they step) of excitations ``inputs`` (engine arrays) and ``tasks``
    (tuples of TASK_FIELDS) as the kernels take them."""
    lengths = [len(x[0]) for x in inputs]
    work = sum(lengths[int(task[0])] for task in tasks)
    if len(inputs) == 1:
        return inputs[0], _offsets(lengths[0]), np.array(tasks, dtype=float), work
    arrays = tuple(np.concatenate([x[k] for x in inputs]) for k in range(4))
    offsets = np.concatenate([[0], np.cumsum(lengths)]).astype(np.int64)
    return arrays, offsets, np.array(tasks, dtype=float), work


def _run_kernel(arrays, offsets, tasks, work):
    """The compiled analyses ``tasks`` (n, len(TASK_FIELDS)) on ``arrays`` (each
    excitation's pieces between its ``offsets``), ``work`` pieces in all: (n, 3, width)
    outcomes, in parallel over cores for a large batch (:data:`PARALLEL_WORK`)."""
    kernel = _fused.kernels()[0 if 2 * work >= PARALLEL_WORK else 1]  # parallel or serial
    out = np.empty((len(tasks), 3, _fused.WIDTH))
    notice_numba("the flexible sliding mass's engine", _fused.COMPILE_SECONDS, kernel)
    kernel(*arrays, offsets, tasks, out)
    return out


@functools.lru_cache(maxsize=64)
def _offsets(n):
    """The offsets (0, ``n``) of one excitation of ``n`` pieces (the kernels only read them)."""
    return np.array([0, n], dtype=np.int64)


def _final_columns(analyses, inputs, input_of):
    """The engine's settings (omega, xi, ky g, coupled) of each of ``analyses`` after its
    equivalent-linear iteration (on the exact no-sliding sup |u|), if any, and the
    column's vs then [m/s]. The iterations run in step: each pass's responses, of every
    analysis still iterating, in one compiled call (analysis q on ``inputs[input_of[q]]``)."""
    finals, iterating = [None] * len(analyses), {}
    for q, analysis in enumerate(analyses):
        if analysis.reference_strain is None:
            finals[q] = _settings(analysis.model), analysis.model.column.vs
        else:
            steps = equivalent_linear_steps(analysis.model.column, analysis.reference_strain)
            iterating[q] = steps, next(steps)
    while iterating:
        order = list(iterating)
        tasks = [(input_of[q], np.pi * iterating[q][1][0] / (2 * analyses[q].model.column.height),
                  iterating[q][1][1], 0.0, False, False, False, True, True) for q in order]
        outcomes = _run_analyses(inputs, tasks)[:, _fused.RESPONSE]
        for q, outcome in zip(order, outcomes):
            steps, (vs, _) = iterating[q]
            check(outcome, f" ({analyses[q].name}, equivalent-linear pass at vs={vs!r} m/s)")
            try:
                iterating[q] = steps, steps.send(outcome[_FIELD["u_sup"]])
            except StopIteration as done:
                del iterating[q]
                model, final = analyses[q].model, done.value
                settings = engine_settings(model.with_parameters({"omega": np.pi * final.vs / (2 * model.column.height),
                                                                  "damping": final.damping}))
                finals[q] = settings, final.vs
    return finals


def slammer_rows(analyses: list[Analysis]) -> list[dict]:
    """The rows of ``analyses`` by SLAMMER 1.1's fixed-step scheme
    (:func:`~._slammer.slammer_flexible`); ``kmax_sup_g`` is nan (SLAMMER looks at the
    samples only)."""
    rows = []
    for analysis in analyses:
        model, record = analysis.model, analysis.record
        row = _row(analysis, np.nan, np.nan, np.nan, np.nan)  # kmax, vs and damping from SLAMMER's runs
        for polarity in analysis.polarities:
            result = slammer_flexible(record.acceleration_samples / model.g, record.dt,
                                      scale=1.0 if polarity == "normal" else -1.0, ky=model.ky, column=model.column,
                                      method=model.method, reference_strain=analysis.reference_strain, g=model.g)
            _, displacement, episodes = _RUN_OF[polarity]
            row |= {displacement: result.displacement, episodes: result.episodes, "kmax_g": result.kmax,
                    "vs_final_m_s": result.vs, "damping_final": result.damping}
        rows.append(row)
    return rows


#: integration scheme -> (rows of a list of :class:`Analysis`, the rounding of the
#: motion's peak when scaling to ``pga``: see :func:`blockdae.excitation.pga_factor`);
#: "exact": continuous time, events located, the exact peak; "slammer": SLAMMER 1.1's
#: fixed-step scheme and its peak rounded to 0.001 g
INTEGRATIONS = {"exact": (exact_rows, "exact"), "slammer": (slammer_rows, "slammer")}


def table_rows(analyses) -> list[dict]:
    """The rows of :func:`flexible` analyses whose ky is a table: the
    no-sliding response (kmax, the equivalent-linear iteration) as for a constant ky,
    then each polarity's slide by the compiled matrix-exponential engine
    (:func:`_slides_in_closed_form`)."""
    rows = exact_rows([dataclasses.replace(a, model=a.model.replace(ky=a.model.ky_at(0.0)), polarities=())
                       for a in analyses])
    for analysis, row in zip(analyses, rows):
        _slides_in_closed_form(analysis, row)
    return rows


def _systems(model):
    """:func:`system_arrays` of ``model``, kept for the values it reads (omega, damping,
    method, g, the table's pieces): a repeated analysis (a warm loop) builds them once."""
    key = (model.omega, model.damping, model.coupled, model.g, tuple(tuple(map(float, part)) for part in model.table))
    found = _SYSTEMS.get(key)
    if found is None:
        if len(_SYSTEMS) >= 256:
            _SYSTEMS.clear()
        found = _SYSTEMS[key] = system_arrays(model)
    return found


#: :func:`_systems`' store
_SYSTEMS = {}


def _slides_in_closed_form(analysis, row):
    """Each polarity's slide of ``analysis`` into ``row`` (its no-sliding columns
    filled) by the compiled matrix-exponential engine (:func:`slide_compiled`, the
    mathematics of :mod:`._table_engine`) on the record with its virtual zero sample: for
    a ky table, or a slip too damped for the closed forms of :mod:`._engine` (ky then a
    one-piece table, :mod:`._damped_slip`). Where the no-sliding sup |HEA| stays below
    ky g at s = 0 nothing slides (no run needed)."""
    if row["kmax_sup_g"] < analysis.model.ky_at(0.0):
        for polarity in analysis.polarities:
            _, displacement, episodes = _RUN_OF[polarity]
            row[displacement], row[episodes] = 0.0, 0
        return
    omega = math.pi * row["vs_final_m_s"] / (2 * analysis.model.column.height)
    model = analysis.model.with_parameters({"omega": omega, "damping": row["damping_final"]})
    if model.table is None:
        model = flat_table_model(model)
    systems = _systems(model)
    t0, h, p0, p1 = _engine_input(analysis.record, analysis.t_end)
    slots = _step_slots(analysis.record, analysis.t_end)
    for polarity in analysis.polarities:
        sign = 1.0 if polarity == "normal" else -1.0  # the record times -1: its pieces' a and a' negated
        outcome, _ = slide_compiled(systems, (t0, h, sign * p0, sign * p1), where=f" ({analysis.name}, {polarity})",
                                    slots=slots)
        _, displacement, episodes = _RUN_OF[polarity]
        row[displacement] = 0.0 + outcome[_table_kernel.OUTCOME_FIELDS.index("s")]
        row[episodes] = int(outcome[_table_kernel.OUTCOME_FIELDS.index("n_onsets")])
