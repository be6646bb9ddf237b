"""design.back_analysis: the posterior of the rigid block's ky given observed displacements."""

import math
import warnings

import numpy as np
import pytest

import blockdae as bd
from blockdae import design

pytest.importorskip("numpyro")
pytest.importorskip("arviz")

KY_TRUE = 0.12  # [g]


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 8, 0.01)
    return bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


def observed(record, ky, pga=None):
    """D [m] of the rigid block of ``ky`` [g] (the synthetic truth)."""
    return float(design.Rigid().displacements(record, pga, {"ky": np.array([ky])})[0])


PRIOR = {"ky": design.LogNormal(median=0.1, sigma_ln=0.5)}


def test_log_posterior_gradient_matches_central_differences(record):
    """The custom derivative (the engine's exact dD/dky) against central differences of
    the log posterior itself (two of the observations under one motion: one engine call),
    step 1e-6 g (their own error, O(h²) f''' + eps f / h, about 1e-10 relative here);
    measured 2e-11 to 5e-11 relative at these four ky."""
    import jax

    observations = [design.Observation(record, sigma_ln=0.2, displacement_m=observed(record, KY_TRUE)),
                    design.Observation(record, sigma_ln=0.3, more_than_m=0.05, pga_g=0.35, name="bound"),
                    design.Observation(record, sigma_ln=0.3, less_than_m=0.5, pga_g=0.25, name="upper"),
                    design.Observation(record, sigma_ln=0.3, more_than_m=0.01, name="same motion")]
    log_p = design.log_posterior(observations, design.Rigid(), PRIOR)
    h = 1e-6
    with jax.enable_x64(True):
        for ky in (0.08, 0.11, 0.14, 0.2):
            exact = float(jax.grad(log_p)(ky))
            central = (float(log_p(ky + h)) - float(log_p(ky - h))) / (2 * h)
            assert exact == pytest.approx(central, rel=1e-6, abs=1e-6)


def test_log_posterior_in_float32_is_refused(record):
    import jax

    log_p = design.log_posterior(design.Observation(record, sigma_ln=0.2, displacement_m=0.1), design.Rigid(), PRIOR)
    with jax.enable_x64(False), pytest.raises(ValueError, match="float32 here"):
        log_p(0.1)


def test_laplace_posterior_concentrates_at_the_true_ky(record):
    """Five records' scalings observed without noise at ky = 0.12 g, sigma_ln 0.1: the
    maximum lies at the truth (the observations are exact) and the posterior is narrow."""
    observations = [design.Observation(record, sigma_ln=0.1, displacement_m=observed(record, KY_TRUE, pga),
                                       pga_g=pga, name=f"pga {pga}") for pga in (0.25, 0.3, 0.35, 0.4, 0.45)]
    result = design.back_analysis(observations, design.Rigid(), PRIOR, method="laplace", draws=400)
    # the prior (median 0.1 g, sigma_ln 0.5) shifts the maximum by about (sd_ln / 0.5)² of the gap: < 0.5 %
    assert result.map_value == pytest.approx(KY_TRUE, rel=0.01)
    summary = result.summary().iloc[0]
    assert summary.q05 < KY_TRUE < summary.q95
    assert summary.sd < 0.05 * KY_TRUE
    assert list(result.samples.columns) == ["chain", "draw", "ky_g"]
    table = result.predictive()
    assert (table.q05_D_m < table.observed_m).all() and (table.observed_m < table.q95_D_m).all()
    assert repr(result).startswith("BackAnalysis(method='laplace', 1600 draws, 5 observations, ky median 0.1")
    future = result.predict(record, pga_g=0.5)
    assert (future.D_m > observed(record, KY_TRUE, 0.4)).all()  # a stronger motion moves it more
    assert (result.predict(record, pga_g=0.05).D_m == 0).all()  # a peak below every ky: no sliding


def test_censored_observations_bound_ky(record):
    """'it moved more than d' puts ky below the ky that gives d; 'less than d' above it."""
    model = design.Rigid()
    d = observed(record, KY_TRUE)
    above = design.back_analysis(design.Observation(record, sigma_ln=0.05, more_than_m=d), model, PRIOR,
                                 method="laplace")
    below = design.back_analysis(design.Observation(record, sigma_ln=0.05, less_than_m=d), model, PRIOR,
                                 method="laplace")
    assert above.samples.ky_g.median() < KY_TRUE < below.samples.ky_g.median()
    assert (model.displacements(record, None, {"ky": np.array([above.map_value])})[0] > d * 0.9)


@pytest.mark.parametrize("prior", [design.Truncated(design.LogNormal(median=0.1, sigma_ln=0.5), low=0.02, high=0.3),
                                   design.Truncated(design.Normal(0.1, 0.05), low=0.0), design.Uniform(0.02, 0.3)])
def test_every_prior_gives_its_own_log_density(prior):
    """The prior's density in the log posterior (no observation weighs: D < 100 m certain)
    against the design distribution's cdf differenced over ±1e-6 g."""
    import jax

    t = np.arange(0, 8, 0.01)
    record = bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")
    silent = design.Observation(record, sigma_ln=0.01, less_than_m=100.0)
    log_p = design.log_posterior(silent, design.Rigid(), {"ky": prior})
    with jax.enable_x64(True):
        for ky in (0.05, 0.12, 0.25):
            density = (prior.cdf(ky + 1e-6) - prior.cdf(ky - 1e-6)) / 2e-6
            assert math.exp(float(log_p(ky))) == pytest.approx(density, rel=1e-6)


