"""A back-analysis's result as ArviZ's InferenceData (the same numbers as its tables) and
its figures (what they draw, with units on every axis)."""

import math
import warnings

import matplotlib
import numpy as np
import pandas as pd
import pytest
from scipy import stats

import blockdae as bd
from blockdae import design

pytest.importorskip("numpyro")
arviz = pytest.importorskip("arviz")
matplotlib.use("Agg")

PRIOR = design.LogNormal(median=0.1, sigma_ln=0.5)  # ky [g]


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 8, 0.01)
    return bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


@pytest.fixture(scope="module")
def observations(record):
    return [design.Observation(record, sigma_ln=0.2, displacement_m=0.1, pga_g=0.3, name="measured"),
            design.Observation(record, sigma_ln=0.3, more_than_m=0.15, pga_g=0.4, name="at least"),
            design.Observation(record, sigma_ln=0.3, less_than_m=0.6, pga_g=0.45, name="at most")]


@pytest.fixture(scope="module")
def nuts(observations):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", design.ConvergenceWarning)  # short chains
        return design.back_analysis(observations, design.Rigid(), {"ky": PRIOR}, chains=2, draws=100, warmup=100)


@pytest.fixture(scope="module")
def laplace(observations):
    return design.back_analysis(observations, design.Rigid(), {"ky": PRIOR}, method="laplace", chains=2, draws=150)


def test_inference_data_holds_the_tables_numbers(nuts, observations):
    """Posterior, sample statistics and predictive D: the very numbers of the result's
    tables; the diagnostics ArviZ computes from it: those of the result."""
    idata = nuts.to_inference_data()
    assert {"posterior", "sample_stats", "posterior_predictive", "observed_data", "log_likelihood",
            "prior"} <= set(idata.groups())
    ky = idata.posterior["ky"]
    assert ky.dims == ("chain", "draw") and ky.shape == (2, 100) and ky.attrs["units"] == "g"
    table = nuts.samples.pivot(index="chain", columns="draw", values="ky_g").to_numpy()
    np.testing.assert_array_equal(ky.values, table)

    summary = nuts.summary().iloc[0]
    assert float(ky.mean()) == pytest.approx(summary["mean"], rel=1e-14)
    assert float(ky.std(ddof=1)) == pytest.approx(summary.sd, rel=1e-12)
    assert float(ky.quantile(0.05)) == pytest.approx(summary.q05, rel=1e-14)
    diagnostics = nuts.diagnostics.iloc[0]
    assert float(arviz.rhat(idata)["ky"]) == pytest.approx(diagnostics.r_hat, rel=1e-12)
    assert float(arviz.ess(idata, method="bulk")["ky"]) == pytest.approx(diagnostics.ess_bulk, rel=1e-12)
    assert int(idata.sample_stats["diverging"].sum()) == diagnostics.divergences
    assert idata.sample_stats["diverging"].dtype == bool
    assert set(idata.sample_stats.data_vars) == {"diverging", "acceptance_rate", "n_steps", "step_size", "energy",
                                                 "lp"}
    assert (idata.sample_stats["acceptance_rate"] >= 0).all() and (idata.sample_stats["acceptance_rate"] <= 1).all()

    d = idata.posterior_predictive["D"]
    assert d.dims == ("chain", "draw", "observation") and d.attrs["units"] == "m"
    assert list(d["observation"].values) == ["measured", "at least", "at most"]
    predictive = nuts.predictive().set_index("observation")
    for name in predictive.index:
        draws = d.sel(observation=name).values.reshape(-1)
        np.testing.assert_allclose(np.quantile(draws, [0.05, 0.5, 0.95]),
                                   predictive.loc[name, ["q05_D_m", "median_D_m", "q95_D_m"]].to_numpy(dtype=float),
                                   rtol=1e-14)
    observed = idata.observed_data["D_measured"]
    assert observed.attrs["units"] == "m"
    assert list(observed.values) == [o.value_m for o in observations]
    assert list(observed["kind"].values) == ["displacement", "more_than", "less_than"]


