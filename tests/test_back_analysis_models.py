"""design.back_analysis of any design model that differentiates D by the parameter inferred:
the flexible mass (decoupled, coupled), the block on a plane and a model of one's own;
the log posterior's gradient against central differences, the Laplace posterior against
a quadrature of the posterior, and the inputs refused."""

import dataclasses
import math
import re

import numpy as np
import pytest
from scipy import integrate, stats

import blockdae as bd
from blockdae import design

pytest.importorskip("numpyro")
pytest.importorskip("arviz")

PGA = 0.3  # [g]
Z95 = stats.norm.ppf(0.95)


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 3, 0.01)
    return bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


def _seen(model, record, priors, name, value):
    """D [m] of ``model`` at ``name`` = ``value``, the others held at their ``priors`` values."""
    fixed = {k: v for k, v in priors.items() if k != name}
    return float(model.displacements(record, PGA, fixed | {name: np.array([value])})[0])


FLEXIBLE = {"height": 10.0, "vs": 250.0, "vr": 800.0}  # vr/vs 3.2: the impedance damping 0.17, below its cap
PLANE = {"mu": design.Truncated(design.LogNormal(median=0.2, sigma_ln=0.3), low=0.06), "bias_x": -0.05}


def _gradient_matches_central_differences(observations, model, priors, points):
    """jax.grad of the log posterior (the model's own dD/dp) against central differences
    of the log posterior itself at a relative step of 1e-6 (their own error, h² f''' / 6
    + eps f / h, below 1e-8 relative here: the forward models are exact to rounding)."""
    import jax

    log_p = design.log_posterior(observations, model, priors)
    with jax.enable_x64(True):
        for value in points:
            h = 1e-6 * value
            central = (float(log_p(value + h)) - float(log_p(value - h))) / (2 * h)
            assert float(jax.grad(log_p)(value)) == pytest.approx(central, rel=1e-6), value


@pytest.mark.slow
def test_flexible_decoupled_gradient_by_ky_matches_central_differences(record):
    """dD/dky through the JAX twin's located events (decoupled); measured 1.5e-10 and
    1.2e-10 relative."""
    model, priors = design.Flexible(method="decoupled"), {"ky": design.LogNormal(0.1, 0.3)} | FLEXIBLE
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=_seen(model, record, priors, "ky", 0.1),
                              pga_g=PGA)
    _gradient_matches_central_differences(seen, model, priors, (0.08, 0.12))


@pytest.mark.slow
def test_flexible_coupled_gradient_by_vs_matches_central_differences(record):
    """dD/dvs (vr held: the impedance damping moves with vs) through the JAX twin's located
    events (coupled); vs is no design parameter, so no sliding limit applies; measured
    4.5e-10 and 1.4e-10 relative."""
    model = design.Flexible(method="coupled")
    priors = FLEXIBLE | {"ky": 0.1, "vs": design.LogNormal(250.0, 0.3)}
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=_seen(model, record, priors, "vs", 250.0),
                              pga_g=PGA)
    _gradient_matches_central_differences(seen, model, priors, (200.0, 300.0))


def test_plane_gradient_by_mu_matches_central_differences(record):
    """dD/dmu, D = |u|, mu_kinetic following mu (both move), a displacement and a bound;
    measured 2.2e-10 and 6.6e-11 relative."""
    model = design.Planar()
    d = _seen(model, record, PLANE, "mu", 0.2)
    observations = [design.Observation(record, sigma_ln=0.2, displacement_m=d, pga_g=PGA),
                    design.Observation(record, sigma_ln=0.3, more_than_m=0.5 * d, pga_g=PGA, name="bound")]
    _gradient_matches_central_differences(observations, model, PLANE, (0.15, 0.25))


def test_a_simulated_model_gradient_matches_central_differences(record):
    """design.Simulated around a PlanarBlock (the contract's gradient through
    bd.sensitivities of the model, one set at a time); measured 3.6e-10 and 1.0e-10
    relative."""
    model = design.Simulated(bd.PlanarBlock(mu=0.1, bias=(-0.05, 0.0)), {"mu": "-"}, "mu", backend="compiled",
                             floor_value=0.06)  # mu above |bias| while the sliding limit is sought
    priors = {"mu": design.Truncated(design.LogNormal(0.1, 0.3), low=0.06)}
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=_seen(model, record, priors, "mu", 0.1),
                              pga_g=PGA)
    _gradient_matches_central_differences(seen, model, priors, (0.08, 0.12))


