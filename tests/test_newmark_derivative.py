"""dD/dky of bd.newmark (derivative=True): exact derivatives through the closed-form engine,
against Newmark's closed form for a rectangular pulse and central differences on a record."""

import json

import numpy as np

import blockdae as bd
from blockdae.cli import main
from conftest import load_sample_record, sample_record_paths

G = bd.STANDARD_GRAVITY


def test_dD_dky_of_a_rectangular_pulse_is_the_closed_form():
    """A pulse of A g for t0 [s] slides the block from t = 0 (relative acceleration
    (A - ky) g) until it stops at t0 A / ky: D = g t0² A (A - ky) / (2 ky), so
    dD/dky = -g t0² A² / (2 ky²) (closed form); the inverted pulse never slides it."""
    amplitude, t0, ky = 0.5, 0.2, np.array([0.1, 0.2, 0.4])
    result = bd.newmark(bd.RectangularPulse(amplitude * G, t0), ky=ky, derivative=True)
    np.testing.assert_allclose(result.normal, G * t0**2 * amplitude * (amplitude - ky) / (2 * ky), rtol=1e-13)
    np.testing.assert_allclose(result.normal_dky, -G * t0**2 * amplitude**2 / (2 * ky**2), rtol=1e-14)
    np.testing.assert_array_equal(result.inverse_dky, 0.0)
    table = result.to_dataframe()
    assert list(table.columns) == ["ky_g", "normal_m", "inverse_m", "mean_m", "max_m", "dD_dky_normal_m_per_g",
                                   "dD_dky_inverse_m_per_g"]


def test_dD_dky_on_records_matches_central_differences():
    """Two records × two target PGAs × two ky (the sweep path), both polarities: against
    central differences of D over ky ± 1e-5 g (their own error, measured on the pulse above
    where the closed form is known: at most 1.0e-8 relative); held to 1e-6 relative."""
    records = [load_sample_record("Kobe_1995_TAK-090"), load_sample_record("Northridge_1994_PAC-175")]
    ky, pga, h = np.array([0.1, 0.2]), [0.3, 0.5], 1e-5
    sweep = bd.newmark(records, ky=ky, pga=pga, derivative=True)
    above, below = bd.newmark(records, ky=ky + h, pga=pga), bd.newmark(records, ky=ky - h, pga=pga)
    for name in ("normal", "inverse"):
        central = (getattr(above, name) - getattr(below, name)) / (2 * h)
        assert np.all(central < 0)
        np.testing.assert_allclose(getattr(sweep, f"{name}_dky"), central, rtol=1e-6)
    assert bd.newmark(records, ky=ky, pga=pga).normal_dky is None


def test_the_command_line_prints_and_writes_dD_dky(tmp_path, capsys):
    """blockdae newmark --derivative: the JSON rows and the CSV carry dD/dky [m/g] as the API gives it."""
    path = next(p for p in sample_record_paths() if "Kobe" in str(p))
    out = tmp_path / "d.csv"
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "0.2", "--derivative", "--json",
                 "--csv", str(out)]) == 0
    rows = json.loads(capsys.readouterr().out)["results"]
    api = bd.newmark(load_sample_record("Kobe_1995_TAK-090"), ky=[0.1, 0.2], derivative=True)
    np.testing.assert_allclose([r["dD_dky_normal_m_per_g"] for r in rows], api.normal_dky, rtol=1e-15)
    np.testing.assert_allclose([r["dD_dky_inverse_m_per_g"] for r in rows], api.inverse_dky, rtol=1e-15)
    assert "dD_dky_normal_m_per_g" in out.read_text().splitlines()[0]
