"""Atomic writes (issue 27): a save interrupted after its first bytes leaves the previous
good file as it was and no temporary file; a table without its footer, or truncated, is
refused by load_study with an error naming the file."""

import csv

import matplotlib
import pandas as pd
import pytest

import blockdae as bd
from blockdae.cli import _common
from blockdae.cli._main import main
from blockdae.core._atomic import atomic_path
from blockdae.studies import _io

TRIANGLE_CSV = "time [s], acceleration [m/s2]\n0.0, 0.0\n0.25, 9.0\n0.5, 0.0\n"


@pytest.fixture
def table():
    return pd.DataFrame({"record": ["a", "b", "NA"], "mu": [0.1, 0.2, 1 / 3], "pga_g": [0.1 + 0.2, 2e-308, -0.0],
                         "n_events": [1, 2, 3]})


def _files(folder):
    return sorted(p.name for p in folder.iterdir())


def test_atomic_path_replaces_only_when_the_writer_finished(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old")
    with pytest.raises(OSError, match="disk full"):
        with atomic_path(target) as temporary:
            assert temporary.parent == tmp_path and temporary.suffix == ".txt" and temporary != target
            temporary.write_text("partial")
            raise OSError("disk full")
    assert target.read_text() == "old" and _files(tmp_path) == ["a.txt"]
    with atomic_path(target) as temporary:
        temporary.write_text("new")
        assert target.read_text() == "old"  # not yet: only once the writer returned
    assert target.read_text() == "new" and _files(tmp_path) == ["a.txt"]
    with pytest.raises(FileNotFoundError, match=f"{tmp_path / 'no' / 'b.txt'}: no such folder"):
        with atomic_path(tmp_path / "no" / "b.txt"):
            pass


def test_save_study_round_trips_floats_to_the_last_bit(table, tmp_path):
    path = bd.save_study(table, tmp_path / "s.csv")
    assert path.read_text().endswith("\n# blockdae study table: 3 rows\n")
    pd.testing.assert_frame_equal(bd.load_study(path), table, check_exact=True)
    assert pd.read_csv(path, comment="#").shape == table.shape  # other readers skip the footer


def test_interrupted_save_study_keeps_the_previous_table(table, tmp_path, monkeypatch):
    path = bd.save_study(table, tmp_path / "s.csv")
    good = path.read_bytes()

    def first_row_then_full_disk(frame, target):
        with open(target, "w") as stream:
            stream.write(frame.to_csv(index=False).splitlines(keepends=True)[0])
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(_io, "_write_csv", first_row_then_full_disk)
    with pytest.raises(OSError, match="No space left"):
        bd.save_study(table.iloc[:1], path)
    assert path.read_bytes() == good and _files(tmp_path) == ["s.csv"]
    pd.testing.assert_frame_equal(bd.load_study(path), table, check_exact=True)


@pytest.mark.parametrize("cut", [1, 10, 40, -35, -1])
def test_load_study_refuses_a_truncated_table(table, tmp_path, cut):
    path = bd.save_study(table, tmp_path / "s.csv")
    data = path.read_bytes()
    path.write_bytes(data[:cut] if cut > 0 else data[:len(data) + cut])
    with pytest.raises(ValueError, match=f"{path}: no footer line"):
        bd.load_study(path)


def test_load_study_refuses_rows_that_the_footer_does_not_count(table, tmp_path):
    path = bd.save_study(table, tmp_path / "s.csv")
    lines = path.read_text().splitlines(keepends=True)
    path.write_text("".join(lines[:2] + lines[-1:]))  # rows lost before an intact footer
    with pytest.raises(ValueError, match=f"{path}: 1 rows before the footer line, which says 3"):
        bd.load_study(path)


def test_interrupted_batch_csv_keeps_the_previous_file(tmp_path, monkeypatch, capsys):
    folder = tmp_path / "records"
    folder.mkdir()
    (folder / "a.csv").write_text(TRIANGLE_CSV)
    out = tmp_path / "out" / "r.csv"
    out.parent.mkdir()
    argv = ["--no-cache", "batch", str(folder), "--mu", "0.6", "1.0", "--g", "9.81", "--units", "m/s2", "--accept-step",
            "--csv", str(out)]
    assert main(argv) == 0
    good = out.read_bytes()

    class FullDisk(csv.DictWriter):
        def writerows(self, rows):
            self.writerow(rows[0])
            raise OSError(28, "No space left on device")

    monkeypatch.setattr(_common.csv, "DictWriter", FullDisk)
    assert main(argv[:5] + ["0.3"] + argv[6:]) == 2
    assert f"--csv {out}: [Errno 28] No space left" in capsys.readouterr().err
    assert out.read_bytes() == good and _files(out.parent) == ["r.csv"]


def test_interrupted_figure_keeps_the_previous_one(tmp_path):
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = tmp_path / "f.png"
    _common.save_figure(plt.figure(), path)
    good = path.read_bytes()
    assert good.startswith(b"\x89PNG")
    figure = plt.figure()

    def first_bytes_then_fail(target, **options):
        target.write_bytes(good[:8])
        raise OSError("interrupted")

    figure.savefig = first_bytes_then_fail
    with pytest.raises(_common.UsageError, match=f"--plot {path}: interrupted"):
        _common.save_figure(figure, path)
    assert path.read_bytes() == good and _files(tmp_path) == ["f.png"]
