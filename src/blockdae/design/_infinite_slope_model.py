"""Back-analysis of the strength shared by several slopes of one geological unit: c' [kPa]
and φ' [deg] common to all, each slope with its own thickness t [m] (a prior, or known),
angle, unit weight and saturated fraction; each slope's ky [g] from the infinite slope of
Jibson et al. (2000) (:func:`blockdae.regional.infinite_slope`'s formula), its D [m] from
the rigid block (:class:`Rigid`'s compiled engine and exact dD/dky), and the posterior of
the named parameters by NUTS on the exact gradient (the chain rule through the formula
in JAX).

A parameter draw under which a slope's FS <= 1 (ky <= 0) has zero posterior density:
the slopes stood before the shaking whose displacements are observed, so each FS > 1 is
known. A draw outside the formula's domain (c' < 0, φ' outside (0, 90) deg, t <= 0)
has zero density too."""

import dataclasses
import math

import numpy as np
import pandas as pd

from ..core import jax_context
from ..excitation import Record
from ..regional import WATER_UNIT_WEIGHT, factor_of_safety
from ._back_analysis import (Observation, by_motion, _log_likelihood as _observation_log_likelihood,
                             check_counts, nuts, observed_values, set_up)
from ._distributions import DISTRIBUTIONS
from ._inferred import InferredParameters, numpyro_prior
from ._models import Rigid
from ._posterior import Posterior

#: the parameters shared by every slope and their units
SHARED = {"c_kPa": "kPa", "phi_deg": "deg"}
#: prior draws examined for the chains' starting points
_START_DRAWS = 256


def _number(field, value, low, high, closed_low=False):
    ok = isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and math.isfinite(value)
    if not (ok and (low <= value if closed_low else low < value) and value < high):
        raise ValueError(f"{field}={value!r} must be a number in {'[' if closed_low else '('}{low:g}, {high:g})")
    return float(value)


@dataclasses.dataclass(frozen=True)
class Slope:
    """One slope of the unit: its angle α [deg], unit weight γ [kN/m³], saturated fraction
    m [-] of the failure-surface thickness, and that thickness t [m], a number (known) or
    a distribution (a prior: :class:`LogNormal`, :class:`Uniform`, :class:`Truncated`
    with t > 0); ``water_unit_weight_kn_m3`` γ_w [kN/m³]."""

    slope_deg: float
    unit_weight_kn_m3: float
    thickness_m: object
    saturated_fraction: float = 0.0
    water_unit_weight_kn_m3: float = WATER_UNIT_WEIGHT

    def __post_init__(self):
        _number("slope_deg", self.slope_deg, 0.0, 90.0)
        _number("unit_weight_kn_m3", self.unit_weight_kn_m3, 0.0, math.inf)
        m = self.saturated_fraction
        if not (isinstance(m, (int, float, np.floating)) and not isinstance(m, bool) and 0.0 <= m <= 1.0):
            raise ValueError(f"saturated_fraction={m!r} must be a number in [0, 1]")
        _number("water_unit_weight_kn_m3", self.water_unit_weight_kn_m3, 0.0, math.inf)
        if not isinstance(self.thickness_m, DISTRIBUTIONS):
            _number("thickness_m", self.thickness_m, 0.0, math.inf)