def test_the_log_likelihood_is_the_one_the_posterior_is_computed_with(nuts, observations):
    """Per draw: the prior's log density plus the observations' log likelihoods (as stored)
    minus design.log_posterior (JAX, the one NUTS samples) is the normal density's constant
    of the measured displacement, -ln(sigma_ln sqrt(2 pi)); the bounds' terms are log
    probabilities with no constant."""
    import jax

    from blockdae.design._back_analysis_result import prior_density

    idata = nuts.to_inference_data()
    log_lik = idata.log_likelihood["D_measured"].values
    assert log_lik.shape == idata.posterior_predictive["D"].shape
    ky = idata.posterior["ky"].values
    log_p = design.log_posterior(observations, design.Rigid(), {"ky": PRIOR})
    constant = -math.log(0.2 * math.sqrt(2 * math.pi))
    with jax.enable_x64(True):
        for chain, draw in [(0, 0), (0, 57), (1, 13), (1, 99)]:
            total = math.log(prior_density(PRIOR, ky[chain, draw])) + log_lik[chain, draw].sum()
            assert total - float(log_p(ky[chain, draw])) == pytest.approx(constant, abs=1e-9)
    assert np.isfinite(arviz.loo(idata).elpd_loo)  # ArviZ finds what it needs


@pytest.mark.parametrize("prior", [PRIOR, design.Truncated(PRIOR, low=0.02, high=0.3),
                                   design.Truncated(design.Normal(0.1, 0.05), low=0.0), design.Uniform(0.02, 0.3)])
def test_the_prior_density_drawn_is_the_priors(prior):
    """Against the distribution's own cdf differenced over ± 1e-6 g."""
    from blockdae.design._back_analysis_result import prior_density

    x = np.array([0.03, 0.08, 0.12, 0.25])
    np.testing.assert_allclose(prior_density(prior, x), (prior.cdf(x + 1e-6) - prior.cdf(x - 1e-6)) / 2e-6, rtol=1e-6)
    assert prior_density(prior, np.array([-0.1]))[0] == 0.0


def test_the_prior_group_is_drawn_from_the_prior(nuts):
    idata = nuts.to_inference_data(seed=3)
    prior = idata.prior["ky"]
    assert prior.shape == (2, 100) and prior.attrs["units"] == "g"
    assert stats.kstest(prior.values.reshape(-1), PRIOR.cdf).pvalue > 0.001
    measured = idata.posterior_predictive["D_measured"].values
    ratio = np.log(measured / idata.posterior_predictive["D"].values)  # the measurement's error
    sigma = idata.posterior_predictive["sigma_ln"].values
    assert stats.kstest((ratio / sigma).reshape(-1), "norm").pvalue > 0.001
    np.testing.assert_array_equal(idata.prior["ky"].values, nuts.to_inference_data(seed=3).prior["ky"].values)


def test_a_laplace_result_has_no_sampler_statistics(laplace):
    idata = laplace.to_inference_data()
    assert "sample_stats" not in idata.groups() and len(laplace.sample_stats) == 0
    np.testing.assert_array_equal(idata.posterior["ky"].values.reshape(-1),
                                  laplace.samples.sort_values(["chain", "draw"]).ky_g.to_numpy())
    assert idata.posterior.attrs["method"] == "laplace"


def test_the_posterior_figure_draws_the_prior_posterior_and_maximum(nuts):
    """Three lines: the prior (its density, against its cdf differenced), the
    posterior's kernel estimate, the maximum a posteriori; the 90 % interval shaded."""
    import matplotlib.pyplot as plt

    fig = nuts.posterior_figure()
    ax, = fig.axes
    assert ax.get_xlabel() == "yield acceleration ky [g]" and ax.get_ylabel() == "density [1/g]"
    prior, posterior, best = ax.get_lines()
    x, y = prior.get_data()
    np.testing.assert_allclose(y, (PRIOR.cdf(x + 1e-7) - PRIOR.cdf(x - 1e-7)) / 2e-7, rtol=1e-6)
    assert best.get_xdata()[0] == nuts.map_value
    x, y = posterior.get_data()
    assert x[np.argmax(y)] == pytest.approx(nuts.samples.ky_g.median(), abs=2 * nuts.summary().sd.iloc[0])
    assert len(ax.collections) == 1  # the interval
    plt.close(fig)


