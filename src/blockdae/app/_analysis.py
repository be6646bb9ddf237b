"""The app's analyses: the settings of the analysis form, checked field by field; the runs
(``bd.newmark`` for the rigid block, ``bd.flexible`` for the flexible sliding mass), one
record at a time so that a long run reports progress and can stop; the table of D per
record; the history of one case and D against ky."""

import dataclasses
import math

import numpy as np

from ..core import simulate
from ..flexible_mass import FlexibleSlidingMass, KyTable, flexible, prechecked_column, with_zero_sample
from ..sliding import SlidingBlock, newmark, newmark_history_figure, yield_acceleration
from ..units import STANDARD_GRAVITY
from ._caught import caught_warnings

#: the analyses offered, in SLAMMER's order
METHODS = {"rigid": "Rigid block (Newmark)", "decoupled": "Decoupled", "coupled": "Coupled",
           "equivalent-linear": "Coupled, equivalent-linear"}
#: the columns of the results table, in order (units in the names); kmax_g only for a flexible mass
COLUMNS = ("record", "pga_g", "ky_g", "normal_m", "inverse_m", "mean_m", "max_m", "kmax_g")


class FieldError(ValueError):
    """A value of the analysis form that cannot be used: names the field and the value."""

    def __init__(self, field, value, reason):
        super().__init__(f"{field}: {value!r} {reason}")


@dataclasses.dataclass(frozen=True)
class Settings:
    """One analysis as the form sets it.

    Attributes:
        method: a key of :data:`METHODS`.
        ky: yield accelerations [g] (a tuple), or a :class:`KyTable` (ky [g] against D [m]).
        height: height H of the sliding mass [m] (flexible only).
        vs: its shear-wave velocity [m/s] (flexible only).
        damping: the soil's damping ratio [-] (flexible only; impedance damping added).
        reference_strain: gamma_ref [-], a fraction (equivalent-linear only).
        pga: target PGA [g], None: each record as read.
        polarity: "both", "normal" or "inverse".
    """

    method: str
    ky: tuple | KyTable
    height: float | None = None
    vs: float | None = None
    damping: float | None = None
    reference_strain: float | None = None
    pga: float | None = None
    polarity: str = "both"

    @property
    def flexible(self) -> bool:
        return self.method != "rigid"


def _number(field, text, *, low=None, high=None, low_open=True, optional=False):
    """``text`` of the field named ``field`` as a float in (low, high); None where
    ``optional`` and empty; FieldError naming the field and the value otherwise."""
    if text is None or str(text).strip() == "":
        if optional:
            return None
        raise FieldError(field, "" if text is None else text, "is empty: give a number")
    try:
        value = float(str(text).strip())
    except ValueError:
        raise FieldError(field, text, "is not a number") from None
    if not math.isfinite(value):
        raise FieldError(field, text, "is not a finite number")
    if low is not None and (value <= low if low_open else value < low):
        raise FieldError(field, text, f"must be {'>' if low_open else '>='} {low:g}")
    if high is not None and value >= high:
        raise FieldError(field, text, f"must be < {high:g}")
    return value


def _ky_values(text):
    """Yield accelerations [g] from "0.05, 0.1 0.2" (commas or blanks)."""
    parts = [part for part in str(text or "").replace(",", " ").split()]
    if not parts:
        raise FieldError("ky [g]", text or "", "is empty: give one or more yield accelerations in g")
    values = tuple(_number("ky [g]", part, low=0.0) for part in parts)
    for part, value in zip(parts, values):
        if value > 1.0:
            raise FieldError("ky [g]", part, "is above 1 g: a ky in m/s²? (0.05 g is 0.49 m/s²)")
    return values


def _ky_table(text):
    """A :class:`KyTable` from lines "D [m], ky [g]"."""
    rows = [line for line in str(text or "").splitlines() if line.strip()]
    if not rows:
        raise FieldError("ky(D) table", text or "", "is empty: give lines 'D [m], ky [g]'")
    displacement, ky = [], []
    for number, line in enumerate(rows, start=1):
        cells = line.replace(",", " ").replace(":", " ").split()
        if len(cells) != 2:
            raise FieldError(f"ky(D) table, row {number}", line, "must be two numbers: D [m], ky [g]")
        displacement.append(_number(f"ky(D) table, row {number}, D [m]", cells[0], low=0.0, low_open=False))
        ky.append(_number(f"ky(D) table, row {number}, ky [g]", cells[1], low=0.0, high=1.0))
    try:
        return KyTable(displacement, ky)
    except ValueError as err:
        raise FieldError("ky(D) table", text, f"is refused: {err}") from None


