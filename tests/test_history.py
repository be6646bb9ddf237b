"""Histories as tables and CSV: Solution.history, blockdae run --history and blockdae newmark
--history, against the solution's own events and the Newmark table."""

import csv
import json

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli import main
from conftest import load_sample_record, sample_record_paths

KOBE = "Kobe_1995_TAK-090"


def test_history_holds_every_sample_and_event_exactly():
    record = load_sample_record(KOBE)
    sol = bd.simulate(bd.SlidingBlock(mu=0.1, direction="negative"), record)
    history = sol.history()
    assert list(history.columns) == ["t_s", "base_acceleration_m_s2", "u_m", "v_m_s", "mode"]
    assert set(sol.t_events) <= set(history.t_s) and set(record.times) <= set(history.t_s)
    at_events = history.set_index("t_s").loc[sol.t_events]
    np.testing.assert_array_equal(at_events.u_m, [e.u for e in sol.events])
    np.testing.assert_array_equal(at_events["mode"], [e.mode_after.name for e in sol.events])
    samples = history.set_index("t_s").loc[record.times[:-1]]  # at the last, a(t) is 0: right-continuous
    np.testing.assert_allclose(samples.base_acceleration_m_s2, record.acceleration_samples[:-1], rtol=1e-15, atol=0)
    assert history.u_m.iloc[-1] == sol.displacement


def _csv(path):
    with open(path) as stream:
        return list(csv.DictReader(stream))


def test_newmark_history_ends_at_the_tables_displacements(tmp_path, capsys):
    path = next(p for p in sample_record_paths() if KOBE in str(p))
    out = tmp_path / "h.csv"
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "--pga", "0.4", "--history", str(out),
                 "--json"]) == 0
    result = json.loads(capsys.readouterr().out)["results"][0]
    rows = _csv(out)
    assert float(rows[-1]["normal_D_m"]) == pytest.approx(result["normal_m"], rel=1e-15)
    assert float(rows[-1]["inverse_D_m"]) == pytest.approx(result["inverse_m"], rel=1e-15)
    d = np.array([float(r["normal_D_m"]) for r in rows])
    assert np.all(np.diff(d) >= 0)  # one-way: D never decreases
    peak = max(abs(float(r["ground_acceleration_g"])) for r in rows)
    assert peak == pytest.approx(0.4, rel=1e-12)
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "0.2", "--history", str(out)]) == 2
    assert "--history takes one record, one --pga (or none) and one --ky" in capsys.readouterr().err


def test_run_history_is_the_solutions(tmp_path, capsys):
    path = next(p for p in sample_record_paths() if KOBE in str(p))
    out = tmp_path / "h.csv"
    assert main(["--no-cache", "run", str(path), "--mu", "0.1", "--units", "g", "--history", str(out)]) == 0
    assert f"history: {out}" in capsys.readouterr().out
    rows = _csv(out)
    sol = bd.simulate(bd.SlidingBlock(mu=0.1), load_sample_record(KOBE))
    assert float(rows[-1]["u_m"]) == pytest.approx(sol.displacement, rel=1e-15)
    assert list(rows[0]) == ["t_s", "base_acceleration_m_s2", "u_m", "v_m_s", "mode"]


def test_a_dimensionless_block_names_its_columns_in_g():
    """With g = 1 (Elms's dimensionless set-up) accelerations are coefficients of g, so lengths
    are in g s² and velocities in g s: the table's names say so, values untouched."""
    record = load_sample_record(KOBE)
    unit = bd.Record(record.acceleration_samples / bd.STANDARD_GRAVITY, record.dt, check_peak=False)
    sol = bd.simulate(bd.SlidingBlock(mu=0.1, g=1.0, direction="negative"), unit)
    history = sol.history()
    assert list(history.columns) == ["t_s", "base_acceleration_g", "u_g_s2", "v_g_s", "mode"]
    assert history.u_g_s2.iloc[-1] == sol.displacement
    assert list(sol.to_dataframe().columns) == ["t_s", "mode_before", "mode_after", "u_g_s2", "v_g_s"]


def test_run_history_of_a_g_1_set_up_is_in_g(tmp_path):
    path = tmp_path / "triangle_g.csv"
    path.write_text(f"time [s], acceleration [g]\n0.0, 0.0\n0.25, {9.0 / 9.81!r}\n0.5, 0.0\n")
    out = tmp_path / "h.csv"
    assert main(["--no-cache", "run", str(path), "--mu", "0.6", "--g", "1", "--units", "g", "--accept-step",
                 "--history", str(out), "--quiet"]) == 0
    rows = _csv(out)
    assert list(rows[0]) == ["t_s", "base_acceleration_g", "u_g_s2", "v_g_s", "mode"]
    assert float(rows[-1]["u_g_s2"]) == pytest.approx(-0.004614, abs=5e-7)  # seed Example 5 in g s²
