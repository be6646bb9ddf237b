"""Back-analysis: the posterior of one or several parameters of a design model (the rigid
block's ky [g], the flexible mass's ky and vs, the plane's mu and its pull bias_x, ...) given
observed displacements, each D [m] seen with a log-normal measurement error (or a bound
on it), under a record scaled to a PGA.

The log posterior is written in JAX; the model's D and its own dD/dp (the rigid block's
exact dD/dky, the flexible mass's and the plane's through the located events of their JAX
twins: :meth:`DesignModel.gradient`) come through a ``jax.pure_callback`` wrapped in a
``jax.custom_jvp`` (:mod:`._inferred`), so that gradient-based samplers (NumPyro's No-U-Turn
sampler) and the maximum a posteriori (:mod:`._laplace`) use the model's derivative; the
Laplace approximation's draws are weighted toward the exact posterior (:mod:`._importance`).
One NUTS (:func:`nuts`, on the vector of the parameters mapped to the real line) serves a
design model's back-analysis and the shared strength of slopes
(:mod:`._infinite_slope_model`); their results share
:class:`._back_analysis_result.Posterior`. JAX, NumPyro and ArviZ (the ``inference``
extra) are imported on first use."""

import dataclasses
import itertools
import math
import warnings

import numpy as np
import pandas as pd

from ..core import jax_context
from ..excitation import Record
from ._inferred import InferredParameters, inferred_parameters, numpyro_prior, support
from ._importance import resampled
from ._laplace import (NotPeaked, REACH_QUANTILES, laplace_approximation, maximum_a_posteriori,
                       minus_log_posterior_on_points, prior_quantiles)
from ._models import DesignModel
from ._posterior import Posterior

#: the most parameters whose every corner of the priors' quantiles 1e-6 and 1 - 1e-6 the reach check runs
_CORNERS_MOST = 10
#: how many measurement sigmas an observation may lie beyond the reachable D [-]
_REACH_SIGMAS = 4.0
#: R-hat above which, and bulk effective sample size per chain below which, a warning is raised
RHAT_LIMIT = 1.01
ESS_PER_CHAIN = 100
#: the least number of draws of the Laplace approximation weighted toward the posterior:
#: enough that Pareto k̂ is estimated steadily and its limit is 0.7 (at sigma_ln 0.2 of one
#: rigid block's D, k̂'s 10-90 % range over seeds is 0.32-0.81 from 200 draws, 0.34-0.58
#: from 4000)
IMPORTANCE_DRAWS = 4000
#: NumPyro's statistics of each NUTS draw -> their names in ArviZ's sample_stats
_NUTS_STATS = {"diverging": "diverging", "accept_prob": "acceptance_rate", "num_steps": "n_steps",
               "adapt_state.step_size": "step_size", "energy": "energy", "potential_energy": "lp"}


class ConvergenceWarning(UserWarning):
    """NUTS chains that did not mix (R-hat above 1.01, a bulk effective sample size below
    100 per chain, or divergent transitions), or a Laplace approximation whose draws,
    weighted toward the posterior, are unreliable (Pareto k̂ above 0.7)."""


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


def _reach_points(parameters):
    """The sets of the parameters' values the reach of the priors is checked at (name ->
    shape (m,)): one parameter's 66 prior quantiles (1e-6, 64 evenly spread, 1 - 1e-6);
    for several, each one's 66 with the others at their medians, and every corner of the
    priors' quantiles 1e-6 and 1 - 1e-6 (up to ten parameters)."""
    priors = parameters.priors
    if len(priors) == 1:
        return {name: prior_quantiles(prior) for name, prior in priors.items()}
    medians = {name: float(prior.ppf(0.5)) for name, prior in priors.items()}
    points = [medians | {name: value} for name, prior in priors.items() for value in prior_quantiles(prior)]
    if len(priors) <= _CORNERS_MOST:
        extremes = [np.asarray(prior.ppf(np.array(REACH_QUANTILES)), dtype=float) for prior in priors.values()]
        points += [dict(zip(priors, corner)) for corner in itertools.product(*extremes)]
    return {name: np.array([point[name] for point in points]) for name in priors}


