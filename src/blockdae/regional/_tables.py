"""Each record's rigid-block displacement as one function of ky/PGA, tabulated with the
exact engine and interpolated by cubic Hermite.

A record scaled by s gives D_s(ky) = s · D_1(ky / s) exactly (the block's equation
v' = s a(t) - ky g is s times the unscaled one at ky / s, event times unchanged). With
D_1 the displacement under the record scaled to a peak of 1 g, a cell of peak ground
acceleration p [g] and yield acceleration ky [g] slides D = p · D_1(ky / p) [m]: one
function of r = ky / PGA per record and polarity, whatever the cell.

The table of each (record, polarity): knots r_k in [r_min, r_top] with D_1(r_k) from the
exact engine (:func:`blockdae.newmark`, all the r of a round in one batched call) and
its exact dD_1/dr(r_k) (:func:`blockdae.sliding.downslope`: -g Σ T_i²/2 over the located
sliding episodes); r_top is the record's largest
acceleration in the sliding direction over its peak |a| (above it D = 0 exactly); below
r_min a cell runs on the exact engine. The knots are placed by halving: every interval is
checked at its quarter points and midpoint against exact runs, and the intervals that miss
``|D_table - D_exact| <= max(rtol · D_exact, atol_m) / 10`` [m, at PGA 1 g] at any of the
three, or are not monotone there (Fritsch & Carlson 1980: α² + β² <= 9), are halved; only
the two halves are checked again. The margin of 10 covers the points between the checks
(the tests check the bound itself against exact runs at random cells).

A cell's lookup costs one logarithm, shared by all members (the knot at or left of each of
equal parts of log r, per member), a step or two along the knots and a cubic in the
power form of its interval.
"""

import dataclasses
import math
import warnings

import numba
import numpy as np

from ..units import STANDARD_GRAVITY

POLARITIES = ("normal", "inverse")
_MAX_HALVINGS = 60
#: the tables are placed to the bound over this factor at the check points (see the module)
_MARGIN = 10.0
#: equal parts of log r of the lookup's index
_INDEX_PARTS = 16384


