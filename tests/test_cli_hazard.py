"""blockdae fragility and blockdae hazard: the command line gives what the library's
newmark sweep, fit_fragility and displacement_hazard give on the same records, and bad
input is refused naming the field."""

import csv

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli import main
from conftest import sample_record_paths

KY, PGA, D = [0.1, 0.2], np.geomspace(0.05, 1.2, 8), [0.05, 0.15]


@pytest.fixture(scope="module")
def fits():
    """{ky: Fragility} of the 18 sample records x PGA x ky through the library."""
    records = [bd.read_record(p, units="g") for p in sample_record_paths()]
    table = bd.newmark(records, ky=KY, pga=PGA).to_dataframe()
    return {ky: bd.hazard.fit_fragility(table[table.ky_g == ky], displacement="max_m", n_boot=20) for ky in KY}


def _rows(path):
    with open(path) as stream:
        return list(csv.DictReader(stream))


def _arguments(folder, *more):
    return ["--no-cache", *more[:1], str(folder), "--ky", *map(str, KY), "--pga", "0.05:1.2:8", "--boot", "20",
            "--units", "g", "--d", *map(str, D), *more[1:]]


def test_fragility_tabulates_the_fitted_exceedance(tmp_path, fits, capsys):
    folder = sample_record_paths()[0].parent
    out = tmp_path / "fragility.csv"
    assert main(_arguments(folder, "fragility", "--at", "0.2", "0.5", "--csv", str(out))) == 0
    assert "18 records x 8 PGAs x 2 ky, both polarities: 576 Newmark analyses" in capsys.readouterr().out
    rows = _rows(out)
    assert len(rows) == 2 * 2 * 2
    for row in rows:
        fit, d, pga = fits[float(row["ky_g"])], float(row["d_m"]), float(row["pga_g"])
        assert float(row["p_exceedance"]) == pytest.approx(float(fit.exceedance(d, pga)), rel=1e-12)
        low, high = fit.band(d, pga)
        assert float(row["p_band_low"]) <= float(row["p_exceedance"]) <= float(row["p_band_high"])
        assert (float(row["p_band_low"]), float(row["p_band_high"])) == pytest.approx((low, high), rel=1e-12)
    p = {(float(r["ky_g"]), float(r["pga_g"]), float(r["d_m"])): float(r["p_exceedance"]) for r in rows}
    assert p[0.1, 0.5, 0.05] > p[0.1, 0.2, 0.05] and p[0.1, 0.5, 0.05] > p[0.1, 0.5, 0.15] > p[0.2, 0.5, 0.15]


def test_hazard_integrates_the_fragility_over_the_curve(tmp_path, fits, capsys):
    folder = sample_record_paths()[0].parent
    curve = tmp_path / "curve.csv"
    x = np.geomspace(0.01, 2.0, 30)
    curve.write_text("pga_g,rate_per_yr\n" + "".join(f"{a!r},{1e-4 * a**-2.5!r}\n" for a in x.tolist()))
    out = tmp_path / "hazard.csv"
    assert main(_arguments(folder, "hazard", "--curve", str(curve), "--csv", str(out))) == 0
    assert "rate of D > d [1/yr]" in capsys.readouterr().out
    hazard = bd.hazard.HazardCurve(x, 1e-4 * x**-2.5)
    for row in _rows(out):
        expected = bd.hazard.displacement_hazard(hazard, fits[float(row["ky_g"])], float(row["d_m"]))
        assert float(row["rate_per_yr"]) == pytest.approx(float(expected), rel=1e-12)
        assert float(row["return_period_yr"]) == pytest.approx(1 / float(expected), rel=1e-12)


@pytest.mark.parametrize("more, message", [
    (["--curve", "missing.csv"], "--curve missing.csv: no such file"),
    (["--curve", "curve.csv", "--pga", "0,0.2"], "PGAs must be positive"),
])
def test_bad_input_is_refused_naming_the_field(tmp_path, capsys, monkeypatch, more, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "curve.csv").write_text("pga_g,rate\n0.1,1e-2\n0.2,1e-3\n")
    folder = sample_record_paths()[0].parent
    assert main(["--no-cache", "hazard", str(folder), "--ky", "0.1", "--pga", "0.1:0.5:3", *more]) == 2
    assert message in capsys.readouterr().err


def test_too_few_records_are_refused(tmp_path, capsys):
    folder = tmp_path / "few"
    folder.mkdir()
    for path in sample_record_paths()[:3]:
        (folder / path.name).write_bytes(path.read_bytes())
    assert main(["--no-cache", "fragility", str(folder), "--ky", "0.1", "--pga", "0.1:0.6:5", "--units", "g"]) == 2
    assert "ky = 0.1 g: the table has 3 records, fewer than 10" in capsys.readouterr().err

