"""Estimates of a design study: the mean displacement's relative standard error and the
Wilson score interval of an exceedance probability."""

import numpy as np

from ._distributions import _normal_ppf


def z_value(confidence):
    """The standard-normal quantile of a two-sided ``confidence`` (0.95 -> 1.96)."""
    if not 0 < confidence < 1:
        raise ValueError(f"confidence={confidence!r} must lie in (0, 1)")
    return float(_normal_ppf(0.5 + 0.5 * confidence))


def wilson(k, n, confidence):
    """The Wilson score interval (low, high) of a probability of ``k`` successes out of
    ``n`` (arrays broadcast)."""
    z = z_value(confidence)
    k, n = np.asarray(k, dtype=float), np.asarray(n, dtype=float)
    p = k / n
    centre = (p + z ** 2 / (2 * n)) / (1 + z ** 2 / n)
    half = z / (1 + z ** 2 / n) * np.sqrt(p * (1 - p) / n + z ** 2 / (4 * n ** 2))
    return centre - half, centre + half


def relative_standard_error(displacements):
    """(mean D [m], its relative standard error [-]) from ``displacements`` (runs,
    records): the run means (each over the record set, the stratum of one run) have the
    mean D as their mean; the standard error is their spread over sqrt(runs). inf where
    the mean is 0 or fewer than two runs."""
    run_means = displacements.mean(axis=1)
    mean = float(run_means.mean())
    if run_means.size < 2 or mean <= 0:
        return mean, float("inf")
    return mean, float(run_means.std(ddof=1) / np.sqrt(run_means.size) / mean)