def _check_reachable(parameters, observations):
    """Raise where an observation lies beyond the D [m] the priors' values of the
    parameters give (:func:`_reach_points`; one model call per observation)."""
    points = _reach_points(parameters)
    names, units = parameters.names, parameters.units
    several = len(names) > 1

    def at(i):
        return ", ".join(f"{name} = {points[name][i]:.4g} {units[name]}" for name in names)

    over = ("over the priors' quantiles from 1e-6 to 1 - 1e-6 of each parameter (the others at their medians) and "
            "their corners" if several else "over the prior's quantiles from 1e-6 to 1 - 1e-6")
    reach = "priors reach" if several else "prior reaches"
    widen = f"widen the priors of {', '.join(names)}" if several else f"widen the prior of {names[0]}"
    for obs in observations:
        try:
            d = parameters.displacements(obs.record, obs.pga_g, points)
        except ValueError as error:
            if several:
                raise ValueError(f"the {parameters.model.kind} model refuses a set of values of {', '.join(names)} "
                                 f"the priors give ({over}): {error}; truncate the priors (design.Truncated(..., "
                                 "low=..., high=...))") from error
            grid = points[names[0]]
            raise ValueError(f"the {parameters.model.kind} model refuses a value of {names[0]} the prior gives (its "
                             f"quantiles from 1e-6 to 1 - 1e-6 span {grid[0]:.4g} to {grid[-1]:.4g} "
                             f"{units[names[0]]}): {error}; truncate the prior (design.Truncated(..., low=..., "
                             "high=...))") from error
        largest, smallest = int(np.argmax(d)), int(np.argmin(d))
        margin = math.exp(_REACH_SIGMAS * obs.sigma_ln)
        if obs.kind != "less_than" and obs.value_m > d[largest] * margin:
            raise ValueError(f"observation {obs.name!r}: {obs.kind}_m={obs.value_m!r} m lies beyond what the "
                             f"{reach}: D = {d[largest]:.4g} m at most (at {at(largest)}, "
                             f"{over}), more than {_REACH_SIGMAS:g} sigma_ln below; {widen} or check the observation")
        if obs.kind != "more_than" and obs.value_m * margin < d[smallest]:
            raise ValueError(f"observation {obs.name!r}: {obs.kind}_m={obs.value_m!r} m lies below what the "
                             f"{reach}: D = {d[smallest]:.4g} m at least (at {at(smallest)}, "
                             f"{over}), more than {_REACH_SIGMAS:g} sigma_ln above; {widen} or check the observation")


def check_counts(chains, draws, warmup, method="nuts"):
    """Raise unless ``chains`` and ``draws`` are whole numbers >= 1 (chains >= 2 for NUTS,
    whose R-hat compares them) and ``warmup`` >= 0."""
    least = {"chains": 2 if method == "nuts" else 1, "draws": 1, "warmup": 0}
    for field, value in (("chains", chains), ("draws", draws), ("warmup", warmup)):
        if not (isinstance(value, int) and not isinstance(value, bool) and value >= least[field]):
            why = " (NUTS's R-hat compares its chains)" if field == "chains" and method == "nuts" else ""
            raise ValueError(f"{field}={value!r} must be a whole number >= {least[field]}{why}")


def _log_likelihood(kind, log_value, sigma_ln, d):
    """ln p(an observation | D = ``d`` [m]) up to a constant, in JAX: the observation's
    ``kind`` ("displacement", "more_than" or "less_than"), the logarithm of its value [ln m]
    and its sigma_ln [-]."""
    import jax.numpy as jnp
    from jax.scipy.special import log_ndtr

    safe = jnp.log(jnp.where(d > 0, d, 1.0))
    log_d = jnp.where(d > 0, safe, -jnp.inf)
    z = (log_d - log_value) / sigma_ln
    if kind == "displacement":
        return jnp.where(d > 0, -0.5 * jnp.where(d > 0, z, 0.0) ** 2, -jnp.inf)
    return log_ndtr(z if kind == "more_than" else -z)


def observed_values(observations):
    """The values a compiled log likelihood takes of ``observations`` (in order): ``log_value``
    [ln m] and ``sigma_ln`` [-], arrays; what they are (their kinds, records and PGAs) is
    part of the set-up the program is compiled for."""
    return {"log_value": np.array([math.log(o.value_m) for o in observations]),
            "sigma_ln": np.array([o.sigma_ln for o in observations])}


