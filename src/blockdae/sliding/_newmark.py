"""Newmark's rigid-block analysis in the conventions of slope-stability practice.

Practitioners (Newmark 1965; Jibson 1993; SLAMMER) state a sliding mass by its yield
acceleration k_y [g] and report the *downslope* displacement as a positive number, for
the record as given ("normal" polarity) and for the record inverted ("inverse"). Here
that is the signed 1-D block of Sawicki & Chybicki 2005 with ``mu = k_y`` sliding one way only
(``direction="negative"``): it slides while the ground acceleration exceeds k_y g, and
the downslope displacement is D = -u(t_end). :func:`newmark` runs one record
(:class:`NewmarkResult`) or many records × target PGAs × k_y (:class:`NewmarkSweep`).
"""

import dataclasses

import numpy as np

from ..core import cases, compact_repr, sensitivities, simulate
from ..units import STANDARD_GRAVITY
from ..excitation import (AbstractExcitation, RecordSet, check_finite_result, pga_keyword, warn_not_sliding,
                          with_metadata)
from ..flexible_mass import downslope_with_table
from ._model import SlidingBlock

_POLARITIES = ("both", "normal", "inverse")


def yield_acceleration(factor_of_safety, thrust_angle):
    """Yield acceleration k_y [g] of a slide from its static factor of safety [-] and
    thrust angle [degrees] (Newmark 1965; Jibson 1993, eq. 2): k_y = (FS - 1) sin(alpha).

    The thrust angle is the direction of the slide's movement when it first yields (the
    slope angle for a planar slide). Array arguments broadcast.
    """
    fs = np.asarray(factor_of_safety, dtype=float)
    alpha = np.asarray(thrust_angle, dtype=float)
    _require(np.isfinite(fs) & (fs >= 1), "factor_of_safety", fs, "must be >= 1 (a slope that stands)")
    _require(np.isfinite(alpha) & (alpha > 0) & (alpha < 90), "thrust_angle", alpha,
             "must lie in (0, 90) degrees")
    ky = (fs - 1.0) * np.sin(np.radians(alpha))
    return float(ky) if ky.ndim == 0 else ky


class _Polarities:
    """D of the polarities run: ``normal`` and ``inverse`` [m] (either None if not run)."""

    @property
    def maximum(self):
        """The larger D of the polarities run [m] (the conservative value)."""
        return _combine(np.maximum, self.normal, self.inverse)

    @property
    def mean(self):
        """The mean D of the polarities run [m] (SLAMMER's "average")."""
        return _combine(lambda a, b: 0.5 * (a + b), self.normal, self.inverse)

    def _columns(self):
        return {"normal_m": self.normal, "inverse_m": self.inverse, "mean_m": self.mean, "max_m": self.maximum,
                "dD_dky_normal_m_per_g": self.normal_dky, "dD_dky_inverse_m_per_g": self.inverse_dky}


@dataclasses.dataclass(frozen=True, eq=False)
class NewmarkResult(_Polarities):
    """Downslope displacements of a rigid block, one value per yield acceleration.

    Attributes:
        ky: yield accelerations [g], scalar or shape (n,).
        normal: downslope displacement D >= 0 for the record as given [m] (None if not run).
        inverse: D for the record inverted [m] (None if not run).
        g: the value of one g used [m/s²].
        normal_dky, inverse_dky: dD/dky of each polarity run [m/g], shaped as ``normal``
            (None unless ``newmark(..., derivative=True)``).
    """

    def __repr__(self):
        return compact_repr(self, f"largest D {np.max(self.maximum):.4g} m over {np.size(self.ky)} ky")

    ky: float | np.ndarray
    normal: float | np.ndarray | None
    inverse: float | np.ndarray | None
    g: float
    normal_dky: float | np.ndarray | None = None
    inverse_dky: float | np.ndarray | None = None

    def to_dataframe(self):
        """One row per k_y: ky_g, normal_m, inverse_m, mean_m, max_m, and where computed
        dD_dky_normal_m_per_g, dD_dky_inverse_m_per_g (pandas)."""
        import pandas as pd

        columns = {"ky_g": self.ky, **self._columns()}
        return pd.DataFrame({k: np.atleast_1d(v) for k, v in columns.items() if v is not None})

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """D [m] of each polarity run against k_y [g] (the other arguments are unused); a
        matplotlib Figure."""
        from ._figures import newmark_figure

        curves = [(f"{name} polarity", np.atleast_1d(d)) for name, d in (("normal", self.normal),
                                                                         ("inverse", self.inverse)) if d is not None]
        return newmark_figure(np.atleast_1d(self.ky), curves, key="polarity", title=title)


