"""A yield coefficient that changes with the sliding displacement: ky against D as a
table, linear between its breakpoints and constant beyond its ends (as pySLAMMER's
``ky=(disp_values, ky_values)`` with ``np.interp``).

D is the downslope sliding displacement accumulated since the start of the analysis
[m] (the s of :class:`FlexibleSlidingMass`, >= 0 and never decreasing: sliding is
one-way); each polarity is its own analysis from D = 0, as in pySLAMMER.
"""

import dataclasses
import math

import numpy as np


@dataclasses.dataclass(frozen=True)
class KyTable:
    """ky [g] against the sliding displacement D [m], linear between the rows.

    Args:
        displacement_m: breakpoints D [m], strictly increasing (any finite values;
            only D > 0 is ever reached).
        ky_g: ky at each breakpoint [g], >= 0.

    Below the first breakpoint ky is ``ky_g[0]``, beyond the last ``ky_g[-1]``. A
    one-row table is the constant ky. ``KyTable.from_pyslammer((disp, ky))`` takes
    pySLAMMER's tuple (displacements first).
    """

    displacement_m: tuple
    ky_g: tuple

    def __post_init__(self):
        d = _finite_vector(self.displacement_m, "displacement_m")
        ky = _finite_vector(self.ky_g, "ky_g")
        if d.size != ky.size:
            raise ValueError(f"KyTable: displacement_m has {d.size} values and ky_g {ky.size}; they must match")
        if d.size == 0:
            raise ValueError("KyTable needs at least one row (displacement_m, ky_g)")
        steps = np.flatnonzero(np.diff(d) <= 0)
        if steps.size:
            i = int(steps[0])
            raise ValueError(f"KyTable: displacement_m must be strictly increasing; displacement_m[{i}] = "
                             f"{float(d[i])!r} m, displacement_m[{i + 1}] = {float(d[i + 1])!r} m")
        negative = np.flatnonzero(ky < 0)
        if negative.size:
            i = int(negative[0])
            raise ValueError(f"KyTable: ky_g[{i}] = {float(ky[i])!r} g; a yield coefficient must be >= 0 [g]")
        object.__setattr__(self, "displacement_m", tuple(float(x) for x in d))
        object.__setattr__(self, "ky_g", tuple(float(x) for x in ky))

    @classmethod
    def from_pyslammer(cls, table) -> "KyTable":
        """pySLAMMER's ``(disp_values [m], ky_values [g])``."""
        if not (isinstance(table, (tuple, list)) and len(table) == 2):
            raise ValueError(f"a pySLAMMER ky table is a pair (disp_values [m], ky_values [g]), got {table!r}")
        return cls(*table)

    @property
    def constant(self) -> bool:
        """Whether ky does not change with D (one row)."""
        return len(self.ky_g) == 1

    def __call__(self, displacement):
        """ky [g] at D = ``displacement`` [m] (np.interp)."""
        return np.interp(displacement, self.displacement_m, self.ky_g)

    def segments(self):
        """The breakpoints D > 0 [m] that a slide from D = 0 can cross, and the linear
        pieces ky = intercept + slope D ([g], [g/m]) before, between and after them:
        (breakpoints (n,), intercepts (n + 1,), slopes (n + 1,))."""
        d, ky = np.array(self.displacement_m), np.array(self.ky_g)
        first = int(np.searchsorted(d, 0.0, side="right"))  # index of the first D > 0
        slopes = np.concatenate([[0.0], np.diff(ky) / np.diff(d), [0.0]])  # piece j: D in [d[j-1], d[j])
        intercepts = np.concatenate([[ky[0]], ky[:-1] - slopes[1:-1] * d[:-1], [ky[-1]]])
        return d[first:], intercepts[first:], slopes[first:]

    def __str__(self):
        rows = ", ".join(f"{d:g} m: {k:g} g" for d, k in zip(self.displacement_m, self.ky_g))
        return f"KyTable({rows})"


def _finite_vector(values, name):
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"KyTable: {name} must be a sequence of numbers, got {values!r}") from None
    if array.ndim != 1:
        raise ValueError(f"KyTable: {name} must be one-dimensional, got shape {array.shape}")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise ValueError(f"KyTable: {name}[{int(bad[0])}] = {float(array[bad[0]])!r} is not a finite number")
    return array


def piecewise_ky(s, breakpoints, intercepts, slopes, xp):
    """ky(s) [g] from :meth:`KyTable.segments`, with the array namespace ``xp`` only
    (its ``where``): the first piece plus each breakpoint's change of slope."""
    ky = intercepts[0] + slopes[0] * s
    for j, d in enumerate(breakpoints):
        ky = ky + xp.where(s > d, (slopes[j + 1] - slopes[j]) * (s - d), 0.0 * s)
    return ky


def piece_ky(passed, s, breakpoints, intercepts, slopes, xp):
    """ky(s) [g] on the piece of :meth:`KyTable.segments` after ``passed`` breakpoints (a
    count, as a float state): its intercept plus its slope times s, with the array
    namespace ``xp`` only (its ``where``)."""
    intercept, slope = intercepts[-1] + 0.0 * passed, slopes[-1] + 0.0 * passed
    for j in reversed(range(len(breakpoints))):
        intercept = xp.where(passed < j + 0.5, intercepts[j] + 0.0 * passed, intercept)
        slope = xp.where(passed < j + 0.5, slopes[j] + 0.0 * passed, slope)
    return intercept + slope * s


def next_breakpoint(passed, breakpoints, xp, beyond=math.inf):
    """The breakpoint [m] after ``passed`` of them (a count, as a float state); ``beyond``
    when all are passed."""
    value = beyond + 0.0 * passed
    for j in reversed(range(len(breakpoints))):
        value = xp.where(passed < j + 0.5, breakpoints[j] + 0.0 * passed, value)
    return value