class SetUp:
    """One set-up of a back-analysis (the model, its fixed parameters, the records and
    PGAs, the kinds of observation and prior) and its JAX programs, each compiled once:
    another analysis of the same set-up with other observed values or prior parameters
    (passed to the programs as arguments) reuses them. ``log_likelihood(values, data)``:
    the observations' joint log likelihood, a JAX function of the parameters' values
    (name -> a scalar) and the observed values (:func:`observed_values`)."""

    def __init__(self, log_likelihood):
        self.log_likelihood = log_likelihood
        self._programs = {}

    def program(self, role, build):
        """The jitted program ``build()`` makes for ``role`` (a hashable name), made once."""
        if role not in self._programs:
            self._programs[role] = build()
        return self._programs[role]


#: the set-ups analysed last (key -> SetUp), the oldest dropped beyond _SET_UPS_KEPT
_SET_UPS = {}
_SET_UPS_KEPT = 16


def set_up(key, make_log_likelihood):
    """The :class:`SetUp` of ``key`` (a hashable description of the set-up), made with
    ``make_log_likelihood()`` the first time and kept for the next analyses."""
    try:
        found = _SET_UPS.pop(key)
    except KeyError:
        found = SetUp(make_log_likelihood())
    except TypeError:  # a set-up that does not hash (a model of one's own): compiled afresh
        return SetUp(make_log_likelihood())
    _SET_UPS[key] = found
    while len(_SET_UPS) > _SET_UPS_KEPT:
        _SET_UPS.pop(next(iter(_SET_UPS)))
    return found


def log_posterior(observations, model, priors):
    """ln p(p | observations) up to a constant of the parameters ``priors`` gives a
    distribution: the priors' log densities plus each observation's log likelihood, as a
    JAX function of their values, each in its unit: of a scalar where one parameter is
    inferred, of the 1-D array of the parameters in the order ``priors`` gives them
    where several are (e.g. ``[mu, bias_x]``). Its gradient (``jax.grad``) follows the
    model's dD/dp (:meth:`DesignModel.gradient`). Evaluate it with JAX in float64
    (inside ``jax.enable_x64(True)``).

    For an :class:`InfiniteSlope` (``observations`` slope name -> observations), a JAX
    function of θ, the 1-D array of its uncertain parameters (c_kPa [kPa], phi_deg [deg],
    then each t_<slope>_m [m] with a prior, in that order)."""
    if hasattr(model, "log_posterior"):  # a parameterisation of its own (design.InfiniteSlope)
        return model.log_posterior(observations, priors)
    observations, parameters = _checked(observations, model, priors)
    return _log_posterior(observations, parameters)


def _log_posterior(observations, parameters):
    setup, data = _set_up(observations, parameters)
    names = parameters.names
    densities = {name: numpyro_prior(prior) for name, prior in parameters.priors.items()}
    if len(names) == 1:
        (name, density), = densities.items()
        return lambda value: density.log_prob(value) + setup.log_likelihood({name: value}, data)

    def log_p(theta):
        values = {name: theta[i] for i, name in enumerate(names)}
        return sum(densities[name].log_prob(values[name]) for name in names) + setup.log_likelihood(values, data)

    return log_p


def _set_up(observations, parameters):
    """(the :class:`SetUp` of the back-analysis of ``parameters`` from ``observations``,
    their observed values)."""
    groups = by_motion(range(len(observations)), key=lambda i: observations[i])
    kinds = tuple((record, pga_g, tuple(observations[i].kind for i in seen)) for (record, pga_g), seen
                  in groups.items())
    key = ("parameters", parameters.model, parameters.names, tuple(sorted(parameters.fixed.items())), kinds,
           tuple(map(tuple, groups.values())))
    return set_up(key, lambda: _log_likelihoods(groups, observations, parameters)), observed_values(observations)