@dataclasses.dataclass(frozen=True)
class InfiniteSlope:
    """Slopes of one geological unit sharing c' [kPa] and φ' [deg], as a back-analysis
    parameterisation (pass it as :func:`back_analysis`'s ``model``): the named
    parameters ``c_kPa``, ``phi_deg`` and ``t_<slope>_m`` for each slope whose thickness
    is a prior map to each slope's ky [g] = (FS - 1) sin α, FS of the infinite slope
    (Jibson et al. 2000); D [m] from ``model`` (the rigid block).

    Attributes:
        slopes: slope name -> :class:`Slope`.
        model: the rigid block (:class:`Rigid`, its polarity and g).
    """

    slopes: dict
    model: Rigid = Rigid()

    def __post_init__(self):
        if not isinstance(self.slopes, dict) or not self.slopes:
            raise ValueError(f"slopes must be a non-empty dict name -> design.Slope, got {self.slopes!r}")
        for name, slope in self.slopes.items():
            if not (isinstance(name, str) and name.isidentifier()) or not isinstance(slope, Slope):
                raise ValueError(f"slopes[{name!r}] must be a design.Slope under a name made of letters, digits and "
                                 f"_ (it names the column t_<name>_m), got {slope!r}")
        if not isinstance(self.model, Rigid):
            raise ValueError(f"model must be the rigid block (design.Rigid), got {type(self.model).__name__}")

    @property
    def thickness_names(self) -> dict:
        """slope name -> the name of its thickness parameter ``t_<slope>_m``."""
        return {name: f"t_{name}_m" for name in self.slopes}

    def log_posterior(self, observations, priors):
        """:func:`log_posterior` for these slopes (what :func:`design.log_posterior` calls)."""
        return log_posterior(observations, self, priors)

    def sample_posterior(self, observations, priors, *, method="nuts", chains=4, draws=500, warmup=500, seed=0):
        """:func:`slopes_back_analysis` (what :func:`design.back_analysis` calls); NUTS only."""
        if method != "nuts":
            raise ValueError(f"method={method!r}: the slopes' shared strength is sampled by NUTS only (method='nuts')")
        return slopes_back_analysis(observations, self, priors, chains=chains, draws=draws, warmup=warmup, seed=seed)

    def yield_accelerations(self, values, xp=np):
        """(FS [-], ky [g]) of each slope, two dicts slope name -> an array, from
        ``values`` (``c_kPa``, ``phi_deg`` and, for a slope whose thickness is a prior,
        ``t_<slope>_m``: numbers or arrays); ``xp`` numpy or jax.numpy. ky is
        (FS - 1) sin α; the slope has one only where FS > 1."""
        fs, ky = {}, {}
        tan_phi = xp.tan(xp.radians(values["phi_deg"]))
        for name, slope in self.slopes.items():
            alpha = math.radians(slope.slope_deg)
            t = values[self.thickness_names[name]] if isinstance(slope.thickness_m, DISTRIBUTIONS) \
                else slope.thickness_m
            fs[name], ky[name] = factor_of_safety(math.sin(alpha), math.tan(alpha), tan_phi, values["c_kPa"],
                                                  slope.unit_weight_kn_m3, t, slope.saturated_fraction,
                                                  slope.water_unit_weight_kn_m3)
        return fs, ky


def _checked(observations, slopes, priors):
    """(observations: slope name -> list of Observation, fixed: name -> number,
    uncertain: name -> distribution), checked."""
    if not isinstance(observations, dict) or not observations:
        raise ValueError("observations must be a dict slope name -> a design.Observation or a list of them")
    by_slope = {}
    for name, seen in observations.items():
        if name not in slopes.slopes:
            raise ValueError(f"observations[{name!r}]: no such slope; the slopes are {list(slopes.slopes)}")
        seen = [seen] if isinstance(seen, Observation) else list(seen)
        if not seen or not all(isinstance(o, Observation) for o in seen):
            raise ValueError(f"observations[{name!r}] must be a design.Observation or a non-empty list of them")
        names = [o.name for o in seen]
        if len(set(names)) != len(names):
            raise ValueError(f"observations[{name!r}]: the observations' names must differ (give each a name=), got "
                             f"{names}")
        by_slope[name] = seen
    if not isinstance(priors, dict) or set(priors) != set(SHARED):
        raise ValueError(f"priors must be {{'c_kPa': ..., 'phi_deg': ...}} (a distribution, or a number where "
                         f"known), got {priors!r}; each slope's thickness is given in its design.Slope")
    fixed, uncertain = {}, {}
    given = dict(priors) | {slopes.thickness_names[n]: s.thickness_m for n, s in slopes.slopes.items()}
    domain = {"c_kPa": (0.0, math.inf, True), "phi_deg": (0.0, 90.0, False)}
    for name, value in given.items():
        low, high, closed = domain.get(name, (0.0, math.inf, False))
        if isinstance(value, DISTRIBUTIONS):
            q_low, q_high = (float(value.ppf(u)) for u in (1e-6, 1.0 - 1e-6))
            if not ((low <= q_low if closed else low < q_low) and q_high < high):
                raise ValueError(f"the prior of {name} ({value!r}) reaches {q_low:.4g} to {q_high:.4g} between its "
                                 f"1e-6 and 1 - 1e-6 quantiles, beyond the infinite slope's domain "
                                 f"{'[' if closed else '('}"
                                 f"{low:g}, {high:g}); truncate it (design.Truncated)")
            uncertain[name] = value
        else:
            fixed[name] = _number(name, value, low, high, closed)
    if not uncertain:
        raise ValueError("every parameter is known: give c_kPa, phi_deg or a slope's thickness_m a distribution")
    return by_slope, fixed, uncertain