def parse_settings(form: dict) -> Settings:
    """The :class:`Settings` of the form's values (text as typed; keys: method, ky_mode
    ("direct", "safety" or "table"), ky, factor_of_safety, thrust_angle, ky_table, height,
    vs, damping, reference_strain, pga, polarity); FieldError naming a bad field."""
    method = form.get("method")
    if method not in METHODS:
        raise FieldError("analysis", method, f"is none of {', '.join(METHODS)}")
    mode = form.get("ky_mode", "direct")
    if mode == "direct":
        ky = _ky_values(form.get("ky"))
    elif mode == "safety":
        fs = _number("factor of safety [-]", form.get("factor_of_safety"), low=1.0)
        angle = _number("thrust angle [°]", form.get("thrust_angle"), low=0.0, high=90.0)
        ky = (round(yield_acceleration(fs, angle), 12),)
    elif mode == "table":
        ky = _ky_table(form.get("ky_table"))
    else:
        raise FieldError("ky from", mode, "is none of direct, safety, table")
    flexible_fields = {}
    if method != "rigid":
        flexible_fields = {"height": _number("slope height H [m]", form.get("height"), low=0.0),
                           "vs": _number("shear-wave velocity Vs [m/s]", form.get("vs"), low=0.0),
                           "damping": _number("damping ratio [-]", form.get("damping"), low=-1.0, high=1.0)}
    strain = None
    if method == "equivalent-linear":
        strain = _number("reference strain [-]", form.get("reference_strain"), low=0.0, high=1.0)
    pga = _number("target PGA [g]", form.get("pga"), low=0.0, optional=True)
    if pga is not None and pga > 2.0:
        raise FieldError("target PGA [g]", form.get("pga"), "is above 2 g: a PGA in m/s²? (0.3 g is 2.94 m/s²)")
    polarity = form.get("polarity", "both")
    if polarity not in ("both", "normal", "inverse"):
        raise FieldError("polarity", polarity, "is none of both, normal, inverse")
    return Settings(method, ky, reference_strain=strain, pga=pga, polarity=polarity, **flexible_fields)


def scaled(record, settings, g=STANDARD_GRAVITY):
    """``record`` scaled to the target PGA of ``settings`` (as read where it sets none)."""
    if settings.pga is None:
        return record
    return record.scaled(settings.pga * g / record.peak_acceleration)


def analyse(name, record, settings: Settings) -> tuple[list[dict], list[str]]:
    """(the rows of one record: dicts with the keys :data:`COLUMNS`; the library's warnings
    and the app's notes as lines). ValueError naming the record where the library refuses."""
    try:
        with caught_warnings() as notes:
            table = library_table(name, record, settings)
    except ValueError as err:
        raise ValueError(f"{name}: {err}") from None
    rows = [_row(row, name, record, settings) for row in table.to_dict(orient="records")]
    return rows, notes  # a ky at or above the peak driving the slide: the library's warning among the notes


def library_table(name, record, settings):
    """The library's table (pandas) of one record under ``settings``."""
    ky = settings.ky if isinstance(settings.ky, KyTable) else np.asarray(settings.ky)
    if not settings.flexible:
        return newmark({name: record}, ky, polarity=settings.polarity, pga=settings.pga, progress=False).to_dataframe()
    ky = ky if isinstance(ky, KyTable) or ky.size > 1 else float(ky[0])
    method = "coupled" if settings.method == "equivalent-linear" else settings.method
    equivalent_linear = settings.method == "equivalent-linear"
    return flexible({name: record}, ky, settings.height, settings.vs, None, settings.damping, method,
                    equivalent_linear, settings.reference_strain, settings.pga, settings.polarity).to_dataframe()


def _row(row, name, record, settings):
    """A row of the library's table with the app's columns (read by name: pga_g, mean_m and
    max_m are computed where the library's table has none), and a flexible mass's
    converged column (vs_final_m_s [m/s], damping_final [-]) for its history."""
    normal, inverse = (_value(row.get(key)) for key in ("normal_m", "inverse_m"))
    run = [d for d in (normal, inverse) if not math.isnan(d)]
    pga = row.get("pga_g", settings.pga if settings.pga is not None else record.peak_acceleration / STANDARD_GRAVITY)
    return {"record": row.get("record", name), "pga_g": float(pga), "ky_g": float(row["ky_g"]),
            "normal_m": normal, "inverse_m": inverse,
            "mean_m": _value(row.get("mean_m", sum(run) / len(run) if run else math.nan)),
            "max_m": _value(row.get("max_m", max(run, default=math.nan))),
            "kmax_g": _value(row.get("kmax_g")), "vs_final_m_s": _value(row.get("vs_final_m_s")),
            "damping_final": _value(row.get("damping_final"))}


def _value(value):
    """A float, nan where absent."""
    return math.nan if value is None or value != value else float(value)