@dataclasses.dataclass(frozen=True, eq=False)
class DisplacementTables:
    """The tabulated D_1(r) [m] of a record set under a peak of 1 g, one table per
    (record, polarity) "member" of the suite; r = ky/PGA [-].

    Attributes:
        members: (record name, polarity) of each table, length n_members.
        knots: r of each table's knots [-], padded with +inf, shape (n_members, n_knots_max).
        values: D_1 at the knots [m]; slopes: dD_1/dr [m], shaped as knots.
        counts: knots of each table, shape (n_members,).
        r_min: below it a cell runs on the exact engine [-]; r_top: above it D = 0, per member.
        rtol, atol_m: the bound enforced at the check points (see the module).
        motions: (samples [m/s²], dt [s], polarity) of each member's record scaled to 1 g,
            for the exact engine (plain arrays: the tables travel to Dask workers).
        g: one g [m/s²].
        pieces: per member and interval, (r_k, r_k+1, then the cubic's coefficients in
            powers of r - r_k [m, m, m, m]); rows past the last interval hold +inf:
            shape (n_members, n_knots_max, 6).
        index: the interval of each member holding the left edge of each of equal parts of
            log r over [r_min, max r_top], shape (n_parts, n_members) (the lookup starts there).
        index_scale: the index's parts per unit of ln r [-].
    """

    members: tuple
    knots: np.ndarray
    values: np.ndarray
    slopes: np.ndarray
    counts: np.ndarray
    r_min: float
    r_top: np.ndarray
    rtol: float
    atol_m: float
    motions: tuple
    g: float
    pieces: np.ndarray
    index: np.ndarray
    index_scale: float

    def __repr__(self):
        return (f"DisplacementTables({len(self.members)} members, {int(self.counts.sum())} knots, "
                f"bound max({self.rtol:g} D, {self.atol_m:g} m) at PGA 1 g)")

    @classmethod
    def build(cls, records, polarity: str = "both", *, rtol: float = 1e-6, atol_m: float = 1e-6, r_min: float = 1e-3,
              g: float = STANDARD_GRAVITY):
        """Tabulate every record of ``records`` (a Record, a sequence or mapping of them,
        a RecordSet) in ``polarity`` ("both", "normal" or "inverse") to the bound
        max(rtol · D, atol_m) [m] at PGA 1 g; cells with ky/PGA < ``r_min`` run exact."""
        named = _named_records(records)
        if polarity not in ("both",) + POLARITIES:
            raise ValueError(f"polarity must be one of ('both', 'normal', 'inverse'), got {polarity!r}")
        if not 0 < r_min < 1:
            raise ValueError(f"r_min={r_min!r} must lie in (0, 1)")
        if not (rtol > 0 and atol_m > 0):
            raise ValueError(f"rtol={rtol!r} and atol_m={atol_m!r} must be > 0")
        polarities = POLARITIES if polarity == "both" else (polarity,)
        members, tables, tops, motions = [], [], [], []
        for name, record in named:
            unit = record.scaled(g / record.peak_acceleration)
            for pol in polarities:
                a = unit.acceleration_m_s2 * (1.0 if pol == "normal" else -1.0)
                top = float(np.max(a)) / g
                members.append((name, pol))
                motions.append((np.asarray(unit.acceleration_m_s2), unit.dt, pol))
                tops.append(top)
                tables.append(_tabulate(unit, pol, r_min, top, rtol, atol_m, g) if top > r_min else
                              (np.array([r_min]), np.zeros(1), np.zeros(1)))
        n = max(len(t[0]) for t in tables)
        pad = lambda k, fill: np.array([np.concatenate([t[k], np.full(n - len(t[k]), fill)]) for t in tables])
        knots, values, slopes, tops = pad(0, np.inf), pad(1, 0.0), pad(2, 0.0), np.array(tops)
        r_hi = max(float(tops.max()), 2 * r_min)
        counts = np.array([len(t[0]) for t in tables])
        return cls(members=tuple(members), knots=knots, values=values, slopes=slopes, counts=counts,
                   r_min=float(r_min), r_top=tops, rtol=float(rtol), atol_m=float(atol_m), motions=tuple(motions),
                   g=float(g), pieces=_pieces(knots, values, slopes, counts),
                   index=_index(knots, r_min, r_hi, _INDEX_PARTS), index_scale=_INDEX_PARTS / math.log(r_hi / r_min))

    def select(self, record: str, polarity: str) -> "DisplacementTables":
        """The table of one member (a record's name and "normal" or "inverse") alone."""
        if (record, polarity) not in self.members:
            raise ValueError(f"no member ({record!r}, {polarity!r}); members: {list(self.members)}")
        k = self.members.index((record, polarity))
        one = slice(k, k + 1)
        return dataclasses.replace(self, members=self.members[one], knots=self.knots[one], values=self.values[one],
                                   slopes=self.slopes[one], counts=self.counts[one], r_top=self.r_top[one],
                                   motions=self.motions[one], pieces=self.pieces[one], index=self.index[:, one])

    def displacement(self, ky_g, pga_g, method: str = "table") -> np.ndarray:
        """D [m] of every member at each cell: shape ``(n_members, *cells)`` (cells: ky and pga broadcast);
        ``ky_g`` [g] > 0 and ``pga_g`` [g] >= 0 (NaN stays NaN); ``method`` "table" or "exact"."""
        ky, pga = _broadcast(ky_g, pga_g)
        flat_ky, flat_pga = ky.ravel(), pga.ravel()
        if method == "exact":
            out = self.exact(flat_ky, flat_pga)
        elif method == "table":
            out = np.empty((len(self.members), flat_ky.size))
            _evaluate(*self._lookup(), flat_ky, flat_pga, *self._exact_below_r_min(flat_ky, flat_pga), out)
        else:
            raise ValueError(f"method must be 'table' or 'exact', got {method!r}")
        return out.reshape((len(self.members),) + ky.shape)

    def statistics(self, ky_g, pga_g, thresholds_m=(), method: str = "table"):
        """(median D [m], P(D > d) for each threshold d [m]) over the members at each cell,
        without storing D per member: shapes ``cells`` and ``(n_thresholds, *cells)``; NaN where
        ky or pga is NaN."""
        ky, pga = _broadcast(ky_g, pga_g)
        flat_ky, flat_pga = ky.ravel(), pga.ravel()
        thresholds = np.asarray(thresholds_m, dtype=float).reshape(-1)
        median = np.empty(flat_ky.size)
        exceed = np.empty((thresholds.size, flat_ky.size))
        if method == "table":
            _statistics(*self._lookup(), flat_ky, flat_pga, *self._exact_below_r_min(flat_ky, flat_pga), thresholds,
                        median, exceed)
        else:
            median[:], exceed[:] = statistics_of(self.displacement(flat_ky, flat_pga, method), thresholds)
        return median.reshape(ky.shape), exceed.reshape((thresholds.size,) + ky.shape)

    def _lookup(self):
        """The arguments of the compiled lookup: (pieces, index, parts per unit of ln r, r_top, r_min)."""
        return self.pieces, self.index, self.index_scale, self.r_top, self.r_min

    def _exact_below_r_min(self, ky, pga):
        """(D [m] of every member at the cells with ky/PGA < r_min, exact: (n_members, n_low);
        per cell its column there or -1)."""
        where = np.empty(ky.size, dtype=np.int64)
        n_low = _below(ky, pga, self.r_min, where)
        if n_low == 0:
            return np.empty((len(self.members), 0)), where
        low = where >= 0
        return self.exact(ky[low], pga[low]), where

    def exact(self, ky_g, pga_g) -> np.ndarray:
        """D [m] of every member at each cell (1-D ky_g, pga_g [g]) from the exact engine:
        D = p · D_1(ky/p), ky/p of all cells in one batched call per member; shape (n_members, n)."""
        from ..excitation import Record
        from ..sliding import newmark

        ky, pga = np.asarray(ky_g, float), np.asarray(pga_g, float)
        out = np.full((len(self.members), ky.size), np.nan)
        valid = np.isfinite(ky) & np.isfinite(pga)
        slides = valid & (pga > 0) & (ky < pga)
        out[:, valid & ~slides] = 0.0
        if np.any(slides):
            r = ky[slides] / pga[slides]
            for m, (samples, dt, pol) in enumerate(self.motions):
                unit = Record(samples, dt, check_peak=False)
                out[m, slides] = pga[slides] * _run(newmark, unit, r, pol, self.g)
        return out