def _log_likelihoods(groups, observations, parameters):
    """The observations' joint log likelihood as a JAX function of the parameters' values
    (name -> a scalar) and their observed values (:func:`observed_values`); ``groups``:
    (record, pga_g) -> the indices of the observations under that motion."""
    import jax.numpy as jnp

    functions = [parameters.displacement_function(record, pga_g) for record, pga_g in groups]
    kinds = [observations[i].kind for i in range(len(observations))]

    def log_likelihood(values, data):
        # the models' parameters > 0; the priors' densities are 0 below
        arguments = [jnp.maximum(values[name], 1e-12) for name in parameters.names]
        total = 0.0
        for seen, f in zip(groups.values(), functions):
            d = f(*arguments)  # one model call for the observations under one motion
            total += sum(_log_likelihood(kinds[i], data["log_value"][i], data["sigma_ln"][i], d) for i in seen)
        return total

    return log_likelihood


def by_motion(observations, key=lambda o: o):
    """The observations grouped by the motion they were seen under: (record, pga_g) -> the
    observations (``key`` maps an item to its :class:`Observation`), in order of first
    appearance; the model runs once per motion."""
    groups = {}
    for item in observations:
        obs = key(item)
        groups.setdefault((obs.record, obs.pga_g), []).append(item)  # a Record is hashed by identity
    return groups


def _checked(observations, model, priors):
    if isinstance(observations, Observation):
        observations = [observations]
    observations = list(observations)
    if not observations or not all(isinstance(o, Observation) for o in observations):
        raise ValueError("observations must be a design.Observation or a non-empty sequence of them")
    names = [o.name for o in observations]
    if len(set(names)) != len(names):
        raise ValueError(f"the observations' names must differ (give each a name=), got {names}")
    return observations, inferred_parameters(model, priors)


@dataclasses.dataclass
class BackAnalysis(Posterior):
    """The posterior of one or several parameters of a design model given the
    observations (its summary, predictive table, ``InferenceData`` and figures:
    :class:`Posterior`).

    Attributes:
        samples: the posterior draws, a table (``chain``, ``draw``, a column per
            parameter inferred, in the order of ``priors``: ``ky_g``, ``vs_m_s``, the
            plane's ``mu``, ...).
        map_values: the maximum a posteriori (name -> its value [its unit]).
        laplace_covariance: the covariance of the Laplace approximation at the maximum, a
            normal in u = ln p: a table with a row and a column per parameter [-] (of the
            parameters' natural logarithms, each taken in its unit: a variance of 0.01
            is a standard deviation of about 10 % of the value); None where the
            approximation does not hold (NUTS then starts from the best of the points
            the search for the maximum tried).
        diagnostics: a table, one row per parameter: NUTS's ``r_hat``, ``ess_bulk``,
            ``ess_tail`` and ``divergences``, or the Laplace approximation's ``pareto_k``
            (k̂ [-] of its importance weights: reliable up to 0.7) and ``ess_importance``
            (the weighted draws' effective sample size), the same for every parameter.
        method: "nuts" or "laplace".
        observations: the observations analysed (:class:`Observation`).
        model: the design model they were analysed with.
        fixed: the values of the model's other parameters (name -> number).
        priors: each parameter's prior (name -> distribution).
        sample_stats: NUTS's statistics of each draw (``chain``, ``draw``, ``diverging``,
            ``acceptance_rate`` [-], ``n_steps``, ``step_size``, ``energy``, ``lp``), a
            table; empty for the Laplace approximation.

    Where one parameter is inferred, ``parameter`` (its name), ``unit``, ``column``,
    ``map_value`` and ``laplace_sd`` give it alone.
    """

    samples: pd.DataFrame
    map_values: dict = dataclasses.field()  # no default: Posterior's empty one is for results without a maximum
    laplace_covariance: pd.DataFrame | None
    diagnostics: pd.DataFrame
    method: str
    observations: list
    model: DesignModel
    fixed: dict
    priors: dict
    sample_stats: pd.DataFrame

    def __repr__(self):
        parts = []
        for _, s in self.summary().iterrows():
            unit = "" if s.unit == "-" else f" {s.unit}"
            parts.append(f"{s.parameter} median {s['median']:.4g}{unit}, 90 % interval {s.q05:.4g}-{s.q95:.4g}{unit}")
        return (f"BackAnalysis(method={self.method!r}, {len(self.samples)} draws, {len(self.observations)} "
                f"observations, {'; '.join(parts)})")

    @property
    def _parameters(self) -> InferredParameters:
        return InferredParameters(self.model, dict.fromkeys(self.priors), self.fixed)

    @property
    def inferred(self) -> list:
        """[(name, column, unit)] of each parameter inferred."""
        parameters = self._parameters
        return [(name, parameters.columns[name], parameters.units[name]) for name in parameters.names]

    def _one(self, attribute):
        """The name of the one parameter inferred; AttributeError where there are several."""
        if len(self.priors) > 1:
            raise AttributeError(f"{attribute} names one parameter, and this posterior is of {len(self.priors)}: "
                                 f"{', '.join(self.priors)}; read inferred, map_values and laplace_covariance")
        return next(iter(self.priors))

    @property
    def parameter(self) -> str:
        """The name of the one parameter inferred (``"ky"``, ``"mu"``, ...)."""
        return self._one("parameter")

    @property
    def unit(self) -> str:
        """Its unit (the model's)."""
        return self._parameters.units[self._one("unit")]

    @property
    def column(self) -> str:
        """Its column in :attr:`samples`."""
        return self._parameters.columns[self._one("column")]

    @property
    def map_value(self) -> float:
        """Its maximum a posteriori value [its unit]."""
        return self.map_values[self._one("map_value")]

    @property
    def laplace_sd(self) -> float | None:
        """The standard deviation [its unit] of the Laplace approximation at the maximum
        (in the parameter's logarithm, mapped back to first order); None where the
        approximation does not hold."""
        name = self._one("laplace_sd")
        if self.laplace_covariance is None:
            return None
        return self.map_values[name] * math.sqrt(self.laplace_covariance.loc[name, name])

    def observed(self) -> list:
        """(observation, (record, pga_g)) of each observation."""
        return [(obs, (obs.record, obs.pga_g)) for obs in self.observations]

    def predict(self, record, pga_g=None) -> pd.DataFrame:
        """The posterior predictive D [m] of the slope under ``record`` scaled to ``pga_g``
        [g] (None: as given): one row per posterior draw (``chain``, ``draw``, the
        parameters' columns, ``D_m``), the model's D without measurement error."""
        if not isinstance(record, Record):
            raise ValueError(f"record must be a blockdae.Record, got {type(record).__name__}")
        if pga_g is not None:
            _positive("pga_g", pga_g)
        table = self.samples.copy()
        parameters = self._parameters
        values = {name: table[column].to_numpy() for name, column in parameters.columns.items()}
        table["D_m"] = parameters.displacements(record, pga_g, values)
        return table