@dataclasses.dataclass(frozen=True, eq=False)
class NewmarkSweep(_Polarities):
    """Downslope displacements of a rigid block over records × target PGAs × yield accelerations.

    Attributes:
        records: the records' names, length n_records.
        peak: each record's own peak |a| [g], shape (n_records,).
        pga: target peaks [g], shape (n_pga,); None: the records as given (n_pga = 1).
        ky: yield accelerations [g], shape (n_ky,).
        normal: D >= 0 for the records as given [m], shape (n_records, n_pga, n_ky) (None if not run).
        inverse: D for the records inverted [m], same shape (None if not run).
        g: the value of one g used [m/s²].
        metadata: for a :class:`RecordSet`, its :attr:`~RecordSet.metadata` (magnitude,
            distance, Vs30, ...; pandas, indexed by name), carried into :meth:`to_dataframe`; else None.
        normal_dky, inverse_dky: dD/dky of each polarity run [m/g], shaped as ``normal``
            (None unless ``newmark(..., derivative=True)``).
    """

    def __repr__(self):
        n_records, n_pga, n_ky = self.shape
        return compact_repr(self, f"{n_records} records x {n_pga} PGA x {n_ky} ky, largest D "
                                  f"{np.nanmax(self.maximum):.4g} m")

    records: tuple[str, ...]
    peak: np.ndarray
    pga: np.ndarray | None
    ky: np.ndarray
    normal: np.ndarray | None
    inverse: np.ndarray | None
    g: float
    metadata: object = None
    normal_dky: np.ndarray | None = None
    inverse_dky: np.ndarray | None = None

    @property
    def shape(self) -> tuple[int, int, int]:
        """(n_records, n_pga, n_ky)."""
        return (len(self.records), 1 if self.pga is None else self.pga.size, self.ky.size)

    @property
    def analysed_pga(self) -> np.ndarray:
        """The peak of each (record, pga) analysed [g], shape (n_records, n_pga): the
        target, or the record's own peak where the records run as given."""
        return np.broadcast_to(self.peak[:, None] if self.pga is None else self.pga[None, :], self.shape[:2])

    def to_dataframe(self):
        """One row per (record, pga, k_y): record, the set's :attr:`metadata` columns if any,
        pga_g (the target peak, or the record's own where it ran as given) [g], ky_g [g],
        normal_m, inverse_m, mean_m, max_m [m], and where computed dD_dky_normal_m_per_g,
        dD_dky_inverse_m_per_g [m/g] (pandas)."""
        import pandas as pd

        index = np.indices(self.shape).reshape(3, -1)
        columns = {"record": np.asarray(self.records, dtype=object)[index[0]],
                   "pga_g": self.analysed_pga[index[0], index[1]], "ky_g": self.ky[index[2]],
                   **{k: v.reshape(-1) for k, v in self._columns().items() if v is not None}}
        return with_metadata(pd.DataFrame(columns), self.metadata)

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """D [m] (the larger of the polarities run) against k_y [g]: a colour per record
        (legend, or a colour scale for many), a line style per target PGA (the other
        arguments are unused); a matplotlib Figure."""
        from ._figures import newmark_figure

        polarity = "larger of the polarities" if self.normal is not None and self.inverse is not None else \
            ("normal polarity" if self.inverse is None else "inverse polarity")
        curves = list(zip(self.records, self.maximum))
        return newmark_figure(self.ky, curves, pga=self.pga, polarity=polarity, title=title)