def _broadcast(ky_g, pga_g):
    """ky and pga as float arrays of their common shape (copied where broadcast: the compiled
    loops then see one kind of array)."""
    ky, pga = np.asarray(ky_g, dtype=float), np.asarray(pga_g, dtype=float)
    shape = np.broadcast_shapes(ky.shape, pga.shape)
    full = lambda a: a if a.shape == shape else np.broadcast_to(a, shape).copy()
    return full(ky), full(pga)


def statistics_of(d, thresholds):
    """(median [m], P(D > d) for each threshold [-]) over the members of ``d`` (n_members, n):
    shapes (n,) and (n_thresholds, n); NaN where D is NaN."""
    median = np.median(d, axis=0)
    exceed = (d[None, :, :] > np.asarray(thresholds)[:, None, None]).mean(axis=1)
    exceed[:, np.isnan(median)] = np.nan
    return median, exceed


def _named_records(records):
    from ..excitation import AbstractExcitation, RecordSet

    if isinstance(records, AbstractExcitation):
        return [(getattr(records, "name", "") or "record", records)]
    if isinstance(records, RecordSet):
        return [(name, records[name]) for name in records.names]
    if isinstance(records, dict):
        return list(records.items())
    named = [(getattr(r, "name", "") or f"record {k}", r) for k, r in enumerate(records)]
    if not named:
        raise ValueError("records is empty: give at least one record")
    return named


