"""The ``blockdae`` command line: examples table, runs on files, batches, errors."""

import csv
import io
import json
import re
import os
import subprocess
import sys

import numpy as np
import pytest

from blockdae.cli._main import main

# seed 000, Example 5: triangular pulse A = 9 m/s², t0 = 0.5 s, sampled exactly by 3 samples
TRIANGLE_CSV = "time [s], acceleration [m/s2]\n0.0, 0.0\n0.25, 9.0\n0.5, 0.0\n"
SEED_G = ["--g", "9.81", "--units", "m/s2", "--accept-step"]  # the pulse's 3 samples, 0.25 s apart


def _cli(args, cache):
    """Run the console command in a fresh interpreter; returns (status, stdout, stderr)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    done = subprocess.run([sys.executable, "-m", "blockdae.cli", "--cache-dir", str(cache), *args],
                          capture_output=True, text=True, env=env, timeout=300)
    return done.returncode, done.stdout, done.stderr


def test_examples_prints_exact_event_times_beside_the_papers(jax_cache_dir):
    """Closed forms: t* = arcsin(mu g / A) T / (2 pi) (Examples 1, 6), 36 t* = mu g
    (Example 5), Eq. 14 (Example 4). Seed 000 values to its printed digits."""
    status, out, err = _cli(["examples"], jax_cache_dir)
    assert status == 0, err
    t_star = np.arcsin(0.6 * 9.81 / 9.0) / (2 * np.pi)
    ex1 = out.split("Example 1:")[1].split("Example 2:")[0]
    rows = [line.split() for line in ex1.splitlines() if line.strip()[:1].isdigit()]
    exact = [float(r[1]) for r in rows]
    assert exact[0] == pytest.approx(t_star, abs=1e-6)
    assert f"{t_star:.6f}" in ex1
    np.testing.assert_allclose(exact[1:4], [0.535, 0.614, 1.035], atol=1e-3)  # seed Table 1
    assert "0.1125" in ex1  # the paper's printed t*, shown beside ours
    ex5 = out.split("Example 5:")[1].split("Example 6:")[0]
    assert f"{0.6 * 9.81 / 36:.6f}" in ex5 and "0.4588" in ex5
    u4 = 9 * 0.5**2 / 2 * (1 - 9 / 9.81 / 0.6)
    assert f"{u4:+.6f} m" in out.split("Example 4:")[1]
    for example in ("Example 2:", "Example 3a:", "Example 3b:", "Example 6:"):
        assert example in out
    assert "t exact [s]" in out and "u [m]" in out


def test_run_on_a_csv_file_matches_seed_example_5(tmp_path, capsys):
    """Seed 000, Example 5: t* = 0.1635 s, t** = 0.4588 s, u = -0.0453 m (printed digits)."""
    path = tmp_path / "triangle.csv"
    path.write_text(TRIANGLE_CSV)
    assert main(["--no-cache", "run", str(path), "--mu", "0.6", *SEED_G, "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["u_end_m"] == pytest.approx(-0.0453, abs=5e-5)
    np.testing.assert_allclose([e["t_s"] for e in result["events"]], [0.1635, 0.4588], atol=5e-5)
    assert [e["to"] for e in result["events"]] == ["SLIP_NEG", "STICK"]

    png = tmp_path / "triangle.png"
    assert main(["--no-cache", "run", str(path), "--mu", "0.6", *SEED_G, "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "permanent displacement u(t_end) = -0.0452" in out
    assert "t [s]" in out and "time:" in out and " s (wall clock" in out
    assert png.stat().st_size > 10_000


def test_run_of_a_g_1_set_up_gives_lengths_in_g_s2(tmp_path, capsys):
    """Example 5 with accelerations as coefficients of g (--g 1): the same event times, u
    = -0.04526 m / 9.81 m/s² = -0.004614 g s², printed in g s², never in m (issue 23 item 5)."""
    path = tmp_path / "triangle_g.csv"
    path.write_text(f"time [s], acceleration [g]\n0.0, 0.0\n0.25, {9.0 / 9.81!r}\n0.5, 0.0\n")
    assert main(["--no-cache", "run", str(path), "--mu", "0.6", "--g", "1", "--units", "g", "--accept-step"]) == 0
    out = capsys.readouterr().out
    assert "permanent displacement u(t_end) = -0.004614 g s²" in out and "max |u| = 0.004614 g s²" in out
    assert "u [g s²]" in out and "[m]" not in out and " m\n" not in out and "m/s²" not in out
    assert "peak 0.9174 g)" in out and "g = 1 (accelerations in g)" in out
    assert "    0.163500     STICK  SLIP_NEG" in out and "    0.458829  SLIP_NEG  STICK        -0.004614" in out
    assert main(["--no-cache", "run", str(path), "--mu", "0.6", "--g", "1", "--units", "g", "--accept-step",
                 "--quiet"]) == 0
    assert capsys.readouterr().out == "-0.004614 g s²\n"


def test_batch_writes_one_csv_row_per_record_and_mu(tmp_path, capsys):
    """A mu above the pulse's peak (9 m/s² < 1.0 g) never slides; mu = 0.6 is seed Example 5."""
    folder = tmp_path / "records"
    folder.mkdir()
    (folder / "a.csv").write_text(TRIANGLE_CSV)
    (folder / "b.txt").write_text(TRIANGLE_CSV.replace("9.0", "-9.0"))
    out_csv = tmp_path / "out.csv"
    argv = ["--no-cache", "batch", str(folder), "--mu", "0.6", "1.0", *SEED_G, "--csv", str(out_csv)]
    assert main(argv) == 0
    captured = capsys.readouterr()
    assert "4 analyses of 2 records" in captured.out and "batch:" not in captured.err  # no bar off a terminal
    rows = list(csv.DictReader(out_csv.open()))
    assert [(r["record"], float(r["mu"])) for r in rows] == [("a", 0.6), ("a", 1.0), ("b", 0.6), ("b", 1.0)]
    u = [float(r["u_end_m"]) for r in rows]
    assert u[0] == pytest.approx(-0.0453, abs=5e-5) and u[2] == pytest.approx(0.0453, abs=5e-5)
    assert u[1] == 0.0 and u[3] == 0.0


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_batch_shows_a_tqdm_bar_over_the_records_on_a_terminal(tmp_path, monkeypatch, capsys):
    folder = tmp_path / "records"
    folder.mkdir()
    (folder / "a.csv").write_text(TRIANGLE_CSV)
    (folder / "b.txt").write_text(TRIANGLE_CSV)
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    assert main(["--no-cache", "batch", str(folder), "--mu", "0.6", *SEED_G]) == 0
    assert re.search(r"batch: 100%.*\| 2/2 \[.*record/s", terminal.getvalue())
    terminal.truncate(0)
    assert main(["--no-cache", "newmark", str(folder), "--ky", "0.1", *SEED_G[2:]]) == 0
    assert "newmark" not in terminal.getvalue()  # every record in one compiled call: no bar to show
    rows = [line.split()[0] for line in capsys.readouterr().out.splitlines()[-2:]]
    assert rows == ["a", "b"]