def _set_up(observations, slopes, fixed):
    """(the :class:`SetUp` of the slopes' back-analysis from ``observations`` (slope name
    -> its observations), its data: the observed values (:func:`observed_values`) and the
    known parameters (``fixed``, name -> a number))."""
    listed = [(name, o) for name, seen in observations.items() for o in seen]
    groups = by_motion(range(len(listed)), key=lambda i: listed[i][1])
    geometry = tuple((name, s.slope_deg, s.unit_weight_kn_m3, s.saturated_fraction, s.water_unit_weight_kn_m3,
                      "prior" if isinstance(s.thickness_m, DISTRIBUTIONS) else s.thickness_m)
                     for name, s in slopes.slopes.items())
    seen = tuple((record, pga_g, tuple((listed[i][0], listed[i][1].kind) for i in members))
                 for (record, pga_g), members in groups.items())
    key = ("slopes", slopes.model, geometry, seen, tuple(sorted(fixed)))
    data = observed_values([o for _, o in listed]) | {"fixed": {name: float(v) for name, v in fixed.items()}}
    return set_up(key, lambda: _log_likelihood(listed, groups, slopes)), data


def _log_likelihood(listed, groups, slopes):
    """The observations' joint log likelihood as a JAX function of the uncertain
    parameters (name -> a scalar) and the data (:func:`_set_up`'s): -inf where a slope's
    FS <= 1 or a value lies outside the formula's domain. ``listed``: (slope name,
    observation) of each observation, ``groups``: (record, pga_g) -> their indices."""
    import jax.numpy as jnp

    rigid = InferredParameters(slopes.model, {"ky": None}, {})  # a slope's D [m] as a function of its ky [g]
    functions = [rigid.displacement_function(record, pga_g) for record, pga_g in groups]

    def log_likelihood(values, data):
        values = dict(data["fixed"]) | dict(values)
        inside = (values["c_kPa"] >= 0) & (values["phi_deg"] > 0) & (values["phi_deg"] < 90)
        for name in slopes.slopes:
            inside &= jnp.asarray(values.get(slopes.thickness_names[name], 1.0)) > 0
        safe = {k: jnp.where(inside, v, _SAFE[k] if k in _SAFE else 1.0) for k, v in values.items()}
        _, ky = slopes.yield_accelerations(safe, jnp)
        stands = {name: ky[name] > 0 for name in slopes.slopes}  # FS > 1
        at = {name: jnp.where(stands[name], ky[name], 1.0) for name in slopes.slopes}  # any ky > 0: masked below
        total = 0.0
        for members, f in zip(groups.values(), functions):
            d = f(jnp.stack([at[listed[i][0]] for i in members]))  # one engine call for the slopes under one motion
            total += sum(jnp.where(stands[listed[i][0]], _observation_log_likelihood(
                listed[i][1].kind, data["log_value"][i], data["sigma_ln"][i], d[j]), -jnp.inf)
                for j, i in enumerate(members))
        return jnp.where(inside, total, -jnp.inf)

    return log_likelihood


#: values inside the formula's domain that stand in for a draw outside it (masked)
_SAFE = {"c_kPa": 0.0, "phi_deg": 30.0}


def _log_prior(values, densities, medians):
    """The uncertain parameters' joint log prior density in JAX (``values``, ``densities``
    (NumPyro distributions) and ``medians``: name -> each's): -inf outside a prior's
    support (its density evaluated at the median there)."""
    import jax.numpy as jnp

    inside = {name: d.support(values[name]) for name, d in densities.items()}
    return sum(jnp.where(inside[n], d.log_prob(jnp.where(inside[n], values[n], medians[n])), -jnp.inf)
               for n, d in densities.items())