def back_analysis(observations, model, priors, *, method="nuts", chains=4, draws=500, warmup=500, seed=0):
    """The posterior of one or several parameters of a design model (a slope's yield
    acceleration ky [g], a flexible mass's ky and vs [m/s], a plane's friction
    coefficient mu and pull bias_x [-], ...), or of the strength shared by slopes
    (:class:`InfiniteSlope`: c' [kPa], φ' [deg], thicknesses [m]), given observed
    displacements.

    Args:
        observations: a :class:`Observation` or a sequence of them (each a record, its
            PGA, and a displacement or a bound [m] with its log-normal error).
        model: a design model that differentiates D by the parameters inferred
            (:attr:`DesignModel.differentiable`): :class:`Rigid` (ky, the exact dD/dky of
            the compiled engine's located episodes), :class:`Flexible` (ky, height, vs, damping; not
            with the equivalent-linear iteration), :class:`Planar` (mu, mu_kinetic,
            bias_x, bias_y), :class:`Simulated` (a differentiable model's parameters),
            or one of your own; or an :class:`InfiniteSlope`: slopes of one unit
            sharing c' and φ' (then ``observations`` is a dict slope name ->
            observations, ``priors`` ``{"c_kPa": ..., "phi_deg": ...}`` (a distribution,
            or a number where known), each slope's thickness t [m] in its
            :class:`Slope`, NUTS only).
        priors: name -> a distribution (:class:`LogNormal`, :class:`Uniform`, or a
            :class:`Truncated` one; positive values) for each parameter inferred, a
            number [its unit] for each other parameter the model needs (e.g.
            ``{"ky": design.LogNormal(0.1, 0.5), "height": 20.0, "vs": 300.0}``, or
            ``{"ky": design.LogNormal(0.1, 0.5), "height": 20.0, "vs":
            design.LogNormal(300.0, 0.3)}`` for ky and vs at once). Several distributions
            give their joint posterior, the priors independent; the draws' columns and
            :func:`log_posterior`'s vector follow the order of ``priors``.
        method: "nuts" (NumPyro's No-U-Turn sampler on the model's gradient, ``chains``
            chains run together, each ``warmup`` then ``draws`` iterations, started from
            draws of the Laplace approximation) or "laplace" (the maximum a posteriori
            with a multivariate normal approximation of the parameters' logarithms there,
            its covariance the inverse of the Hessian of -ln posterior by central
            differences of the exact gradient; its draws, ``chains * draws`` and at least
            4000, weighted toward the exact posterior by Pareto-smoothed importance
            sampling (Vehtari et al. 2024), the model run at each, and ``chains * draws``
            of them resampled by their weights).
        seed: the random seed.

    The JAX programs (the maximum a posteriori's, NUTS's start, warm-up and draws) are
    compiled once per set-up (the model and its fixed parameters, the records and PGAs,
    the kinds of observation and of prior, the counts of chains, draws and warm-up) and
    kept for the process (the 16 set-ups used last): the observed values and the priors'
    parameters are their arguments, so that another analysis of the set-up runs without
    compiling, with the draws a fresh one gives for the seed.

    Returns:
        a :class:`BackAnalysis` (a :class:`SlopesBackAnalysis` for an
        :class:`InfiniteSlope`), both with the same summary, figures and
        ``to_inference_data``: a column of draws per parameter, ``map_values`` and
        ``laplace_covariance`` (in the parameters' logarithms). A
        :class:`ConvergenceWarning` is raised where R-hat exceeds 1.01, the bulk
        effective sample size is below 100 per chain, or NUTS made divergent
        transitions; for the Laplace approximation, where the Pareto k̂ of its
        importance weights exceeds min(1 - 1/log10 S, 0.7) for S weighted draws (0.7
        from 2155 draws on).

    Raises:
        ValueError: an observation beyond what the priors can give (D more than 4
            sigma_ln above the largest D over the priors' quantiles from 1e-6 to
            1 - 1e-6, or below the smallest; for several parameters, each one's
            quantiles with the others at their medians, and the corners), a prior
            giving values <= 0 a probability, a parameter the model lacks, a required
            one missing, no distribution, a parameter the model does not differentiate
            D by (NUTS and the Laplace approximation both need dD/dp), or (the Laplace
            approximation) a posterior not peaked at its maximum (the Hessian in the
            parameters' logarithms not positive definite: a ridge the observations and
            priors leave flat).
    """
    if hasattr(model, "sample_posterior"):  # a parameterisation that samples itself (design.InfiniteSlope)
        return model.sample_posterior(observations, priors, method=method, chains=chains, draws=draws, warmup=warmup,
                                      seed=seed)
    observations, parameters = _checked(observations, model, priors)
    if method not in ("nuts", "laplace"):
        raise ValueError(f"method={method!r} is unknown; choose 'nuts' or 'laplace'")
    check_counts(chains, draws, warmup, method)
    _check_reachable(parameters, observations)
    names = parameters.names
    with jax_context():  # float64 on this thread only
        setup, data = _set_up(observations, parameters)
        search = maximum_a_posteriori(setup, data, parameters.priors)
        maximum = {name: math.exp(u) for name, u in zip(names, search.u)}
        try:
            laplace = laplace_approximation(maximum, search.hessian)
        except NotPeaked:
            if method == "laplace":
                raise
            laplace = None
        if method == "laplace":
            u = laplace.draws(max(chains * draws, IMPORTANCE_DRAWS), seed)
            values, diagnostics = _importance_corrected(setup, data, parameters, laplace, u, chains * draws, seed)
            stats = pd.DataFrame()
        else:
            u = search.best_points(chains) if laplace is None else laplace.draws(chains, seed)
            starts = _starts_in_support(parameters, np.exp(u), search.u)
            drawn, diagnostics, stats = nuts(setup, data, parameters.priors,
                                             {name: starts[:, i] for i, name in enumerate(names)}, draws, warmup, seed)
            values = np.stack([drawn[name].reshape(-1) for name in names], axis=-1)
    samples = pd.DataFrame({"chain": np.repeat(np.arange(chains), draws), "draw": np.tile(np.arange(draws), chains)}
                           | {parameters.columns[name]: values[:, i] for i, name in enumerate(names)})
    covariance = None if laplace is None else pd.DataFrame(laplace.covariance, index=list(names), columns=list(names))
    return BackAnalysis(samples, maximum, covariance, diagnostics, method, observations, model, parameters.fixed,
                        dict(parameters.priors), stats)


