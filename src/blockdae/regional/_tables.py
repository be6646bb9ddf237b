"""Each record's rigid-block displacement as one function of ky/PGA, tabulated with the
exact engine and interpolated by cubic Hermite with its exact derivative.

A record scaled by s gives D_s(ky) = s · D_1(ky / s) exactly (the block's equation
v' = s a(t) - ky g is s times the unscaled one at ky / s, event times unchanged). With
D_1 the displacement under the record scaled to a peak of 1 g, a cell of peak ground
acceleration p [g] and yield acceleration ky [g] slides D = p · D_1(ky / p) [m]: one
function of r = ky / PGA per record and polarity, whatever the cell.

The table of each (record, polarity): knots r_k in [r_min, r_top] with D_1(r_k) and dD_1/dr
(r_k) from the exact engine (:func:`blockdae.newmark`, its ``derivative=True``, exact
through the event times); r_top is the record's largest acceleration in the sliding
direction over its peak |a| (above it D = 0 exactly); below r_min a cell runs on the exact
engine. The knots are placed by halving: every interval is checked at its quarter points
and midpoint against exact runs, and halved until the cubic Hermite interpolant meets
``|D_table - D_exact| <= max(rtol · D_exact, atol_m)`` [m, at PGA 1 g] at all three and is
monotone there (Fritsch & Carlson 1980: α² + β² <= 9). Halving uses central differences
of exact runs for speed; the final knots carry the exact derivatives, and the check is
repeated on that final interpolant until it passes.
"""

import dataclasses
import warnings

import numba
import numpy as np

from ..units import STANDARD_GRAVITY

POLARITIES = ("normal", "inverse")
#: knots evaluated together in one derivative call (a fixed size: JAX compiles once per record length)
_DERIVATIVE_BATCH = 1024
_MAX_HALVINGS = 60


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
        buckets: for each member, the knot at or left of each of equal parts of [r_min, r_top]
            (the lookup starts there), shape (n_members, n_buckets).
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
    buckets: np.ndarray

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
        knots, tops = pad(0, np.inf), np.array(tops)
        return cls(members=tuple(members), knots=knots, values=pad(1, 0.0), slopes=pad(2, 0.0),
                   counts=np.array([len(t[0]) for t in tables]), r_min=float(r_min), r_top=tops,
                   rtol=float(rtol), atol_m=float(atol_m), motions=tuple(motions), g=float(g),
                   buckets=_buckets(knots, r_min, tops, 4 * n))

    def select(self, record: str, polarity: str) -> "DisplacementTables":
        """The table of one member (a record's name and "normal" or "inverse") alone."""
        if (record, polarity) not in self.members:
            raise ValueError(f"no member ({record!r}, {polarity!r}); members: {list(self.members)}")
        k = self.members.index((record, polarity))
        one = slice(k, k + 1)
        return dataclasses.replace(self, members=self.members[one], knots=self.knots[one], values=self.values[one],
                                   slopes=self.slopes[one], counts=self.counts[one], r_top=self.r_top[one],
                                   motions=self.motions[one], buckets=self.buckets[one])

    def displacement(self, ky_g, pga_g, method: str = "table") -> np.ndarray:
        """D [m] of every member at each cell: shape ``(n_members, *cells)`` (cells: ky and pga broadcast);
        ``ky_g`` [g] > 0 and ``pga_g`` [g] >= 0 (NaN stays NaN); ``method`` "table" or "exact"."""
        ky, pga = np.broadcast_arrays(np.asarray(ky_g, float), np.asarray(pga_g, float))
        flat_ky, flat_pga = ky.ravel(), pga.ravel()
        if method == "exact":
            out = self.exact(flat_ky, flat_pga)
        elif method == "table":
            out = np.empty((len(self.members), flat_ky.size))
            _evaluate(self.knots, self.values, self.slopes, self.buckets, self.r_top, self.r_min, flat_ky, flat_pga,
                      *self._exact_below_r_min(flat_ky, flat_pga), out)
        else:
            raise ValueError(f"method must be 'table' or 'exact', got {method!r}")
        return out.reshape((len(self.members),) + ky.shape)

    def statistics(self, ky_g, pga_g, thresholds_m=(), method: str = "table"):
        """(median D [m], P(D > d) for each threshold d [m]) over the members at each cell,
        without storing D per member: shapes ``cells`` and ``(n_thresholds, *cells)``; NaN where
        ky or pga is NaN."""
        ky, pga = np.broadcast_arrays(np.asarray(ky_g, float), np.asarray(pga_g, float))
        flat_ky, flat_pga = ky.ravel(), pga.ravel()
        thresholds = np.asarray(thresholds_m, dtype=float).reshape(-1)
        median = np.empty(flat_ky.size)
        exceed = np.empty((thresholds.size, flat_ky.size))
        if method == "table":
            _statistics(self.knots, self.values, self.slopes, self.buckets, self.r_top, self.r_min, flat_ky, flat_pga,
                        *self._exact_below_r_min(flat_ky, flat_pga), thresholds, median, exceed)
        else:
            median[:], exceed[:] = statistics_of(self.displacement(flat_ky, flat_pga, method), thresholds)
        return median.reshape(ky.shape), exceed.reshape((thresholds.size,) + ky.shape)

    def _exact_below_r_min(self, ky, pga):
        """(D [m] of every member at the cells with ky/PGA < r_min, exact: (n_members, n_low);
        per cell its column there or -1)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            low = np.isfinite(ky) & np.isfinite(pga) & (pga > 0) & (ky < self.r_min * pga)
        where = np.full(ky.size, -1, dtype=np.int64)
        where[low] = np.arange(np.count_nonzero(low))
        exact = self.exact(ky[low], pga[low]) if np.any(low) else np.empty((len(self.members), 0))
        return exact, where

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


def _run(newmark, unit, r, polarity, g, derivative=False):
    """D_1(r) [m] (and dD_1/dr [m]) of ``unit`` (a record of peak 1 g) in ``polarity``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # r at or above the peak in this direction: D = 0, as wanted
        result = newmark(unit, np.asarray(r, float), polarity=polarity, g=g, derivative=derivative)
    d = np.asarray(getattr(result, polarity), float)
    return (d, np.asarray(getattr(result, f"{polarity}_dky"), float)) if derivative else d


