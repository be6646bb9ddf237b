"""Design studies (blockdae.design): distributions, sampling, the stopping rule and the
statistics of the result, each against a closed form or an independent computation."""

import math

import numpy as np
import pytest
from scipy import stats

import blockdae as bd
import blockdae.design as dz


def _record(name="pulse train", n=400, dt=0.01, peak=0.4):
    """A short record [m/s²]: a decaying 2 Hz sine of peak ``peak`` g, then a 1 Hz one."""
    t = np.arange(n) * dt
    a = np.sin(2 * np.pi * 2.0 * t) * np.exp(-t) + 0.5 * np.sin(2 * np.pi * 1.0 * t)
    return bd.Record(a / np.max(np.abs(a)) * peak * bd.STANDARD_GRAVITY, dt, name)


RECORDS = {"first": _record("first"), "second": _record("second", n=300, dt=0.02)}


def test_log_normal_by_mean_and_cov_matches_its_closed_form():
    """Closed form: sigma_ln² = ln(1 + cov²), median = mean / sqrt(1 + cov²); the quantile at
    Phi(1) is median exp(sigma_ln); the mean is the quadrature of the quantile over (0, 1)."""
    dist = dz.LogNormal(mean=0.13, cov=0.2)
    assert dist.sigma_ln == pytest.approx(math.sqrt(math.log(1.04)), rel=1e-15)
    assert dist.median == pytest.approx(0.13 / math.sqrt(1.04), rel=1e-15)
    assert float(dist.ppf(stats.norm.cdf(1.0))) == pytest.approx(dist.median * math.exp(dist.sigma_ln), rel=1e-12)
    from scipy import integrate
    assert integrate.quad(lambda u: float(dist.ppf(u)), 0, 1, limit=200)[0] == pytest.approx(0.13, rel=1e-7)
    other = dz.LogNormal(median=dist.median, sigma_ln=dist.sigma_ln)
    assert (other.mean, other.cov) == pytest.approx((0.13, 0.2), rel=1e-14)


def test_distributions_match_scipy():
    """Independent computation: scipy.stats' normal, uniform and truncated normal."""
    u = np.linspace(0.01, 0.99, 17)
    np.testing.assert_allclose(dz.Normal(3.0, 0.5).ppf(u), stats.norm(3.0, 0.5).ppf(u), rtol=1e-13)
    np.testing.assert_allclose(dz.Uniform(1.0, 4.0).ppf(u), stats.uniform(1.0, 3.0).ppf(u), rtol=1e-13)
    truncated = dz.Truncated(dz.Normal(3.0, 0.5), low=2.5, high=4.0)
    reference = stats.truncnorm((2.5 - 3.0) / 0.5, (4.0 - 3.0) / 0.5, loc=3.0, scale=0.5)
    np.testing.assert_allclose(truncated.ppf(u), reference.ppf(u), rtol=1e-11)
    np.testing.assert_allclose(truncated.cdf(truncated.ppf(u)), u, rtol=1e-11)
    assert truncated.mean == pytest.approx(reference.mean(), rel=1e-8)
    lognormal = dz.LogNormal(median=2.0, sigma_ln=0.3)
    np.testing.assert_allclose(lognormal.cdf(lognormal.ppf(u)), u, rtol=1e-12)
    np.testing.assert_allclose(lognormal.ppf(u), stats.lognorm(0.3, scale=2.0).ppf(u), rtol=1e-13)


@pytest.mark.parametrize("kwargs, field", [({"mean": 0.1}, "cov"), ({"mean": 0.1, "cov": 0.2, "median": 0.1},
                                                                    "mean=0.1"),
                                           ({"median": -1.0, "sigma_ln": 0.2}, "median")])
def test_bad_log_normal_names_the_field(kwargs, field):
    with pytest.raises(ValueError, match=field):
        dz.LogNormal(**kwargs)