def _quadrature(model, record, priors, name, prior_pdf, observed, sigma_ln, n=2001):
    """The posterior's mean, 5 %, 50 % and 95 % quantiles [its unit], its sd and the
    skewness of ln p, by quadrature: the forward model on ``n`` values evenly spread in
    ln p over the prior's quantiles from 1e-6 to 1 - 1e-6 (2001: about 10 per posterior
    sd; against 8001 the moments move by less than 1e-8 sd, the quantiles by less than 0.003 sd), the density
    from scipy (independent of blockdae's)."""
    prior = priors[name]
    log_grid = np.linspace(math.log(prior.ppf(1e-6)), math.log(prior.ppf(1 - 1e-6)), n)
    grid = np.exp(log_grid)
    fixed = {k: np.full(grid.shape, v) for k, v in priors.items() if k != name}
    d = model.displacements(record, PGA, fixed | {name: grid})
    with np.errstate(divide="ignore"):
        log_density = stats.norm.logpdf(np.log(d / observed), scale=sigma_ln) + np.log(prior_pdf(grid))
    density = np.exp(log_density - log_density.max())
    density /= integrate.trapezoid(density, grid)
    cdf = integrate.cumulative_trapezoid(density, grid, initial=0.0)
    mean = integrate.trapezoid(grid * density, grid)
    sd = math.sqrt(integrate.trapezoid((grid - mean) ** 2 * density, grid))
    of_log = density * grid  # the density of ln p
    log_mean = integrate.trapezoid(log_grid * of_log, log_grid)
    moments = [integrate.trapezoid((log_grid - log_mean) ** k * of_log, log_grid) for k in (2, 3)]
    quantiles = {key: np.interp(q, cdf, grid) for key, q in (("q05", 0.05), ("median", 0.5), ("q95", 0.95))}
    return {"mean": mean, **quantiles}, sd, moments[1] / moments[0] ** 1.5


def _laplace_matches_quadrature(result, reference, sd, skewness):
    """The Laplace approximation (normal in ln p at the maximum, sd_ln = laplace_sd / map)
    against the quadrature: its mean, median and 5 %, 95 % quantiles within |skewness|
    posterior sd, its own error to first order (the skewness of ln p puts the mode about
    skewness / 2 sd from the mean, and Cornish-Fisher the 5 % and 95 % quantiles a further
    skewness (z² - 1) / 6 = 0.28 skewness sd from a normal's); its draws (weighted toward
    the posterior by Pareto-smoothed importance sampling, then resampled) against the
    quadrature within 4 Monte Carlo standard errors: sd sqrt(1 / ESS + 1 / n) for the
    mean, the importance sample's error and the resampling's (ESS the importance
    sampling's, n the draws), sqrt(q (1 - q) (1 / ESS + 1 / n)) / density for the median
    (the density from a kernel estimate of the draws)."""
    sd_ln = result.laplace_sd / result.map_value
    laplace = {"mean": result.map_value * math.exp(sd_ln ** 2 / 2), "median": result.map_value,
               "q05": result.map_value * math.exp(-Z95 * sd_ln), "q95": result.map_value * math.exp(Z95 * sd_ln)}
    for key, value in reference.items():
        assert abs(laplace[key] - value) < abs(skewness) * sd, key
    draws = result.samples[result.column].to_numpy()
    error = math.sqrt(1 / float(result.diagnostics.ess_importance.iloc[0]) + 1 / len(draws))
    assert abs(draws.mean() - reference["mean"]) < 4 * sd * error
    density = stats.gaussian_kde(draws)(reference["median"])[0]
    assert abs(np.median(draws) - reference["median"]) < 4 * 0.5 * error / density


def test_plane_laplace_matches_quadrature(record):
    """mu of a plane (bias_x -0.05 held) from one displacement seen at mu = 0.2 with
    sigma_ln 0.05, the prior a log-normal truncated at 0.06 (mu must exceed |bias|).
    Measured: the Laplace mean, q05, median, q95 within 0.043, 0.070, 0.029, 0.063
    posterior sd of the quadrature's, the skewness of ln mu -0.086; the corrected draws'
    mean and median 1.6 and 2.0 Monte Carlo standard errors from it (k̂ 0.36)."""
    model = design.Planar()
    observed = _seen(model, record, PLANE, "mu", 0.2)
    result = design.back_analysis(design.Observation(record, sigma_ln=0.05, displacement_m=observed, pga_g=PGA),
                                  model, PLANE, method="laplace", draws=1000)
    assert result.parameter == "mu" and result.unit == "-" and list(result.samples.columns) == ["chain", "draw", "mu"]
    reference, sd, skewness = _quadrature(model, record, PLANE, "mu", stats.lognorm(0.3, scale=0.2).pdf, observed,
                                          0.05)
    _laplace_matches_quadrature(result, reference, sd, skewness)
    future = result.predict(record, pga_g=0.4)
    assert list(future.columns) == ["chain", "draw", "mu", "D_m"] and (future.D_m > observed).all()
    assert re.fullmatch(r"BackAnalysis\(method='laplace', 4000 draws, 1 observations, mu median 0\.\d+, 90 % "
                        r"interval 0\.\d+-0\.\d+\)", repr(result))  # mu has no unit to print