def case_solution(record, settings: Settings, row: dict, polarity: str):
    """(the solution of one case: ``record`` under ``settings`` at the row's ky, the
    polarity run; the motion it ran on)."""
    motion = scaled(record, settings)
    motion = motion.inverted() if polarity == "inverse" else motion
    ky = settings.ky if isinstance(settings.ky, KyTable) else row["ky_g"]
    if not settings.flexible:
        if isinstance(ky, KyTable):
            raise ValueError("the history of a rigid block with a ky(D) table is not drawn; give ky directly")
        block = SlidingBlock(mu=ky, direction="negative", g=STANDARD_GRAVITY)
        return simulate(block, motion), motion
    method = "coupled" if settings.method == "equivalent-linear" else settings.method
    if settings.method == "equivalent-linear":  # the converged column, its damping total
        column = prechecked_column(settings.height, row["vs_final_m_s"], settings.vs, row["damping_final"],
                                   impedance=False)
    else:  # checked by the run of bd.flexible that gave the row
        column = prechecked_column(settings.height, settings.vs, None, settings.damping)
    model = FlexibleSlidingMass(column, ky, method, STANDARD_GRAVITY)
    return simulate(model, with_zero_sample(motion), t_end=motion.duration + motion.dt), motion


def history_figure(record, settings: Settings, row: dict, polarity: str):
    """The three panels of one case against t [s] (accelerations with ky, velocity, displacement
    D; sliding shaded); a matplotlib Figure."""
    from .._plot import plot

    solution, motion = case_solution(record, settings, row, polarity)
    d = row[f"{polarity}_m"]
    title = f"{row['record']}, {polarity} polarity, PGA {row['pga_g']:.3g} g\n" \
            f"{METHODS[settings.method].lower()}: ky = {row['ky_g']:g} g, D = {d:.4g} m"
    if not settings.flexible:
        return newmark_history_figure(solution, motion, row["ky_g"], STANDARD_GRAVITY, polarity=polarity,
                                      n_points=3000, title=title)
    return plot(solution, n_points=3000, title=title + " (t from the zero sample at -dt)")


def displacement_figure(rows):
    """D (the larger polarity) [m] against ky [g], one line per (record, PGA), each axis
    logarithmic where its values span a decade or more (as :meth:`bd.NewmarkSweep.figure`
    draws them; D = 0 and ky = 0 have no place on a log axis: such points are left out and
    their number stated in the title); with one ky, a bar per (record, PGA). A matplotlib
    Figure."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

    cases = {}
    for row in rows:
        cases.setdefault((row["record"], row["pga_g"]), []).append((row["ky_g"], row["max_m"]))
    fig = Figure(figsize=(8.5, max(3.0, 1.2 + 0.22 * len(cases))) if len({r["ky_g"] for r in rows}) == 1 else
                 (8.5, 4.5), layout="constrained")
    ax = fig.subplots()
    labels = [f"{name} (PGA {pga:.3g} g)" for name, pga in cases]
    if len({row["ky_g"] for row in rows}) == 1:
        ax.barh(labels[::-1], [points[0][1] for points in cases.values()][::-1], height=0.6, color="C0")
        ax.set(xlabel="downslope displacement D [m] (larger polarity)", title=f"D at ky = {rows[0]['ky_g']:g} g")
        ax.tick_params(axis="y", labelsize="small")
        ax.grid(True, axis="x", alpha=0.3)
        return fig
    log_ky, log_d = (_spans_a_decade([point[i] for points in cases.values() for point in points]) for i in (0, 1))
    left_out = 0
    for label, points in zip(labels, cases.values()):
        ky, d = np.array(sorted(points)).T
        shown = ((ky > 0) | ~log_ky) & ((d > 0) | ~log_d)
        left_out += int(np.count_nonzero(~shown))
        ax.plot(ky[shown], d[shown], marker="o", ms=3.5, lw=1.2, label=label)
    ax.set(xscale="log" if log_ky else "linear", yscale="log" if log_d else "linear",
           xlabel="yield acceleration ky [g]", ylabel="downslope displacement D [m]\n(larger polarity)",
           title="D against ky" + (f"\n({left_out} points at D = 0 or ky = 0 not shown on the log axes)"
                                   if left_out else ""))
    for axis, log in ((ax.xaxis, log_ky), (ax.yaxis, log_d)):
        if log:  # plain numbers at 1, 2 and 5 times the powers of ten (0.05, 0.1, 0.2)
            axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(FormatStrFormatter("%g"))
            axis.set_minor_formatter(NullFormatter())
    ax.grid(True, alpha=0.3)
    if len(cases) <= _LEGEND_ENTRIES:
        fig.legend(loc="outside right upper", fontsize="x-small")
    return fig


def _spans_a_decade(values) -> bool:
    """Whether the positive ``values`` span a factor of 10 or more (a log axis then reads best)."""
    positive = np.asarray(values, dtype=float)
    positive = positive[positive > 0]
    return positive.size > 0 and positive.max() >= 10 * positive.min()


#: the most curves of D against ky that get a legend (beyond, the table names them)
_LEGEND_ENTRIES = 20
