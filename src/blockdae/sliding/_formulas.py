"""Newmark's sliding formula and the adjustment factor of the SMiRT paper on Newmark's formula.

A body resting with friction coefficient μ on a base whose acceleration is one
rectangular pulse of height A g and duration t0 slides from t = 0 until its velocity
μ g t catches the base's, V = A g t0, at t1 = A t0 / μ. The largest displacement
relative to the base is (Newmark 1965; the SMiRT paper on Newmark's formula, eqs. 1-3)

    R_d = V² / (2 μ g) · (1 - μ / A)                                  (eq. 1)
    Sd  = (A g t0² / 2) · (2 A / μ - 1)   (the base displacement at t1) (eq. 2)
    R_d = (Sd / 2) · (A/μ - 1) / (A/μ - 0.5)                          (eq. 3)

exactly for that pulse. For earthquakes the SMiRT paper on Newmark's formula takes Sd from the absolute
displacement spectrum at its long-period end and multiplies eq. 3 by an adjustment
factor (eq. 4). The printed eq. 4 is garbled; we read it, as its text describes it
("the larger the coefficient of friction, the smaller the factor, but proportional to
the square root of the size of the base motion"), as

    Adj = a · √A / (μ + b),   a = 0.19, b = 0.06,                     (eq. 4)

with a and b parameters of :class:`AdjustmentFactor` and :func:`fit_adjustment_factor`
refitting them to an ensemble's results. Accelerations A are in g, as in the paper.
"""

import dataclasses

import numpy as np

from ..units import STANDARD_GRAVITY


def newmark_rd(pgv, pga, mu, g: float = STANDARD_GRAVITY):
    """Newmark's sliding distance from the peak base velocity (the SMiRT paper on Newmark's formula, eq. 1).

    Args:
        pgv: peak base velocity V [m/s].
        pga: peak base acceleration A [g].
        mu: friction coefficient μ > 0 [-].
        g: the value of one g [m/s²].

    Returns:
        R_d = V²/(2μg)·(1 - μ/A) [m], 0 where A <= μ (the body does not slide);
        arguments broadcast, a float for scalars. Exact for one rectangular pulse.
    """
    pgv, pga, mu = _nonnegative("pgv", pgv, "m/s"), _positive("pga", pga, "g"), _positive("mu", mu, "-")
    g = float(_positive("g", g, "m/s²"))
    return _scalar(pgv**2 / (2.0 * mu * g) * (1.0 - 1.0 / np.maximum(pga / mu, 1.0)))


def pulse_sd(pga, duration, mu, g: float = STANDARD_GRAVITY):
    """Base displacement when the body stops sliding under one rectangular pulse
    (the SMiRT paper on Newmark's formula, eq. 2): the Sd that makes eq. 3 exact for that pulse.

    Args:
        pga: pulse height A [g]; duration: pulse length t0 [s]; mu: μ > 0 [-];
        g: the value of one g [m/s²].

    Returns:
        Sd = (A g t0²/2)·(2A/μ - 1) [m] where A > μ; where A <= μ the body never
        slides and Sd is the base displacement at the end of the pulse, A g t0²/2.
    """
    pga, t0, mu = _positive("pga", pga, "g"), _positive("duration", duration, "s"), _positive("mu", mu, "-")
    g = float(_positive("g", g, "m/s²"))
    return _scalar(0.5 * pga * g * t0**2 * np.maximum(2.0 * pga / mu - 1.0, 1.0))


def newmark_rd_sd(sd, pga, mu):
    """Newmark's sliding distance from the base displacement Sd (the SMiRT paper on Newmark's formula, eq. 3).

    Args:
        sd: the largest base displacement Sd [m] (for an earthquake, the absolute
            displacement spectrum at its long-period end; for a pulse, :func:`pulse_sd`).
        pga: peak base acceleration A [g]; mu: friction coefficient μ > 0 [-].

    Returns:
        R_d = (Sd/2)·(A/μ - 1)/(A/μ - 0.5) [m], 0 where A <= μ; arguments broadcast.
    """
    sd, pga, mu = _nonnegative("sd", sd, "m"), _positive("pga", pga, "g"), _positive("mu", mu, "-")
    ratio = np.maximum(pga / mu, 1.0)
    return _scalar(0.5 * sd * (ratio - 1.0) / (ratio - 0.5))