@pytest.mark.slow
def test_flexible_decoupled_laplace_matches_quadrature(record):
    """ky of a decoupled flexible mass (H 10 m, vs 250 m/s, vr 800 m/s held) from one
    displacement seen at ky = 0.1 g with sigma_ln 0.05. Measured: the Laplace mean, q05,
    median, q95 within 0.071, 0.114, 0.047, 0.109 posterior sd of the quadrature's, the
    skewness of ln ky -0.143; the corrected draws' mean and median 0.86 and 1.45 Monte
    Carlo standard errors from it (k̂ 0.40)."""
    model = design.Flexible(method="decoupled")
    priors = {"ky": design.LogNormal(median=0.1, sigma_ln=0.3)} | FLEXIBLE
    observed = _seen(model, record, priors, "ky", 0.1)
    result = design.back_analysis(design.Observation(record, sigma_ln=0.05, displacement_m=observed, pga_g=PGA),
                                  model, priors, method="laplace", draws=1000)
    assert list(result.samples.columns) == ["chain", "draw", "ky_g"] and result.fixed == FLEXIBLE
    reference, sd, skewness = _quadrature(model, record, priors, "ky", stats.lognorm(0.3, scale=0.1).pdf, observed,
                                          0.05)
    _laplace_matches_quadrature(result, reference, sd, skewness)


@dataclasses.dataclass(frozen=True)
class PowerLaw(design.DesignModel):
    """A model of one's own in closed form: D = 0.1 m (pga / ky - 1)² below ky = pga, with
    its exact dD/dky (``has_derivative``), or without (``derivative=False``)."""

    derivative: bool = True

    PARAMETERS = {"ky": "g"}
    REQUIRED = ("ky",)
    DESIGN = "ky"
    kind = "power law"

    @property
    def has_derivative(self):
        return self.derivative

    def displacements(self, record, pga, values, derivative=False):
        ky = np.asarray(values["ky"], dtype=float)
        ratio = np.maximum(pga / ky - 1.0, 0.0)
        d = 0.1 * ratio ** 2
        return (d, -0.2 * ratio * pga / ky ** 2) if derivative else d

    def sliding_limit(self, record, pga, values):
        return np.full(np.shape(values["ky"]), float(pga))


@pytest.mark.slow
def test_a_model_of_your_own_nuts_and_laplace_match_quadrature(record):
    """The contract alone (no class of blockdae's): NUTS (4 chains) matches the
    quadrature's mean and 5 %, 95 % quantiles within 4 Monte Carlo standard errors
    (sd / sqrt(ESS); for a quantile sqrt(q (1 - q) / ESS) / density, the density from a
    kernel estimate of the draws), the Laplace approximation within |skewness| sd
    (sigma_ln 0.1; measured within 0.047 sd, the skewness of ln ky -0.060) and its
    corrected draws within 4 Monte Carlo standard errors (measured 0.74 and 1.29 for the
    mean and median)."""
    priors = {"ky": design.LogNormal(median=0.1, sigma_ln=0.5)}
    observed = 0.1 * (PGA / 0.12 - 1) ** 2
    seen = design.Observation(record, sigma_ln=0.1, displacement_m=observed, pga_g=PGA)
    reference, sd, skewness = _quadrature(PowerLaw(), record, priors, "ky", stats.lognorm(0.5, scale=0.1).pdf,
                                          observed, 0.1)
    laplace = design.back_analysis(seen, PowerLaw(), priors, method="laplace", draws=1000)
    _laplace_matches_quadrature(laplace, reference, sd, skewness)
    nuts = design.back_analysis(seen, PowerLaw(), priors, chains=4, draws=500, warmup=500)
    ess = float(nuts.diagnostics.ess_bulk.iloc[0])
    ky = nuts.samples.ky_g.to_numpy()
    assert abs(ky.mean() - reference["mean"]) < 4 * sd / math.sqrt(ess)
    for key, q in (("q05", 0.05), ("q95", 0.95)):
        density = stats.gaussian_kde(ky)(reference[key])[0]
        assert abs(np.quantile(ky, q) - reference[key]) < 4 * math.sqrt(q * (1 - q) / ess) / density, key