def test_the_predictive_figure_draws_each_observation_and_scenario(nuts, observations, record):
    """One errorbar of the predictive D over the observations, one per observation (its
    value and 90 % measurement interval), one over the scenarios; D [m] on the y axis."""
    import matplotlib.pyplot as plt

    fig = nuts.predictive_figure(scenarios={"design motion": (record, 0.5)})
    ax, = fig.axes
    assert ax.get_ylabel() == "displacement D [m]" and ax.get_yscale() == "log"
    assert len(ax.containers) == 1 + 1 + len(observations)
    predictive, scenario, *seen = ax.containers
    np.testing.assert_allclose(predictive.lines[0].get_ydata(), nuts.predictive().median_D_m, rtol=1e-14)
    np.testing.assert_allclose(scenario.lines[0].get_ydata(), np.median(nuts.predict(record, 0.5).D_m), rtol=1e-14)
    for container, obs in zip(seen, observations):
        assert container.lines[0].get_ydata()[0] == obs.value_m
        bar = container.lines[2][0].get_segments()[0]
        spread = math.exp(1.6448536269514722 * obs.sigma_ln)
        np.testing.assert_allclose(bar[:, 1], [obs.value_m / spread, obs.value_m * spread], rtol=1e-12)
    ticks = [t.get_text() for t in ax.get_xticklabels()]
    assert ticks == ["measured\nPGA 0.3 g", "at least\nPGA 0.4 g", "at most\nPGA 0.45 g", "design motion\nPGA 0.5 g"]
    plt.close(fig)


def test_the_pair_figure_needs_two_parameters(nuts):
    """One parameter: a clear error. Two (a table of the shared c' and phi' of slopes): a
    2 x 2 corner, the pair's draws below the diagonal, units on the outer axes."""
    import matplotlib.pyplot as plt

    with pytest.raises(ValueError, match=r"needs two or more parameters; this posterior has one \(ky\)"):
        nuts.pair_figure()
    rng = np.random.default_rng(0)
    samples = pd.DataFrame({"chain": np.repeat([0, 1], 50), "draw": np.tile(np.arange(50), 2),
                            "c_kPa": rng.lognormal(np.log(6.0), 0.3, 100), "phi_deg": rng.normal(32, 2, 100)})
    slopes = design.InfiniteSlope({"north": design.Slope(slope_deg=30.0, unit_weight_kn_m3=19.0, thickness_m=3.0)})
    priors = {"c_kPa": design.LogNormal(median=6.0, sigma_ln=0.5), "phi_deg": design.Normal(32.0, 3.0)}
    two = design.SlopesBackAnalysis(samples, pd.DataFrame(), {"north": nuts.observations}, slopes, 0.0, priors,
                                    pd.DataFrame())
    fig = two.pair_figure()
    axes = np.array(fig.axes).reshape(2, 2)
    assert not axes[0, 1].get_visible()
    assert axes[1, 0].get_xlabel() == "effective cohesion c [kPa]"
    assert axes[1, 0].get_ylabel() == "effective friction angle phi [deg]"
    assert axes[1, 1].get_xlabel() == "effective friction angle phi [deg]"
    np.testing.assert_array_equal(axes[1, 0].collections[0].get_offsets(), samples[["c_kPa", "phi_deg"]].to_numpy())
    assert len(axes[0, 0].patches) == 40 and len(axes[1, 1].patches) == 40  # the histograms' bars
    plt.close(fig)