def _exact_slopes(unit, r, polarity, g):
    """dD_1/dr [m] at ``r``, exact, in batches of a fixed size (JAX compiles once per record length)."""
    from ..sliding import newmark

    out = np.empty(r.size)
    for start in range(0, r.size, _DERIVATIVE_BATCH):
        part = r[start:start + _DERIVATIVE_BATCH]
        padded = np.concatenate([part, np.full(_DERIVATIVE_BATCH - part.size, part[-1])])
        out[start:start + part.size] = _run(newmark, unit, padded, polarity, g, derivative=True)[1][:part.size]
    return out


def _tabulate(unit, polarity, r_min, top, rtol, atol, g):
    """(knots r, D_1, dD_1/dr) of one member meeting the bound at every interval's check points."""
    from ..sliding import newmark

    exact = lambda r: _run(newmark, unit, r, polarity, g)
    knots = np.unique(np.concatenate([np.geomspace(r_min, top, 65), np.linspace(r_min, top, 65)]))
    values = exact(knots)
    values[-1] = 0.0
    # placement: slopes by central differences of exact runs (cheap), intervals halved until they pass
    slopes = _central_slopes(exact, knots, top)
    knots, values, slopes = _refine(exact, knots, values, slopes, rtol / 10, atol / 10,
                                    lambda r: _central_slopes(exact, r, top))
    # the table: exact slopes at the final knots, checked again (and halved where needed)
    slopes = _exact_slopes(unit, knots, polarity, g)
    slopes[-1] = 0.0
    return _refine(exact, knots, values, slopes, rtol, atol, lambda r: _exact_slopes(unit, r, polarity, g))


def _central_slopes(exact, r, top):
    h = 1e-7 * np.maximum(r, 1e-3)
    lo, hi = np.maximum(r - h, 1e-12), np.minimum(r + h, top)
    d = np.where(hi > lo, (exact(hi) - exact(lo)) / (hi - lo), 0.0)
    d[-1] = 0.0 if r[-1] >= top else d[-1]
    return d


def _refine(exact, knots, values, slopes, rtol, atol, slopes_at):
    """Halve every interval that fails the bound or monotonicity at its check points until
    none does; returns (knots, values, slopes)."""
    for _ in range(_MAX_HALVINGS):
        bad = _failing(exact, knots, values, slopes, rtol, atol)
        if not np.any(bad):
            return knots, values, slopes
        new = 0.5 * (knots[:-1][bad] + knots[1:][bad])
        new_values, new_slopes = exact(new), slopes_at(new)
        order = np.argsort(np.concatenate([knots, new]), kind="stable")
        knots = np.concatenate([knots, new])[order]
        values = np.concatenate([values, new_values])[order]
        slopes = np.concatenate([slopes, new_slopes])[order]
    raise RuntimeError(f"the table did not meet max({rtol:g} D, {atol:g} m) after {_MAX_HALVINGS} halvings "
                       f"near r = {knots[:-1][bad][:5]}")