def test_gaussian_copula_gives_the_correlation_of_the_logarithms():
    """Closed form: ln ky and ln vs of correlated log-normals are bivariate normal with
    correlation rho; the sample correlation of n pairs has standard deviation about
    (1 - rho²)/sqrt(n): the estimate must lie within 4 of them."""
    from blockdae.design._study import Draws

    rho, runs = 0.6, 2048
    draws = Draws(dz.Flexible(), {"ky": dz.LogNormal(mean=0.15, cov=0.3), "vs": dz.LogNormal(mean=300, cov=0.2),
                                  "height": 10.0}, 1, "mc", 7, {("ky", "vs"): rho}, 16)
    values = draws.block(0, runs)
    estimate = np.corrcoef(np.log(values["ky"]), np.log(values["vs"]))[0, 1]
    assert abs(estimate - rho) < 4 * (1 - rho ** 2) / math.sqrt(runs)
    assert np.all(values["height"] == 10.0)


@pytest.mark.parametrize("sampling", ["sobol", "lhs"])
def test_stratified_samplings_put_one_sample_in_each_stratum(sampling):
    """Closed form: 16 scrambled Sobol points (a (0, 4, 1)-net in one dimension) or a Latin
    hypercube of 16 put exactly one point in each of the 16 equal intervals of (0, 1);
    the samples' F(ky) (the uniform each came from) must show it, record by record."""
    dist = dz.LogNormal(mean=0.15, cov=0.3)
    result = dz.exceedance(RECORDS, dz.Rigid(), {"ky": dist}, pga=0.4, threshold=0.05, sampling=sampling, runs=16,
                           runs_per_block=16, seed=3)
    for _, rows in result.table.groupby("record"):
        strata = np.floor(dist.cdf(rows["ky_g"].to_numpy()) * 16).astype(int)
        assert sorted(strata) == list(range(16))


def test_a_seed_reproduces_its_samples():
    parameters = {"ky": dz.LogNormal(mean=0.15, cov=0.3)}
    run = lambda seed: dz.exceedance(RECORDS, dz.Rigid(), parameters, pga=0.4, threshold=0.05, seed=seed, runs=8,
                                     runs_per_block=8).table
    first, again, other = run(5), run(5), run(6)
    assert first.equals(again)
    assert not np.allclose(first["ky_g"], other["ky_g"])


def test_each_sample_is_the_analysis_run_alone():
    """The package's own other path (not an independent computation): bd.newmark and
    bd.flexible called on each row's parameters alone, outside the study's batches, give
    the table's D; the engines themselves are checked against independent references in
    tests/test_newmark.py and tests/test_flexible.py."""
    rigid = dz.exceedance(RECORDS, dz.Rigid(polarity="larger"), {"ky": dz.LogNormal(mean=0.15, cov=0.3)}, pga=0.4,
                          threshold=0.05, runs=4, runs_per_block=4, sampling="mc")
    for row in rigid.table.itertuples():
        alone = bd.newmark(RECORDS[row.record], ky=row.ky_g, pga=0.4, polarity="both").maximum
        assert row.D_m == pytest.approx(float(alone), rel=1e-12, abs=1e-15)
    model = dz.Flexible(method="coupled", equivalent_linear=True, reference_strain=5e-4)
    flexible = dz.exceedance(RECORDS, model, {"ky": dz.LogNormal(mean=0.1, cov=0.2), "vs": dz.LogNormal(mean=250,
                             cov=0.15), "height": 10.0, "vr": 600.0}, pga={"first": 0.4, "second": 0.3},
                             threshold=0.05, runs=2, sampling="lhs")
    for row in flexible.table.itertuples():
        alone = bd.flexible(RECORDS[row.record], ky=row.ky_g, height=10.0, vs=row.vs_m_s, vr=600.0,
                            equivalent_linear=True, reference_strain=5e-4, pga=row.pga_g, polarity="normal")
        assert row.D_m == pytest.approx(alone["normal_m"][0], rel=1e-12, abs=1e-15)


