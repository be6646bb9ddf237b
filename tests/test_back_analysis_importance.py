"""The Laplace approximation's draws weighted toward the exact posterior by Pareto-smoothed
importance sampling (Vehtari, Simpson, Gelman, Yao & Gabry 2024) and resampled: against
closed forms (normal proposals and targets, any dimension), and for the rigid block's ky
against the posterior by quadrature (the exact forward model at every grid point), where
the plain normal is measurably off; Pareto k̂ small where the normal holds, a warning
naming k̂ where it does not."""

import math
import warnings

import numpy as np
import pytest
from scipy import integrate, stats

import blockdae as bd
from blockdae import design
from blockdae.design._importance import pareto_k_limit, resampled

pytest.importorskip("numpyro")
pytest.importorskip("arviz")

Z95 = stats.norm.ppf(0.95)
PRIOR = design.LogNormal(median=0.1, sigma_ln=0.5)  # ky [g]


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 8, 0.01)
    return bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


def _normal_log_density(x, mean, sd):
    return stats.norm.logpdf(x, mean, sd).sum(axis=-1)


def test_the_limit_of_k_hat_follows_the_number_of_draws():
    """min(1 - 1 / log10 S, 0.7): 0.5 at 100 draws, 2/3 at 1000, 0.7 from 2155 on."""
    assert pareto_k_limit(100) == pytest.approx(0.5)
    assert pareto_k_limit(1000) == pytest.approx(2 / 3)
    assert pareto_k_limit(2155) == pytest.approx(0.7) and pareto_k_limit(10 ** 6) == 0.7
    assert pareto_k_limit(5) == -math.inf


def test_normal_draws_resampled_toward_a_shifted_narrower_normal():
    """Two dimensions: draws of N(0, 1) weighted toward N((0.5, -0.3), 0.8²) (weights
    bounded: k̂ about 0); the resampled means within 4 Monte Carlo standard errors of the
    target's, sd sqrt(1 / ESS + 1 / n); the ESS of the closed form's weights, n / E[w²]
    with E[w²] = exp(m² / (2 - s²)) / (s sqrt(2 - s²)) per dimension (s 0.8, m the
    shift), within 5 %."""
    rng = np.random.default_rng(3)
    n, mean, sd = 20000, np.array([0.5, -0.3]), 0.8
    draws = rng.standard_normal((n, 2))
    found = resampled(draws, _normal_log_density(draws, 0.0, 1.0), _normal_log_density(draws, mean, sd), n, rng)
    assert found.draws.shape == (n, 2) and found.pareto_k < 0.5 and found.limit == 0.7
    second_moment = np.prod(np.exp(mean ** 2 / (2 - sd ** 2)) / (sd * math.sqrt(2 - sd ** 2)))
    assert found.ess == pytest.approx(n / second_moment, rel=0.05)
    error = sd * math.sqrt(1 / found.ess + 1 / n)
    assert np.all(np.abs(found.draws.mean(axis=0) - mean) < 4 * error)


def test_a_target_wider_than_the_proposal_gives_a_large_k_hat():
    """Draws of N(0, 1) toward N(0, 3²): the weights' tail has k = 1 - 1/3² = 0.89 (a
    normal's tail against a wider one's): k̂ above 0.7 over 4000 draws. A draw where the
    target is zero (-inf, or nan) is never resampled."""
    rng = np.random.default_rng(4)
    draws = rng.standard_normal((4000, 1))
    log_target = _normal_log_density(draws, 0.0, 3.0)
    found = resampled(draws, _normal_log_density(draws, 0.0, 1.0), log_target, 4000, rng)
    assert found.pareto_k > 0.7
    log_target[draws[:, 0] < 0] = -np.inf
    log_target[:10] = np.nan
    found = resampled(draws, _normal_log_density(draws, 0.0, 1.0), log_target, 4000, rng)
    assert np.all(found.draws >= 0) and not np.isin(found.draws, draws[:10]).any()
    with pytest.raises(ValueError, match="zero at every draw"):
        resampled(draws, _normal_log_density(draws, 0.0, 1.0), np.full(4000, -np.inf), 10, rng)


def _quadrature(record, d, sigma_ln):
    """The posterior of ky [g] by quadrature: the exact forward model at 8001 ky evenly
    spread in ln ky from 0.03 g to 0.3 g (above the record's peak, 0.279 g, D = 0: the
    posterior is zero there; at 0.03 g its density is 2e-15 of its peak), the trapezoid
    rule; against 16001 points the mean and quantiles move by less than 1e-5 sd. Returns (mean,
    sd, the 5 %, 50 % and 95 % quantiles, the density at each)."""
    grid = np.exp(np.linspace(math.log(0.03), math.log(0.3), 8001))
    model_d = design.Rigid().displacements(record, None, {"ky": grid})
    with np.errstate(divide="ignore"):
        log_density = (stats.norm.logpdf(np.log(model_d / d), scale=sigma_ln)
                       + stats.lognorm.logpdf(grid, PRIOR.sigma_ln, scale=PRIOR.median))
    density = np.exp(log_density - log_density.max())
    density /= integrate.trapezoid(density, grid)
    cdf = integrate.cumulative_trapezoid(density, grid, initial=0.0)
    mean = integrate.trapezoid(grid * density, grid)
    sd = math.sqrt(integrate.trapezoid((grid - mean) ** 2 * density, grid))
    quantiles = {q: float(np.interp(q, cdf, grid)) for q in (0.05, 0.5, 0.95)}
    return mean, sd, quantiles, {q: float(np.interp(x, grid, density)) for q, x in quantiles.items()}