@pytest.mark.parametrize("content, line", [("0.0, 0.0\n0.01, 0.1\n0.02, abc\n", 3),
                                           ("t, a\n0.0, 0.0\n0.01, 0.1, 7\n", 3)])
def test_bad_row_names_file_and_line(tmp_path, capsys, content, line):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    assert main(["--no-cache", "run", str(path), "--mu", "0.2"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("blockdae: error: ") and f"{path}, line {line}" in err


def test_batch_analyses_the_good_files_and_lists_the_bad_ones(tmp_path, capsys):
    """One bad file does not stop the batch: the good ones are written, the bad ones listed
    with their reasons, exit status 1; --strict stops at the first with status 2."""
    folder = tmp_path / "records"
    folder.mkdir()
    (folder / "good.csv").write_text(TRIANGLE_CSV)
    (folder / "nan.csv").write_text("0.0, 0.0\n0.5, nan\n")
    (folder / "zbad.csv").write_text("0.0, 0.0\n0.5, x\n")
    out_csv = tmp_path / "out.csv"
    argv = ["--no-cache", "batch", str(folder), "--mu", "0.6", *SEED_G, "--csv", str(out_csv)]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert "2 of 3 files failed" in err and f"{folder / 'zbad.csv'}, line 2" in err
    assert f"{folder / 'nan.csv'}" in err
    assert [r["record"] for r in csv.DictReader(out_csv.open())] == ["good"]
    assert main([*argv, "--strict"]) == 2
    assert capsys.readouterr().err.splitlines()[-1].startswith(f"blockdae: error: {folder / 'nan.csv'}")


def test_batch_grid_over_mu_kinetic_and_bias_with_clean_columns(tmp_path, capsys):
    """Every combination of the grids is a row, with its parameters, g and clean numbers;
    each row equals a single run of the same block (independent call of simulate)."""
    import blockdae as bd

    folder = tmp_path / "records"
    folder.mkdir()
    (folder / "tri.csv").write_text(TRIANGLE_CSV)
    out_csv = tmp_path / "out.csv"
    argv = ["--no-cache", "batch", str(folder), "--mu", "0.5", "0.6", "--mu-kinetic", "0.3", "0.4",
            "--bias", "0.0", "0.1", *SEED_G, "--csv", str(out_csv), "--t-end", "1.2"]
    assert main(argv) == 0
    capsys.readouterr()
    rows = list(csv.DictReader(out_csv.open()))
    assert len(rows) == 8 and "wall_time_s" not in rows[0]
    assert rows[0]["dt_s"] == "0.25" and rows[0]["t_end_s"] == "1.2" and rows[0]["g_m_s2"] == "9.81"
    record = bd.read_record(folder / "tri.csv", units="m/s2", check_step=False)
    for row in rows:
        block = bd.SlidingBlock(mu=float(row["mu"]), mu_kinetic=float(row["mu_kinetic"]),
                                bias=float(row["bias"]), g=9.81)
        assert float(row["u_end_m"]) == bd.simulate(block, record, t_end=1.2).displacement
    assert main([*argv[:-4], "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert len(result["rows"]) == 8 and result["failed"] == []


def test_python_and_cli_print_the_same_digits(tmp_path, capsys):
    """Same defaults (standard gravity) in Python and on the command line: Kobe, mu 0.15, one-way."""
    import blockdae as bd
    from conftest import sample_record_paths

    path = next(p for p in sample_record_paths() if p.name.startswith("Kobe"))
    assert main(["--no-cache", "run", str(path), "--mu", "0.15", "--direction", "negative", "--quiet"]) == 0
    printed = capsys.readouterr().out.strip()
    u = bd.simulate(bd.SlidingBlock(mu=0.15, direction="negative"), bd.read_record(path)).displacement
    assert printed == f"{u:+.6f} m"


def test_long_event_lists_are_summarised(tmp_path, capsys):
    """A harmonic record with many events prints the first and last five unless --events all."""
    t = np.arange(0, 20.0, 0.01)
    path = tmp_path / "sine.csv"
    np.savetxt(path, np.column_stack([t, 0.5 * np.sin(2 * np.pi * t)]), delimiter=",", header="t (s), a (g)")
    assert main(["--no-cache", "run", str(path), "--mu", "0.2"]) == 0
    out = capsys.readouterr().out
    n = int(out.split("events: ")[1].split()[0])
    assert n > 20 and f"({n - 10} more events; --events all prints them)" in out
    assert sum(1 for line in out.splitlines() if "SLIP" in line or "STICK" in line) == 10
    assert main(["--no-cache", "run", str(path), "--mu", "0.2", "--events", "all"]) == 0
    out = capsys.readouterr().out
    assert sum(1 for line in out.splitlines() if "SLIP" in line or "STICK" in line) == n


def test_version(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.startswith("blockdae ")


def test_newmark_command_prints_positive_downslope_displacements(tmp_path, capsys):
    """Seed 000 rectangular-pulse closed form D = (A t0²/2)(A/(ky g) - 1) for the normal
    polarity, 0 for the inverse one."""
    path = tmp_path / "pulse.csv"
    path.write_text("t (s), a (g)\n0.0, 0.4\n0.5, 0.4\n")
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "0.2", "--json", "--accept-step"]) == 0
    rows = json.loads(capsys.readouterr().out)["results"]
    a = 0.4 * 9.80665
    for row, ky in zip(rows, (0.1, 0.2)):
        assert row["normal_m"] == pytest.approx(a * 0.25 / 2 * (a / (ky * 9.80665) - 1), rel=1e-13)
        assert row["inverse_m"] == 0.0
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "--accept-step"]) == 0
    assert "downslope displacement D >= 0 [m]" in capsys.readouterr().out


def _sine_csv(tmp_path, header):
    """A 2 Hz sine of 6 m/s² (about 0.61 g) over 1 s at 0.01 s, with ``header`` (or none), and its samples."""
    t = 0.01 * np.arange(101)
    a = 6.0 * np.sin(2 * np.pi * 2.0 * t)
    path = tmp_path / ("with_header.csv" if header else "no_header.csv")
    path.write_text((header + "\n" if header else "") + "".join(f"{x:.17g}, {y:.17g}\n" for x, y in zip(t, a)))
    return path, a


def test_newmark_reads_a_csv_header_in_m_s2_as_m_s2(tmp_path, capsys):
    """A CSV whose header says m/s² gives D of the record built in m/s² directly (it was read
    as g: a 6 g peak, D ~ 50 times too large); --units g contradicting it exits 2 naming the
    file, the line and both units."""
    import blockdae as bd

    path, a = _sine_csv(tmp_path, "time (s),Acceleration (m/s2)")
    direct = bd.newmark(bd.Record(a, 0.01, units="m/s2"), 0.1)
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "--json"]) == 0
    row = json.loads(capsys.readouterr().out)["results"][0]
    assert (row["normal_m"], row["inverse_m"]) == (direct.normal, direct.inverse) and direct.normal > 0
    bare, _ = _sine_csv(tmp_path, None)  # the same numbers, no header: units needed
    assert main(["--no-cache", "newmark", str(bare), "--ky", "0.1", "--json"]) == 2
    assert f"blockdae: error: {bare}: the units of the accelerations are not stated" in capsys.readouterr().err
    assert main(["--no-cache", "newmark", str(bare), "--ky", "0.1", "--json", "--units", "g", "--accept-peak"]) == 0
    assert json.loads(capsys.readouterr().out)["results"][0]["normal_m"] > 10 * direct.normal
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "--units", "g"]) == 2
    assert (f"blockdae: error: {path}: units='g' (g) contradicts the header, line 1: "
            "'time (s),Acceleration (m/s2)', which says m/s²") in capsys.readouterr().err


