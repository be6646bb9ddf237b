"""design.InfiniteSlope: the back-analysis of c' and phi' shared by slopes of one unit, and
design.Rigid's fast path (D and the exact dD/dky straight from the compiled engine)."""

import math

import numpy as np
import pytest

import blockdae as bd
from blockdae import design
from blockdae.regional import infinite_slope

G = 9.80665


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 8, 0.01)
    return bd.Record(0.3 * G * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


@pytest.fixture(scope="module")
def noise():
    rng = np.random.default_rng(3)
    return bd.Record(np.convolve(rng.standard_normal(1500), np.hanning(9), "same"), 0.01, "noise")


SLOPES = design.InfiniteSlope({
    "north": design.Slope(slope_deg=30.0, unit_weight_kn_m3=19.0,
                          thickness_m=design.LogNormal(median=3.0, sigma_ln=0.2)),
    "south": design.Slope(slope_deg=25.0, unit_weight_kn_m3=19.0, saturated_fraction=0.3,
                          thickness_m=design.LogNormal(median=2.0, sigma_ln=0.2))})
PRIORS = {"c_kPa": design.LogNormal(median=6.0, sigma_ln=0.5),
          "phi_deg": design.Truncated(design.Normal(32.0, 3.0), low=15.0, high=45.0)}
TRUTH = {"c_kPa": 8.0, "phi_deg": 30.0, "t_north_m": 3.0, "t_south_m": 2.0}
PGA = 0.4  # g


def observations(record, sigma_ln=0.3):
    _, ky = SLOPES.yield_accelerations(TRUTH)
    return {name: design.Observation(record, sigma_ln=sigma_ln, pga_g=PGA, displacement_m=float(
        design.Rigid().displacements(record, PGA, {"ky": np.array([ky[name]])})[0])) for name in ky}


@pytest.mark.parametrize("polarity", ["normal", "inverse", "larger"])
def test_rigid_fast_path_matches_newmark_differentiated_through_the_jax_kernel(noise, polarity):
    """D and dD/dky = -g sum T_i^2 / 2 from the located episodes against bd.newmark with
    derivative=True (an independent computation: forward-mode differentiation of the
    JAX kernel through the event times); measured 3e-12 relative at worst."""
    ky = np.array([0.02, 0.05, 0.1, 0.2, 0.5])
    d, slope = design.Rigid(polarity=polarity).displacements(noise, 0.3, {"ky": ky}, derivative=True)
    with pytest.warns(bd.UnitsWarning, match="does not slide"):  # ky = 0.5 g
        reference = bd.newmark(noise, ky=ky, pga=0.3, polarity="both", derivative=True)
    if polarity == "larger":
        pick_inverse = reference.inverse > reference.normal
        ref_d = np.where(pick_inverse, reference.inverse, reference.normal)
        ref_slope = np.where(pick_inverse, reference.inverse_dky, reference.normal_dky)
    else:
        ref_d, ref_slope = getattr(reference, polarity), getattr(reference, polarity + "_dky")
    assert np.all(ref_d[:-1] > 0) and ref_d[-1] == 0  # 0.5 g lies above the peak: no sliding
    np.testing.assert_allclose(d, ref_d, rtol=1e-12, atol=0)
    np.testing.assert_allclose(slope, ref_slope, rtol=1e-9, atol=1e-12)
    with pytest.raises(ValueError, match=r"ky=-0\.1 must be a positive"):
        design.Rigid().displacements(noise, 0.3, {"ky": np.array([0.1, -0.1])}, derivative=True)


def test_each_slopes_ky_is_the_infinite_slope_of_jibson_et_al():
    """The same formula as the regional maps (one function), against it typed out here."""
    fs, ky = SLOPES.yield_accelerations(TRUTH)
    for name, slope in SLOPES.slopes.items():
        a, phi = math.radians(slope.slope_deg), math.radians(TRUTH["phi_deg"])
        t = TRUTH[f"t_{name}_m"]
        expected = (TRUTH["c_kPa"] / (slope.unit_weight_kn_m3 * t * math.sin(a)) + math.tan(phi) / math.tan(a)
                    - slope.saturated_fraction * 9.80665 * math.tan(phi) / (slope.unit_weight_kn_m3 * math.tan(a)))
        assert fs[name] == pytest.approx(expected, rel=1e-14)
        assert ky[name] == pytest.approx((expected - 1) * math.sin(a), rel=1e-14)
        regional_fs, regional_ky, _ = infinite_slope(slope.slope_deg, TRUTH["c_kPa"], TRUTH["phi_deg"],
                                                     slope.unit_weight_kn_m3, t, slope.saturated_fraction)
        assert (float(regional_fs), float(regional_ky)) == (fs[name], ky[name])


def test_gradient_of_the_four_parameter_posterior_matches_central_differences(record):
    """The chain rule through the formula and the engine's exact dD/dky against central
    differences of the log posterior, step 1e-6 of each value (their own error about
    1e-9 relative here); away from the truth, where the likelihood pulls."""
    import jax

    log_p = design.log_posterior(observations(record), SLOPES, PRIORS)
    h = 1e-6
    with jax.enable_x64(True):
        for theta in ([6.0, 31.0, 2.6, 2.3], [10.0, 28.5, 3.4, 1.8]):
            theta = jax.numpy.array(theta)
            exact = np.asarray(jax.grad(log_p)(theta))
            for i in range(4):
                step = h * float(theta[i])
                e = jax.numpy.zeros(4).at[i].set(step)
                central = (float(log_p(theta + e)) - float(log_p(theta - e))) / (2 * step)
                assert exact[i] == pytest.approx(central, rel=1e-6), (theta, i)
            assert np.all(np.abs(exact) > 1e-3)  # every parameter moves the posterior


def test_a_draw_under_which_a_slope_would_not_stand_has_zero_density(record):
    """FS <= 1 (here c' = 0 and phi' = 20 deg on 25-30 deg slopes) or a value outside the
    formula's domain: ln p = -inf, and its gradient stays finite (no NaN into NUTS)."""
    import jax

    log_p = design.log_posterior(observations(record), SLOPES, PRIORS)
    with jax.enable_x64(True):
        unstable = jax.numpy.array([0.5, 20.0, 3.0, 2.0])
        fs, _ = SLOPES.yield_accelerations(dict(zip(TRUTH, np.asarray(unstable))))
        assert fs["north"] < 1 and fs["south"] < 1
        assert float(log_p(unstable)) == -np.inf
        assert np.all(np.isfinite(np.asarray(jax.grad(log_p)(unstable))))
        assert float(log_p(jax.numpy.array([8.0, 30.0, -1.0, 2.0]))) == -np.inf  # t < 0
        assert np.isfinite(float(log_p(jax.numpy.array([8.0, 30.0, 3.0, 2.0]))))


def test_priors_that_leave_no_slope_standing_are_refused_naming_the_share(record):
    weak = {"c_kPa": 0.5, "phi_deg": design.Uniform(5.0, 15.0)}
    with pytest.raises(ValueError, match=r"FS <= 1 .* \{'north': '100%', 'south': '100%'\}"):
        design.back_analysis(observations(record), SLOPES, weak)


@pytest.mark.parametrize("observed, priors, message", [
    ({"east": None}, PRIORS, r"observations\['east'\]: no such slope"),
    ({"north": [design.Observation(bd.Record(np.ones(3), 0.01, "same"), sigma_ln=0.2, displacement_m=0.1)] * 2},
     PRIORS, r"observations\['north'\]: the observations' names must differ"),
    (None, {"c_kPa": design.LogNormal(median=6.0, sigma_ln=0.5)}, r"priors must be \{'c_kPa'"),
    (None, {"c_kPa": 5.0, "phi_deg": design.Normal(30.0, 20.0)}, r"prior of phi_deg .* beyond"),
])
def test_bad_input_is_refused_naming_the_field(record, observed, priors, message):
    with pytest.raises(ValueError, match=message):
        design.back_analysis(observations(record) if observed is None else observed, SLOPES, priors)
    with pytest.raises(ValueError, match="saturated_fraction=1.5"):
        design.Slope(slope_deg=30.0, unit_weight_kn_m3=19.0, thickness_m=2.0, saturated_fraction=1.5)
    with pytest.raises(ValueError, match="NUTS only"):
        design.back_analysis(observations(record), SLOPES, PRIORS, method="laplace")
    with pytest.raises(ValueError, match="chains=1 must be a whole number >= 2"):
        design.back_analysis(observations(record), SLOPES, PRIORS, chains=1)


@pytest.mark.slow
def test_shared_strength_posterior_covers_the_truth_and_its_ky(record):
    """Two slopes observed at the truth (sigma_ln 0.1): the chains mix, each slope's ky is
    pinned near its true value (the data inform ky, less so c' and phi' apart), and the
    90 % intervals hold the truth."""
    result = design.back_analysis(observations(record, sigma_ln=0.1), SLOPES, PRIORS, chains=4, draws=300,
                                  warmup=300, seed=1)
    assert (result.diagnostics.r_hat < 1.05).all()
    summary = result.summary().set_index("parameter")
    _, ky = SLOPES.yield_accelerations(TRUTH)
    for name, value in TRUTH.items():
        assert summary.q05[name] < value < summary.q95[name]
    for name in ky:
        row = summary.loc[f"ky_{name}_g"]
        assert row.q05 < ky[name] < row.q95 and row.sd < 0.15 * ky[name]
    assert (result.samples.filter(like="fs_") > 1).all().all()
    assert list(result.samples.columns[:6]) == ["chain", "draw", "c_kPa", "phi_deg", "t_north_m", "t_south_m"]


@pytest.fixture(scope="module")
def short_run(record):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", design.ConvergenceWarning)  # short chains
        return design.back_analysis(observations(record), SLOPES, PRIORS, chains=2, draws=60, warmup=60, seed=2)


def test_the_slopes_posterior_as_inference_data_holds_every_parameter(short_run, record):
    """Each uncertain parameter in the posterior and prior groups with its unit, NUTS's
    statistics per draw, and each slope's observation with the predictive D of its own ky."""
    pytest.importorskip("arviz")
    idata = short_run.to_inference_data()
    assert list(idata.posterior.data_vars) == ["c_kPa", "phi_deg", "t_north_m", "t_south_m"]
    assert [idata.posterior[n].attrs["units"] for n in idata.posterior.data_vars] == ["kPa", "deg", "m", "m"]
    assert list(idata.prior.data_vars) == list(idata.posterior.data_vars)
    np.testing.assert_array_equal(idata.posterior["phi_deg"].values.reshape(-1),
                                  short_run.samples.sort_values(["chain", "draw"]).phi_deg.to_numpy())
    assert int(idata.sample_stats["diverging"].sum()) == short_run.diagnostics.divergences.iloc[0]
    d = idata.posterior_predictive["D"]
    assert d.shape == (2, 60, 2) and list(d["observation"].values) == ["north: decaying sine", "south: decaying sine"]
    for i, slope in enumerate(["north", "south"]):
        np.testing.assert_array_equal(d.values[..., i].reshape(-1), short_run.predict(record, PGA, slope).D_m)
    predictive = short_run.predictive()
    assert list(predictive.observation) == ["north: decaying sine", "south: decaying sine"]
    summary = short_run.summary()
    assert list(summary.parameter) == ["c_kPa", "phi_deg", "t_north_m", "t_south_m", "ky_north_g", "ky_south_g"]
    assert list(summary.unit) == ["kPa", "deg", "m", "m", "g", "g"]


def test_the_slopes_figures_take_every_parameter(short_run, record):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = short_run.posterior_figure()
    assert [ax.get_xlabel() for ax in fig.axes] == ["effective cohesion c [kPa]", "effective friction angle phi [deg]",
                                                    "t_north [m]", "t_south [m]"]
    assert all(len(ax.get_lines()) == 2 for ax in fig.axes)  # prior and posterior; no maximum a posteriori
    plt.close(fig)
    fig = short_run.pair_figure()
    assert len(fig.axes) == 16
    plt.close(fig)
    fig = short_run.predictive_figure(scenarios={"north at 0.5 g": (record, 0.5, "north")})
    ax, = fig.axes
    assert [t.get_text() for t in ax.get_xticklabels()][-1] == "north at 0.5 g\nPGA 0.5 g"
    plt.close(fig)
    with pytest.raises(ValueError, match="slope='east' is none of the slopes"):
        short_run.predict(record, 0.5, "east")