def _starts_in_support(parameters, values, at_maximum):
    """NUTS's starting points: ``values`` (draws of the Laplace approximation, or the
    search's best points, shape (chains, d) [each parameter's unit]), each draw that
    lies beyond a prior's support replaced by the maximum a posteriori (``at_maximum``,
    in u = ln p, found within the priors' quantiles from 1e-6 to 1 - 1e-6): a chain
    starts where the posterior density is above 0."""
    outside = np.zeros(len(values), dtype=bool)
    for i, prior in enumerate(parameters.priors.values()):
        low, high = support(prior)
        outside |= (values[:, i] <= low) | (values[:, i] >= high)
    return np.where(outside[:, None], np.exp(at_maximum), values)


def _importance_corrected(setup, data, parameters, laplace, u, size, seed):
    """``size`` draws (shape (size, d) [each parameter's unit]) resampled from the Laplace
    approximation's draws ``u`` (of u = ln p, shape (n, d)) by their Pareto-smoothed
    importance weights toward the exact posterior (at all n draws in one batched model
    call per motion; a draw beyond a prior's support gets no weight), and their
    diagnostics (``parameter``, ``pareto_k``, ``ess_importance``, the same for every
    parameter: the weights are the draws'): a :class:`ConvergenceWarning` where k̂ exceeds
    the limit for n draws."""
    names = parameters.names
    densities = {name: numpyro_prior(prior) for name, prior in parameters.priors.items()}
    log_target = -np.asarray(minus_log_posterior_on_points(setup, names)(u, densities, data), dtype=float)
    for i, prior in enumerate(parameters.priors.values()):
        low, high = support(prior)
        log_target[(np.exp(u[:, i]) <= low) | (np.exp(u[:, i]) >= high)] = -np.inf
    found = resampled(u, laplace.log_density(u), log_target, size, np.random.default_rng((seed, 1)))
    if not found.pareto_k <= found.limit:
        warnings.warn(f"the Laplace approximation of {', '.join(names)}, weighted toward its posterior, is unreliable: "
                      f"Pareto k̂ = {found.pareto_k:.2f}, above {found.limit:.2f}, the limit for {len(u)} draws "
                      "(Vehtari et al. 2024); use method='nuts'", ConvergenceWarning, stacklevel=3)
    diagnostics = pd.DataFrame([{"parameter": name, "pareto_k": found.pareto_k, "ess_importance": found.ess}
                                for name in names])
    return np.exp(found.draws), diagnostics