def test_newmark_pga_and_ky_checks(tmp_path, capsys):
    """--pga 0.3 [g] equals bd.newmark(record, ky, pga=0.3) (and --pga-rounding slammer its
    SLAMMER twin); --ky 9.81 (m/s² for 1 g) exits 2 naming the value and unit; a ky at or above
    the record's peak warns on stderr that D = 0."""
    import blockdae as bd

    path, a = _sine_csv(tmp_path, "time (s),Acceleration (m/s2)")
    record = bd.read_record(path)
    for rounding in ("exact", "slammer"):
        assert main(["--no-cache", "newmark", str(path), "--ky", "0.05", "0.1", "--pga", "0.3",
                     "--pga-rounding", rounding, "--json"]) == 0
        out = json.loads(capsys.readouterr().out)
        expected = bd.newmark(record, [0.05, 0.1], pga=0.3, pga_rounding=rounding)
        assert [r["normal_m"] for r in out["results"]] == list(expected.normal)
        assert (out["pga_g"], out["pga_rounding"]) == (0.3, rounding)
    assert main(["--no-cache", "newmark", str(path), "--ky", "9.81"]) == 2
    peak = f"{record.peak_acceleration / bd.STANDARD_GRAVITY:.4g}"
    assert (f"blockdae: error: {path}: ky=9.81 g is above 1 g and the motion's peak ({peak} g): it looks like "
            "m/s² (9.81 m/s² = 1 g); give ky in g") in capsys.readouterr().err
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "0.7"]) == 0
    captured = capsys.readouterr()
    assert (f"blockdae: warning: {path}: ky=0.7 g >= PGA = {peak} g: the block does not slide, D = 0 m"
            in captured.err)
    assert main(["--no-cache", "newmark", str(path), "--ky", "0.1", "--pga", "9.81"]) == 2
    assert "pga=9.81 g is implausible" in capsys.readouterr().err