def test_exceedance_statistics_match_an_independent_count():
    """Independent computation: the fraction of the table's D above each d, and scipy's
    Wilson interval (stats.binomtest(...).proportion_ci(method="wilson"))."""
    result = dz.exceedance(RECORDS, dz.Rigid(), {"ky": dz.LogNormal(mean=0.12, cov=0.3)}, pga=0.4, threshold=0.2,
                           runs=32, seed=2)
    d = result.table["D_m"].to_numpy()
    k = int(np.sum(d > 0.2))
    assert 0 < k < d.size
    assert result.probability == k / d.size
    reference = stats.binomtest(k, d.size).proportion_ci(0.95, method="wilson")
    assert result.probability_interval == pytest.approx((reference.low, reference.high), rel=1e-12)
    grid = np.array([0.001, 0.01, 0.1, 0.2, 0.5])
    curve = result.curve(grid)
    np.testing.assert_array_equal(curve["P_exceed"], [np.mean(d > x) for x in grid])
    assert np.all(curve["P_low"] <= curve["P_exceed"]) and np.all(curve["P_exceed"] <= curve["P_high"])
    shares = result.contributions()
    assert shares["share"].sum() == pytest.approx(1.0, rel=1e-15)
    for row in shares.itertuples():
        mine = result.table[result.table["record"] == row.record]["D_m"]
        assert row.P_exceed == np.mean(mine > 0.2) and row.share == np.sum(mine > 0.2) / k
        assert row.mean_D_m == pytest.approx(mine.mean(), rel=1e-15)


def test_the_stopping_rule_stops_at_the_first_block_that_meets_it():
    """The relative standard error is recomputed from the table (run means over the
    record set, their standard deviation over sqrt(runs)); the block before the last did
    not meet the bar, the last does."""
    result = dz.exceedance(RECORDS, dz.Rigid(), {"ky": dz.LogNormal(mean=0.12, cov=0.4)}, pga=0.4, threshold=0.03,
                           rse=0.03, runs_per_block=4, sampling="mc", seed=4)
    assert result.converged and len(result.history) >= 2
    run_means = result.displacements.mean(axis=1)
    assert result.rse == pytest.approx(run_means.std(ddof=1) / math.sqrt(run_means.size) / run_means.mean(),
                                       rel=1e-12)
    assert result.rse <= 0.03 < result.history["rse"].iloc[-2]
    assert result.history["runs"].iloc[-1] == run_means.size == 4 * len(result.history)


def test_the_interval_rule_and_the_run_limit():
    result = dz.exceedance(RECORDS, dz.Rigid(), {"ky": dz.LogNormal(mean=0.12, cov=0.4)}, pga=0.4, threshold=0.03,
                           rse=None, halfwidth=0.001, runs_per_block=4, max_runs=8, sampling="mc")
    assert not result.converged and result.history["runs"].iloc[-1] == 8
    assert result.history["halfwidth"].iloc[-1] > 0.001


@pytest.mark.parametrize("parameters, match", [({"ky": 0.1, "mu": 0.2}, "'mu'"), ({"vs": 200.0}, "needs"),
                                               ({"ky": "0.1"}, "ky")])
def test_bad_parameters_are_named(parameters, match):
    with pytest.raises(ValueError, match=match):
        dz.exceedance(RECORDS, dz.Rigid() if "vs" not in parameters else dz.Flexible(), parameters, threshold=0.1,
                      runs=2)


def test_bad_inputs_are_named():
    ky = {"ky": dz.LogNormal(mean=0.1, cov=0.2)}
    with pytest.raises(ValueError, match="model="):
        dz.exceedance(RECORDS, bd.SlidingBlock(mu=0.1), ky, threshold=0.1, runs=2)
    with pytest.raises(ValueError, match="missing \\['second'\\]"):
        dz.exceedance(RECORDS, dz.Rigid(), ky, pga={"first": 0.3}, threshold=0.1, runs=2)
    with pytest.raises(ValueError, match="power of 2"):
        dz.exceedance(RECORDS, dz.Rigid(), ky, threshold=0.1, runs_per_block=6)
    with pytest.raises(ValueError, match="threshold"):
        dz.exceedance(RECORDS, dz.Rigid(), ky, threshold=-0.1, runs=2)
    with pytest.raises(ValueError, match="positive definite"):
        dz.exceedance(RECORDS, dz.Flexible(), {"ky": dz.LogNormal(mean=0.1, cov=0.2), "vs": dz.Uniform(200, 300),
                      "height": dz.Uniform(5, 10)}, threshold=0.1, runs=2,
                      correlation={("ky", "vs"): 0.9, ("vs", "height"): 0.9, ("ky", "height"): -0.9})


