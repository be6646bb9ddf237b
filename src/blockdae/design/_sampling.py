"""Drawing parameter sets: Monte Carlo, Latin hypercube or scrambled Sobol uniform
numbers, mapped through each parameter's quantile function, with correlation by a
Gaussian copula (the Nataf model: the correlation is that of the standard-normal scores,
for log-normal parameters that of their logarithms)."""

import math

import numpy as np
from ._distributions import DISTRIBUTIONS, _normal_cdf, _normal_ppf
from ._models import DesignModel

#: the samplers: "mc" (Monte Carlo), "lhs" (Latin hypercube, each block of runs its own
#: design), "sobol" (scrambled Sobol, one sequence per record continued run after run)
SAMPLINGS = ("mc", "lhs", "sobol")


def split_parameters(parameters, model):
    """(fixed: name -> float, uncertain: name -> distribution) of ``parameters`` (name
    -> a number or a distribution), checked against ``model``'s parameters."""
    if not isinstance(model, DesignModel):
        raise ValueError(f"model={model!r} must be a design model: design.Rigid(...), design.Flexible(...), "
                         "design.Planar(...), design.Simulated(any model, ...) or a design.DesignModel of your own")
    if not isinstance(parameters, dict):
        raise ValueError(f"parameters must be a dict name -> number or distribution, got {parameters!r}")
    fixed, uncertain = {}, {}
    for name, value in parameters.items():
        if name not in model.PARAMETERS:
            raise ValueError(f"parameter {name!r} is not one of the {model.kind} model's: {tuple(model.PARAMETERS)}")
        if isinstance(value, DISTRIBUTIONS):
            uncertain[name] = value
        elif isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and math.isfinite(value):
            fixed[name] = float(value)
        else:
            raise ValueError(f"parameter {name}={value!r} must be a finite number [{model.PARAMETERS[name]}] or a "
                             "distribution (LogNormal, Normal, Uniform, Truncated)")
    missing = [name for name in model.REQUIRED if name not in parameters]
    if missing:
        raise ValueError(f"the {model.kind} model needs the parameters {missing} (a number or a distribution)")
    return fixed, uncertain


def correlation_matrix(correlation, names):
    """The correlation matrix (Cholesky factor) of the normal scores of ``names`` from
    ``correlation`` ({(name, name): rho}); identity where None."""
    matrix = np.eye(len(names))
    for pair, rho in (correlation or {}).items():
        if not (isinstance(pair, tuple) and len(pair) == 2 and all(p in names for p in pair) and pair[0] != pair[1]):
            raise ValueError(f"correlation key {pair!r} must be a pair of two different uncertain parameters of "
                             f"{tuple(names)}")
        if not (isinstance(rho, (int, float)) and -1 < rho < 1):
            raise ValueError(f"correlation[{pair!r}]={rho!r} must lie in (-1, 1)")
        i, j = names.index(pair[0]), names.index(pair[1])
        matrix[i, j] = matrix[j, i] = rho
    try:
        return np.linalg.cholesky(matrix)
    except np.linalg.LinAlgError:
        raise ValueError(f"correlation={correlation!r} is not a valid correlation matrix (not positive definite)") \
            from None


class RecordSampler:
    """The uniform numbers of one record's samples, block after block of runs."""

    def __init__(self, sampling, dimension, seed_sequence):
        self.sampling, self.dimension = sampling, dimension
        from scipy.stats import qmc  # on first use: scipy.stats is slow to import

        self.qmc, self.rng = qmc, np.random.default_rng(seed_sequence)
        self.sobol = qmc.Sobol(dimension, scramble=True, seed=self.rng) if sampling == "sobol" else None

    def uniforms(self, n):
        """(n, dimension) numbers in (0, 1)."""
        if self.sampling == "mc":
            return self.rng.random((n, self.dimension))
        if self.sampling == "lhs":
            return self.qmc.LatinHypercube(self.dimension, seed=self.rng).random(n)
        return self.sobol.random(n)


def to_parameters(uniforms, uncertain, cholesky):
    """name -> values (shape (n,)) of the uncertain parameters from ``uniforms`` (n, d):
    normal scores correlated by ``cholesky``, back to uniforms, through each quantile."""
    if cholesky.shape[0] > 1 and not np.allclose(cholesky, np.eye(cholesky.shape[0])):
        uniforms = _normal_cdf(_normal_ppf(uniforms) @ cholesky.T)
    return {name: np.asarray(dist.ppf(uniforms[:, k]), dtype=float) for k, (name, dist) in enumerate(uncertain.items())}


def check_sampling(sampling, runs_per_block):
    if sampling not in SAMPLINGS:
        raise ValueError(f"sampling={sampling!r} is unknown; choose one of {SAMPLINGS}")
    if not (isinstance(runs_per_block, int) and runs_per_block >= 2):
        raise ValueError(f"runs_per_block={runs_per_block!r} must be an integer >= 2")
    if sampling == "sobol" and runs_per_block & (runs_per_block - 1):
        raise ValueError(f"runs_per_block={runs_per_block!r}: scrambled Sobol keeps its balance in blocks of a power "
                         "of 2 (e.g. 16)")