def test_newmark_over_files_and_folders_writes_one_csv_row_per_record_pga_and_ky(tmp_path, capsys):
    """Several files, or a folder of them (sorted by name), x --pga x --ky: the rows of
    bd.newmark over the records read, printed with units and written by --csv; a folder
    without records exits 2 naming it."""
    import blockdae as bd

    folder = tmp_path / "records"
    folder.mkdir()
    path, _ = _sine_csv(tmp_path, "time (s),Acceleration (m/s2)")
    paths = [folder / "b_second.csv", folder / "a_first.csv"]
    for copy in paths:
        copy.write_text(path.read_text())
    records = [bd.read_record(p) for p in sorted(paths)]
    expected = bd.newmark(records, [0.05, 0.1], pga=[0.2, 0.4]).to_dataframe()
    out_csv = tmp_path / "out.csv"
    for given in ([str(folder)], [str(p) for p in sorted(paths)]):
        assert main(["--no-cache", "newmark", *given, "--ky", "0.05", "0.1", "--pga", "0.2", "0.4",
                     "--csv", str(out_csv)]) == 0
        out = capsys.readouterr().out
        assert "2 records; PGA [g]: the target" in out and f"results: {out_csv}" in out
        assert re.search(r"record +PGA \[g\] +ky \[g\] +normal \[m\] +inverse \[m\] +mean \[m\] +max \[m\]", out)
        rows = list(csv.DictReader(out_csv.open()))
        assert list(rows[0]) == list(expected.columns) and len(rows) == len(expected) == 8
        assert [r["record"] for r in rows] == list(expected["record"]) and rows[0]["record"] == "a_first"
        for column in ("pga_g", "ky_g", "normal_m", "inverse_m", "max_m"):
            assert [float(r[column]) for r in rows] == list(expected[column])
    empty = tmp_path / "empty"
    empty.mkdir()
    assert main(["--no-cache", "newmark", str(empty), "--ky", "0.1"]) == 2
    assert f"blockdae: error: {empty}: no record files (.csv" in capsys.readouterr().err


