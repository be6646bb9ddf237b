"""Back-analysis: the posterior of a slope's yield acceleration ky [g] given observed
displacements, each D [m] seen with a log-normal measurement error (or a bound on it),
under a record scaled to a PGA.

The log posterior is written in JAX; the rigid block's D(ky) and its exact dD/dky come from
the compiled engine (:func:`blockdae.newmark` with ``derivative=True``) through a
``jax.pure_callback`` wrapped in a ``jax.custom_jvp``, so that gradient-based samplers
(NumPyro's No-U-Turn sampler) and the maximum a posteriori use the exact derivative.
JAX, NumPyro and ArviZ (the ``inference`` extra) are imported on first use."""

import contextlib
import dataclasses
import math
import warnings

import numpy as np
import pandas as pd

from ..excitation import Record
from ._distributions import LogNormal, Normal, Truncated, Uniform
from ._models import Rigid

#: the prior quantiles whose D bound what an observation may be (the reachability check)
_REACH_QUANTILES = (1e-6, 1.0 - 1e-6)
#: how many measurement sigmas an observation may lie beyond the reachable D [-]
_REACH_SIGMAS = 4.0
#: R-hat above which, and bulk effective sample size per chain below which, a warning is raised
RHAT_LIMIT = 1.01
ESS_PER_CHAIN = 100
#: NumPyro's statistics of each NUTS draw -> their names in ArviZ's sample_stats
_NUTS_STATS = {"diverging": "diverging", "accept_prob": "acceptance_rate", "num_steps": "n_steps",
               "adapt_state.step_size": "step_size", "energy": "energy", "potential_energy": "lp"}


class ConvergenceWarning(UserWarning):
    """NUTS chains that did not mix (R-hat above 1.01, a bulk effective sample size below
    100 per chain, or divergent transitions), or a Laplace approximation that reaches
    beyond the prior's support."""


def _positive(field, value):
    if not (isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and math.isfinite(value)
            and value > 0):
        raise ValueError(f"{field}={value!r} must be a finite number > 0")
    return float(value)