def newmark(motion, ky, polarity: str = "both", g: float = STANDARD_GRAVITY, t_end: float | None = None,
            backend: str = "exact", *, pga=None, target_pga=None, pga_rounding: str = "exact", check_peak=True,
            progress=None, derivative: bool = False, **options) -> NewmarkResult | NewmarkSweep:
    """Newmark's rigid-block (one-way) downslope displacement, positive downslope.

    Args:
        motion: ground acceleration along the slope [m/s²]: one excitation (e.g. a
            :class:`Record`); or many: a sequence of them, a mapping name -> excitation,
            a :class:`RecordSet` (its metadata carried into the table), or a path to a
            folder (every record file in it, sorted by name) or to one file, read by
            :func:`blockdae.read_record` (units as the files state them; for files that do not,
            read them with ``bd.read_records(path, units=...)`` and pass the set).
        ky: yield acceleration(s) [g], a number or 1-D array (a batch, one compiled
            call); see :func:`yield_acceleration` and :meth:`SlidingBlock.on_incline`. Or a
            :class:`KyTable` of ky against the sliding displacement D (a slide that softens
            or hardens as it moves), exact (the table's ky at D = 0 is the table column
            ``ky_g``; no derivatives). A ky
            at or above the motion's peak [g] slides nowhere (D = 0): a :class:`UnitsWarning`
            says so; one also above 1 g is refused (likely m/s², e.g. ``ky=9.81``). A ky in
            m/s² below the peak cannot be told from one in g: 0.49 (0.05 g in m/s²) under a
            motion of peak 0.3 g gives millimetres where 0.05 g gives decimetres; check that
            ky is in g (ky = 0.05 g is 0.49 m/s²).
        polarity: "both" (default, as SLAMMER reports), "normal" (the record as given:
            sliding while a(t) > ky g) or "inverse" (the record inverted).
        g: the value of one g [m/s²]; standard gravity by default.
        t_end: final time [s]; None: until the block rests after the record.
        backend, **options: as for :func:`blockdae.simulate`.
        pga: target peak ground acceleration(s) [g] (SLAMMER's target PGA), a number or a
            1-D sequence: the motion is scaled so that its peak |a| is each ``pga`` g (see
            :func:`blockdae.excitation.pga_factor`); None: as given. A value above 2 g is refused (likely
            m/s²: 2.94 is 0.3 g in m/s²) unless ``check_peak=False``.
        target_pga: the deprecated name of ``pga`` (a DeprecationWarning); not both.
        pga_rounding: "exact" (default) or "slammer": the motion's own peak rounded to
            0.001 g before scaling, as SLAMMER scales (to reproduce its tables).
        check_peak: False accepts a ``pga`` above 2 g.
        progress: where the cases run one by one (a backend other than "exact"), a tqdm
            bar over them on stderr; None (default): only when stderr is a terminal. On
            "exact" every case runs in one compiled call.
        derivative: also dD/dky [m/g] of each polarity run (``normal_dky``,
            ``inverse_dky``), exact: differentiated through the closed-form engine
            (:func:`blockdae.sensitivities` with respect to "mu"; its first call in a
            process compiles a JAX kernel, about 10 s).

    Returns:
        For one excitation and at most one ``pga``, a :class:`NewmarkResult`; else a
        :class:`NewmarkSweep` (records × pga × ky). ``D = -u(t_end)`` of
        ``SlidingBlock(mu=ky, direction="negative", g=g)`` for each polarity run.
    """
    if polarity not in _POLARITIES:
        raise ValueError(f"polarity must be one of {_POLARITIES}, got {polarity!r}")
    pga = pga_keyword("bd.newmark", pga, target_pga)
    ky, table = _yield_accelerations(ky)
    if table is not None and (derivative or backend != "exact"):
        raise ValueError(f"ky={table}: a ky table runs on the exact engine without derivatives (backend 'exact', "
                         "derivative=False)")
    ky_array = np.asarray(ky, dtype=float)
    _require(np.isfinite(ky_array) & (ky_array > 0), "ky", ky_array, "must be a positive yield acceleration [g]")
    one = isinstance(motion, AbstractExcitation) and np.ndim(pga) == 0
    if not one and ky_array.ndim > 1:
        raise ValueError(f"ky must be a number or a 1-D sequence of yield accelerations [g], got shape {ky_array.shape}")
    block = SlidingBlock(mu=np.atleast_1d(ky_array), direction="negative", g=g)
    settings = dict(pga=pga, polarity=polarity, pga_rounding=pga_rounding, check_peak=check_peak)
    if table is None:
        runs = simulate(block, motion, t_end, backend, final_only=True, progress=progress, **settings, **options)
        given = runs.cases
        downslope = np.moveaxis(0.0 - runs.displacement, 2, 0)  # (polarity, record, pga, ky); no -0.0 where none slid
    else:
        given = cases(motion, g=g, **settings)
        given.check(block.check_motion)
        downslope = np.array([[[[downslope_with_table(given.motion(i, k, p), table, g, t_end)]
                                for k in range(given.shape[1])] for i in range(given.shape[0])]
                              for p in range(given.shape[2])])
    _check_finite(downslope, given, np.atleast_1d(ky_array), g)
    _warn_not_sliding(given, np.atleast_1d(ky_array), g)
    slopes = _slopes(given, np.atleast_1d(ky_array), g, t_end) if derivative else None
    columns = dict(zip(given.polarities, downslope))
    derivatives = dict(zip(given.polarities, slopes)) if derivative else {}
    if one:
        squeeze = (lambda d: d[0, 0]) if ky_array.ndim else (lambda d: float(d[0, 0, 0]))
        pick = lambda name, values: None if name not in values else squeeze(values[name])
        return NewmarkResult(ky=float(ky_array) if ky_array.ndim == 0 else ky_array, normal=pick("normal", columns),
                             inverse=pick("inverse", columns), g=float(g), normal_dky=pick("normal", derivatives),
                             inverse_dky=pick("inverse", derivatives))
    metadata = motion.metadata if isinstance(motion, RecordSet) else None
    return NewmarkSweep(records=given.names, peak=np.array([m.peak_acceleration / g for m in given.motions]),
                        pga=None if pga is None else given.targets, ky=np.atleast_1d(ky_array), g=float(g),
                        metadata=metadata, normal=columns.get("normal"), inverse=columns.get("inverse"),
                        normal_dky=derivatives.get("normal"), inverse_dky=derivatives.get("inverse"))


