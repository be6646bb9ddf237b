"""``bd.study`` on the flexible sliding mass: the mass at every yield acceleration ky of a
study, its rows from ``bd.flexible``'s exact compiled path (:func:`._analysis.exact_rows`).

The mass declares what a study sweeps (``FlexibleSlidingMass.study_parameter``: ky [g],
the column ky_g); :func:`study_batch` is its ``study_batch`` method, attached by the
package's ``__init__``: the rows come from :mod:`._analysis`, which imports the model, so
the model's own module cannot import them (no import cycle).
"""

import dataclasses

import numpy as np

from ..excitation import Record
from ._analysis import Analysis, exact_rows
from ._model import FlexibleSlidingMass

#: both polarities, as ``bd.flexible``'s default
POLARITIES = ("normal", "inverse")
#: the columns a study takes from ``bd.flexible``'s rows (same names, same units)
STUDY_COLUMNS = ("height_m", "vs_m_s", "normal_m", "inverse_m", "kmax_g", "kmax_sup_g", "vs_final_m_s",
                 "damping_final", "episodes_normal", "episodes_inverse")


@dataclasses.dataclass(frozen=True, eq=False)
class FlexibleStudyBatch:
    """A flexible sliding mass at every yield acceleration of a study.

    Attributes:
        masses: the mass at each ky [g], shape (m,) (linear-elastic columns).
    """

    masses: tuple

    def study_columns(self, motions, t_end, scale, rtol=None) -> dict:
        """What :func:`bd.study` tabulates of the masses on ``motions`` (records along the
        slope [m/s²]) at the factors ``scale`` on a(t) [-]: one row per motion x ky x
        factor, the columns :data:`STUDY_COLUMNS` of ``bd.flexible`` (both polarities)
        from its exact engine (``rtol`` is not used: nothing is integrated). ``t_end``:
        the end on each record's axis [s]; None: its last sample."""
        analyses = []
        for i, motion in enumerate(motions):
            if not isinstance(motion, Record):
                raise TypeError(f"the flexible sliding mass takes records along the slope (bd.Record), motion {i} "
                                f"is a {type(motion).__name__}")
            end = motion.duration if t_end is None else float(t_end)
            if not 0 < end <= motion.duration:
                raise ValueError(f"t_end={t_end!r} must lie in (0, {motion.duration!r}] s (the record "
                                 f"{motion.name!r}): the flexible mass runs to a record's last sample at most")
            scaled = [motion.scaled(factor) for factor in scale]  # shared by every ky: one no-sliding run each
            analyses += [Analysis(record, motion.name, mass, POLARITIES, end, None)
                         for mass in self.masses for record in scaled]
        rows = exact_rows(analyses)
        return {name: np.array([row[name] for row in rows]) for name in STUDY_COLUMNS}


def study_batch(mass: FlexibleSlidingMass, ky) -> FlexibleStudyBatch:
    """``mass`` at every yield acceleration ``ky`` [g] (a 1-D array), each checked (its
    ky; the column's total damping is in (0, 1) already) before any work."""
    return FlexibleStudyBatch(tuple(mass.replace(ky=float(k)) for k in np.atleast_1d(ky)))