def _prior_arguments(uncertain):
    """(name -> the NumPyro distribution, name -> the median) of each uncertain parameter."""
    return ({name: numpyro_prior(prior) for name, prior in uncertain.items()},
            {name: float(prior.ppf(0.5)) for name, prior in uncertain.items()})


def log_posterior(observations, slopes, priors):
    """ln p(θ | observations) up to a constant as a JAX function of θ, a 1-D array of
    the uncertain parameters in :func:`parameter_names`' order (c_kPa [kPa], phi_deg
    [deg], then t_<slope>_m [m]); its gradient (``jax.grad``) is exact: the chain rule
    through the infinite slope's formula and the engine's dD/dky. Evaluate it with JAX in
    float64 (inside ``jax.enable_x64(True)``)."""
    observations, fixed, uncertain = _checked(observations, slopes, priors)
    setup, data = _set_up(observations, slopes, fixed)
    densities, medians = _prior_arguments(uncertain)
    names = list(uncertain)

    def log_p(theta):
        values = {name: theta[i] for i, name in enumerate(names)}
        return _log_prior(values, densities, medians) + setup.log_likelihood(values, data)

    return log_p


def parameter_names(slopes, priors) -> list:
    """The names of the uncertain parameters, in the order of :func:`log_posterior`'s θ."""
    given = dict(priors) | {slopes.thickness_names[n]: s.thickness_m for n, s in slopes.slopes.items()}
    return [name for name, value in given.items() if isinstance(value, DISTRIBUTIONS)]


@dataclasses.dataclass
class SlopesBackAnalysis(Posterior):
    """The posterior of the strength shared by the slopes (and of their thicknesses): its
    summary, predictive table, ``InferenceData`` and figures (:class:`Posterior`).

    Attributes:
        samples: the posterior draws, a table: ``chain``, ``draw``, each uncertain
            parameter (``c_kPa``, ``phi_deg``, ``t_<slope>_m``) and each slope's
            ``ky_<slope>_g`` and ``fs_<slope>`` [-].
        diagnostics: per uncertain parameter: R-hat, bulk and tail effective sample
            sizes, divergent transitions (of all chains), a table.
        observations: slope name -> the observations analysed.
        slopes: the :class:`InfiniteSlope` they were analysed with.
        seconds: the wall time of the sampling [s] (compiling included).
        priors: each uncertain parameter's prior (name -> distribution).
        sample_stats: NUTS's statistics of each draw (``chain``, ``draw``, ``diverging``,
            ``acceptance_rate`` [-], ``n_steps``, ``step_size``, ``energy``, ``lp``), a table.
    """

    samples: pd.DataFrame
    diagnostics: pd.DataFrame
    observations: dict
    slopes: InfiniteSlope
    seconds: float
    priors: dict
    sample_stats: pd.DataFrame
    method = "nuts"

    def __repr__(self):
        return (f"SlopesBackAnalysis({len(self.samples)} draws, {len(self.slopes.slopes)} slopes, "
                f"{sum(len(v) for v in self.observations.values())} observations, parameters "
                f"{list(self.priors)})")

    @property
    def inferred(self) -> list:
        """(name, column, unit) of each uncertain parameter (``("c_kPa", "c_kPa", "kPa")``)."""
        return [(name, name, SHARED.get(name, "m")) for name in self.priors]

    def summarised(self):
        """The uncertain parameters, then each slope's ky [g]."""
        return self.inferred + [(f"ky_{n}_g", f"ky_{n}_g", "g") for n in self.slopes.slopes]

    def observed(self) -> list:
        """(observation named ``<slope>: <its name>``, (record, pga_g, slope)) of each
        observation."""
        return [(dataclasses.replace(obs, name=f"{slope}: {obs.name}"), (obs.record, obs.pga_g, slope))
                for slope, seen in self.observations.items() for obs in seen]

    def predict(self, record, pga_g=None, slope=None) -> pd.DataFrame:
        """The posterior predictive D [m] of ``slope`` (its name) under ``record`` scaled
        to ``pga_g`` [g] (None: as given): one row per posterior draw (``chain``,
        ``draw``, the parameters, ``ky_<slope>_g``, ``D_m``), the rigid block's D without
        measurement error."""
        if slope not in self.slopes.slopes:
            raise ValueError(f"slope={slope!r} is none of the slopes {list(self.slopes.slopes)}")
        if not isinstance(record, Record):
            raise ValueError(f"record must be a blockdae.Record, got {type(record).__name__}")
        if pga_g is not None:
            _number("pga_g", pga_g, 0.0, math.inf)
        table = self.samples[["chain", "draw", *self.priors, f"ky_{slope}_g"]].copy()
        rigid = InferredParameters(self.slopes.model, {"ky": None}, {})
        table["D_m"] = rigid.displacements(record, pga_g, {"ky": table[f"ky_{slope}_g"].to_numpy()})
        return table