def nuts(setup, data, priors, starts, draws, warmup, seed, stacklevel=3):
    """NumPyro's No-U-Turn sampler on the vector of the parameters ``priors`` names
    (name -> a :mod:`blockdae.design` distribution), each mapped to the real line
    (NumPyro's ``biject_to`` of its support, the Jacobian in the potential), a dense mass
    matrix adapted in warm-up; the log likelihood ``setup``'s (a :class:`SetUp`) of the
    observed values ``data``; one chain from each of ``starts`` (name -> shape
    (chains,)), the chains vectorised (one model call per step for all of them). The
    sampler (start, warm-up and draws) is one program, compiled once per set-up, names,
    counts of chains, warm-up and draws, and kinds of prior: the observed values and the
    priors' parameters are its arguments.

    Returns:
        (the draws, name -> shape (chains, draws); per parameter ArviZ's R-hat, bulk and
        tail effective sample sizes and the divergent transitions of all chains, a table;
        NUTS's statistics of each draw (``chain``, ``draw``, ``diverging``,
        ``acceptance_rate``, ``n_steps``, ``step_size``, ``energy``, ``lp``), a table). A
        :class:`ConvergenceWarning` where the chains did not mix (``stacklevel``:
        warnings.warn's, the user's call it names)."""
    import jax
    from numpyro.distributions.transforms import biject_to

    with warnings.catch_warnings():  # ArviZ's notice of its coming refactor, at import
        warnings.simplefilter("ignore", FutureWarning)
        import arviz

    names = list(priors)
    densities = {name: numpyro_prior(prior) for name, prior in priors.items()}
    chains = len(next(iter(starts.values())))
    init = jax.numpy.stack([biject_to(densities[n].support).inv(jax.numpy.asarray(starts[n])) for n in names], axis=-1)
    sampler = setup.program(("nuts", tuple(names), chains, draws, warmup),
                            lambda: _nuts_program(setup.log_likelihood, names, chains, draws, warmup))
    values, fields = sampler(jax.random.PRNGKey(seed), init, densities, data)
    samples = {n: np.asarray(v, dtype=float) for n, v in values.items()}
    stats = pd.DataFrame({"chain": np.repeat(np.arange(chains), draws), "draw": np.tile(np.arange(draws), chains)}
                         | {name: np.asarray(fields[name]).reshape(-1) for name in _NUTS_STATS.values()})
    stats["lp"] = -stats["lp"]  # NumPyro's potential energy: minus the log density (in the sampler's space)
    divergences = int(stats["diverging"].sum())
    diagnostics = pd.DataFrame([{"parameter": name, "r_hat": float(arviz.rhat(x)) if chains > 1 else np.nan,
                                 "ess_bulk": float(arviz.ess(x, method="bulk")),
                                 "ess_tail": float(arviz.ess(x, method="tail")), "divergences": divergences}
                                for name, x in samples.items()])
    worst_rhat, least_ess = diagnostics.r_hat.max(), diagnostics.ess_bulk.min()
    if (chains > 1 and worst_rhat > RHAT_LIMIT) or least_ess < ESS_PER_CHAIN * chains or divergences:
        warnings.warn(f"the NUTS chains of {', '.join(names)} did not mix well: largest R-hat {worst_rhat:.3f} (want "
                      f"<= {RHAT_LIMIT}), smallest bulk ESS {least_ess:.0f} (want >= {ESS_PER_CHAIN * chains}), "
                      f"{divergences} divergent transitions; run more draws or warmup", ConvergenceWarning,
                      stacklevel=stacklevel)
    return samples, diagnostics, stats


