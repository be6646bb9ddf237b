"""Displacement fragility fitted to a study table by maximum likelihood, with bootstrap bands.

The model (zero displacements treated as Bray & Travasarou 2007 treat them: a probability
of negligible displacement, and a lognormal above it):

    P(D > d0 | im) = Φ(b0 + b1 ln im)                              (a probit in ln im)
    ln D | D > d0, im ~ N(c0 + c1 ln im, σ²)                        (linear in ln im)
    P(D > d | im) = Φ(b0 + b1 ln im) · Φ((c0 + c1 ln im - ln d) / σ),   d >= d0

The likelihood factorises: the probit is fitted to the indicator D > d0 of every row
(Newton's method on its log-likelihood), the lognormal by least squares to the rows
with D > d0 (σ² its maximum-likelihood estimate, the mean squared residual). Bands come
from refitting to records drawn with replacement (all rows of a record together).
"""

import dataclasses

import numpy as np
from ..core import compact_repr

MIN_RECORDS = 10
#: columns that name the slope (or the location) of a row: a fit takes one value of each
SLOPE_COLUMNS = ("mu", "location", "ky_g", "height_m", "vs_m_s")
_LN_SQRT_2PI = 0.5 * np.log(2.0 * np.pi)


@dataclasses.dataclass(frozen=True)
class Fragility:
    """A fitted fragility (see the module's model); ``boot`` holds the bootstrap refits.

    Attributes:
        im: the name of the intensity column; d0_m: the negligible displacement [m].
        b0, b1: the probit of P(D > d0) in ln im (b1 = 0, b0 = inf: every row slid).
        c0, c1, sigma: median ln D [ln m] = c0 + c1 ln im above d0, and σ of ln D [-].
        n_records, n_rows: what it was fitted to; boot: (n_boot, 5) array of
        (b0, b1, c0, c1, sigma) refitted to resampled records (empty: none).
    """

    def __repr__(self):
        return compact_repr(self, _summary(self))

    im: str
    d0_m: float
    b0: float
    b1: float
    c0: float
    c1: float
    sigma: float
    n_records: int
    n_rows: int
    boot: np.ndarray

    @property
    def params(self) -> np.ndarray:
        return np.array([self.b0, self.b1, self.c0, self.c1, self.sigma])

    def exceedance(self, d_m, im):
        """P(D > d | im) for d [m] >= d0 and im > 0 (in the column's units), broadcast."""
        return _exceedance(self.params, np.asarray(d_m, dtype=float), _positive_im(self.im, im))

    def band(self, d_m, im, level=0.90):
        """The bootstrap band (lower, upper) of P(D > d | im) at ``level`` (central), broadcast."""
        if self.boot.size == 0:
            raise ValueError("no bootstrap refits: fit with n_boot > 0")
        d, x = np.asarray(d_m, dtype=float), _positive_im(self.im, im)
        p = np.stack([_exceedance(theta, d, x) for theta in self.boot])
        tail = 50.0 * (1.0 - level)
        return np.percentile(p, tail, axis=0), np.percentile(p, 100.0 - tail, axis=0)


def _summary(fragility) -> str:
    """One line: the median D above d0 [m] as a power of the intensity, the spread, the data."""
    f = fragility
    return (f"median D = {np.exp(f.c0):.4g} m x ({f.im})^{f.c1:.3g} above {f.d0_m:g} m, sigma ln D = {f.sigma:.3g}; "
            f"{f.n_records} records, {f.n_rows} rows, {len(f.boot)} bootstrap refits")


def fit_fragility(table, im="pga_g", displacement="max_abs_displacement_m", *, d0_m=0.01, n_boot=200, seed=0):
    """Fit P(D > d | im) to a study table by maximum likelihood, with bootstrap refits.

    Args:
        table: a DataFrame with a "record" column and one slope (one value in each of
            :data:`SLOPE_COLUMNS` it has): :func:`bd.study`'s of one μ and one location
            (the 1-D block, or ``block=bd.PlanarBlock(...)``), or ``bd.flexible(...)``'s
            of one (ky, H, Vs), its runs at several ``pga`` concatenated with a
            ``pga_g`` column.
        im: the column of the intensity measure (PGA [g], PGV, Arias intensity, Sa(T),
            a flexible mass's kmax_g...).
        displacement: the column of the displacement [m] (its absolute value is used),
            or several columns: each row's largest absolute value among them, NaN
            skipped (a flexible table's ``("normal_m", "inverse_m")``: the worse polarity).
        d0_m: displacements at or below it are negligible [m] (Bray & Travasarou: 1 cm).
        n_boot: bootstrap refits over records drawn with replacement (0: none).
        seed: of the bootstrap's random generator.

    Returns:
        A :class:`Fragility`.
    """
    x, d, records = _checked(table, im, displacement, d0_m)
    params = _fit(np.log(x), d > d0_m, np.log(np.maximum(d, d0_m)))
    names, index = np.unique(records, return_inverse=True)
    rows = [np.flatnonzero(index == i) for i in range(names.size)]
    rng = np.random.default_rng(seed)
    boot = []
    for _ in range(int(n_boot)):
        pick = np.concatenate([rows[i] for i in rng.integers(0, names.size, names.size)])
        try:
            boot.append(_fit(np.log(x[pick]), d[pick] > d0_m, np.log(np.maximum(d[pick], d0_m))))
        except ValueError:  # a draw with fewer than two distinct intensities above d0
            continue
    return Fragility(im, float(d0_m), *params, n_records=names.size, n_rows=x.size,
                     boot=np.array(boot).reshape(-1, 5))


