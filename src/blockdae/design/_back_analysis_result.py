"""What every back-analysis result shares (:class:`Posterior`: its summary, its
predictive table, ArviZ's ``InferenceData``, its figures) and the pieces of it: the
parameters with their columns and units, the priors' densities, each observation's
posterior predictive D [m]."""

import math
import warnings

import numpy as np
import pandas as pd

from ._distributions import LogNormal, Normal, Truncated, Uniform


class Posterior:
    """The posterior draws of one or several parameters given observed displacements, as
    a table and as ArviZ's ``InferenceData``, with its figures. A result provides:

    - ``samples`` (a table: ``chain``, ``draw``, a column per parameter),
      ``method``, ``priors`` (parameter name -> distribution), ``sample_stats`` (NUTS's
      statistics per draw, a table; empty for the Laplace approximation);
    - ``inferred``: (name, column, unit) of each parameter inferred;
    - ``observed()``: (observation, the arguments of ``predict`` that give its D) of each
      observation, under a name unique among them;
    - ``predict(*arguments)``: a table with the model's D [m] (``D_m``) at each draw;
    - ``map_values``: parameter name -> its maximum a posteriori, where computed."""

    map_values = {}

    def summarised(self):
        """(label, column, unit) of each row of :meth:`summary`: the parameters inferred."""
        return self.inferred

    def summary(self) -> pd.DataFrame:
        """Each parameter's mean, standard deviation, median and 90 % interval, one row
        each (``parameter``, ``unit``, ``mean``, ``sd``, ``median``, ``q05``, ``q95``: in
        its unit)."""
        rows = []
        for label, column, unit in self.summarised():
            value = self.samples[column].to_numpy()
            q05, q50, q95 = np.quantile(value, [0.05, 0.5, 0.95])
            rows.append({"parameter": label, "unit": unit, "mean": value.mean(), "sd": value.std(ddof=1),
                         "median": q50, "q05": q05, "q95": q95})
        return pd.DataFrame(rows)

    def predictive(self) -> pd.DataFrame:
        """Each observation beside its posterior predictive D [m] (median and 90 %
        interval of the model's D over the posterior draws): ``observation``, ``kind``,
        ``observed_m``, ``median_D_m``, ``q05_D_m``, ``q95_D_m``."""
        rows = []
        for obs, arguments in self.observed():
            q05, q50, q95 = np.quantile(self.predict(*arguments)["D_m"].to_numpy(), [0.05, 0.5, 0.95])
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
        return inference_data(self, seed=seed)

    def posterior_figure(self, *, title=None):
        """Each parameter's prior and posterior densities, the maximum a posteriori (where
        computed) and the 90 % interval marked; a matplotlib Figure."""
        from ._back_analysis_figures import posterior_figure

        return posterior_figure(self, title=title)

    def predictive_figure(self, *, scenarios=None, title=None):
        """Each observation (with its measurement error, or its bound) beside the posterior
        predictive D [m], and the D predicted under each of ``scenarios`` (label -> the
        arguments of :meth:`predict`: (record, pga_g [g])); a matplotlib Figure."""
        from ._back_analysis_figures import predictive_figure

        return predictive_figure(self, scenarios=scenarios, title=title)

    def pair_figure(self, *, title=None):
        """The posterior draws of each pair of parameters (two or more); a matplotlib Figure."""
        from ._back_analysis_figures import pair_figure

        return pair_figure(self, title=title)


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