def test_figures_draw():
    import matplotlib
    matplotlib.use("Agg")
    result = dz.exceedance(RECORDS, dz.Rigid(), {"ky": dz.LogNormal(mean=0.12, cov=0.3)}, pga=0.4, threshold=0.03,
                           runs=8, runs_per_block=8)
    assert "P(D > d)" in result.figure().axes[0].get_ylabel()
    assert "ky" in result.ky_figure().axes[0].get_xlabel()


def test_a_checkpoint_resumes_to_the_same_result(tmp_path, monkeypatch):
    """A rerun with the checkpoint runs only the missing block and gives the table of an
    uninterrupted run, bit for bit; another study's folder is refused, naming what differs."""
    parameters = {"ky": dz.LogNormal(mean=0.12, cov=0.4)}
    run = lambda **kw: dz.exceedance(RECORDS, dz.Rigid(), parameters, pga=0.4, threshold=0.03, runs_per_block=4,
                                     rse=0.03, sampling="lhs", seed=4, **kw)
    whole = run()
    first = run(checkpoint=tmp_path / "c")
    assert first.table.equals(whole.table) and first.history.equals(whole.history)
    blocks = sorted((tmp_path / "c").glob("block-*.csv"))
    assert len(blocks) == len(whole.history) >= 2
    blocks[1].unlink()
    calls = []
    original = dz.Rigid.displacements
    monkeypatch.setattr(dz.Rigid, "displacements", lambda self, *a, **k: calls.append(1) or original(self, *a, **k))
    again = run(checkpoint=tmp_path / "c")
    assert again.table.equals(whole.table) and len(calls) == len(RECORDS)  # block 1 only, each record once
    with pytest.raises(ValueError, match="seed differ"):
        dz.exceedance(RECORDS, dz.Rigid(), parameters, pga=0.4, threshold=0.03, runs_per_block=4, rse=0.03,
                      sampling="lhs", seed=5, checkpoint=tmp_path / "c")


def test_a_checkpoint_block_changed_after_it_was_saved_is_refused(tmp_path):
    """A block's table with one digit of D changed (footer intact) was read back as the
    result; its SHA-256 in the manifest now refuses it, naming the file."""
    import json

    parameters = {"ky": dz.LogNormal(mean=0.12, cov=0.4)}
    run = lambda: dz.exceedance(RECORDS, dz.Rigid(), parameters, pga=0.4, threshold=0.03, runs=8, runs_per_block=4,
                                seed=4, checkpoint=tmp_path / "c")
    first = run()
    block = tmp_path / "c" / "block-000000.csv"
    assert sorted(json.loads((tmp_path / "c" / "manifest.json").read_text())["files"]) == [
        "block-000000.csv", "block-000001.csv"]
    lines = block.read_text().splitlines(keepends=True)
    at = lines[0].rstrip("\n").split(",").index("D_m")
    row = next(i for i in range(1, len(lines)) if float(lines[i].split(",")[at]) > 0)
    fields = lines[row].rstrip("\n").split(",")
    fields[at] = fields[at][:-1] + ("1" if fields[at][-1] != "1" else "2")
    block.write_text("".join(lines[:row] + [",".join(fields) + "\n"] + lines[row + 1:]))
    assert float(fields[at]) not in first.table["D_m"].to_numpy()
    with pytest.raises(ValueError, match=rf"^{block}: its SHA-256 differs"):
        run()


def test_an_executor_gives_the_local_result():
    """Each record's block submitted to a concurrent.futures executor (a Dask Client has the
    same submit/result): the table of the local run, bit for bit."""
    import concurrent.futures

    parameters = {"ky": dz.LogNormal(mean=0.12, cov=0.4)}
    run = lambda **kw: dz.exceedance(RECORDS, dz.Rigid(), parameters, pga=0.4, threshold=0.03, runs=8,
                                     runs_per_block=4, **kw)
    with concurrent.futures.ThreadPoolExecutor(2) as executor:
        assert run(executor=executor).table.equals(run().table)


@pytest.mark.slow
def test_a_dask_client_gives_the_local_result():
    distributed = pytest.importorskip("dask.distributed")
    parameters = {"ky": dz.LogNormal(mean=0.12, cov=0.4)}
    run = lambda **kw: dz.exceedance(RECORDS, dz.Rigid(), parameters, pga=0.4, threshold=0.03, runs=8,
                                     runs_per_block=4, **kw)
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None) as client:
        assert run(executor=client).table.equals(run().table)
