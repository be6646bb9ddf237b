"""The `blockdae spectrum` and `blockdae two-point` commands."""

import csv

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli._main import main
from conftest import sample_record_paths


@pytest.fixture(scope="module")
def kobe_path():
    return next(p for p in sample_record_paths() if p.name.startswith("Kobe"))


def test_spectrum_csv_matches_the_api(kobe_path, tmp_path, capsys):
    out = tmp_path / "s.csv"
    assert main(["spectrum", str(kobe_path), "--periods", "0.1", "1", "--damping", "0.05", "--csv", str(out)]) == 0
    rows = list(csv.DictReader(open(out)))
    spec = bd.motions.response_spectrum(bd.read_record(kobe_path, units="g"), [0.1, 1.0], 0.05)
    np.testing.assert_allclose([float(r["psa_m_s2"]) for r in rows], spec.psa, rtol=1e-12)
    assert "PSa" in capsys.readouterr().out


def test_two_point_table_and_plot(kobe_path, tmp_path, capsys):
    png = tmp_path / "r.png"
    assert main(["two-point", str(kobe_path), "--lags", "0.05", "0.5", "--pga", "0.1", "--plot", str(png)]) == 0
    assert png.stat().st_size > 1000
    text = capsys.readouterr().out
    assert "v_m τ" in text and len(text.splitlines()) == 4 + 4  # title, header, 2 lags, 4 legend lines
    for column in ("τ [s]", "R [m]", "t_R [s]", "v_m τ [m]", "eq.1 − [m]", "eq.1 + [m]", "2 Fourier [m]",
                   "2 Sd(2τ) [m]", "envelope [m]"):  # issue 23 item 5: every column says its unit
        assert column in text.splitlines()[1], column
    legend = " ".join(text.splitlines()[4:])
    for words in ("eq.1 −, eq.1 +: Newmark's formula v_m τ − a_m τ²/2", "envelope: min(v_m τ, d_m)",
                  "'for most earthquakes'", "R: largest |d(t) − d(t − τ)|"):
        assert words in legend, words


@pytest.mark.parametrize("argv, message", [
    (["spectrum", "/no/such.csv"], "no such file"),
    (["spectrum", "KOBE", "--damping", "1.0"], "argument --damping: must be in [0, 1)"),
    (["spectrum", "KOBE", "--periods", "-1"], "argument --periods: must be a positive finite number"),
    (["two-point", "KOBE", "--lags", "-0.1"], "argument --lags: must be a number >= 0"),
    (["spectrum", "KOBE", "--periods", "1", "--pga", "9.81"],
     "--pga=9.81 g is implausible for a peak ground acceleration (above 2 g); it looks like m/s² "
     "(9.81 m/s² = 1 g): give --pga in g, or check_peak=False (command line: --accept-peak) to accept it"),
])
def test_errors_name_the_argument(kobe_path, capsys, argv, message):
    argv = [str(kobe_path) if a == "KOBE" else a for a in argv]
    assert main(argv) == 2
    assert message in capsys.readouterr().err