def _run(newmark, unit, r, polarity, g):
    """D_1(r) [m] of ``unit`` (a record of peak 1 g) in ``polarity``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # r at or above the peak in this direction: D = 0, as wanted
        result = newmark(unit, np.asarray(r, float), polarity=polarity, g=g)
    return np.asarray(getattr(result, polarity), float)


def _tabulate(unit, polarity, r_min, top, rtol, atol, g):
    """(knots r, D_1, dD_1/dr) of one member meeting the bound at every interval's check points."""
    from ..sliding import downslope, newmark

    exact = lambda r: _run(newmark, unit, r, polarity, g)
    sign = 1.0 if polarity == "normal" else -1.0
    derivative = lambda r: downslope(unit, r, sign, g)[1]
    knots = np.unique(np.concatenate([np.geomspace(r_min, top, 65), np.linspace(r_min, top, 65)]))
    values, slopes = _values(exact, knots, top), _slopes(derivative, knots, top)
    values[-1], slopes[-1] = 0.0, 0.0
    return _refine(exact, derivative, knots, values, slopes, rtol / _MARGIN, atol / _MARGIN, top)


def _values(exact, r, top):
    """D_1(r) [m]; 0 from r_top on."""
    return np.where(r >= top, 0.0, exact(r))


def _slopes(derivative, r, top):
    """dD_1/dr [m] from the exact engine's ``derivative``; 0 from r_top on."""
    below = r < top
    slopes = np.zeros(r.shape)
    if np.any(below):
        slopes[below] = derivative(r[below])
    return slopes


def _refine(exact, derivative, knots, values, slopes, rtol, atol, top):
    """Halve every interval that fails the bound or monotonicity at its check points until
    none does, checking only the halves of those halved; returns (knots, values, slopes).
    A halved interval's midpoint is its new knot and its quarter points the midpoints of
    its halves: those exact runs are reused."""
    pending = np.ones(knots.size - 1, dtype=bool)  # intervals to check, by their left knot
    # (r [-], D_1 [m]) at each interval's midpoint where known (NaN elsewhere), by left knot
    middle = np.full((knots.size - 1, 2), np.nan)
    for _ in range(_MAX_HALVINGS):
        bad = np.zeros(knots.size - 1, dtype=bool)
        failing, points, truth = _failing(exact, knots, values, slopes, pending, middle[pending], rtol, atol)
        bad[pending] = failing
        if not np.any(bad):
            return knots, values, slopes
        points, truth = points[failing], truth[failing]
        new = points[:, 1]
        new_values, new_slopes = np.where(new >= top, 0.0, truth[:, 1]), _slopes(derivative, new, top)
        order = np.argsort(np.concatenate([knots, new]), kind="stable")
        knots = np.concatenate([knots, new])[order]
        values = np.concatenate([values, new_values])[order]
        slopes = np.concatenate([slopes, new_slopes])[order]
        # the halves: each halved interval's left part and the new knot's right part
        pending = np.concatenate([bad, [False], np.ones(new.size, dtype=bool)])[order][:-1]
        left = np.full((bad.size + 1, 2), np.nan)
        left[:-1][bad] = np.column_stack([points[:, 0], truth[:, 0]])
        middle = np.concatenate([left, np.column_stack([points[:, 2], truth[:, 2]])])[order][:-1]
    raise RuntimeError(f"the table did not meet max({rtol:g} D, {atol:g} m) after {_MAX_HALVINGS} halvings "
                       f"near r = {knots[:-1][pending][:5]}")