def test_the_corrected_draws_match_the_posterior_where_the_normal_is_off(record):
    """ky from one displacement (the block's D at 0.12 g, sigma_ln 0.2): the posterior's
    longer tail toward low ky leaves the plain normal in ln ky (map_value, laplace_sd)
    measurably off the quadrature, its 5 % and 95 % quantiles each more than 4 Monte Carlo
    standard errors of the corrected draws away (measured 7.7 and 9.0: 0.27 and 0.29
    posterior sd), while the corrected draws (8000, resampled from as many normal draws;
    k̂ 0.56, ESS 7400) match the quadrature's mean, 5 % and 95 % quantiles within 4 of
    them (measured 0.16, 0.07 and 0.03). The Monte Carlo standard error: sd sqrt(1 / ESS
    + 1 / n) for the mean, sqrt(q (1 - q) (1 / ESS + 1 / n)) / density for a quantile (ESS
    the importance sampling's, n the draws: the weighted sample's error and the
    resampling's; over 40 seeds the errors in these units have sd 0.6 to 1.1)."""
    d = float(design.Rigid().displacements(record, None, {"ky": np.array([0.12])})[0])
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=d)
    with warnings.catch_warnings():
        warnings.simplefilter("error", design.ConvergenceWarning)
        result = design.back_analysis(seen, design.Rigid(), {"ky": PRIOR}, method="laplace", chains=4, draws=2000)
    assert list(result.diagnostics.columns) == ["parameter", "pareto_k", "ess_importance"]
    diagnostics = result.diagnostics.iloc[0]
    assert diagnostics.parameter == "ky" and diagnostics.pareto_k < 0.7 and diagnostics.ess_importance > 5000
    mean, sd, quantiles, density = _quadrature(record, d, 0.2)
    ky, n = result.samples.ky_g.to_numpy(), len(result.samples)
    relative = math.sqrt(1 / diagnostics.ess_importance + 1 / n)
    assert abs(ky.mean() - mean) < 4 * sd * relative
    sd_ln = result.laplace_sd / result.map_value
    normal = {0.05: result.map_value * math.exp(-Z95 * sd_ln), 0.95: result.map_value * math.exp(Z95 * sd_ln)}
    for q in (0.05, 0.95):
        error = math.sqrt(q * (1 - q)) * relative / density[q]
        assert abs(np.quantile(ky, q) - quantiles[q]) < 4 * error, q
        assert abs(normal[q] - quantiles[q]) > 4 * error, q


def test_k_hat_is_small_where_the_normal_holds(record):
    """A surveyed displacement (sigma_ln 0.05) pins ky: the posterior is near a normal in
    ln ky, k̂ below 0.5 (measured 0.36) and no warning."""
    d = float(design.Rigid().displacements(record, None, {"ky": np.array([0.12])})[0])
    seen = design.Observation(record, sigma_ln=0.05, displacement_m=d)
    with warnings.catch_warnings():
        warnings.simplefilter("error", design.ConvergenceWarning)
        result = design.back_analysis(seen, design.Rigid(), {"ky": PRIOR}, method="laplace", draws=500)
    assert result.diagnostics.pareto_k.iloc[0] < 0.5
    assert len(result.samples) == 2000 and result.samples.ky_g.between(0.1, 0.14).all()


def test_a_one_sided_posterior_warns_with_k_hat(record):
    """A bound ("it moved more than 0.5 m", sigma_ln 0.05) under a wide prior (sigma_ln
    1.0): the posterior follows the prior toward low ky and falls off sharply above, and
    the normal at its maximum (sd_ln 0.19, against the prior's 1.0 on the long side) is far
    off: k̂ above 0.7 (measured 0.85, ESS 150 of 4000), a ConvergenceWarning naming k̂
    and advising NUTS."""
    seen = design.Observation(record, sigma_ln=0.05, more_than_m=0.5)
    prior = {"ky": design.LogNormal(median=0.1, sigma_ln=1.0)}
    with pytest.warns(design.ConvergenceWarning, match=r"Pareto k̂ = \d\.\d\d, above 0\.70, the limit for 4000 "
                                                         r"draws .*; use method='nuts'$"):
        result = design.back_analysis(seen, design.Rigid(), prior, method="laplace", draws=1000)
    assert result.diagnostics.pareto_k.iloc[0] > 0.7