def test_newmark_over_records_warns_where_ky_reaches_a_records_pga(tmp_path, capsys):
    six_g, _ = _sine_csv(tmp_path, None)  # 6 m/s² read as g: 6 g
    weak = tmp_path / "weak.csv"
    weak.write_text("time (s), acceleration (g)\n0.0, 0.0\n0.01, 0.15\n0.02, 0.0\n")
    assert main(["--no-cache", "newmark", str(six_g), str(weak), "--ky", "0.1", "0.2", "--json", "--units", "g",
                 "--accept-peak"]) == 0
    captured = capsys.readouterr()
    assert ("blockdae: warning: ky >= PGA in 1 of 2 (record, PGA) cases: the block does not slide there, D = 0 m: "
            "weak (PGA 0.15 g): ky=0.2 g") in captured.err
    results = json.loads(captured.out)["results"]
    assert [(r["record"], r["ky_g"]) for r in results] == [("no_header", 0.1), ("no_header", 0.2),
                                                            ("weak", 0.1), ("weak", 0.2)]
    assert results[3]["max_m"] == 0.0 and results[2]["max_m"] > 0


def test_newmark_plot_is_d_against_ky_or_the_history_of_one_case(tmp_path, capsys, monkeypatch):
    """D against ky for several ky; for one ky the history of the polarity with the larger D,
    drawn downslope positive as its title says: the drawn D ends at the title's D >= 0
    and never goes below zero; the acceleration panel marks ky."""
    import re
    from blockdae.cli import _main as cli_main

    figures = {}
    real = cli_main.save_figure
    monkeypatch.setattr(cli_main, "save_figure", lambda fig, path: (figures.__setitem__(path.stem, fig),
                                                                    real(fig, path)))
    path, _ = _sine_csv(tmp_path, "time (s),Acceleration (m/s2)")
    for ky, plot in ((["0.05", "0.1"], tmp_path / "d_ky.png"), (["0.1"], tmp_path / "history.png")):
        assert main(["--no-cache", "newmark", str(path), "--ky", *ky, "--plot", str(plot)]) == 0
        assert f"figure: {plot}" in capsys.readouterr().out
    d_ky = figures["d_ky"].axes[0]
    assert d_ky.get_xlabel() == "yield acceleration k_y [g]" and d_ky.get_ylabel() == "downslope displacement D [m]"
    acceleration, velocity, displacement = figures["history"].axes
    title = figures["history"]._suptitle.get_text()
    d = float(re.search(r"D = ([0-9.e+-]+) m", title).group(1))
    drawn = displacement.lines[0].get_ydata()
    assert d > 0 and drawn[-1] == pytest.approx(d, rel=1e-3) and drawn.min() >= 0
    assert displacement.get_ylabel() == "downslope displacement D [m]"
    assert any(np.allclose(line.get_ydata(), 0.1) for line in acceleration.lines)  # ky [g]


