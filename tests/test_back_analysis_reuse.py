"""design.back_analysis compiles its JAX programs (the maximum a posteriori's, NUTS's start,
warm-up and draws) once per set-up (the model, its fixed parameters, the records and
PGAs, the kinds of observation and of prior): another analysis of the same set-up with
other observed values or prior parameters runs the compiled programs (no JAX compile) and
gives the posterior a fresh analysis gives."""

import warnings

import numpy as np
import pytest

import blockdae as bd
from blockdae import design
from blockdae.design import _back_analysis

pytest.importorskip("numpyro")
pytest.importorskip("arviz")

_COMPILES = {"count": 0}


def _count(event, seconds, **_):
    if event == "/jax/core/compile/backend_compile_duration":
        _COMPILES["count"] += 1


@pytest.fixture(scope="module", autouse=True)
def listener():
    import jax

    jax.monitoring.register_event_duration_secs_listener(_count)


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 8, 0.01)
    return bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


def compiles_in(call):
    """(what ``call()`` returns, the JAX compiles it made)."""
    before = _COMPILES["count"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", design.ConvergenceWarning)
        result = call()
    return result, _COMPILES["count"] - before


def test_a_second_analysis_with_other_data_and_prior_runs_compiled(record):
    """The second analysis (another displacement, its sigma_ln, another prior median)
    makes no JAX compile; its posterior is that of a fresh analysis (the cache of set-ups
    emptied, everything compiled again) with the same seed, draw for draw (the model's
    values cross into the compiled program as their bits, on whichever thread it calls
    them: the runs are reproducible to the last bit)."""
    def analysis(d, sigma_ln, median):
        return design.back_analysis(design.Observation(record, sigma_ln=sigma_ln, displacement_m=d, pga_g=0.5),
                                    design.Rigid(), {"ky": design.LogNormal(median, 0.4)}, chains=2, draws=300,
                                    warmup=200, seed=7)

    compiles_in(lambda: analysis(0.05, 0.2, 0.1))
    reused, compiled = compiles_in(lambda: analysis(0.08, 0.3, 0.12))
    assert compiled == 0
    _back_analysis._SET_UPS.clear()
    fresh, compiled = compiles_in(lambda: analysis(0.08, 0.3, 0.12))
    assert compiled > 0  # the counter sees compiles
    assert reused.map_value == fresh.map_value
    np.testing.assert_array_equal(reused.samples.ky_g, fresh.samples.ky_g)


def test_a_second_analysis_of_shared_strength_runs_compiled(record):
    """Two slopes sharing c' and phi' (one thickness a prior, one known): another pair of
    displacements and another prior of c' make no JAX compile; the draws are those of a
    fresh analysis, and the log posterior of the compiled set-up equals one built afresh
    at them."""
    slopes = design.InfiniteSlope({
        "north": design.Slope(slope_deg=30.0, unit_weight_kn_m3=19.0,
                              thickness_m=design.LogNormal(median=3.0, sigma_ln=0.2)),
        "south": design.Slope(slope_deg=25.0, unit_weight_kn_m3=19.0, thickness_m=2.0)})

    def analysis(d_north, d_south, c_median):
        observations = {"north": design.Observation(record, sigma_ln=0.3, displacement_m=d_north, pga_g=0.4),
                        "south": design.Observation(record, sigma_ln=0.3, displacement_m=d_south, pga_g=0.4)}
        priors = {"c_kPa": design.LogNormal(median=c_median, sigma_ln=0.5),
                  "phi_deg": design.Truncated(design.Normal(32.0, 3.0), low=15.0, high=45.0)}
        return observations, priors, design.back_analysis(observations, slopes, priors, chains=2, draws=50,
                                                          warmup=50)

    compiles_in(lambda: analysis(0.02, 0.03, 6.0))
    (observations, priors, result), compiled = compiles_in(lambda: analysis(0.03, 0.01, 7.0))
    assert compiled == 0
    _back_analysis._SET_UPS.clear()
    _, _, fresh = analysis(0.03, 0.01, 7.0)
    names = ["c_kPa", "phi_deg", "t_north_m"]
    np.testing.assert_array_equal(result.samples[names], fresh.samples[names])
    import jax

    theta = result.samples[names].to_numpy()[:20]
    with jax.enable_x64(True):
        compiled = [float(design.log_posterior(observations, slopes, priors)(t)) for t in theta]
        _back_analysis._SET_UPS.clear()
        afresh = [float(design.log_posterior(observations, slopes, priors)(t)) for t in theta]
    assert np.all(np.isfinite(compiled))
    np.testing.assert_array_equal(compiled, afresh)
