"""The ``blockdae`` command line: examples table, runs on files, batches, errors."""

import csv
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from blockdae._cli import main

# seed 000, Example 5: triangular pulse A = 9 m/s², t0 = 0.5 s, sampled exactly by 3 samples
TRIANGLE_CSV = "time [s], acceleration [m/s2]\n0.0, 0.0\n0.25, 9.0\n0.5, 0.0\n"
SEED_G = ["--g", "9.81", "--units", "m/s2"]


def _cli(args, cache):
    """Run the console command in a fresh interpreter; returns (status, stdout, stderr)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    done = subprocess.run([sys.executable, "-m", "blockdae._cli", "--cache-dir", str(cache), *args],
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
    assert result["displacement_m"] == pytest.approx(-0.0453, abs=5e-5)
    np.testing.assert_allclose([e["t_s"] for e in result["events"]], [0.1635, 0.4588], atol=5e-5)
    assert [e["to"] for e in result["events"]] == ["SLIP_NEG", "STICK"]

    png = tmp_path / "triangle.png"
    assert main(["--no-cache", "run", str(path), "--mu", "0.6", *SEED_G, "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "permanent displacement u(t_end) = -0.0452" in out
    assert "t [s]" in out and "time:" in out and " s (wall clock" in out
    assert png.stat().st_size > 10_000


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
    assert "2/2" in captured.err
    rows = list(csv.DictReader(out_csv.open()))
    assert [(r["record"], float(r["mu"])) for r in rows] == [("a", 0.6), ("a", 1.0), ("b", 0.6), ("b", 1.0)]
    u = [float(r["displacement_m"]) for r in rows]
    assert u[0] == pytest.approx(-0.0453, abs=5e-5) and u[2] == pytest.approx(0.0453, abs=5e-5)
    assert u[1] == 0.0 and u[3] == 0.0


@pytest.mark.parametrize("content, line", [("0.0, 0.0\n0.01, 0.1\n0.02, abc\n", 3),
                                           ("t, a\n0.0, 0.0\n0.01, 0.1, 7\n", 3)])
def test_bad_row_names_file_and_line(tmp_path, capsys, content, line):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    assert main(["--no-cache", "run", str(path), "--mu", "0.2"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("blockdae: error: ") and f"{path}, line {line}" in err


def test_batch_stops_on_a_bad_file_before_computing(tmp_path, capsys):
    (tmp_path / "good.csv").write_text(TRIANGLE_CSV)
    (tmp_path / "zbad.csv").write_text("0.0, 0.0\n0.5, x\n")
    assert main(["--no-cache", "batch", str(tmp_path), "--mu", "0.2"]) == 2
    assert f"{tmp_path / 'zbad.csv'}, line 2" in capsys.readouterr().err


@pytest.mark.parametrize("argv, message", [
    (["--units", "furlong"], "units='furlong' is unknown"),
    (["--mu-kinetic", "0.5"], "mu_kinetic="),
    (["--backend", "nope"], "--backend 'nope' is unknown"),
    (["--bias", "0.3"], "bias="),
])
def test_bad_arguments_exit_2_naming_the_argument(tmp_path, capsys, argv, message):
    path = tmp_path / "ok.csv"
    path.write_text(TRIANGLE_CSV)
    assert main(["--no-cache", "run", str(path), "--mu", "0.2", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("blockdae: error: ") and message in err


def test_missing_file_and_folder(tmp_path, capsys):
    assert main(["--no-cache", "run", str(tmp_path / "none.csv"), "--mu", "0.2"]) == 2
    assert f"{tmp_path / 'none.csv'}: no such file" in capsys.readouterr().err
    assert main(["--no-cache", "batch", str(tmp_path / "nodir"), "--mu", "0.2"]) == 2
    assert "not a folder" in capsys.readouterr().err


def test_argparse_errors_return_2(capsys):
    assert main(["run", "x.csv", "--mu", "abc"]) == 2
    assert "invalid float value: 'abc'" in capsys.readouterr().err
    assert main([]) == 2
