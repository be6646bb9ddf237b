"""Uncertain parameters: each a distribution with its quantile function ``ppf`` (from a
uniform number in (0, 1)) and its distribution function ``cdf``; the samplers map
uniform (quasi-)random numbers through ``ppf``."""

import dataclasses
import math

import numpy as np


def _check_positive(field, value, what):
    if not (isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and math.isfinite(value)
            and value > 0):
        raise ValueError(f"{field}={value!r} must be {what} (a finite number > 0)")
    return float(value)


def _check_finite(field, value):
    if not (isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and math.isfinite(value)):
        raise ValueError(f"{field}={value!r} must be a finite number")
    return float(value)


def _normal_ppf(u):
    """The standard normal's quantile at ``u`` (scipy.special on first use: slow to import)."""
    from scipy import special

    return special.ndtri(u)


def _normal_cdf(z):
    """The standard normal's distribution function at ``z``."""
    from scipy import special

    return special.ndtr(z)


@dataclasses.dataclass(frozen=True)
class LogNormal:
    """A log-normal parameter, given by its ``mean`` and coefficient of variation
    ``cov``, or by its ``median`` and the standard deviation of its logarithm
    ``sigma_ln`` (one pair, not both): ln X is normal with mean ln(median) and standard
    deviation sigma_ln; mean = median exp(sigma_ln²/2), cov² = exp(sigma_ln²) - 1.
    Values in the parameter's unit (ky in g, vs in m/s, ...)."""

    mean: float | None = None
    cov: float | None = None
    median: float | None = None
    sigma_ln: float | None = None

    def __post_init__(self):
        by_mean = self.mean is not None or self.cov is not None
        by_median = self.median is not None or self.sigma_ln is not None
        if by_mean == by_median:
            raise ValueError(f"LogNormal takes (mean, cov) or (median, sigma_ln), got mean={self.mean!r}, "
                             f"cov={self.cov!r}, median={self.median!r}, sigma_ln={self.sigma_ln!r}")
        if by_mean:
            mean, cov = _check_positive("mean", self.mean, "the mean"), _check_positive("cov", self.cov, "the cov")
            sigma = math.sqrt(math.log1p(cov ** 2))
            object.__setattr__(self, "median", mean / math.sqrt(1.0 + cov ** 2))
            object.__setattr__(self, "sigma_ln", sigma)
        else:
            median = _check_positive("median", self.median, "the median")
            sigma = _check_positive("sigma_ln", self.sigma_ln, "the standard deviation of ln X")
            object.__setattr__(self, "mean", median * math.exp(0.5 * sigma ** 2))
            object.__setattr__(self, "cov", math.sqrt(math.expm1(sigma ** 2)))

    def ppf(self, u):
        """The quantiles at ``u`` in (0, 1) (an array)."""
        return self.median * np.exp(self.sigma_ln * _normal_ppf(u))

    def cdf(self, x):
        """P(X <= x) (an array)."""
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return np.where(x > 0, _normal_cdf(np.log(np.maximum(x, 1e-300) / self.median) / self.sigma_ln), 0.0)


@dataclasses.dataclass(frozen=True)
class Normal:
    """A normal parameter of mean ``mean`` and standard deviation ``std`` (in the
    parameter's unit); truncate it (:class:`Truncated`) where negative values are
    meaningless."""

    mean: float
    std: float

    def __post_init__(self):
        _check_finite("mean", self.mean)
        _check_positive("std", self.std, "the standard deviation")

    def ppf(self, u):
        """The quantiles at ``u`` in (0, 1) (an array)."""
        return self.mean + self.std * _normal_ppf(u)

    def cdf(self, x):
        """P(X <= x) (an array)."""
        return _normal_cdf((np.asarray(x, dtype=float) - self.mean) / self.std)


@dataclasses.dataclass(frozen=True)
class Uniform:
    """A parameter uniform on [``low``, ``high``] (in the parameter's unit)."""

    low: float
    high: float

    def __post_init__(self):
        low, high = _check_finite("low", self.low), _check_finite("high", self.high)
        if not high > low:
            raise ValueError(f"Uniform needs high > low, got low={low!r}, high={high!r}")

    @property
    def mean(self):
        """The mean (low + high) / 2."""
        return 0.5 * (self.low + self.high)

    def ppf(self, u):
        """The quantiles at ``u`` in (0, 1) (an array)."""
        return self.low + (self.high - self.low) * np.asarray(u, dtype=float)

    def cdf(self, x):
        """P(X <= x) (an array)."""
        return np.clip((np.asarray(x, dtype=float) - self.low) / (self.high - self.low), 0.0, 1.0)


@dataclasses.dataclass(frozen=True)
class Truncated:
    """``distribution`` restricted to [``low``, ``high``] (either None: unbounded on that
    side) and renormalised: its quantile at u is the parent's at
    F(low) + u (F(high) - F(low))."""

    distribution: object
    low: float | None = None
    high: float | None = None

    def __post_init__(self):
        if not isinstance(self.distribution, (LogNormal, Normal, Uniform)):
            raise ValueError(f"distribution={self.distribution!r} must be a LogNormal, Normal or Uniform")
        low = -math.inf if self.low is None else _check_finite("low", self.low)
        high = math.inf if self.high is None else _check_finite("high", self.high)
        if not high > low:
            raise ValueError(f"Truncated needs high > low, got low={self.low!r}, high={self.high!r}")
        if not self._bounds()[1] > self._bounds()[0]:
            raise ValueError(f"Truncated: [{self.low!r}, {self.high!r}] holds no probability of {self.distribution}")

    def _bounds(self):
        """(F(low), F(high)) of the parent distribution."""
        low = 0.0 if self.low is None else float(self.distribution.cdf(self.low))
        high = 1.0 if self.high is None else float(self.distribution.cdf(self.high))
        return low, high

    def ppf(self, u):
        """The quantiles at ``u`` in (0, 1) (an array)."""
        low, high = self._bounds()
        return self.distribution.ppf(low + np.asarray(u, dtype=float) * (high - low))

    def cdf(self, x):
        """P(X <= x) (an array)."""
        low, high = self._bounds()
        return np.clip((self.distribution.cdf(x) - low) / (high - low), 0.0, 1.0)

    @property
    def mean(self):
        """The mean, by quadrature of the quantile function over (0, 1)."""
        from scipy import integrate

        return integrate.quad(lambda u: float(self.ppf(u)), 0.0, 1.0, limit=200)[0]


#: the distributions a parameter may follow
DISTRIBUTIONS = (LogNormal, Normal, Uniform, Truncated)
