"""A back-analysis result (:class:`._posterior.Posterior`) as ArviZ's ``InferenceData``,
and what its figures share: axis labels, the priors' densities, each observation's
posterior predictive D [m]."""

import math
import warnings

import numpy as np

from ._distributions import LogNormal, Normal, Truncated, Uniform


#: what a parameter is, on a figure's axis
_MEANINGS = {"ky": "yield acceleration", "c": "effective cohesion", "phi": "effective friction angle"}


def axis_label(name, unit):
    """"yield acceleration ky [g]", "effective cohesion c [kPa]" (of ``c_kPa``)."""
    if unit and name.endswith(f"_{unit}"):
        name = name[:-len(unit) - 1]
    meaning = _MEANINGS.get(name)
    label = name if meaning is None else f"{meaning} {name}"
    return f"{label} [{unit}]"


def prior_density(prior, x):
    """The density of ``prior`` (a :mod:`blockdae.design` distribution) at ``x`` (an array,
    in the parameter's unit), per unit of it."""
    from scipy import stats

    x = np.asarray(x, dtype=float)
    if isinstance(prior, Truncated):
        low, high = (-math.inf if prior.low is None else prior.low), (math.inf if prior.high is None else prior.high)
        mass = float(np.diff(prior.distribution.cdf(np.array([low, high])))[0])
        return np.where((x >= low) & (x <= high), prior_density(prior.distribution, x) / mass, 0.0)
    if isinstance(prior, LogNormal):
        return stats.lognorm.pdf(x, prior.sigma_ln, scale=prior.median)
    if isinstance(prior, Normal):
        return stats.norm.pdf(x, prior.mean, prior.std)
    if isinstance(prior, Uniform):
        return stats.uniform.pdf(x, prior.low, prior.high - prior.low)
    raise ValueError(f"prior={prior!r} must be a design.LogNormal, Normal, Uniform or Truncated")


def predictive_draws(result):
    """The model's D [m] at each posterior draw, for each observation: shape (chains,
    draws, observations), draws in the order of (chain, draw)."""
    chains, draws = result.samples["chain"].nunique(), result.samples["draw"].nunique()
    d = [result.predict(*arguments).sort_values(["chain", "draw"])["D_m"].to_numpy()
         for _, arguments in result.observed()]
    return np.stack(d, axis=-1).reshape(chains, draws, len(d))


def log_likelihood(observations, d):
    """ln p(observation | D = ``d`` [m]) of each of ``observations`` (the last axis of
    ``d``): the normal log density of ln D_observed (mean ln D, sd sigma_ln), or ln Phi(z)
    of a bound (z = (ln D - ln bound) / sigma_ln; Phi(-z) for 'less than'); -inf for a
    displacement seen where D = 0."""
    from scipy import stats

    columns = []
    for i, obs in enumerate(observations):
        with np.errstate(divide="ignore"):
            z = (np.log(d[..., i]) - math.log(obs.value_m)) / obs.sigma_ln
        if obs.kind == "displacement":
            columns.append(stats.norm.logpdf(z) - math.log(obs.sigma_ln))
        else:
            columns.append(stats.norm.logcdf(z if obs.kind == "more_than" else -z))
    return np.stack(columns, axis=-1)


def inference_data(result, *, seed=0):
    """``result`` (a :class:`Posterior`) as ArviZ's ``InferenceData``: its groups are
    those :meth:`Posterior.to_inference_data` lists."""
    with warnings.catch_warnings():  # ArviZ's notice of its coming refactor, at import
        warnings.simplefilter("ignore", FutureWarning)
        import arviz
    import xarray as xr

    samples = result.samples.sort_values(["chain", "draw"])
    chains, draws = samples["chain"].nunique(), samples["draw"].nunique()
    coords = {"chain": np.arange(chains), "draw": np.arange(draws)}
    observations = [obs for obs, _ in result.observed()]
    names = [o.name for o in observations]

    def dataset(variables, attrs, extra_coords=None):
        return xr.Dataset({name: xr.DataArray(values, dims=dims, attrs=attrs[name])
                           for name, (dims, values) in variables.items()}, coords=coords | (extra_coords or {}))

    chain_draw = ("chain", "draw")
    posterior = {name: (chain_draw, samples[column].to_numpy().reshape(chains, draws))
                 for name, column, _ in result.inferred}
    parameter_attrs = {name: {"units": unit, "column": column} for name, column, unit in result.inferred}
    groups = {"posterior": dataset(posterior, parameter_attrs)}
    groups["posterior"].attrs.update(inference_library="blockdae", method=result.method)

    if len(result.sample_stats):
        stats = result.sample_stats.sort_values(["chain", "draw"])
        stat_units = dict.fromkeys(("diverging", "acceptance_rate", "n_steps", "step_size", "energy", "lp"),
                                   {"units": "-"})
        groups["sample_stats"] = dataset({name: (chain_draw, stats[name].to_numpy().reshape(chains, draws))
                                          for name in stat_units if name in stats}, stat_units)

    observation_coords = {"observation": names, "kind": ("observation", [o.kind for o in observations]),
                          "sigma_ln": ("observation", [o.sigma_ln for o in observations])}
    d = predictive_draws(result)
    sigma = np.array([o.sigma_ln for o in observations])
    rng = np.random.default_rng(seed)
    with np.errstate(divide="ignore"):  # D = 0 is measured as 0
        measured = np.exp(np.log(d) + sigma * rng.standard_normal(d.shape))
    dims = ("chain", "draw", "observation")
    groups["posterior_predictive"] = dataset({"D": (dims, d), "D_measured": (dims, measured)},
                                             {"D": {"units": "m"}, "D_measured": {"units": "m"}}, observation_coords)
    groups["observed_data"] = xr.Dataset(
        {"D_measured": xr.DataArray([o.value_m for o in observations], dims=("observation",),
                                    attrs={"units": "m"})}, coords=observation_coords)
    groups["log_likelihood"] = dataset({"D_measured": (dims, log_likelihood(observations, d))},
                                       {"D_measured": {"units": "-"}}, observation_coords)

    prior_draws = {name: (chain_draw, np.asarray(result.priors[name].ppf(rng.uniform(size=(chains, draws))),
                                                 dtype=float)) for name, _, _ in result.inferred}
    groups["prior"] = dataset(prior_draws, parameter_attrs)
    return arviz.InferenceData(**groups)
