"""Study checkpoints (issue 27): finished tasks saved as they complete; a rerun skips them
and returns a table bit-identical to an uninterrupted run's (locally, on an executor, on
Dask, after a SIGKILL, after a lost Dask worker); another study's folder is refused."""

import concurrent.futures
import functools
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pandas as pd
import pytest

import blockdae as bd
from blockdae.cli._main import main
from blockdae.studies import _study as study_module
from conftest import load_sample_record, sample_record_paths

SHORT = ("Northridge_1994_PAC-175", "Cape_Mendocino_1992_PET-090", "Kobe_1995_TAK-090")
FRAME = bd.ShearFrame(5, 0.3, 0.05)
GRID = dict(mu=[0.1, 0.3], pga=[0.2, 0.6], where=["ground", FRAME.floor(1)])
PER_RECORD = 2 * 2 * 2 * 2  # analyses of one record: locations × polarities × mu × pga
_RUN_TASK = study_module.run_task
_RELEASE = threading.Event()  # lets the hung tasks of test_dask_worker_lost_then_resumed end


@pytest.fixture(scope="module")
def records():
    return [load_sample_record(stem) for stem in SHORT]


@pytest.fixture(scope="module")
def table(records):
    """The uninterrupted run, without a checkpoint (one task)."""
    return bd.study(records, **GRID)


@pytest.fixture
def one_record_per_task(monkeypatch):
    monkeypatch.setattr(study_module, "TASK_ANALYSES", PER_RECORD)


def _counting_tasks(monkeypatch):
    """The records of each task run from now on, in a list."""
    ran = []

    def run_task(chunk, grid):
        ran.append([r.name for r in chunk])
        return _RUN_TASK(chunk, grid)
    monkeypatch.setattr(study_module, "run_task", run_task)
    return ran


def _saved(folder):
    return sorted(p.name for p in folder.iterdir())


def test_rerun_skips_saved_tasks_and_is_bit_identical(records, table, tmp_path, monkeypatch, one_record_per_task):
    folder = tmp_path / "ck"
    pd.testing.assert_frame_equal(bd.study(records, **GRID, checkpoint=folder), table, check_exact=True)
    assert _saved(folder) == ["manifest.json", "task-000000.csv", "task-000001.csv", "task-000002.csv"]
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["mu"] == GRID["mu"] and manifest["pga"] == GRID["pga"] and manifest["records_per_task"] == 1
    assert [r["name"] for r in manifest["records"]] == list(SHORT)
    ran = _counting_tasks(monkeypatch)
    pd.testing.assert_frame_equal(bd.study(records, **GRID, checkpoint=folder), table, check_exact=True)
    assert ran == []  # everything loaded
    (folder / "task-000001.csv").unlink()
    pd.testing.assert_frame_equal(bd.study(records, **GRID, checkpoint=folder), table, check_exact=True)
    assert ran == [[SHORT[1]]]


def test_numpy_settings_are_written(records, table, tmp_path):
    got = bd.study(records, **dict(GRID, mu=np.array(GRID["mu"])), refine=np.int64(4), g=np.float64(9.80665),
                   checkpoint=tmp_path / "ck")
    pd.testing.assert_frame_equal(got, table, check_exact=True)
    assert json.loads((tmp_path / "ck" / "manifest.json").read_text())["refine"] == 4


def test_an_executor_saves_what_finished_before_a_task_failed(records, table, tmp_path, monkeypatch,
                                                              one_record_per_task):
    folder = tmp_path / "ck"

    def run_task(chunk, grid):
        if chunk[0].name == SHORT[0]:
            raise RuntimeError("a task failed")
        return _RUN_TASK(chunk, grid)
    monkeypatch.setattr(study_module, "run_task", run_task)
    with concurrent.futures.ThreadPoolExecutor(1) as pool, pytest.raises(RuntimeError, match="a task failed"):
        bd.study(records, **GRID, executor=pool, checkpoint=folder)
    assert _saved(folder) == ["manifest.json", "task-000001.csv", "task-000002.csv"]
    ran = _counting_tasks(monkeypatch)
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        resumed = bd.study(records, **GRID, executor=pool, checkpoint=folder)
    pd.testing.assert_frame_equal(resumed, table, check_exact=True)
    assert ran == [[SHORT[0]]]