def _exceedance(theta, d, x):
    from scipy.stats import norm  # on use: importing scipy.stats takes about a second

    b0, b1, c0, c1, sigma = theta
    ln_x = np.log(x)
    slide = 1.0 if np.isinf(b0) else norm.cdf(b0 + b1 * ln_x)
    return slide * norm.cdf((c0 + c1 * ln_x - np.log(d)) / sigma)


def _fit(u, slid, ln_d):
    """(b0, b1, c0, c1, σ) by maximum likelihood from ln im, the indicator D > d0 and ln D."""
    above = u[slid]
    if np.unique(above).size < 2:
        raise ValueError("fewer than two distinct intensities with D > d0: no lognormal fit")
    c1, c0 = np.polyfit(above, ln_d[slid], 1)
    sigma = float(np.sqrt(np.mean((ln_d[slid] - c0 - c1 * above) ** 2)))
    b0, b1 = (np.inf, 0.0) if slid.all() else _probit(u, slid)
    return np.array([b0, b1, c0, c1, sigma])


def _probit(u, y, iterations=50):
    """Maximum-likelihood probit P(y) = Φ(b0 + b1 u) by Newton's method (concave); stops
    when the step or the gradient vanishes (with separated classes the slope grows until
    the gradient does)."""
    from scipy.special import log_ndtr  # on use, as scipy.stats: a fresh process imports neither

    X = np.column_stack([np.ones_like(u), u])
    s = np.where(y, 1.0, -1.0)
    beta = np.zeros(2)
    for _ in range(iterations):
        z = s * (X @ beta)
        ratio = np.exp(-0.5 * z * z - _LN_SQRT_2PI - log_ndtr(z))  # φ/Φ, stable in the tails
        grad = X.T @ (s * ratio)
        weight = ratio * (z + ratio)
        step = np.linalg.solve((X * weight[:, None]).T @ X + 1e-12 * np.eye(2), grad)
        beta += step
        if np.max(np.abs(step)) < 1e-10 or np.max(np.abs(grad)) < 1e-9 * u.size:
            break
    return float(beta[0]), float(beta[1])


def _positive_im(name, im):
    x = np.asarray(im, dtype=float)
    bad = ~(np.isfinite(x) & (x > 0))
    if np.any(bad):
        raise ValueError(f"{name} must be positive and finite, got {float(x[bad].flat[0])!r}")
    return x


def _checked(table, im, displacement, d0_m):
    displacements = [displacement] if isinstance(displacement, str) else list(displacement)
    if not displacements:
        raise ValueError("displacement must name at least one column")
    for column in ("record", im, *displacements):
        if column not in table.columns:
            raise ValueError(f"the table has no column {column!r} (columns: {list(table.columns)})")
    for column in SLOPE_COLUMNS:
        if column in table.columns and table[column].nunique() > 1:
            raise ValueError(f"the table holds {table[column].nunique()} values of {column}: fit one slope at a "
                             f"time, e.g. table[table.{column} == {table[column].iloc[0]!r}]")
    if not (np.isfinite(d0_m) and d0_m > 0):
        raise ValueError(f"d0_m must be positive and finite [m], got {d0_m!r}")
    n = table["record"].nunique()
    if n < MIN_RECORDS:
        raise ValueError(f"the table has {n} records, fewer than {MIN_RECORDS}: too few for a fragility")
    x = table[im].to_numpy(dtype=float)
    bad = ~(np.isfinite(x) & (x > 0))
    if np.any(bad):
        row = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{im} must be positive and finite: row {row} ({table['record'].iloc[row]!r}) "
                         f"has {im}={float(x[row])!r}")
    values = np.abs(table[displacements].to_numpy(dtype=float))
    name = displacements[0] if len(displacements) == 1 else f"max |{', '.join(displacements)}|"
    missing = np.flatnonzero(np.isnan(values).all(axis=1) | np.isinf(values).any(axis=1))
    if missing.size:
        row = int(missing[0])
        raise ValueError(f"{name} is not finite: row {row} ({table['record'].iloc[row]!r}) has "
                         f"{dict(zip(displacements, values[row]))}")
    d = np.nanmax(values, axis=1)
    if np.count_nonzero(d > d0_m) < 2:
        raise ValueError(f"fewer than two rows with {name} > d0_m = {d0_m:g} m: nothing to fit")
    return x, d, table["record"].to_numpy()