def _yield_accelerations(ky):
    """(``ky`` [g] as numbers, None), or for a ky table (:class:`bd.KyTable`, or pySLAMMER's
    pair (displacements [m], ky [g])) that varies with the sliding displacement (its ky at
    D = 0 [g], the table); a constant table is its one value. A TypeError says what is
    taken where ``ky`` is none of these."""
    from ..flexible_mass import as_ky_table

    table = as_ky_table(ky)
    if table is not None:
        return float(table.ky_g[0]) if table.constant else float(np.interp(0.0, table.displacement_m, table.ky_g)), \
            None if table.constant else table
    try:
        return np.asarray(ky, dtype=float) if np.ndim(ky) else float(ky), None
    except (TypeError, ValueError):
        raise TypeError(f"ky={ky!r:.80}: newmark takes yield accelerations [g], a number or a 1-D sequence "
                        "of numbers, or a bd.KyTable of ky against the sliding displacement") from None


def _slopes(given, ky, g, t_end) -> np.ndarray:
    """dD/dky [m/g] of every case of ``given`` (motions x factors x polarities), (polarity,
    record, pga, ky): exact, through the closed-form engine (mu = ky moves the kinetic
    coefficient too: mu_kinetic is None)."""
    block = SlidingBlock(mu=ky, direction="negative", g=g)
    n_motions, n_scales, n_polarities = given.shape
    return np.array([[[-np.asarray(sensitivities(block, given.motion(i, k, p), t_end=t_end, wrt=("mu",))["mu"])
                       for k in range(n_scales)] for i in range(n_motions)] for p in range(n_polarities)])


def _warn_not_sliding(cases, ky, g):
    """The ky rule (:func:`blockdae.excitation.warn_not_sliding`) on every (record, PGA)
    case of ``cases``: a UnitsWarning where some ky [g] is at or above the motion's peak
    (D = 0), a ValueError where such a ky is also above 1 g (it reads as m/s²)."""
    peaks = [(name, peak, ky) for name, case_peaks in zip(cases.names, cases.peak_g(g)) for peak in case_peaks]
    warn_not_sliding(peaks, len(cases.names) * cases.factors.shape[1])


def _check_finite(downslope, given, ky, g):
    """ValueError naming the case whose D [m] in ``downslope`` (polarity, record, pga, ky)
    is not finite (an overflow)."""
    def describe(index):
        p, i, k, j = index
        return (f"bd.newmark: D of {given.names[i]!r} ({given.polarities[p]} polarity, PGA "
                f"{given.peak_g(g)[i, k]:.4g} g, ky={ky[j]:g} g) [m]")
    check_finite_result(downslope, describe)


def _combine(op, normal, inverse):
    if normal is None or inverse is None:
        return inverse if normal is None else normal
    return op(normal, inverse)


def _require(ok, name, values, message):
    if not np.all(ok):
        raise ValueError(f"{name}={float(np.asarray(values)[~np.asarray(ok)].flat[0])!r} {message}")