def test_dask_resumes_a_local_checkpoint(records, table, tmp_path, one_record_per_task):
    distributed = pytest.importorskip("distributed")
    folder = tmp_path / "ck"
    bd.study(records, **GRID, checkpoint=folder)
    (folder / "task-000000.csv").unlink()
    (folder / "task-000002.csv").unlink()
    kept = (folder / "task-000001.csv").stat().st_ino  # a task run again would be saved again: a new file
    with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1, dashboard_address=None) \
            as cluster, distributed.Client(cluster) as client:
        resumed = bd.study(records, **GRID, executor=client, checkpoint=folder)
    pd.testing.assert_frame_equal(resumed, table, check_exact=True)
    assert (folder / "task-000001.csv").stat().st_ino == kept
    assert _saved(folder) == ["manifest.json", "task-000000.csv", "task-000001.csv", "task-000002.csv"]


def _task_losing_its_worker(chunk, grid, saved=None):
    """run_task; every task but the first record's waits until the first is ``saved`` (a
    path; None: no wait), then closes its worker and hangs until released."""
    if chunk[0].name != SHORT[0]:
        from distributed import get_worker
        while saved is not None and not saved.exists():
            time.sleep(0.01)
        worker = get_worker()
        worker.loop.add_callback(worker.close, executor_wait=False)
        _RELEASE.wait(30)
    return _RUN_TASK(chunk, grid)


def test_dask_worker_lost_then_resumed(records, table, tmp_path, monkeypatch, one_record_per_task):
    distributed = pytest.importorskip("distributed")
    folder = tmp_path / "ck"
    monkeypatch.setattr(study_module, "run_task", functools.partial(_task_losing_its_worker,
                                                                    saved=folder / "task-000000.csv"))
    _RELEASE.clear()
    try:
        with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            with pytest.raises(bd.studies.NoWorkerError, match="1 of 3 tasks finished"):
                bd.study(records, **GRID, executor=client, checkpoint=folder, no_worker_timeout=1.5)
    finally:
        _RELEASE.set()
    assert _saved(folder) == ["manifest.json", "task-000000.csv"]
    ran = _counting_tasks(monkeypatch)
    pd.testing.assert_frame_equal(bd.study(records, **GRID, checkpoint=folder), table, check_exact=True)
    assert ran == [[SHORT[1]], [SHORT[2]]]


def test_a_result_lost_with_its_worker_is_no_hang(records, tmp_path, monkeypatch, one_record_per_task):
    """The worker closes as soon as the first task finished: its result may go with it; the
    study still stops after no_worker_timeout [s] (it used to wait for that result forever)."""
    distributed = pytest.importorskip("distributed")
    monkeypatch.setattr(study_module, "run_task", _task_losing_its_worker)
    _RELEASE.clear()
    try:
        with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            start = time.monotonic()
            with pytest.raises(bd.studies.NoWorkerError, match="[01] of 3 tasks finished"):
                bd.study(records, **GRID, executor=client, checkpoint=tmp_path / "ck", no_worker_timeout=1.5)
            assert time.monotonic() - start < 1.5 + 3
    finally:
        _RELEASE.set()


def _task_killing_its_worker_once(chunk, grid, marker):
    """run_task; the second record's task first SIGKILLs its worker process (once: ``marker``)."""
    if chunk[0].name == SHORT[1] and not marker.exists():
        marker.touch()
        os.kill(os.getpid(), signal.SIGKILL)
    return _RUN_TASK(chunk, grid)


def test_a_worker_killed_mid_study_changes_nothing(records, table, tmp_path, monkeypatch, one_record_per_task):
    """Two worker processes, one SIGKILLed in a task: the task runs again elsewhere and the
    table (and its checkpoint) equal the uninterrupted run's."""
    distributed = pytest.importorskip("distributed")
    marker = tmp_path / "killed"
    monkeypatch.setattr(study_module, "run_task", functools.partial(_task_killing_its_worker_once, marker=marker))
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) \
            as cluster, distributed.Client(cluster) as client:
        got = bd.study(records, **GRID, executor=client, checkpoint=tmp_path / "ck")
    assert marker.exists()
    pd.testing.assert_frame_equal(got, table, check_exact=True)
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    pd.testing.assert_frame_equal(bd.study(records, **GRID, checkpoint=tmp_path / "ck"), table, check_exact=True)