def test_an_observation_beyond_the_prior_is_an_error(record):
    too_far = design.Observation(record, sigma_ln=0.1, displacement_m=50.0)
    with pytest.raises(ValueError, match="displacement_m=50.0 m lies beyond what the prior reaches"):
        design.back_analysis(too_far, design.Rigid(), PRIOR, method="laplace")
    with pytest.raises(ValueError, match="exactly one of displacement_m, more_than_m, less_than_m"):
        design.Observation(record, sigma_ln=0.1, displacement_m=0.1, less_than_m=0.2)
    with pytest.raises(ValueError, match="gives ky < 0"):
        design.back_analysis(design.Observation(record, sigma_ln=0.1, displacement_m=0.1), design.Rigid(),
                             {"ky": design.Normal(0.1, 0.05)}, method="laplace")
    with pytest.raises(ValueError, match=r"the flexible model needs the parameters \['height', 'vs'\]"):
        design.back_analysis(design.Observation(record, sigma_ln=0.1, displacement_m=0.1), design.Flexible(),
                             PRIOR, method="laplace")
    seen = design.Observation(record, sigma_ln=0.1, displacement_m=0.1)
    with pytest.raises(ValueError, match=r"chains=1 must be a whole number >= 2 \(NUTS's R-hat compares its chains\)"):
        design.back_analysis(seen, design.Rigid(), PRIOR, method="nuts", chains=1)


@pytest.mark.slow
def test_nuts_agrees_with_quadrature_and_laplace_within_monte_carlo_error(record):
    """One observation (D at 0.12 g, sigma_ln 0.2). The reference: the posterior by
    quadrature on 4001 ky from 0.05 to 0.25 g (the exact forward model at each; the
    posterior mass outside is below 1e-12, the trapezoid error far below the Monte Carlo
    one). NUTS (4 chains) matches its mean, 5 % and 95 % quantiles within 4 Monte Carlo
    standard errors (sd / sqrt(ESS); for a quantile sqrt(q (1 - q) / ESS) / density).
    The Laplace approximation's draws (a normal in ln ky at the maximum, 0.18 posterior sd
    high in its mean here, weighted toward the posterior and resampled) match its mean
    within 4 Monte Carlo standard errors, sd sqrt(1 / ESS + 1 / n) (ESS the importance
    sampling's, n the draws; measured 0.16)."""
    from scipy import integrate, stats

    d = observed(record, KY_TRUE)
    observation = design.Observation(record, sigma_ln=0.2, displacement_m=d)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", design.ConvergenceWarning)
        nuts = design.back_analysis(observation, design.Rigid(), PRIOR, chains=4, draws=300, warmup=300)
    laplace = design.back_analysis(observation, design.Rigid(), PRIOR, method="laplace", draws=2000)

    grid = np.linspace(0.05, 0.25, 4001)
    model_d = design.Rigid().displacements(record, None, {"ky": grid})
    log_density = stats.norm.logpdf(np.log(model_d / d), scale=0.2) + stats.lognorm.logpdf(grid, 0.5, scale=0.1)
    density = np.exp(log_density - log_density.max())
    density /= integrate.trapezoid(density, grid)
    cdf = integrate.cumulative_trapezoid(density, grid, initial=0.0)
    mean = integrate.trapezoid(grid * density, grid)
    sd = math.sqrt(integrate.trapezoid((grid - mean) ** 2 * density, grid))

    ess = float(nuts.diagnostics.ess_bulk.iloc[0])
    ky = nuts.samples.ky_g.to_numpy()
    assert abs(ky.mean() - mean) < 4 * sd / math.sqrt(ess)
    for q in (0.05, 0.95):
        exact = np.interp(q, cdf, grid)
        error = math.sqrt(q * (1 - q) / ess) / np.interp(exact, grid, density)
        assert abs(np.quantile(ky, q) - exact) < 4 * error, q
    relative = math.sqrt(1 / laplace.diagnostics.ess_importance.iloc[0] + 1 / len(laplace.samples))
    assert abs(laplace.samples.ky_g.mean() - mean) < 4 * sd * relative
    assert nuts.diagnostics.r_hat.iloc[0] < 1.05


def test_short_nuts_chains_warn_and_report_their_diagnostics(record):
    """Two chains of 30 draws cannot reach 100 effective samples each: a warning, and the
    diagnostics ArviZ computed."""
    observation = design.Observation(record, sigma_ln=0.2, displacement_m=observed(record, KY_TRUE))
    with pytest.warns(design.ConvergenceWarning, match="did not mix well"):
        result = design.back_analysis(observation, design.Rigid(), PRIOR, chains=2, draws=30, warmup=30)
    assert list(result.diagnostics.columns) == ["parameter", "r_hat", "ess_bulk", "ess_tail", "divergences"]
    assert result.diagnostics.ess_bulk.iloc[0] < 200
    assert len(result.samples) == 60 and set(result.samples.chain) == {0, 1}
    assert 0.05 < result.samples.ky_g.median() < 0.25


def test_back_analysis_keeps_float64_to_its_own_thread(record):
    """JAX's float64 holds only inside the analysis, on its thread: another thread's JAX
    keeps its own precision while it runs (float32, JAX's default, unless the process
    turned float64 on), and the global flag is as it was after."""
    import threading

    import jax
    import jax.numpy as jnp

    before = jax.config.jax_enable_x64
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=observed(record, KY_TRUE))
    results = []
    worker = threading.Thread(target=lambda: results.append(
        design.back_analysis(seen, design.Rigid(), PRIOR, method="laplace", draws=100)))
    worker.start()
    dtypes = set()
    while worker.is_alive():
        dtypes.add(str(jnp.asarray(1.0).dtype))
    worker.join()
    assert results and results[0].map_value == pytest.approx(KY_TRUE, rel=0.2)
    assert dtypes == {"float64" if before else "float32"} and jax.config.jax_enable_x64 == before
