"""The Laplace approximation of a back-analysis's posterior: the maximum a posteriori in
the logarithms of the parameters inferred, u = ln p (a vector, one entry per parameter),
the Hessian of -ln posterior in u there (central differences of the exact gradient), and
the multivariate normal in u it gives, with its draws."""

import dataclasses
import itertools
import math

import numpy as np

from ._inferred import numpyro_prior

#: the extreme prior quantiles searched for the maximum and for what D an observation may be
REACH_QUANTILES = (1e-6, 1.0 - 1e-6)
#: each parameter's prior quantiles whose combinations start the search for several parameters
_START_QUANTILES = (0.1, 0.5, 0.9)
#: the most parameters whose every combination of _START_QUANTILES is tried (3^5 = 243 points)
_GRID_MOST = 5
#: the step in u of the central differences of the gradient [-]
_STEP = 1e-4
#: the Hessian counts as positive definite where its smallest eigenvalue exceeds this share of its largest
_CONDITION = 1e-8
#: how far above the start's value the search meets a wall where the posterior is zero [-]
_WALL = 1e6


class NotPeaked(ValueError):
    """The posterior in u = ln p is not peaked at the maximum found (the Hessian of
    -ln posterior there is not positive definite): the Laplace approximation does not
    hold."""


def prior_quantiles(prior):
    """66 quantiles of ``prior``: 1e-6, 64 evenly spread, 1 - 1e-6."""
    quantiles = np.concatenate([[REACH_QUANTILES[0]], (np.arange(64) + 0.5) / 64, [REACH_QUANTILES[1]]])
    return np.asarray(prior.ppf(quantiles), dtype=float)


@dataclasses.dataclass(frozen=True)
class Laplace:
    """The normal approximation of the posterior in u = ln p at its maximum (p each
    parameter in its unit).

    Attributes:
        names: the parameters, in the order of u.
        mean: ln of each parameter's maximum a posteriori value, shape (d,).
        covariance: the inverse of the Hessian of -ln posterior in u there, shape (d, d)
            [-] (of the logarithms: a variance of 0.01 is a standard deviation of about
            10 % of the value).
        factor: A with A Aᵀ = ``covariance`` (the transposed inverse of the Hessian's
            lower Cholesky factor), shape (d, d).
    """

    names: tuple
    mean: np.ndarray
    covariance: np.ndarray
    factor: np.ndarray

    def draws(self, n, seed):
        """``n`` independent draws of u = ln p, shape (n, d): ``mean`` + A z, z standard
        normal (NumPy's default generator seeded with ``seed``)."""
        z = np.random.default_rng(seed).standard_normal((n, len(self.names)))
        return self.mean + z @ self.factor.T

    def log_density(self, u):
        """ln of the normal's density at ``u`` (shape (n, d)), up to a constant, shape (n,)."""
        z = np.linalg.solve(self.factor, (np.asarray(u, dtype=float) - self.mean).T)
        return -0.5 * np.sum(z ** 2, axis=0)


def laplace_approximation(maximum, hessian) -> Laplace:
    """The :class:`Laplace` approximation at ``maximum`` (name -> the maximum a posteriori
    value [its unit]) with ``hessian`` (of -ln posterior in u = ln p there, shape (d, d));
    :class:`NotPeaked` where the Hessian is not positive definite (its smallest eigenvalue
    not above 1e-8 of its largest), naming the parameters."""
    names = tuple(maximum)
    symmetric = 0.5 * (hessian + hessian.T)
    eigenvalues = np.linalg.eigvalsh(symmetric) if np.isfinite(symmetric).all() else np.full(len(names), np.nan)
    if not eigenvalues[0] > _CONDITION * eigenvalues[-1]:
        raise NotPeaked(_not_peaked(names, symmetric, eigenvalues))
    root = np.linalg.cholesky(symmetric)
    factor = np.linalg.inv(root).T
    return Laplace(names, np.array([math.log(value) for value in maximum.values()]), factor @ factor.T, factor)


def _not_peaked(names, hessian, eigenvalues):
    """Why the Laplace approximation of ``names`` does not hold, for an error."""
    logs = ", ".join(f"ln {name}" for name in names)
    if len(names) == 1:
        return (f"the posterior of ln {names[0]} is not peaked at its maximum (curvature {hessian[0, 0]:.3g}): the "
                "Laplace approximation does not hold; use method='nuts'")
    if np.isnan(eigenvalues).any():
        why = "the posterior is zero within a step of 1e-4 in ln p of its maximum"
    else:
        flat = np.linalg.eigh(hessian)[1][:, 0]
        along = " ".join(f"{w:+.2f} ln {name}" for w, name in zip(flat, names))
        why = (f"the Hessian of -ln posterior in ({logs}) has eigenvalues {np.array2string(eigenvalues, precision=3)}"
               f", the smallest not above 1e-8 of the largest: it is flat or falls along {along} (the observations "
               f"pin a combination of {', '.join(names)}, and the priors do not pin the rest)")
    return (f"the posterior of {logs} is not peaked at its maximum: {why}; the Laplace approximation does not hold; "
            "use method='nuts' (or priors that say more of each parameter)")


@dataclasses.dataclass(frozen=True)
class Search:
    """What :func:`maximum_a_posteriori` found: ``u``, the maximum in u = ln p (d,);
    ``hessian``, of -ln posterior in u there (d, d); ``points``, the starting points tried
    in u (m, d), and ``values``, -ln posterior at each (m,) (inf where it is zero)."""

    u: np.ndarray
    hessian: np.ndarray
    points: np.ndarray
    values: np.ndarray

    def best_points(self, k):
        """The ``k`` most probable starting points in u, shape (k, d) (repeated where
        fewer have a posterior density above 0)."""
        order = np.argsort(self.values)[: max(1, min(k, int(np.isfinite(self.values).sum())))]
        return self.points[np.resize(order, k)]