def _failing(exact, knots, values, slopes, rtol, atol) -> np.ndarray:
    """Per interval: True where the Hermite interpolant misses the bound at a quarter point
    or the midpoint, or fails Fritsch & Carlson's monotonicity condition."""
    h = np.diff(knots)
    fractions = np.array([0.25, 0.5, 0.75])
    points = knots[:-1, None] + fractions[None, :] * h[:, None]
    truth = exact(points.ravel()).reshape(points.shape)
    guess = _hermite(values[:-1, None], values[1:, None], slopes[:-1, None], slopes[1:, None], h[:, None],
                     fractions[None, :])
    missed = np.any(np.abs(guess - truth) > np.maximum(rtol * np.abs(truth), atol), axis=1)
    secant = np.diff(values) / h
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha, beta = slopes[:-1] / secant, slopes[1:] / secant
    flat = secant == 0
    wrong_way = ~flat & ((alpha < 0) | (beta < 0) | (alpha**2 + beta**2 > 9))
    steps_in_flat = flat & ((slopes[:-1] != 0) | (slopes[1:] != 0))
    # an interval of adjacent floats cannot be halved: it passes or the table fails
    splittable = h > 4 * np.spacing(knots[1:])
    return (missed | ((wrong_way | steps_in_flat) & (np.abs(values[:-1] - values[1:]) > atol))) & splittable


def _hermite(y0, y1, d0, d1, h, t):
    t2, t3 = t * t, t * t * t
    return (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * d0 + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * h * d1


def _buckets(knots, r_min, tops, n_buckets):
    """Per member, the index of the last knot <= the left edge of each of ``n_buckets``
    equal parts of [r_min, r_top]: shape (n_members, n_buckets)."""
    out = np.zeros((knots.shape[0], n_buckets), dtype=np.int64)
    for m, top in enumerate(tops):
        if top > r_min:
            edges = r_min + (top - r_min) * np.arange(n_buckets) / n_buckets
            out[m] = np.maximum(np.searchsorted(knots[m], edges, side="right") - 1, 0)
    return out


@numba.njit(cache=True, nogil=True, inline="always")
def _unit(knots, values, slopes, buckets, r_min, per_bucket, r):
    """D_1(r) [m] of one member by its table, for r_min <= r < r_top."""
    b = min(int((r - r_min) * per_bucket), buckets.size - 1)
    lo = buckets[b]
    while knots[lo + 1] <= r:  # knots[-1] is r_top > r
        lo += 1
    h = knots[lo + 1] - knots[lo]
    t = (r - knots[lo]) / h
    t2 = t * t
    t3 = t2 * t
    return ((2 * t3 - 3 * t2 + 1) * values[lo] + (t3 - 2 * t2 + t) * h * slopes[lo]
            + (-2 * t3 + 3 * t2) * values[lo + 1] + (t3 - t2) * h * slopes[lo + 1])


@numba.njit(cache=True, nogil=True, inline="always")
def _cell(knots, values, slopes, buckets, tops, r_min, ky, pga, low, exact_low, buffer):
    """D [m] of every member at one cell into ``buffer``: NaN where ky or pga is NaN, the
    exact runs ``exact_low[:, low]`` where ``low`` >= 0 (r < r_min), else the tables."""
    if not (ky == ky) or not (pga == pga):
        buffer[:] = np.nan
        return
    if low >= 0:
        buffer[:] = exact_low[:, low]
        return
    if pga <= 0.0 or ky >= pga:
        buffer[:] = 0.0
        return
    r = ky / pga
    for m in range(knots.shape[0]):
        top = tops[m]
        if r >= top:
            buffer[m] = 0.0
        else:
            buffer[m] = pga * _unit(knots[m], values[m], slopes[m], buckets[m], r_min,
                                    buckets.shape[1] / (top - r_min), r)


@numba.njit(cache=True, nogil=True)
def _evaluate(knots, values, slopes, buckets, tops, r_min, ky, pga, exact_low, where_low, out):
    buffer = np.empty(knots.shape[0])
    for i in range(ky.size):
        _cell(knots, values, slopes, buckets, tops, r_min, ky[i], pga[i], where_low[i], exact_low, buffer)
        out[:, i] = buffer


@numba.njit(cache=True, nogil=True)
def _statistics(knots, values, slopes, buckets, tops, r_min, ky, pga, exact_low, where_low, thresholds, median, exceed):
    n = knots.shape[0]
    buffer = np.empty(n)
    for i in range(ky.size):
        _cell(knots, values, slopes, buckets, tops, r_min, ky[i], pga[i], where_low[i], exact_low, buffer)
        if not (buffer[0] == buffer[0]):
            median[i] = np.nan
            exceed[:, i] = np.nan
            continue
        for a in range(1, n):  # insertion sort: a few tens of members
            v = buffer[a]
            b = a - 1
            while b >= 0 and buffer[b] > v:
                buffer[b + 1] = buffer[b]
                b -= 1
            buffer[b + 1] = v
        median[i] = 0.5 * (buffer[(n - 1) // 2] + buffer[n // 2])
        for j in range(thresholds.size):
            above = 0
            for m in range(n):
                if buffer[m] > thresholds[j]:
                    above += 1
            exceed[j, i] = above / n