def test_another_study_is_refused(records, tmp_path, monkeypatch, one_record_per_task):
    folder = tmp_path / "ck"
    bd.study(records[:2], **GRID, checkpoint=folder)
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    cases = [
        (dict(GRID, mu=[0.1, 0.2]), records[:2], r"mu was \[0\.1, 0\.3\], now \[0\.1, 0\.2\]"),
        (dict(GRID, pga=None, scale=[1.0]), records[:2], r"pga was \[0\.2, 0\.6\], now None; records_per_task was 1, now 2; "
                                                             r"scale was None, now \[1\.0\]"),
        (GRID, records, r"records: new records \['Kobe_1995_TAK-090'\]"),
        (GRID, records[1::-1], r"records: another order"),
        (GRID, [records[0], records[1].scaled(1.5)], r"records: records with other samples \['Cape_Mendocino"),
        (dict(GRID, where=["ground"]), records[:2], r"where was \['ground', \{'frame'"),
    ]
    for kwargs, recs, message in cases:
        with pytest.raises(ValueError, match=rf"^checkpoint {folder} holds another study: {message}"):
            bd.study(recs, **kwargs, checkpoint=folder)
    (folder / "manifest.json").write_text("{")
    with pytest.raises(ValueError, match=f"{folder / 'manifest.json'}: not a study checkpoint's manifest"):
        bd.study(records, **GRID, checkpoint=folder)
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "a.txt").write_text("mine")
    with pytest.raises(ValueError, match=f"checkpoint {tmp_path / 'notes'}: the folder holds files but no "
                                         "manifest.json"):
        bd.study(records, **GRID, checkpoint=tmp_path / "notes")
    assert _saved(folder) == ["manifest.json", "task-000000.csv", "task-000001.csv"]  # nothing written


def test_a_task_file_of_other_records_is_refused(records, tmp_path, one_record_per_task):
    folder = tmp_path / "ck"
    bd.study(records[:2], **GRID, checkpoint=folder)
    (folder / "task-000000.csv").write_bytes((folder / "task-000001.csv").read_bytes())
    with pytest.raises(ValueError, match=rf"{folder / 'task-000000.csv'}: 16 rows of records \['Cape_Mendocino"
                                         rf"_1992_PET-090'\], expected 16 rows of each of \['Northridge"):
        bd.study(records[:2], **GRID, checkpoint=folder)


def _change_one_digit(path, column):
    """Change the last digit of the first row's ``column`` in the CSV table at ``path``
    (its footer and row count intact, as an edit by hand would leave them)."""
    lines = path.read_text().splitlines(keepends=True)
    at = lines[0].rstrip("\n").split(",").index(column)
    fields = lines[1].rstrip("\n").split(",")
    fields[at] = fields[at][:-1] + ("1" if fields[at][-1] != "1" else "2")
    lines[1] = ",".join(fields) + "\n"
    path.write_text("".join(lines))
    return float(fields[at])


def test_a_task_file_changed_after_it_was_saved_is_refused(records, tmp_path, one_record_per_task):
    """A task's table with one digit changed (footer intact) was read back as the study's
    result; its SHA-256 in the manifest now refuses it, naming the file."""
    folder = tmp_path / "ck"
    first = bd.study(records[:2], **GRID, checkpoint=folder)
    manifest = json.loads((folder / "manifest.json").read_text())
    assert sorted(manifest["files"]) == ["task-000000.csv", "task-000001.csv"]
    changed = _change_one_digit(folder / "task-000000.csv", "max_abs_displacement_m")
    assert changed != first["max_abs_displacement_m"].iloc[0]
    with pytest.raises(ValueError, match=rf"^{folder / 'task-000000.csv'}: its SHA-256 differs from the one the "
                                         "checkpoint's manifest recorded"):
        bd.study(records[:2], **GRID, checkpoint=folder)