@dataclasses.dataclass(frozen=True)
class Observation:
    """What was seen of a slope under one record: exactly one of ``displacement_m`` (D was
    measured), ``more_than_m`` (it moved more than this) or ``less_than_m`` (it moved less),
    each [m], with the standard deviation ``sigma_ln`` [-] of the log of the measurement
    (ln D_observed = ln D + ε, ε ~ N(0, sigma_ln²); a bound holds with the same error).

    Attributes:
        record: the ground acceleration along the slope [m/s²] (a :class:`blockdae.Record`).
        pga_g: the PGA [g] the record is scaled to (None: as given).
        name: the observation's name in tables (default: the record's name).
    """

    record: Record
    sigma_ln: float
    displacement_m: float | None = None
    more_than_m: float | None = None
    less_than_m: float | None = None
    pga_g: float | None = None
    name: str | None = None

    def __post_init__(self):
        if not isinstance(self.record, Record):
            raise ValueError(f"record must be a blockdae.Record, got {type(self.record).__name__}")
        given = [k for k in ("displacement_m", "more_than_m", "less_than_m") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("an Observation takes exactly one of displacement_m, more_than_m, less_than_m [m]; "
                             f"got {given or 'none'}")
        _positive(given[0], getattr(self, given[0]))
        _positive("sigma_ln", self.sigma_ln)
        if self.pga_g is not None:
            _positive("pga_g", self.pga_g)
        if self.name is None:
            object.__setattr__(self, "name", self.record.name or "observation")

    @property
    def kind(self) -> str:
        """"displacement", "more_than" or "less_than"."""
        return next(k[:-2] for k in ("displacement_m", "more_than_m", "less_than_m") if getattr(self, k) is not None)

    @property
    def value_m(self) -> float:
        """The observed displacement or bound [m]."""
        return float(getattr(self, self.kind + "_m"))


def _support(prior):
    """(low, high) of ``prior``'s values."""
    if isinstance(prior, LogNormal):
        return 0.0, math.inf
    if isinstance(prior, Normal):
        return -math.inf, math.inf
    if isinstance(prior, Uniform):
        return prior.low, prior.high
    low, high = _support(prior.distribution)
    return max(low, -math.inf if prior.low is None else prior.low), min(high, math.inf if prior.high is None
                                                                         else prior.high)


def _numpyro_prior(prior):
    """The NumPyro distribution of a :mod:`blockdae.design` distribution."""
    import numpyro.distributions as dist

    if isinstance(prior, LogNormal):
        return dist.LogNormal(math.log(prior.median), prior.sigma_ln)
    if isinstance(prior, Normal):
        return dist.Normal(prior.mean, prior.std)
    if isinstance(prior, Uniform):
        return dist.Uniform(prior.low, prior.high)
    low, high = _support(prior)
    parent = prior.distribution
    if isinstance(parent, Uniform):
        return dist.Uniform(low, high)
    if isinstance(parent, LogNormal):  # exp of a truncated normal of ln X
        log_bounds = {"low": math.log(low) if low > 0 else None, "high": math.log(high) if high < math.inf else None}
        return dist.TransformedDistribution(
            dist.TruncatedNormal(math.log(parent.median), parent.sigma_ln, **log_bounds),
            dist.transforms.ExpTransform())
    return dist.TruncatedNormal(parent.mean, parent.std, low=None if low == -math.inf else low,
                                high=None if high == math.inf else high)


def _check_priors(model, priors):
    if not isinstance(model, Rigid):
        raise ValueError(f"back_analysis takes the rigid block (design.Rigid), got {type(model).__name__}")
    if not isinstance(priors, dict) or set(priors) != {"ky"}:
        raise ValueError(f"priors must be {{'ky': a distribution}} for the rigid block, got {priors!r}")
    prior = priors["ky"]
    if not isinstance(prior, (LogNormal, Normal, Uniform, Truncated)):
        raise ValueError(f"priors['ky']={prior!r} must be a design.LogNormal, Normal, Uniform or Truncated")
    low, _ = _support(prior)
    if low < 0:
        raise ValueError(f"priors['ky']={prior!r} gives ky < 0 [g] a probability; truncate it "
                         "(design.Truncated(..., low=0)) or use a LogNormal")
    return prior


def _check_reachable(model, observations, prior):
    """Raise where an observation lies beyond the D [m] the prior's values of ky can give."""
    ky_low, ky_high = (float(prior.ppf(u)) for u in _REACH_QUANTILES)
    for obs in observations:
        d_max, d_min = _engine(model, obs.record, obs.pga_g, np.array([ky_low, ky_high]))[0]
        margin = math.exp(_REACH_SIGMAS * obs.sigma_ln)
        if obs.kind != "less_than" and obs.value_m > d_max * margin:
            raise ValueError(f"observation {obs.name!r}: {obs.kind}_m={obs.value_m!r} m lies beyond what the prior "
                             f"reaches: D = {d_max:.4g} m at ky = {ky_low:.4g} g (its 1e-6 quantile), more than "
                             f"{_REACH_SIGMAS:g} sigma_ln below; widen the prior of ky or check the observation")
        if obs.kind != "more_than" and obs.value_m * margin < d_min:
            raise ValueError(f"observation {obs.name!r}: {obs.kind}_m={obs.value_m!r} m lies below what the prior "
                             f"reaches: D = {d_min:.4g} m at ky = {ky_high:.4g} g (its 1 - 1e-6 quantile), more "
                             f"than {_REACH_SIGMAS:g} sigma_ln above; widen the prior of ky or check the observation")


def _engine(model, record, pga_g, ky):
    """D [m] and dD/dky [m/g] at each ky [g] (an array): 0 and 0 from the record's
    sliding limit (its scaled peak) on. The engine runs on every entry (half the limit in
    place of those at or above it), so that its kernel compiles once per batch shape."""
    ky = np.asarray(ky, dtype=float)
    flat = ky.reshape(-1)
    limit = model.sliding_limit(record, pga_g, {"ky": flat})
    slides = flat < limit
    d, slope = model.displacements(record, pga_g, {"ky": np.where(slides, flat, 0.5 * limit)}, derivative=True)
    return np.where(slides, d, 0.0).reshape(ky.shape), np.where(slides, slope, 0.0).reshape(ky.shape)


def displacement_function(model, record, pga_g):
    """D [m] of ``record`` scaled to ``pga_g`` [g] as a JAX function of ky [g] (any shape),
    differentiable through the engine's exact dD/dky [m/g] (a ``jax.custom_jvp`` around
    a ``jax.pure_callback``; batches under ``jax.vmap`` into one engine call)."""
    import jax
    import jax.numpy as jnp

    def both(ky):
        shape = jax.ShapeDtypeStruct(jnp.shape(ky), jnp.float64)
        return jax.pure_callback(lambda k: _engine(model, record, pga_g, k), (shape, shape), ky,
                                 vmap_method="broadcast_all")

    @jax.custom_jvp
    def displacement(ky):
        return both(ky)[0]

    @displacement.defjvp
    def _jvp(primals, tangents):
        d, slope = both(primals[0])
        return d, slope * tangents[0]

    return displacement


def _log_likelihood(obs, d):
    """ln p(obs | D = ``d`` [m]) up to a constant, in JAX."""
    import jax.numpy as jnp
    from jax.scipy.special import log_ndtr

    safe = jnp.log(jnp.where(d > 0, d, 1.0))
    log_d = jnp.where(d > 0, safe, -jnp.inf)
    z = (log_d - math.log(obs.value_m)) / obs.sigma_ln
    if obs.kind == "displacement":
        return jnp.where(d > 0, -0.5 * jnp.where(d > 0, z, 0.0) ** 2, -jnp.inf)
    return log_ndtr(z if obs.kind == "more_than" else -z)


def log_posterior(observations, model, priors):
    """ln p(ky | observations) up to a constant, as a JAX function of ky [g] (a scalar):
    the prior's log density plus each observation's log likelihood; its gradient
    (``jax.grad``) is exact, through the engine's dD/dky. Evaluate it with JAX in float64
    (inside ``jax.enable_x64(True)``)."""
    observations, prior = _checked(observations, model, priors)
    return _log_posterior(observations, model, prior)


def _log_posterior(observations, model, prior):
    density = _numpyro_prior(prior)
    log_likelihood = _log_likelihoods(observations, model)
    return lambda ky: density.log_prob(ky) + log_likelihood(ky)


def _log_likelihoods(observations, model):
    """The observations' joint log likelihood as a JAX function of ky [g]."""
    import jax.numpy as jnp

    functions = [displacement_function(model, o.record, o.pga_g) for o in observations]

    def log_likelihood(ky):
        ky = jnp.maximum(ky, 1e-12)  # the engine's ky > 0; the prior's density is 0 below
        return sum(_log_likelihood(obs, f(ky)) for obs, f in zip(observations, functions))

    return log_likelihood


def _checked(observations, model, priors):
    if isinstance(observations, Observation):
        observations = [observations]
    observations = list(observations)
    if not observations or not all(isinstance(o, Observation) for o in observations):
        raise ValueError("observations must be a design.Observation or a non-empty sequence of them")
    names = [o.name for o in observations]
    if len(set(names)) != len(names):
        raise ValueError(f"the observations' names must differ (give each a name=), got {names}")
    prior = _check_priors(model, priors)
    return observations, prior


@dataclasses.dataclass
class BackAnalysis:
    """The posterior of ky [g] given the observations.

    Attributes:
        samples: the posterior draws, a table (``chain``, ``draw``, ``ky_g``).
        map_ky_g: the maximum a posteriori ky [g].
        laplace_sd_g: the standard deviation [g] of the Laplace approximation at the
            maximum (in ln ky, mapped back to ky to first order).
        diagnostics: R-hat and bulk/tail effective sample sizes of ky (NUTS only; empty
            for the Laplace approximation), a table.
        method: "nuts" or "laplace".
        observations: the observations analysed (:class:`Observation`).
        model: the :class:`Rigid` block they were analysed with.
        priors: the priors given (parameter -> distribution).
        sample_stats: NUTS's statistics of each draw (``chain``, ``draw``, ``diverging``,
            ``acceptance_rate`` [-], ``n_steps``, ``step_size``, ``energy``, ``lp``), a
            table; empty for the Laplace approximation.
    """

    samples: pd.DataFrame
    map_ky_g: float
    laplace_sd_g: float
    diagnostics: pd.DataFrame
    method: str
    observations: list
    model: Rigid
    priors: dict | None = None
    sample_stats: pd.DataFrame = dataclasses.field(default_factory=pd.DataFrame)

    def __repr__(self):
        s = self.summary().iloc[0]
        return (f"BackAnalysis(method={self.method!r}, {len(self.samples)} draws, {len(self.observations)} "
                f"observations, ky median {s.median_g:.4g} g, 90 % interval {s.q05_g:.4g}-{s.q95_g:.4g} g)")

    def summary(self) -> pd.DataFrame:
        """ky's mean, standard deviation, median and 90 % interval [g], one row."""
        ky = self.samples["ky_g"].to_numpy()
        q05, q50, q95 = np.quantile(ky, [0.05, 0.5, 0.95])
        return pd.DataFrame({"parameter": ["ky"], "mean_g": [ky.mean()], "sd_g": [ky.std(ddof=1)],
                             "median_g": [q50], "q05_g": [q05], "q95_g": [q95]})

    def predict(self, record, pga_g=None) -> pd.DataFrame:
        """The posterior predictive D [m] of the slope under ``record`` scaled to ``pga_g``
        [g] (None: as given): one row per posterior draw (``chain``, ``draw``, ``ky_g``,
        ``D_m``), the model's D without measurement error."""
        if not isinstance(record, Record):
            raise ValueError(f"record must be a blockdae.Record, got {type(record).__name__}")
        if pga_g is not None:
            _positive("pga_g", pga_g)
        table = self.samples.copy()
        ky = table["ky_g"].to_numpy()
        slides = ky < self.model.sliding_limit(record, pga_g, {"ky": ky})  # D = 0 from the scaled peak on
        d = np.zeros(ky.shape)
        if slides.any():
            d[slides] = self.model.displacements(record, pga_g, {"ky": ky[slides]})
        table["D_m"] = d
        return table

    def predictive(self) -> pd.DataFrame:
        """Each observation beside its posterior predictive D [m] (median and 90 %
        interval of the model's D over the posterior draws): ``observation``, ``kind``,
        ``observed_m``, ``median_D_m``, ``q05_D_m``, ``q95_D_m``."""
        rows = []
        for obs in self.observations:
            d = self.predict(obs.record, obs.pga_g)["D_m"].to_numpy()
            q05, q50, q95 = np.quantile(d, [0.05, 0.5, 0.95])
            rows.append({"observation": obs.name, "kind": obs.kind, "observed_m": obs.value_m,
                         "median_D_m": q50, "q05_D_m": q05, "q95_D_m": q95})
        return pd.DataFrame(rows)

    def to_inference_data(self, *, seed=0):
        """The result as ArviZ's ``InferenceData``; each variable's unit in its
        ``attrs["units"]``. Groups: ``posterior`` (each parameter by name, e.g. ``ky``, shape
        (chain, draw)); ``sample_stats`` (NUTS's ``diverging``, ``acceptance_rate``,
        ``n_steps``, ``step_size``, ``energy``, ``lp`` of each draw; none for the Laplace
        approximation); ``posterior_predictive`` (``D``: the model's D [m] at each draw for
        each observation; ``D_measured``: D with its log-normal measurement error, drawn
        with ``seed``); ``observed_data`` (``D_measured``: the value or bound [m], each
        observation's ``kind`` and ``sigma_ln`` as coordinates); ``log_likelihood``
        (``D_measured``: ln of the normal density of ln D_observed, or ln P of the bound,
        per draw and observation); ``prior`` (each parameter drawn from its prior, as many
        draws as the posterior, with ``seed``). Needs ArviZ (the ``inference`` extra)."""
        from ._back_analysis_result import inference_data

        return inference_data(self, seed=seed)

    def posterior_figure(self, *, title=None):
        """Each parameter's prior and posterior densities, the maximum a posteriori and the
        90 % interval marked; a matplotlib Figure."""
        from ._back_analysis_figures import posterior_figure

        return posterior_figure(self, title=title)

    def predictive_figure(self, *, scenarios=None, title=None):
        """Each observation (with its measurement error, or its bound) beside the posterior
        predictive D [m], and the D predicted under each of ``scenarios`` (label ->
        (record, pga_g)); a matplotlib Figure."""
        from ._back_analysis_figures import predictive_figure

        return predictive_figure(self, scenarios=scenarios, title=title)

    def pair_figure(self, *, title=None):
        """The posterior draws of each pair of parameters (two or more); a matplotlib Figure."""
        from ._back_analysis_figures import pair_figure

        return pair_figure(self, title=title)


@contextlib.contextmanager
def _float64():
    """JAX in float64 for the calls inside, on every thread (the engine's callbacks run on
    XLA's threads, outside a thread-local ``jax.enable_x64``); the setting is restored."""
    import jax

    before = jax.config.jax_enable_x64
    jax.config.update("jax_enable_x64", True)
    try:
        yield
    finally:
        jax.config.update("jax_enable_x64", before)


def _maximum(log_p, prior):
    """The maximum a posteriori ky [g] and the Laplace standard deviation of ln ky: the
    best of 66 prior quantiles (1e-6, 64 evenly spread, 1 - 1e-6; one batched engine call
    per observation), then scipy's L-BFGS-B in u = ln ky on the exact gradient between
    its neighbours; the curvature at the maximum by central differences of the exact
    gradient."""
    import jax
    from scipy import optimize

    def minus_log_density(u):  # of ln ky
        return -log_p(jax.numpy.exp(u)) - u

    f = jax.jit(jax.value_and_grad(minus_log_density))

    def objective(u):
        value, grad = f(float(u[0]))
        return float(value), np.array([float(grad)])

    quantiles = np.concatenate([[_REACH_QUANTILES[0]], (np.arange(64) + 0.5) / 64, [_REACH_QUANTILES[1]]])
    grid = np.log(np.asarray(prior.ppf(quantiles), dtype=float))
    values = np.asarray(jax.jit(jax.vmap(minus_log_density))(grid), dtype=float)
    if not np.isfinite(values).any():
        raise ValueError("the posterior of ky is zero at every prior quantile from 1e-6 to 1 - 1e-6: check the "
                         "observations against the prior")
    best = int(np.nanargmin(np.where(np.isfinite(values), values, np.inf)))
    bounds = []
    for neighbour in (max(best - 1, 0), min(best + 1, len(grid) - 1)):
        edge = grid[neighbour]
        while not np.isfinite(objective([edge])[0]):  # halve the way toward the best point
            edge = 0.5 * (edge + grid[best])
        bounds.append(edge)
    found = optimize.minimize(objective, [grid[best]], jac=True, method="L-BFGS-B", bounds=[tuple(bounds)],
                              options={"ftol": 1e-15, "gtol": 1e-10})
    u = float(found.x[0])
    h = 1e-4
    curvature = (objective([u + h])[1][0] - objective([u - h])[1][0]) / (2 * h)
    if not curvature > 0:
        raise ValueError(f"the posterior of ln ky is not peaked at its maximum (curvature {curvature:.3g}): the "
                         "Laplace approximation does not hold; use method='nuts'")
    return math.exp(u), 1.0 / math.sqrt(curvature)


def back_analysis(observations, model, priors, *, method="nuts", chains=4, draws=500, warmup=500, seed=0):
    """The posterior of a slope's yield acceleration ky [g] given observed displacements.

    Args:
        observations: a :class:`Observation` or a sequence of them (each a record, its
            PGA, and a displacement or a bound [m] with its log-normal error).
        model: :class:`Rigid` (the rigid block; D from :func:`blockdae.newmark`).
        priors: ``{"ky": distribution}`` (:class:`LogNormal`, :class:`Uniform`, or a
            :class:`Truncated` one; ky > 0 [g]).
        method: "nuts" (NumPyro's No-U-Turn sampler on the exact gradient, ``chains``
            chains run together, each ``warmup`` then ``draws`` iterations) or "laplace"
            (the maximum a posteriori with a normal approximation of ln ky there,
            ``chains * draws`` independent draws).
        seed: the random seed.

    Returns:
        a :class:`BackAnalysis`. A :class:`ConvergenceWarning` is raised where R-hat
        exceeds 1.01 or the bulk effective sample size is below 100 per chain.

    Raises:
        ValueError: an observation beyond what the prior's ky can give (D more than
            4 sigma_ln above D at the prior's 1e-6 quantile of ky, or below D at its
            1 - 1e-6 quantile), a prior with ky <= 0, a model other than the rigid block.
    """
    observations, prior = _checked(observations, model, priors)
    if method not in ("nuts", "laplace"):
        raise ValueError(f"method={method!r} is unknown; choose 'nuts' or 'laplace'")
    for field, value in (("chains", chains), ("draws", draws), ("warmup", warmup)):
        if not (isinstance(value, int) and not isinstance(value, bool) and value >= (field != "warmup")):
            raise ValueError(f"{field}={value!r} must be a whole number >= {int(field != 'warmup')}")
    _check_reachable(model, observations, prior)
    with _float64():
        log_p = _log_posterior(observations, model, prior)
        ky_map, sd_ln = _maximum(log_p, prior)
        if method == "laplace":
            ky, diagnostics, stats = _laplace_draws(prior, ky_map, sd_ln, chains, draws, seed)
        else:
            starts = _laplace_draws(prior, ky_map, sd_ln, chains, 1, seed)[0][:, 0]
            ky, diagnostics, stats = _nuts(_log_likelihoods(observations, model), prior, starts, draws, warmup, seed)
    samples = pd.DataFrame({"chain": np.repeat(np.arange(chains), draws), "draw": np.tile(np.arange(draws), chains),
                            "ky_g": ky.reshape(-1)})
    return BackAnalysis(samples, ky_map, ky_map * sd_ln, diagnostics, method, observations, model, dict(priors),
                        stats)


def _laplace_draws(prior, ky_map, sd_ln, chains, draws, seed):
    """ky = exp(N(ln ky_map, sd_ln²)) [g], restricted to the prior's support."""
    low, high = _support(prior)
    rng = np.random.default_rng(seed)
    ky = np.exp(math.log(ky_map) + sd_ln * rng.standard_normal((chains, draws)))
    if ky.min() <= low or ky.max() >= high:
        warnings.warn(f"the Laplace approximation reaches beyond the prior's support [{low}, {high}] g; "
                      "use method='nuts'", ConvergenceWarning, stacklevel=3)
    return ky, pd.DataFrame(), pd.DataFrame()


def _nuts(log_likelihood, prior, starts, draws, warmup, seed):
    """NumPyro's NUTS, one chain from each of ``starts`` [g] (draws of the Laplace
    approximation), vectorised (one engine call per step for all chains); its R-hat and
    effective sample sizes from ArviZ, and the statistics of each draw (a table)."""
    import jax
    import numpyro

    with warnings.catch_warnings():  # ArviZ's notice of its coming refactor, at import
        warnings.simplefilter("ignore", FutureWarning)
        import arviz
    from numpyro.distributions.transforms import biject_to
    from numpyro.infer import MCMC, NUTS

    density = _numpyro_prior(prior)
    chains = len(starts)

    def numpyro_model():
        numpyro.factor("observations", log_likelihood(numpyro.sample("ky", density)))

    mcmc = MCMC(NUTS(numpyro_model), num_warmup=warmup, num_samples=draws, num_chains=chains,
                chain_method="vectorized", progress_bar=False)
    start = biject_to(density.support).inv(jax.numpy.asarray(starts))
    mcmc.run(jax.random.PRNGKey(seed), init_params={"ky": start}, extra_fields=tuple(_NUTS_STATS))
    ky = np.asarray(mcmc.get_samples(group_by_chain=True)["ky"], dtype=float)
    fields = mcmc.get_extra_fields(group_by_chain=True)
    stats = pd.DataFrame({"chain": np.repeat(np.arange(chains), draws), "draw": np.tile(np.arange(draws), chains)}
                         | {name: np.asarray(fields[field]).reshape(-1) for field, name in _NUTS_STATS.items()})
    stats["lp"] = -stats["lp"]  # NumPyro's potential energy: minus the log density (in the sampler's space)
    diagnostics = pd.DataFrame({"parameter": ["ky"], "r_hat": [float(arviz.rhat(ky)) if chains > 1 else np.nan],
                                "ess_bulk": [float(arviz.ess(ky, method="bulk"))],
                                "ess_tail": [float(arviz.ess(ky, method="tail"))],
                                "divergences": [int(stats["diverging"].sum())]})
    row = diagnostics.iloc[0]
    if (chains > 1 and row.r_hat > RHAT_LIMIT) or row.ess_bulk < ESS_PER_CHAIN * chains or row.divergences:
        warnings.warn(f"the NUTS chains of ky did not mix well: R-hat {row.r_hat:.3f} (want <= {RHAT_LIMIT}), bulk "
                      f"ESS {row.ess_bulk:.0f} (want >= {ESS_PER_CHAIN * chains}), {row.divergences} divergent "
                      "transitions; run more draws or warmup", ConvergenceWarning, stacklevel=3)
    return ky, diagnostics, stats