@pytest.mark.parametrize("argv, message", [
    (["--units", "furlong"], "units='furlong' is unknown"),
    (["--mu-kinetic", "0.5"], "mu_kinetic="),
    (["--backend", "nope"], "--backend 'nope' is unknown"),
    (["--bias", "0.3"], "argument --bias: bias=0.3 must satisfy"),
    (["--t-end", "-5"], "argument --t-end: must be a positive finite number, got -5"),
    (["--dt", "0"], "argument --dt: must be a positive finite number, got 0"),
    (["--mu", "nan"], "argument --mu: must be a finite number, got nan"),
])
def test_bad_arguments_exit_2_naming_the_argument(tmp_path, capsys, argv, message):
    path = tmp_path / "ok.csv"  # a record the readers take silently: 0.01 s steps, no offset
    t = 0.01 * np.arange(201)
    np.savetxt(path, np.c_[t, 3.0 * np.sin(2 * np.pi * t)], delimiter=",", header="t (s), a (m/s2)")
    assert main(["--no-cache", "run", str(path), "--mu", "0.2", *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and str(path) not in err


def test_missing_file_and_folder(tmp_path, capsys):
    assert main(["--no-cache", "run", str(tmp_path / "none.csv"), "--mu", "0.2"]) == 2
    assert f"{tmp_path / 'none.csv'}: no such file" in capsys.readouterr().err
    assert main(["--no-cache", "batch", str(tmp_path / "nodir"), "--mu", "0.2"]) == 2
    assert "not a folder" in capsys.readouterr().err


def test_argparse_errors_return_2(capsys):
    assert main(["run", "x.csv", "--mu", "abc"]) == 2
    assert "invalid float value: 'abc'" in capsys.readouterr().err
    assert main([]) == 2


@pytest.mark.parametrize("setting, kept", [("cache", True), ("off", False)])
def test_python_api_keeps_compiled_kernels_in_the_cache_folder(tmp_path, setting, kept):
    """Without the CLI, a first compiled call writes the JAX cache under $BLOCKDAE_CACHE_DIR
    (nothing when it is "off"), so that a new process does not compile again."""
    folder = tmp_path / "cache"
    code = ("import blockdae as bd; bd.sensitivities(bd.SlidingBlock(mu=0.2), "
            "bd.Record([0.0, 3.0, 0.0], 0.5), wrt=('mu',))")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path),
               BLOCKDAE_CACHE_DIR=str(folder) if setting == "cache" else setting)
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300,
                          cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (folder.is_dir() and any(folder.iterdir())) == kept