def _failing(exact, knots, values, slopes, which, middle, rtol, atol):
    """For the intervals ``which`` (a mask by left knot), with (r, D_1) at their midpoints
    where known (``middle``, (n, 2), NaN elsewhere: a midpoint within a rounding of the
    exact one): (True where the Hermite interpolant misses the bound at a quarter point or
    the midpoint, or fails Fritsch & Carlson's monotonicity condition; the three points r
    [-] and D_1 there [m], each shape (n, 3))."""
    x0, x1 = knots[:-1][which], knots[1:][which]
    y0, y1, d0, d1 = values[:-1][which], values[1:][which], slopes[:-1][which], slopes[1:][which]
    h = x1 - x0
    points = x0[:, None] + np.array([0.25, 0.5, 0.75])[None, :] * h[:, None]
    known = ~np.isnan(middle[:, 1])
    points[known, 1] = middle[known, 0]
    truth = np.empty(points.shape)
    truth[known, 1] = middle[known, 1]
    unknown = np.ones(points.shape, dtype=bool)
    unknown[known, 1] = False
    truth[unknown] = exact(points[unknown])
    fractions = (points - x0[:, None]) / h[:, None]
    guess = _hermite(y0[:, None], y1[:, None], d0[:, None], d1[:, None], h[:, None], fractions)
    missed = np.any(np.abs(guess - truth) > np.maximum(rtol * np.abs(truth), atol), axis=1)
    secant = (y1 - y0) / h
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha, beta = d0 / secant, d1 / secant
    flat = secant == 0
    wrong_way = ~flat & ((alpha < 0) | (beta < 0) | (alpha**2 + beta**2 > 9))
    steps_in_flat = flat & ((d0 != 0) | (d1 != 0))
    # an interval of adjacent floats cannot be halved: it passes or the table fails
    splittable = h > 4 * np.spacing(x1)
    return (missed | ((wrong_way | steps_in_flat) & (np.abs(y0 - y1) > atol))) & splittable, points, truth


