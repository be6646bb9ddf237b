"""``blockdae back-analysis``: its printed numbers are those of design.back_analysis called on
the same record files (read by bd.read_record; the same seed gives the same draws), and bad
input ends with a usage error naming the flag."""

import numpy as np
import pandas as pd
import pytest

import blockdae as bd
from blockdae import design
from blockdae.cli import main
from test_design import RECORDS

PRIOR = {"ky": design.LogNormal(mean=0.1, cov=0.5)}


@pytest.fixture
def files(tmp_path):
    paths = []
    for name, record in RECORDS.items():
        t = np.arange(record.acceleration_samples.size) * record.dt
        path = tmp_path / f"{name}.csv"
        np.savetxt(path, np.c_[t, record.acceleration_samples / 9.80665], delimiter=",", header="time (s), acc (g)",
                   comments="")
        paths.append(path)
    return paths


def _observations(files, seen, pga):
    return [design.Observation(bd.read_record(path), sigma_ln=0.2, pga_g=pga, name=path.stem, **kind)
            for path, kind in zip(files, seen)]


def test_laplace_prints_the_posterior_and_the_design_motion(files, capsys, tmp_path):
    draws = tmp_path / "draws.csv"
    assert main(["back-analysis", str(files[0]), str(files[1]), "--seen", "0.05", "--seen", "more:0.01",
                 "--sigma-ln", "0.2", "--pga", "0.4", "--param", "ky=lognormal:0.1:0.5", "--method", "laplace",
                 "--predict", str(files[0]), "--predict-pga", "0.5", "--csv", str(draws),
                 "--plot", str(tmp_path / "seen.png")]) == 0
    out = capsys.readouterr().out
    result = design.back_analysis(_observations(files, [{"displacement_m": 0.05}, {"more_than_m": 0.01}], 0.4),
                                  design.Rigid(), PRIOR, method="laplace")
    s = result.summary().iloc[0]
    assert "2 observations, Laplace approximation, 2000 draws" in out
    assert f"{s['median']:.4g}" in out and f"{s.q05:.4g}" in out and f"{s.q95:.4g}" in out
    assert list(result.predictive().observation) == ["first", "second"]
    low, mid, high = np.quantile(result.predict(bd.read_record(files[0]), 0.5).D_m, [0.05, 0.5, 0.95])
    assert f"D under first at 0.5 g: median {mid:.4g} m, 90 % interval {low:.4g}-{high:.4g} m" in out
    written = pd.read_csv(draws)
    assert list(written.columns) == ["chain", "draw", "ky_g"]
    np.testing.assert_array_equal(written.ky_g.to_numpy(), result.samples.ky_g.to_numpy())
    assert (tmp_path / "seen.png").stat().st_size > 0


@pytest.mark.filterwarnings("ignore::blockdae.design.ConvergenceWarning")
def test_nuts_gives_the_draws_of_the_function(files, capsys):
    assert main(["back-analysis", str(files[0]), "--seen", "0.05", "--sigma-ln", "0.2", "--pga", "0.4",
                 "--param", "ky=lognormal:0.1:0.5", "--chains", "2", "--draws", "100", "--warmup", "100",
                 "--seed", "3"]) == 0
    out = capsys.readouterr().out
    result = design.back_analysis(_observations(files[:1], [{"displacement_m": 0.05}], 0.4), design.Rigid(),
                                  PRIOR, chains=2, draws=100, warmup=100, seed=3)
    assert "NUTS, 2 chains x 100 draws after 100 of warm-up" in out
    assert f"{result.summary().iloc[0]['median']:.4g}" in out
    assert f"{result.diagnostics.iloc[0].ess_bulk:.4g}" in out


@pytest.mark.parametrize("arguments, message", [
    (["--seen", "0.05", "--seen", "0.1"], "--seen was given 2 times for 1 record files"),
    (["--seen", "above:0.05"], "--seen 'above:0.05': expected D_M"),
    (["--seen", "-0.05"], "--seen '-0.05': expected D_M"),
    (["--seen", "0.05", "--predict-pga", "0.5"], "--predict-pga needs --predict RECORD"),
    (["--seen", "0.05", "--pga", "0.3", "--pga", "0.4"], "--pga was given 2 times for 1 record files"),
    (["--seen", "0.05", "--chains", "0"], "--chains must be a positive whole number, got 0"),
])
def test_bad_input_is_a_usage_error(files, capsys, arguments, message):
    assert main(["back-analysis", str(files[0]), "--sigma-ln", "0.2", "--param", "ky=lognormal:0.1:0.5",
                 *arguments]) == 2
    assert message in capsys.readouterr().err


def test_an_observation_beyond_the_prior_is_named(files, capsys):
    assert main(["back-analysis", str(files[0]), "--seen", "50", "--sigma-ln", "0.2", "--pga", "0.4",
                 "--param", "ky=lognormal:0.1:0.5", "--method", "laplace"]) == 2
    assert "first" in capsys.readouterr().err