def test_a_task_file_without_its_hash_is_run_again(records, tmp_path, monkeypatch, one_record_per_task):
    """A table saved but killed before its hash reached the manifest is run again."""
    folder = tmp_path / "ck"
    first = bd.study(records[:2], **GRID, checkpoint=folder)
    manifest = json.loads((folder / "manifest.json").read_text())
    del manifest["files"]["task-000001.csv"]
    (folder / "manifest.json").write_text(json.dumps(manifest))
    ran = _counting_tasks(monkeypatch)
    pd.testing.assert_frame_equal(bd.study(records[:2], **GRID, checkpoint=folder), first, check_exact=True)
    assert ran == [[SHORT[1]]]
    assert "task-000001.csv" in json.loads((folder / "manifest.json").read_text())["files"]


SCRIPT = """
import sys, time
import blockdae as bd
from blockdae.studies import _study
from conftest import load_sample_record

_study.TASK_ANALYSES = {per_record}  # one task per record
run_task = _study.run_task

def slow_task(chunk, grid):
    time.sleep(0.3)  # a long study: time to be killed between tasks
    return run_task(chunk, grid)

_study.run_task = slow_task
records = [load_sample_record(stem) for stem in {stems!r}]
bd.study(records, **{grid!r}, checkpoint=sys.argv[1])
print("finished")
"""


def test_a_study_killed_mid_run_resumes_bit_identical(tmp_path, monkeypatch, one_record_per_task):
    stems = [p.stem for p in sample_record_paths()][:8]
    records = [load_sample_record(stem) for stem in stems]
    grid = dict(mu=[0.1, 0.3], pga=[0.2, 0.6], where=["ground"])
    monkeypatch.setattr(study_module, "TASK_ANALYSES", 4)
    script = tmp_path / "run.py"
    script.write_text(textwrap.dedent(SCRIPT.format(per_record=4, stems=stems, grid=grid)))
    folder = tmp_path / "ck"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    process = subprocess.Popen([sys.executable, str(script), str(folder)], env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while len(list(folder.glob("task-*.csv"))) < 3:
            assert process.poll() is None, process.communicate()
            assert time.monotonic() < deadline, "no task saved in 120 s"
            time.sleep(0.02)
        process.send_signal(signal.SIGKILL)
    finally:
        out, _ = process.communicate(timeout=60)
    assert process.returncode == -signal.SIGKILL and "finished" not in out
    on_disk = {path.name for path in folder.glob("task-*.csv")}
    # a table saved just before the kill, its hash not yet in the manifest, is run again
    saved = len(on_disk & set(json.loads((folder / "manifest.json").read_text()).get("files", {})))
    assert 2 <= saved <= len(on_disk) and 3 <= len(on_disk) < len(stems)
    ran = _counting_tasks(monkeypatch)
    resumed = bd.study(records, **grid, checkpoint=folder)
    assert len(ran) == len(stems) - saved
    pd.testing.assert_frame_equal(resumed, bd.study(records, **grid), check_exact=True)


def test_command_checkpoint(tmp_path, capsys, monkeypatch, one_record_per_task):
    records = tmp_path / "records"
    records.mkdir()
    for path in sample_record_paths():
        if path.stem in SHORT[:2]:
            (records / path.name).write_bytes(path.read_bytes())
    argv = ["--no-cache", "study", str(records), "--mu", "0.1", "0.3", "--pga", "0.2", "0.6", "--frame", "0.3",
            "--checkpoint", str(tmp_path / "ck")]
    assert main(argv + ["--out", str(tmp_path / "a.csv")]) == 0
    assert len(list((tmp_path / "ck").glob("task-*.csv"))) == 2
    ran = _counting_tasks(monkeypatch)
    assert main(argv + ["--out", str(tmp_path / "b.csv")]) == 0
    assert ran == []
    pd.testing.assert_frame_equal(bd.load_study(tmp_path / "b.csv"), bd.load_study(tmp_path / "a.csv"),
                                  check_exact=True)
    capsys.readouterr()
    assert main(argv[:5] + ["0.2"] + argv[6:] + ["--out", str(tmp_path / "c.csv")]) == 2
    assert f"blockdae: error: checkpoint {tmp_path / 'ck'} holds another study: mu was" in capsys.readouterr().err