def _nuts_program(log_likelihood, names, chains, draws, warmup):
    """NUTS (NumPyro's ``hmc`` kernels, its default adaptation, a dense mass matrix) as one
    jitted function of (a PRNG key, the chains' unconstrained starts (chains, d), the
    priors (name -> a NumPyro distribution), the observed values) -> (name -> the
    constrained draws (chains, draws), the statistics of each draw (their names in
    ArviZ's sample_stats -> (chains, draws)))."""
    import jax
    from numpyro.distributions.transforms import biject_to
    from numpyro.infer.hmc import hmc

    def constrained(z, densities):
        return {n: biject_to(densities[n].support)(z[..., i]) for i, n in enumerate(names)}

    def potential_of(densities, data):
        def potential(z):  # -ln p of the unconstrained parameters (the transforms' Jacobians included)
            values = constrained(z, densities)
            log_p = sum(densities[n].log_prob(values[n])
                        + biject_to(densities[n].support).log_abs_det_jacobian(z[i], values[n])
                        for i, n in enumerate(names))
            return -(log_p + log_likelihood(values, data))

        return potential

    init_kernel, sample_kernel = hmc(potential_fn_gen=potential_of, algo="NUTS")

    def chain(key, start, densities, data):
        args = (densities, data)
        state = init_kernel(start, warmup, dense_mass=True, model_args=args, rng_key=key)

        def step(state, _):
            state = sample_kernel(state, model_args=args)
            return state, (state.z, {name: _field(state, field) for field, name in _NUTS_STATS.items()})

        state, _ = jax.lax.scan(step, state, None, length=warmup)
        _, (z, fields) = jax.lax.scan(step, state, None, length=draws)
        return z, fields

    def run(key, starts, densities, data):
        z, fields = jax.vmap(chain, (0, 0, None, None))(jax.random.split(key, chains), starts, densities, data)
        return constrained(z, densities), fields

    return jax.jit(run)


def _field(state, dotted):
    """The field of NumPyro's HMC state a dotted name names (``adapt_state.step_size``)."""
    for part in dotted.split("."):
        state = getattr(state, part)
    return state
