"""``bd.study`` on the flexible sliding mass: the mass at every yield acceleration ky of a
study (numbers [g], or ky tables of the sliding displacement: :class:`KyTable`), its rows
from ``bd.flexible``'s exact path (:func:`._analysis.exact_rows`; :func:`._analysis.table_rows`
for a table).

The mass declares what a study sweeps (``FlexibleSlidingMass.study_parameter``: ky [g],
the column ky_g); :func:`study_sweep` and :func:`study_batch` are its ``study_sweep`` and
``study_batch`` methods, attached by the package's ``__init__``: the rows come from
:mod:`._analysis`, which imports the model, so the model's own module cannot import them
(no import cycle).
"""

import dataclasses

import numpy as np

from ..core.contract import StudyBatch
from ..excitation import Record, ky_not_reached
from ._analysis import Analysis, check_finite_rows, driving_peak, exact_rows, table_rows
from ._ky_table import KyTable
from ._model import FlexibleSlidingMass

#: both polarities, as ``bd.flexible``'s default
POLARITIES = ("normal", "inverse")
#: the columns a study takes from ``bd.flexible``'s rows (same names, same units)
STUDY_COLUMNS = ("height_m", "vs_m_s", "normal_m", "inverse_m", "kmax_g", "kmax_sup_g", "vs_final_m_s",
                 "damping_final", "episodes_normal", "episodes_inverse")


@dataclasses.dataclass(frozen=True, eq=False)
class FlexibleStudyBatch(StudyBatch):
    """A flexible sliding mass at every yield acceleration of a study.

    Attributes:
        masses: the mass at each ky [g], shape (m,) (linear-elastic columns).
    """

    masses: tuple

    def check_motions(self, motions, t_end):
        """Raise ValueError unless every one of ``motions`` is a :class:`bd.Record` (along
        the slope) that lasts at least ``t_end`` [s] (None: each runs to its last sample)."""
        for i, motion in enumerate(motions):
            if not isinstance(motion, Record):
                name = " + ".join(c.name for c in motion.components if c is not None) \
                    if hasattr(motion, "components") else None
                raise ValueError(f"records[{i}] ({name!r}) is a {type(motion).__name__}: the flexible sliding mass "
                                 "takes records along the slope (bd.Record), one component")
            if t_end is not None and not float(t_end) <= motion.duration:
                raise ValueError(f"t_end={t_end!r} must lie in (0, {motion.duration!r}] s (the record "
                                 f"{motion.name!r}, records[{i}]): the flexible mass runs to a record's last "
                                 "sample at most")

    def study_columns(self, motions, t_end, scale, rtol=None) -> dict:
        """What :func:`bd.study` tabulates of the masses on ``motions`` (records along the
        slope [m/s²]) at the factors ``scale`` on a(t) [-]: one row per motion x ky x
        factor, the columns :data:`STUDY_COLUMNS` of ``bd.flexible`` (both polarities)
        from its exact engine (``rtol`` is not used: nothing is integrated), each finite
        (else a ValueError); a ky above 1 g that kmax does not reach is refused (likely
        m/s²). ``t_end``: the end on each record's axis [s]; None: its last sample."""
        self.check_motions(motions, t_end)  # bd.study checked its records; here also floor motions
        analyses = []
        for motion in motions:
            end = motion.duration if t_end is None else float(t_end)
            scaled = [motion.scaled(factor) for factor in scale]  # shared by every ky: one no-sliding run each
            analyses += [Analysis(record, motion.name, mass, POLARITIES, end, None)
                         for mass in self.masses for record in scaled]
        rows = _rows(analyses)
        check_finite_rows(rows, analyses, "bd.study")
        for row, analysis in zip(rows, analyses):  # a sweep reaches ky >= kmax (D = 0): only the refusal
            ky_not_reached(analysis.model.ky_at(0.0), driving_peak(row), f"{row['record']}: ", "kmax")
        return {name: np.array([row[name] for row in rows]) for name in STUDY_COLUMNS}


def _rows(analyses):
    """``bd.flexible``'s exact rows of ``analyses``, in order: those with a ky table by
    :func:`table_rows`, the others by :func:`exact_rows` (all in one call)."""
    tables = [a.model.table is not None for a in analyses]
    rows = {kind: iter(rows_of([a for a, table in zip(analyses, tables) if table == kind]) if kind in tables else ())
            for kind, rows_of in ((False, exact_rows), (True, table_rows))}
    return [next(rows[table]) for table in tables]


def study_sweep(mass: FlexibleSlidingMass, ky):
    """The ky tables of a study, ``ky`` a :class:`KyTable` or a sequence of them: (ky at
    zero displacement [g] of each, the table's ``ky_g`` column, shape (m,); the tables);
    None where ``ky`` holds numbers [g] (bd.study checks them)."""
    tables = [ky] if isinstance(ky, KyTable) else list(ky) if isinstance(ky, (list, tuple)) else []
    if not any(isinstance(table, KyTable) for table in tables):
        return None
    for i, table in enumerate(tables):
        if not isinstance(table, KyTable):
            raise ValueError(f"ky[{i}]={table!r}: give ky as numbers [g] or as ky tables (bd.KyTable), not both")
    return np.array([float(table(0.0)) for table in tables]), tuple(tables)


def study_batch(mass: FlexibleSlidingMass, ky) -> FlexibleStudyBatch:
    """``mass`` at every yield acceleration ``ky`` [g] (a 1-D array) or ky table (a tuple of
    :class:`KyTable`), each checked (its ky; the column's total damping is in (0, 1)
    already) before any work."""
    return FlexibleStudyBatch(tuple(mass.replace(ky=k if isinstance(k, KyTable) else float(k)) for k in
                                    (ky if isinstance(ky, tuple) else np.atleast_1d(ky))))