def test_units_mix_up_and_time_origin_are_reported(tmp_path, capsys):
    """A record in cm/s² read as g is refused (naming the peak); --accept-peak takes it; a
    time column starting at 5 s is said in the output and kept in the JSON (start_time_s)."""
    path = tmp_path / "cms2.csv"
    t = 5.0 + 0.01 * np.arange(200)
    np.savetxt(path, np.column_stack([t, 300.0 * np.sin(2 * np.pi * t)]), delimiter=",")
    assert main(["--no-cache", "run", str(path), "--mu", "0.2", "--t-end", "1", "--units", "g"]) == 2
    err = capsys.readouterr().err
    assert "cm/s² read as g" in err and "300" in err
    assert main(["--no-cache", "run", str(path), "--mu", "0.2", "--units", "cm/s2"]) == 0
    assert "at t = 5 s on the file's axis" in capsys.readouterr().out
    assert main(["--no-cache", "run", str(path), "--mu", "0.2", "--units", "cm/s2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["start_time_s"] == 5.0
    assert main(["--no-cache", "run", str(path), "--mu", "0.2", "--t-end", "1", "--units", "g", "--accept-peak",
                 "--quiet"]) == 0


# ---- a block on a plane (seed 001): --y, --z and three-column tables ---------------------

ELMS = ["--mu", "0.8", "--bias", "-0.3", "--g", "1"]  # Elms: N/A = 0.5, P = 0.3 in -x, accelerations in g


def _elms_files(tmp_path, ratio, dt=0.01):
    """Elms's one sine wave C_x = sin(pi t) on 0 <= t <= 2 sampled at ``dt`` [s], C_y = R C_x
    [g]: a three-column table and one file per component."""
    t = np.arange(0.0, 2.0 + dt / 2, dt)
    a_x = np.sin(np.pi * t)
    table, x, y = tmp_path / "elms.csv", tmp_path / "x.csv", tmp_path / "y.csv"
    np.savetxt(table, np.c_[t, a_x, ratio * a_x], delimiter=",", header="t [s], a_x [g], a_y [g]", fmt="%.17g")
    np.savetxt(x, np.c_[t, a_x], delimiter=",", header="t [s], a_x [g]", fmt="%.17g")
    np.savetxt(y, np.c_[t, ratio * a_x], delimiter=",", header="t [s], a_y [g]", fmt="%.17g")
    return table, x, y


def _planar_json(argv, capsys):
    assert main(["--no-cache", "run", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_run_on_a_table_or_two_files_slides_a_block_on_a_plane(tmp_path, capsys):
    """A three-column table and --y give the same block on a plane (IDA by default); the
    onset slide direction is seed 001 eqs. 19-20, -(C_x + P, C_y), at the onset time."""
    table, x, y = _elms_files(tmp_path, ratio=0.8)
    from_table = _planar_json([str(table), *ELMS], capsys)
    from_files = _planar_json([str(x), "--y", str(y), *ELMS], capsys)
    assert from_table["backend"] == "ida" and from_table["components"]["z"] is None
    assert from_table["displacement_m"] == from_files["displacement_m"]
    u_x, u_y = from_table["displacement_m"]
    assert u_x < -0.1 and u_y < -0.05  # Elms Fig. 6: d_x and d_y both negative
    onset = from_table["events"][0]
    assert (onset["from"], onset["to"]) == ("STICK", "SLIP")
    t = onset["t_s"]
    c_x = np.interp(t, np.arange(0.0, 2.005, 0.01), np.sin(np.pi * np.arange(0.0, 2.005, 0.01)))
    expected = np.degrees(np.arctan2(-0.8 * c_x, -(c_x + 0.3)))
    assert onset["slide_deg"] == pytest.approx(expected, abs=1e-6)
    assert np.hypot(c_x + 0.3, 0.8 * c_x) == pytest.approx(0.8, abs=1e-9)  # on the friction circle (eq. 9)

    assert main(["--no-cache", "run", str(table), *ELMS]) == 0
    out = capsys.readouterr().out
    assert f"(u_x, u_y)(t_end) = ({u_x:+.6f}, {u_y:+.6f}) g s²" in out  # --g 1: lengths in g s², not m
    assert "u_x [g s²]" in out and "[m]" not in out
    assert "max |u| = " in out and "slide [deg]" in out and "direction [deg]" in out
    assert "nan" not in out and "blank where the block was at rest" in out  # issue 23 item 5
    assert main(["--no-cache", "run", str(table), *ELMS, "--quiet"]) == 0
    assert capsys.readouterr().out.strip() == f"({u_x:+.6f}, {u_y:+.6f}) g s²"
    png = tmp_path / "path.png"
    assert main(["--no-cache", "run", str(table), *ELMS, "--plot", str(png), "--events", "none"]) == 0
    assert f"figure: {png}" in capsys.readouterr().out and png.stat().st_size > 10_000


def test_a_zero_second_component_gives_the_1d_exact_answer(tmp_path, capsys):
    """Independent: the 1-D exact backend (closed forms) on the x file alone."""
    _, x, y = _elms_files(tmp_path, ratio=0.0)
    one_d = json.loads((main(["--no-cache", "run", str(x), *ELMS, "--json"]), capsys.readouterr().out)[1])
    planar = _planar_json([str(x), "--y", str(y), *ELMS, "--accept-peak"], capsys)  # a zero a_y
    assert one_d["backend"] == "exact"
    assert planar["displacement_m"][1] == 0.0
    # IDA at its default rtol 1e-10 (tests/test_planar_ida.py: within 1e-7 of the exact 1-D u)
    assert planar["displacement_m"][0] == pytest.approx(one_d["u_end_m"], rel=1e-7)
    np.testing.assert_allclose([e["t_s"] for e in planar["events"]], [e["t_s"] for e in one_d["events"]],
                               rtol=0, atol=1e-9)


@pytest.mark.parametrize("extra, message", [
    (["--y", "{bad_dt}"], r"{x} \(x\), {bad_dt} \(y\): components x \('x'\) and y \('y2'\) are Records with "
                          r"different dt \(x: dt=0.01 s, y: dt=0.02 s\)"),
    (["--y", "{nan}"], r"{nan}, line 4: value nan is not finite"),
    (["--z", "{missing}"], r"argument --z: {missing}: no such file"),
    (["--bias-y", "0.1"], r"argument --bias-y: needs a second horizontal component"),
    (["--y", "{y}", "--direction", "negative"], r"argument --direction: 'negative' applies to one component"),
    (["--y", "{y}", "--bias-y", "0.9"], r"argument --bias/--bias-y: bias=\(-0.3, 0.9\) must satisfy"),
])
def test_bad_planar_input_names_the_file_line_or_argument(tmp_path, capsys, extra, message):
    _, x, y = _elms_files(tmp_path, ratio=0.4)
    files = dict(x=x, y=y, bad_dt=tmp_path / "y2.csv", nan=tmp_path / "nan.csv", missing=tmp_path / "none.csv")
    files["bad_dt"].write_text("t (s), a (g)\n0.0, 0.1\n0.02, 0.2\n0.04, 0.0\n")
    files["nan"].write_text("t (s), a (g)\n0.0, 0.1\n0.01, 0.2\n0.02, nan\n")
    argv = [a.format(**files) for a in extra]
    assert main(["--no-cache", "run", str(x), *ELMS, *argv]) == 2
    err = capsys.readouterr().err.splitlines()[-1]  # after the readers' warnings (the short files' offsets)
    assert err.startswith("blockdae: error: ")
    assert re.search(message.format(**{k: re.escape(str(v)) for k, v in files.items()}), err), err


def test_resample_runs_components_of_mixed_steps(tmp_path, capsys):
    """Issue 23 item 4: x at 0.01 s and y at 0.02 s fail with a pointer to --resample; with
    --resample 0.01 they run, and give the same answer as y written at 0.01 s (0.01 divides
    0.02, so resampling y changes no a(t)); y at 0.01 s is C_y linear between the 0.02 s samples."""
    _, x, _ = _elms_files(tmp_path, ratio=0.8)
    t = np.arange(0.0, 2.0 + 0.01, 0.02)
    coarse, fine = tmp_path / "y_coarse.csv", tmp_path / "y_fine.csv"
    np.savetxt(coarse, np.c_[t, 0.8 * np.sin(np.pi * t)], delimiter=",", header="t [s], a_y [g]", fmt="%.17g")
    t_fine = np.arange(0.0, 2.0 + 0.005, 0.01)
    np.savetxt(fine, np.c_[t_fine, np.interp(t_fine, t, 0.8 * np.sin(np.pi * t))], delimiter=",",
               header="t [s], a_y [g]", fmt="%.17g")
    assert main(["--no-cache", "run", str(x), "--y", str(coarse), *ELMS]) == 2
    assert "--resample DT on the command line" in capsys.readouterr().err
    resampled = _planar_json([str(x), "--y", str(coarse), *ELMS, "--resample", "0.01"], capsys)
    direct = _planar_json([str(x), "--y", str(fine), *ELMS], capsys)
    assert resampled["components"]["y"]["dt_s"] == 0.01
    np.testing.assert_allclose(resampled["displacement_m"], direct["displacement_m"], rtol=1e-12, atol=1e-15)
    assert resampled["displacement_m"][1] < -0.05
    assert main(["--no-cache", "run", str(x), "--y", str(coarse), *ELMS, "--resample", "0"]) == 2
    assert "argument --resample" in capsys.readouterr().err