def slopes_back_analysis(observations, slopes, priors, *, chains=4, draws=500, warmup=500, seed=0):
    """:func:`back_analysis` for an :class:`InfiniteSlope`: NUTS (NumPyro, ``chains``
    chains run together, vectorised: one engine call per observation and step for all
    chains), started from the most probable of 256 prior draws."""
    import time

    started = time.perf_counter()
    check_counts(chains, draws, warmup)
    observations, fixed, uncertain = _checked(observations, slopes, priors)
    names = list(uncertain)
    with jax_context():  # float64 on this thread only
        setup, data = _set_up(observations, slopes, fixed)
        starts = _starting_points(setup, data, uncertain, slopes, fixed, chains, seed)
        samples, diagnostics, stats = nuts(setup, data, uncertain, starts, draws, warmup, seed, stacklevel=5)
    table = {"chain": np.repeat(np.arange(chains), draws), "draw": np.tile(np.arange(draws), chains)}
    table |= {name: samples[name].reshape(-1) for name in names}
    fs, ky = slopes.yield_accelerations(fixed | {name: table[name] for name in names})
    for name in slopes.slopes:
        table[f"ky_{name}_g"] = np.broadcast_to(ky[name], (chains * draws,)).astype(float)
        table[f"fs_{name}"] = np.broadcast_to(fs[name], (chains * draws,)).astype(float)
    return SlopesBackAnalysis(pd.DataFrame(table), diagnostics, observations, slopes, time.perf_counter() - started,
                              uncertain, stats)


def _starting_points(setup, data, uncertain, slopes, fixed, chains, seed):
    """The ``chains`` most probable of :data:`_START_DRAWS` prior draws (name -> shape
    (chains,)); ValueError where none has a positive posterior density (each slope's
    share of draws with FS <= 1 named)."""
    import jax

    def log_p(values, densities, medians, data):
        return _log_prior(values, densities, medians) + setup.log_likelihood(values, data)

    rng = np.random.default_rng(seed)
    draws = {name: np.asarray(prior.ppf(rng.uniform(size=_START_DRAWS)), dtype=float)
             for name, prior in uncertain.items()}
    on_draws = setup.program(("on prior draws", tuple(uncertain)),
                             lambda: jax.jit(jax.vmap(log_p, (0, None, None, None))))
    values = np.asarray(on_draws(draws, *_prior_arguments(uncertain), data), dtype=float)
    finite = np.isfinite(values)
    if finite.sum() < 1:
        fs, _ = slopes.yield_accelerations(fixed | draws)
        unstable = {name: f"{np.mean(np.broadcast_to(f, (_START_DRAWS,)) <= 1):.0%}" for name, f in fs.items()}
        raise ValueError(f"none of {_START_DRAWS} draws of the priors explains the observations: the share of draws "
                         f"under which a slope's FS <= 1 (it would not have stood: zero density) is {unstable}; "
                         "otherwise the observations lie beyond the D the priors give. Check the priors of c_kPa, "
                         "phi_deg and the thicknesses against the slopes")
    best = np.argsort(np.where(finite, -values, np.inf))[:chains]
    best = np.resize(best[: max(1, min(chains, int(finite.sum())))], chains)
    return {name: v[best] for name, v in draws.items()}