def test_an_observation_the_model_cannot_reach_is_an_error(record):
    """50 m of a plane whose D is at most about 1 m over the prior; 10 m of a flexible mass
    over its prior of vs (D need not fall as vs rises: the largest D over the prior's
    quantiles bounds it); a prior giving a mu the plane refuses (below |bias|)."""
    with pytest.raises(ValueError, match=r"displacement_m=50.0 m lies beyond what the prior reaches: D = .* m at "
                                         r"most \(at mu = "):
        design.back_analysis(design.Observation(record, sigma_ln=0.1, displacement_m=50.0, pga_g=PGA),
                             design.Planar(), PLANE, method="laplace")
    with pytest.raises(ValueError, match=r"less_than_m=1e-06 m lies below what the prior reaches"):
        design.back_analysis(design.Observation(record, sigma_ln=0.1, less_than_m=1e-6, pga_g=PGA),
                             design.Planar(), {"mu": design.Uniform(0.06, 0.1), "bias_x": -0.05}, method="laplace")
    flexible = FLEXIBLE | {"ky": 0.1, "vs": design.LogNormal(250.0, 0.3)}
    with pytest.raises(ValueError, match=r"displacement_m=10.0 m lies beyond .* \(at vs = .* m/s"):
        design.back_analysis(design.Observation(record, sigma_ln=0.2, displacement_m=10.0, pga_g=PGA),
                             design.Flexible(method="decoupled"), flexible, method="laplace")
    with pytest.raises(ValueError, match=r"the planar model refuses a value of mu the prior gives .*mu_kinetic="
                                         r".* must exceed \|bias\|.*truncate the prior"):
        design.back_analysis(design.Observation(record, sigma_ln=0.1, displacement_m=0.1, pga_g=PGA),
                             design.Planar(), {"mu": design.LogNormal(0.2, 0.3), "bias_x": -0.05}, method="laplace")


def test_a_model_without_the_derivative_is_refused_naming_what_it_lacks(record):
    """NUTS and the Laplace approximation both follow the gradient: a model that gives no
    dD/dp is refused before any run, naming the model, the parameter and what it does
    differentiate by."""
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=0.1, pga_g=PGA)
    equivalent_linear = design.Flexible(equivalent_linear=True, reference_strain=5e-4)
    for method in ("nuts", "laplace"):
        with pytest.raises(ValueError, match=r"the flexible model gives no dD/dky, and back_analysis needs it .* "
                                             r"it differentiates D by no parameter"):
            design.back_analysis(seen, equivalent_linear, {"ky": design.LogNormal(0.1, 0.3)} | FLEXIBLE,
                                 method=method)
    with pytest.raises(ValueError, match=r"the flexible model gives no dD/dvr.* by \['ky', 'height', 'vs', "
                                         r"'damping'\]"):
        design.log_posterior(seen, design.Flexible(), FLEXIBLE | {"ky": 0.1, "vr": design.LogNormal(800.0, 0.2)})
    with pytest.raises(ValueError, match=r"the power law model gives no dD/dky.*has_derivative"):
        design.back_analysis(seen, PowerLaw(derivative=False), {"ky": design.LogNormal(0.1, 0.5)})
    peak = design.Simulated(bd.SlidingBlock(mu=0.1, direction="negative"), {"mu": "-"}, "mu", measure="peak")
    with pytest.raises(ValueError, match=r"the SlidingBlock model gives no dD/dmu"):
        design.back_analysis(seen, peak, {"mu": design.LogNormal(0.1, 0.3)})


def test_priors_are_checked_against_the_model_parameters(record):
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=0.1, pga_g=PGA)
    with pytest.raises(ValueError, match=r"parameter 'ky' is not one of the planar model's: \('mu', "):
        design.back_analysis(seen, design.Planar(), {"ky": design.LogNormal(0.1, 0.3)})
    with pytest.raises(ValueError, match=r"the flexible model needs the parameters \['vs'\]"):
        design.back_analysis(seen, design.Flexible(), {"ky": design.LogNormal(0.1, 0.3), "height": 10.0})
    with pytest.raises(ValueError, match=r"infers the parameters of the flexible model that priors gives a "
                                         r"distribution; got none"):
        design.back_analysis(seen, design.Flexible(), {"ky": 0.1, "height": 10.0, "vs": 250.0})
    with pytest.raises(ValueError, match=r"priors\['bias_x'\]=.* gives bias_x < 0 \[-\] a probability"):
        design.back_analysis(seen, design.Planar(), {"mu": 0.3, "bias_x": design.Normal(-0.05, 0.02)})
    with pytest.raises(ValueError, match=r"priors must be a dict"):
        design.log_posterior(seen, design.Planar(), [("mu", design.LogNormal(0.2, 0.3))])
