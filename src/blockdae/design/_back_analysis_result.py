"""A back-analysis as ArviZ's ``InferenceData``, and what its figures share: the
parameters with their columns and units, the priors' densities, each observation's
posterior predictive D [m]."""

import math
import warnings

import numpy as np

from ._distributions import LogNormal, Normal, Truncated, Uniform
from ._result import column_name


def parameters(result):
    """(name, column, unit) of each parameter of ``result``'s posterior table, in its order:
    the model's own parameters with their units ("ky", "ky_g", "g"); any other column of
    the table as its own name, its unit in that name (unit None)."""
    own = {column_name(name, result.model): (name, unit) for name, unit in result.model.PARAMETERS.items()}
    listed = []
    for column in result.samples.columns:
        if column not in ("chain", "draw"):
            name, unit = own.get(column, (column, None))
            listed.append((name, column, unit))
    return listed


#: what a parameter is, on a figure's axis
_MEANINGS = {"ky": "yield acceleration"}


def axis_label(name, unit):
    """"yield acceleration ky [g]"; a column named with its unit ("ky_g") as it is."""
    meaning = _MEANINGS.get(name)
    label = name if meaning is None else f"{meaning} {name}"
    return label if unit is None else f"{label} [{unit}]"


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
    d = [result.predict(o.record, o.pga_g).sort_values(["chain", "draw"])["D_m"].to_numpy()
         for o in result.observations]
    return np.stack(d, axis=-1).reshape(chains, draws, len(result.observations))


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
    """``result`` (a :class:`BackAnalysis`) as ArviZ's ``InferenceData``: its groups are
    those :meth:`BackAnalysis.to_inference_data` lists."""
    with warnings.catch_warnings():  # ArviZ's notice of its coming refactor, at import
        warnings.simplefilter("ignore", FutureWarning)
        import arviz
    import xarray as xr

    samples = result.samples.sort_values(["chain", "draw"])
    chains, draws = samples["chain"].nunique(), samples["draw"].nunique()
    coords = {"chain": np.arange(chains), "draw": np.arange(draws)}
    names = [o.name for o in result.observations]

    def dataset(variables, attrs, extra_coords=None):
        return xr.Dataset({name: xr.DataArray(values, dims=dims, attrs=attrs[name])
                           for name, (dims, values) in variables.items()}, coords=coords | (extra_coords or {}))

    chain_draw = ("chain", "draw")
    posterior = {name: (chain_draw, samples[column].to_numpy().reshape(chains, draws))
                 for name, column, _ in parameters(result)}
    parameter_attrs = {name: {"units": unit, "column": column} if unit else {"column": column}
                       for name, column, unit in parameters(result)}
    groups = {"posterior": dataset(posterior, parameter_attrs)}
    groups["posterior"].attrs.update(inference_library="blockdae", method=result.method)

    if len(result.sample_stats):
        stats = result.sample_stats.sort_values(["chain", "draw"])
        stat_units = dict.fromkeys(("diverging", "acceptance_rate", "n_steps", "step_size", "energy", "lp"),
                                   {"units": "-"})
        groups["sample_stats"] = dataset({name: (chain_draw, stats[name].to_numpy().reshape(chains, draws))
                                          for name in stat_units if name in stats}, stat_units)

    observation_coords = {"observation": names, "kind": ("observation", [o.kind for o in result.observations]),
                          "sigma_ln": ("observation", [o.sigma_ln for o in result.observations])}
    d = predictive_draws(result)
    sigma = np.array([o.sigma_ln for o in result.observations])
    rng = np.random.default_rng(seed)
    with np.errstate(divide="ignore"):  # D = 0 is measured as 0
        measured = np.exp(np.log(d) + sigma * rng.standard_normal(d.shape))
    dims = ("chain", "draw", "observation")
    groups["posterior_predictive"] = dataset({"D": (dims, d), "D_measured": (dims, measured)},
                                             {"D": {"units": "m"}, "D_measured": {"units": "m"}}, observation_coords)
    groups["observed_data"] = xr.Dataset(
        {"D_measured": xr.DataArray([o.value_m for o in result.observations], dims=("observation",),
                                    attrs={"units": "m"})}, coords=observation_coords)
    groups["log_likelihood"] = dataset({"D_measured": (dims, log_likelihood(result.observations, d))},
                                       {"D_measured": {"units": "-"}}, observation_coords)

    if result.priors:
        prior_draws = {name: (chain_draw, np.asarray(result.priors[name].ppf(rng.uniform(size=(chains, draws))),
                                                     dtype=float))
                       for name, _, _ in parameters(result) if name in result.priors}
        groups["prior"] = dataset(prior_draws, parameter_attrs)
    return arviz.InferenceData(**groups)