def _minus_log_density(setup, names):
    """-ln posterior of u = ln p (the parameters ``names``, in that order), up to a
    constant, the Jacobian of p = exp(u) included: a JAX function of (u (d,), the priors
    as NumPyro distributions (name -> distribution), the observed values)."""
    import jax

    def minus_log_density(u, densities, data):
        values = {name: jax.numpy.exp(u[i]) for i, name in enumerate(names)}
        return (-sum(densities[name].log_prob(values[name]) for name in names)
                - setup.log_likelihood(values, data) - jax.numpy.sum(u))

    return minus_log_density


def minus_log_posterior_on_points(setup, names):
    """:func:`_minus_log_density` at many points u, shape (m, d) -> (m,): compiled once per
    set-up, one batched model call per motion."""
    import jax

    return setup.program("on points", lambda: jax.jit(jax.vmap(_minus_log_density(setup, names), (0, None, None))))


def maximum_a_posteriori(setup, data, priors) -> Search:
    """The maximum a posteriori of the parameters ``priors`` names (name -> a
    :mod:`blockdae.design` distribution) in u = ln p, and the Hessian of -ln posterior in
    u there. ``setup``: the analysis's set-up (its ``log_likelihood`` and compiled
    programs), ``data`` its observed values.

    The search starts from the best of a few points (one batched model call per motion):
    for one parameter its 66 prior quantiles (1e-6, 64 evenly spread, 1 - 1e-6), and
    scipy's L-BFGS-B runs between the best one's neighbours; for several, every
    combination of each prior's 10 %, 50 % and 90 % quantiles (up to five parameters;
    beyond, the medians and each parameter alone at those quantiles, the others at their
    medians), and L-BFGS-B runs within each prior's quantiles from 1e-6 to 1 - 1e-6,
    meeting a wall where the posterior is zero. Both follow the model's gradient; the
    Hessian comes from central differences of that gradient (a step of 1e-4 in u)."""
    import jax
    from scipy import optimize

    names = list(priors)
    densities = {name: numpyro_prior(prior) for name, prior in priors.items()}
    minus_log_density = _minus_log_density(setup, names)
    value_only = setup.program("minus log density", lambda: jax.jit(minus_log_density))
    f = setup.program("its gradient", lambda: jax.jit(jax.value_and_grad(minus_log_density)))
    on_points = minus_log_posterior_on_points(setup, names)

    if len(names) == 1:
        points = np.log(prior_quantiles(priors[names[0]]))[:, None]
    else:
        points = _start_points(list(priors.values()))
    values = np.asarray(on_points(points, densities, data), dtype=float)
    values = np.where(np.isfinite(values), values, np.inf)
    if not np.isfinite(values).any():
        where = ("every prior quantile from 1e-6 to 1 - 1e-6" if len(names) == 1 else
                 "every combination of the priors' 10 %, 50 % and 90 % quantiles")
        raise ValueError(f"the posterior of {', '.join(names)} is zero at {where}: check the observations against "
                         "the prior" + ("" if len(names) == 1 else "s"))
    best = int(np.argmin(values))
    wall = values[best] + _WALL * (1.0 + abs(values[best]))

    def exact(u):  # -ln posterior and its gradient at u
        value, grad = f(np.asarray(u, dtype=float), densities, data)
        return float(value), np.asarray(grad, dtype=float)

    def objective(u):
        value, grad = exact(u)
        return (value, grad) if math.isfinite(value) else (wall, np.zeros_like(grad))

    if len(names) == 1:
        bounds = [tuple(_finite_edges(points[:, 0], best, lambda u: value_only(np.array([u]), densities, data)))]
    else:
        bounds = [tuple(np.log(prior.ppf(np.array(REACH_QUANTILES)))) for prior in priors.values()]
    found = optimize.minimize(objective, points[best], jac=True, method="L-BFGS-B", bounds=bounds,
                              options={"ftol": 1e-15, "gtol": 1e-10})
    u = np.asarray(found.x, dtype=float)
    hessian = np.empty((len(names), len(names)))
    for j, step in enumerate(_STEP * np.eye(len(names))):
        hessian[:, j] = (exact(u + step)[1] - exact(u - step)[1]) / (2 * _STEP)
    return Search(u, hessian, points, values)


def _finite_edges(grid, best, value_only):
    """The bounds of one parameter's search in u: the neighbours of ``grid[best]``, each
    moved halfway toward it until the posterior there is above 0."""
    edges = []
    for neighbour in (max(best - 1, 0), min(best + 1, len(grid) - 1)):
        edge = grid[neighbour]
        while not np.isfinite(float(value_only(edge))):
            edge = 0.5 * (edge + grid[best])
        edges.append(edge)
    return edges


def _start_points(priors):
    """The starting points in u = ln p of the search for several parameters, shape (m, d)."""
    levels = np.log(np.array([prior.ppf(np.array(_START_QUANTILES)) for prior in priors], dtype=float))  # (d, 3)
    d = len(priors)
    if d <= _GRID_MOST:
        combinations = np.array(list(itertools.product(range(len(_START_QUANTILES)), repeat=d)))
    else:
        combinations = np.ones((2 * d + 1, d), dtype=int)
        for i in range(d):
            combinations[1 + 2 * i, i], combinations[2 + 2 * i, i] = 0, 2
    return levels[np.arange(d), combinations]