def _hermite(y0, y1, d0, d1, h, t):
    t2, t3 = t * t, t * t * t
    return (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * d0 + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * h * d1


def _pieces(knots, values, slopes, counts):
    """Each interval's (r_k, r_k+1, c0, c1, c2, c3): the Hermite cubic as c0 + c1 x + c2 x² + c3 x³,
    x = r - r_k; +inf past the last interval. Shape (n_members, n_knots_max, 6)."""
    out = np.full(knots.shape + (6,), np.inf)
    for m, k in enumerate(counts):
        x, y, d = knots[m, :k], values[m, :k], slopes[m, :k]
        h = np.diff(x)
        secant = np.diff(y) / h
        out[m, :k - 1] = np.stack([x[:-1], x[1:], y[:-1], d[:-1], (3 * secant - 2 * d[:-1] - d[1:]) / h,
                                   (d[:-1] + d[1:] - 2 * secant) / h**2], axis=1)
    return out


def _index(knots, r_min, r_hi, parts):
    """The index of each member's last knot <= the left edge of each of ``parts`` equal
    parts of log r over [r_min, r_hi]: shape (parts, n_members), int32 (a part's members side by side)."""
    edges = r_min * np.exp(math.log(r_hi / r_min) * np.arange(parts) / parts)
    starts = [np.maximum(np.searchsorted(k, edges, side="right") - 1, 0) for k in knots]
    return np.ascontiguousarray(np.array(starts, dtype=np.int32).T)


@numba.njit(cache=True, nogil=True)
def _below(ky, pga, r_min, where):
    """Number the cells with 0 < ky < r_min · pga (finite) in ``where`` (0, 1, ...; -1 elsewhere); returns how many."""
    n_low = 0
    for i in range(ky.size):
        k, p = ky[i], pga[i]
        if k == k and p == p and p > 0.0 and k < r_min * p and abs(k) < np.inf and abs(p) < np.inf:
            where[i] = n_low
            n_low += 1
        else:
            where[i] = -1
    return n_low


@numba.njit(cache=True, nogil=True, inline="always")
def _unit(pieces, index, m, part, r):
    """D_1(r) [m] of member m by its table, for r_min <= r < r_top; ``part``: r's part of the index."""
    k = index[part, m]
    while pieces[m, k, 1] <= r:  # the last interval ends at r_top > r
        k += 1
    while k > 0 and pieces[m, k, 0] > r:  # log r rounded into the next part
        k -= 1
    x = r - pieces[m, k, 0]
    return pieces[m, k, 2] + x * (pieces[m, k, 3] + x * (pieces[m, k, 4] + x * pieces[m, k, 5]))


@numba.njit(cache=True, nogil=True, inline="always")
def _cell(pieces, index, per_log, tops, r_min, ky, pga, low, exact_low, buffer):
    """D [m] of every member at one cell into ``buffer``: NaN where ky or pga is NaN, the
    exact runs ``exact_low[:, low]`` where ``low`` >= 0 (r < r_min), else the tables."""
    if not (ky == ky) or not (pga == pga):
        buffer[:] = np.nan
    elif low >= 0:
        buffer[:] = exact_low[:, low]
    else:
        cell_displacements(pieces, index, per_log, tops, r_min, ky, pga, buffer)


@numba.njit(cache=True, nogil=True, inline="always")
def cell_displacements(pieces, index, per_log, tops, r_min, ky, pga, buffer):
    """D [m] of every member at one cell from the tables into ``buffer`` (ky [g] >= r_min · pga,
    pga [g] >= 0; the arguments before them: :meth:`DisplacementTables._lookup`)."""
    if pga <= 0.0 or ky >= pga:
        buffer[:] = 0.0
        return
    r = ky / pga
    part = min(int(math.log(r / r_min) * per_log), index.shape[0] - 1)  # one logarithm per cell
    for m in range(pieces.shape[0]):
        if r >= tops[m]:
            buffer[m] = 0.0
        else:
            buffer[m] = pga * _unit(pieces, index, m, part, r)


@numba.njit(cache=True, nogil=True)
def _evaluate(pieces, index, per_log, tops, r_min, ky, pga, exact_low, where_low, out):
    buffer = np.empty(pieces.shape[0])
    for i in range(ky.size):
        _cell(pieces, index, per_log, tops, r_min, ky[i], pga[i], where_low[i], exact_low, buffer)
        out[:, i] = buffer


@numba.njit(cache=True, nogil=True)
def _statistics(pieces, index, per_log, tops, r_min, ky, pga, exact_low, where_low, thresholds, median, exceed):
    n = pieces.shape[0]
    buffer, values, order = np.empty(n), np.empty(n), np.arange(n)
    for i in range(ky.size):
        _cell(pieces, index, per_log, tops, r_min, ky[i], pga[i], where_low[i], exact_low, buffer)
        if not (buffer[0] == buffer[0]):
            median[i] = np.nan
            exceed[:, i] = np.nan
            continue
        for j in range(thresholds.size):
            above = 0
            for m in range(n):
                if buffer[m] > thresholds[j]:
                    above += 1
            exceed[j, i] = above / n
        median[i] = median_of(buffer, order, values)


@numba.njit(cache=True, nogil=True, inline="always")
def median_of(buffer, order, values):
    """The median of ``buffer`` (n,), the mean of its two middle values for an even n: 0 where
    more than half of it is 0 and none below; else its n // 2 + 1 smallest values sorted into
    the head of ``values`` (n,), starting from the permutation ``order`` (int, n) of the last
    call, updated: a neighbouring cell's members come nearly in order, and a value above the
    head's largest costs one comparison."""
    n = buffer.size
    zeros, negative = 0, False
    for m in range(n):
        zeros += buffer[m] == 0.0
        negative |= buffer[m] < 0.0
    if zeros > n // 2 and not negative:  # both middle values are 0
        return 0.0
    for t in range(n):
        values[t] = buffer[order[t]]
    head = n // 2 + 1
    for a in range(1, n):  # insertion into the sorted head
        v, o = values[a], order[a]
        if a < head:
            b = a - 1
        elif v < values[head - 1]:  # the head's largest leaves it for a's place
            values[a], order[a] = values[head - 1], order[head - 1]
            b = head - 2
        else:
            continue
        while b >= 0 and values[b] > v:
            values[b + 1] = values[b]
            order[b + 1] = order[b]
            b -= 1
        values[b + 1] = v
        order[b + 1] = o
    return 0.5 * (values[(n - 1) // 2] + values[n // 2])
