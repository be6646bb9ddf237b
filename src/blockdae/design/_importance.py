"""Draws of an approximation of a posterior (a normal in the parameters' logarithms)
checked and corrected by Pareto-smoothed importance sampling (Vehtari, Simpson, Gelman,
Yao & Gabry 2024, "Pareto smoothed importance sampling", JMLR 25(72)): each draw weighted
by the exact posterior's density over the approximation's, the largest weights smoothed
by a generalized Pareto distribution fitted to them (ArviZ's ``psislw``), whose shape k̂
says whether the weighted draws estimate the posterior reliably; the draws then resampled
by their weights, so that they again carry equal weight."""

import dataclasses
import math
import warnings

import numpy as np


def pareto_k_limit(n):
    """The largest Pareto k̂ at which ``n`` weighted draws give reliable estimates:
    min(1 - 1 / log10 n, 0.7) (Vehtari et al. 2024: above it the estimates' error falls
    too slowly with n to be trusted; above 0.7 it would take impractically many draws):
    0.5 at 100 draws, 0.67 at 1000, 0.7 from 2155 on; -inf below 10 draws, too few to
    tell."""
    return min(1.0 - 1.0 / math.log10(n), 0.7) if n >= 10 else -math.inf


@dataclasses.dataclass(frozen=True)
class Resampled:
    """Draws resampled by their Pareto-smoothed importance weights.

    Attributes:
        draws: the resampled draws, shape (size, d), in random order, each with equal
            weight.
        pareto_k: the shape k̂ [-] of the generalized Pareto distribution fitted to the
            largest weights (inf where too few weights were positive to fit it).
        ess: the importance sampling's effective sample size, 1 / Σ w² of the smoothed
            weights normalised to sum 1 [draws].
        limit: the largest k̂ that is reliable for the n draws weighted
            (:func:`pareto_k_limit`).
    """

    draws: np.ndarray
    pareto_k: float
    ess: float
    limit: float


def resampled(draws, log_proposal, log_target, size, rng):
    """``draws`` of a proposal (shape (n, d)) reweighted toward a target and ``size`` of
    them resampled by their Pareto-smoothed weights (systematic resampling, then shuffled).

    Args:
        draws: the proposal's draws, shape (n, d).
        log_proposal: the proposal's log density at each draw, shape (n,), up to a constant.
        log_target: the target's log density at each draw, shape (n,), up to a constant
            (-inf, or nan, where it is zero: such a draw gets no weight).
        size: how many draws to resample.
        rng: a NumPy random generator.

    Returns:
        a :class:`Resampled`.
    """
    with warnings.catch_warnings():  # ArviZ's notice of its coming refactor, at import
        warnings.simplefilter("ignore", FutureWarning)
        import arviz

    draws = np.asarray(draws, dtype=float)
    n = len(draws)
    log_weights = np.asarray(log_target, dtype=float) - np.asarray(log_proposal, dtype=float)
    log_weights = np.where(np.isnan(log_weights), -np.inf, log_weights)
    if not np.isfinite(log_weights).any():
        raise ValueError("the posterior's density is zero at every draw of the approximation")
    smoothed, pareto_k = arviz.psislw(log_weights, reff=1.0)  # independent draws
    weights = np.exp(smoothed - np.max(smoothed))
    weights /= weights.sum()
    positions = (rng.uniform() + np.arange(size)) / size
    chosen = np.minimum(np.searchsorted(np.cumsum(weights), positions), n - 1)
    return Resampled(draws[rng.permutation(chosen)], float(pareto_k), float(1.0 / np.sum(weights ** 2)),
                     pareto_k_limit(n))