@dataclasses.dataclass(frozen=True)
class AdjustmentFactor:
    """The SMiRT paper's adjustment factor Adj = scale·√A/(μ + offset) (eq. 4, read as in the
    module docstring); the paper's values are the defaults.

    Args:
        scale: a > 0 [-] (the SMiRT paper on Newmark's formula: 0.19).
        offset: b [-] (the SMiRT paper on Newmark's formula: 0.06); μ + b must stay positive.

    Calling it, ``adj(pga, mu)`` with A [g] and μ [-], gives the factor [-] (arguments
    broadcast); ``adj(pga, mu) * newmark_rd_sd(sd, pga, mu)`` is the adjusted R_d [m].
    """

    scale: float = 0.19
    offset: float = 0.06

    def __post_init__(self):
        object.__setattr__(self, "scale", float(_positive("scale", self.scale, "-")))
        offset = float(self.offset)
        if not np.isfinite(offset):
            raise ValueError(f"offset must be finite [-], got {offset!r}")
        object.__setattr__(self, "offset", offset)

    def __call__(self, pga, mu):
        pga, mu = _positive("pga", pga, "g"), _positive("mu", mu, "-")
        if np.any(mu + self.offset <= 0):
            raise ValueError(f"mu + offset must be positive; offset={self.offset!r} and mu={float(np.min(mu))!r}")
        return _scalar(self.scale * np.sqrt(pga) / (mu + self.offset))


def fit_adjustment_factor(rc, rd, pga, mu, *, space: str = "log") -> AdjustmentFactor:
    """Least-squares refit of eq. 4's two coefficients so that Adj·R_d matches R_c.

    Args:
        rc: computed sliding distances R_c [m] (e.g. means over records), any shape.
        rd: eq. 3's R_d for the same cases [m], broadcastable to ``rc``.
        pga: A [g]; mu: μ [-]; broadcastable to ``rc``.
        space: "log" (default) minimises Σ (ln R_c - ln(Adj·R_d))², so that every case
            counts by its relative error (R_c spans decades over A); "linear" minimises
            Σ (R_c - Adj·R_d)². Cases with R_d = 0 (A <= μ) are left out, and in "log"
            also those with R_c = 0.

    Returns:
        The :class:`AdjustmentFactor` with the fitted ``scale`` and ``offset``.

    The model is linear in the scale for a fixed offset, so the scale is eliminated in
    closed form (variable projection) and the offset minimises the remaining one-variable
    sum of squares over (-min μ, 100 max μ]: a scan of 400 offsets, then a bounded Brent
    search between the neighbours of the best one (exact synthetic data give back their
    coefficients to about 1e-9 relative).
    """
    from scipy.optimize import minimize_scalar

    if space not in ("log", "linear"):
        raise ValueError(f"space must be 'log' or 'linear', got {space!r}")
    rc, rd, pga, mu = np.broadcast_arrays(_nonnegative("rc", rc, "m"), _nonnegative("rd", rd, "m"),
                                          _positive("pga", pga, "g"), _positive("mu", mu, "-"))
    keep = (rd > 0) & (rc > 0) if space == "log" else rd > 0  # R_d = 0 cases do not depend on the fit
    rc, rd, pga, mu = (x[keep].ravel() for x in (rc, rd, pga, mu))
    if rc.size < 2:
        needs = "R_c > 0 and R_d > 0" if space == "log" else "R_d > 0"
        raise ValueError(f"fit_adjustment_factor needs at least 2 cases with {needs}, got {rc.size}")
    if np.ptp(mu) == 0:
        raise ValueError("fit_adjustment_factor needs at least two values of mu to separate scale and offset")

    def scale_and_cost(offset):
        x = np.sqrt(pga) * rd / (mu + offset)  # Adj·R_d = scale · x
        if space == "log":
            r = np.log(rc) - np.log(x)
            log_scale = np.mean(r)
            return np.exp(log_scale), np.sum((r - log_scale) ** 2)
        scale = np.dot(x, rc) / np.dot(x, x)
        return scale, np.sum((rc - scale * x) ** 2)

    low, high = -np.min(mu), 100.0 * np.max(mu)
    grid = low + (high - low) * np.linspace(0.0, 1.0, 401)[1:] ** 3  # dense near the pole at -min μ
    costs = [scale_and_cost(b)[1] for b in grid]
    i = int(np.argmin(costs))
    bracket = (grid[i - 1] if i else 0.5 * (low + grid[0]), grid[min(i + 1, grid.size - 1)])
    best = minimize_scalar(lambda b: scale_and_cost(b)[1], bounds=bracket, method="bounded",
                           options={"xatol": 1e-14 * (high - low)})
    offset = best.x if best.fun <= costs[i] else grid[i]
    return AdjustmentFactor(scale=scale_and_cost(offset)[0], offset=offset)


def _positive(name, value, unit):
    return _checked(name, value, lambda x: x > 0, f"must be positive and finite [{unit}]")


def _nonnegative(name, value, unit):
    return _checked(name, value, lambda x: x >= 0, f"must be >= 0 and finite [{unit}]")


def _checked(name, value, ok, message):
    x = np.asarray(value, dtype=float)
    bad = ~(np.isfinite(x) & ok(x))
    if np.any(bad):
        raise ValueError(f"{name}={float(x[bad].flat[0] if x.ndim else x)!r} {message}")
    return x


def _scalar(x):
    return float(x) if np.ndim(x) == 0 else x
