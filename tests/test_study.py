"""bd.study: rows against independent simulations, local == Dask, errors before work,
a Dask cluster that loses its workers, the seed-002 summaries, save and reload, the
command and the benchmark's smoke run."""

import concurrent.futures
import re
import threading
import time

import numpy as np
import pandas as pd
import pytest

import blockdae as bd
from blockdae.cli._main import main
from blockdae.cli import _study as command_module
from blockdae.studies import _study as study_module
from conftest import load_sample_record, sample_record_paths
from conftest import load_benchmark as _load_benchmark


#: the deprecated many-motion functions keep their tests for the release they stay
pytestmark = [pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_many is deprecated:DeprecationWarning"),
              pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_final is deprecated:DeprecationWarning")]


SHORT = ("Northridge_1994_PAC-175", "Cape_Mendocino_1992_PET-090", "Kobe_1995_TAK-090")
FRAME = bd.ShearFrame(5, 0.3, 0.05)
WHERE = ["ground", FRAME.floor(1), FRAME.floor(5)]
MU = [0.1, 0.3]
PGA = [0.2, 0.6]
_RUN_TASK = study_module.run_task
_RELEASE = threading.Event()  # lets the hung task of test_worker_lost_mid_study end


@pytest.fixture(scope="module")
def records():
    return [load_sample_record(stem) for stem in SHORT]


@pytest.fixture(scope="module")
def table(records):
    return bd.study(records, mu=MU, pga=PGA, where=WHERE)


def test_shape_order_and_units(table, records):
    """Both polarities of the one-way block by default, as bd.newmark runs them."""
    assert len(table) == len(records) * len(WHERE) * 2 * len(MU) * len(PGA)
    assert list(table["record"].unique()) == list(SHORT)
    assert list(table.loc[:7, "pga_g"]) == PGA * 4
    assert list(table.loc[:7, "polarity"]) == ["normal"] * 4 + ["inverse"] * 4
    assert list(table.columns[:6]) == ["record", "location", "floor", "frame_period_s", "polarity", "mu"]
    assert (table["D_m"] >= 0).all() and "u_end_m" not in table and "displacement_m" not in table
    assert set(table["floor"]) == {0, 1, 5}
    np.testing.assert_allclose(table["pga_m_s2"], table["pga_g"] * bd.STANDARD_GRAVITY, rtol=1e-14)
    assert (table["n_slips"] == (table["n_events"] + 1) // 2).all()
    assert table["frame_period_s"].isna().eq(table["location"] == "ground").all()


@pytest.mark.parametrize("row", [0, 5, 10, 17, 23, 30, 35])
def test_rows_equal_independent_simulations(table, records, row):
    r = table.iloc[row]
    record = records[SHORT.index(r["record"])]
    motion = record if r["floor"] == 0 else FRAME.floor(int(r["floor"])).motion(record)
    used = motion.scaled(r["scale"] * {"normal": 1.0, "inverse": -1.0}[r["polarity"]])
    sol = bd.simulate(bd.SlidingBlock(mu=r["mu"], direction="negative"), used)
    np.testing.assert_allclose(r["max_abs_displacement_m"], sol.max_abs_displacement, rtol=1e-12, atol=0)
    np.testing.assert_allclose(r["D_m"], -sol.displacement, rtol=1e-12, atol=1e-300)
    assert r["n_events"] == len(sol.events)
    assert r["n_slips"] == sum(int(e.mode_after) != 0 for e in sol.events)
    im = bd.motions.intensity_measures(used)
    np.testing.assert_allclose([r["pga_m_s2"], r["pgv_m_s"]], [im.pga, im.pgv], rtol=1e-12)
    np.testing.assert_allclose(r["sd_m"], bd.motions.response_spectrum(used, 10.0, 0.05).sd, rtol=1e-12)


def test_scale_grid_is_the_pga_grid_by_other_names(records, table):
    ground = table[table["floor"] == 0]
    k = ground["scale"].to_numpy().reshape(len(records), -1)[:, :len(PGA)]
    by_scale = bd.study(records[:1], mu=MU[:1], scale=k[0], where="ground", direction="negative")
    np.testing.assert_allclose(by_scale["max_abs_displacement_m"],
                               ground["max_abs_displacement_m"].to_numpy()[:len(PGA)], rtol=1e-12)
    np.testing.assert_allclose(by_scale["pga_g"], PGA, rtol=1e-14)


@pytest.mark.parametrize("no_worker_timeout", [None, 2.0])
def test_local_equals_dask(records, table, no_worker_timeout):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) \
            as cluster, distributed.Client(cluster) as client:
        on_dask = bd.study(records, mu=MU, pga=PGA, where=WHERE, executor=client, no_worker_timeout=no_worker_timeout)
    pd.testing.assert_frame_equal(on_dask, table)


def _one_thread_cluster(distributed):
    """A LocalCluster of one worker thread in this process (no nanny to restart it)."""
    return distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1, dashboard_address=None)


def test_no_worker_from_the_start_raises_after_the_timeout(records):
    distributed = pytest.importorskip("distributed")
    with _one_thread_cluster(distributed) as cluster, distributed.Client(cluster) as client:
        cluster.scale(0)
        while client.nthreads():
            time.sleep(0.05)
        start = time.monotonic()
        with pytest.raises(bd.studies.NoWorkerError, match=r"no_worker_timeout=1 s\): 0 of 1 tasks finished, 1 "
                                                            r"unfinished.*raise no_worker_timeout"):
            bd.study(records, mu=MU, pga=PGA, executor=client, no_worker_timeout=1)
        assert 1 <= time.monotonic() - start < 4


def _task_losing_its_worker(records, grid):
    """run_task; every task but the first record's first closes its worker (0.5 s later: the
    client has fetched the first task's result by then, which would go with the worker) and
    hangs until released."""
    if records[0].name != SHORT[0]:
        from distributed import get_worker
        time.sleep(0.5)
        worker = get_worker()
        worker.loop.add_callback(worker.close, executor_wait=False)
        _RELEASE.wait(30)
    return _RUN_TASK(records, grid)


def test_worker_lost_mid_study(records, monkeypatch):
    distributed = pytest.importorskip("distributed")
    monkeypatch.setattr(study_module, "TASK_ANALYSES", 1)  # one task per record
    monkeypatch.setattr(study_module, "run_task", _task_losing_its_worker)
    _RELEASE.clear()
    try:
        with _one_thread_cluster(distributed) as cluster, distributed.Client(cluster) as client:
            start = time.monotonic()
            with pytest.raises(RuntimeError, match=r"no Dask worker alive for \d+\.\d s \(no_worker_timeout=1\.5 s\): "
                                                   r"1 of 3 tasks finished, 2 unfinished"):
                bd.study(records, mu=MU, pga=PGA, executor=client, no_worker_timeout=1.5)
            assert time.monotonic() - start < 1.5 + 3
            assert not client.nthreads()
    finally:
        _RELEASE.set()


@pytest.mark.parametrize("value", [-1.0, 0, np.nan, np.inf, "60", True, [60]])
def test_bad_no_worker_timeout_fails_before_work(records, value, monkeypatch):
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    with pytest.raises(ValueError, match=rf"no_worker_timeout must be a positive finite number of seconds \[s\] "
                                         rf"or None \(wait forever\), got {re.escape(repr(value))}"):
        bd.study(records, mu=MU, pga=PGA, no_worker_timeout=value)


def test_local_equals_executor(records, table, monkeypatch):
    monkeypatch.setattr(study_module, "TASK_ANALYSES", 1)  # one task per record
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        pd.testing.assert_frame_equal(bd.study(records, mu=MU, pga=PGA, where=WHERE, executor=pool), table)


@pytest.mark.parametrize("kwargs, match", [
    (dict(records=[]), "records is empty"),
    (dict(records=["x"]), "must be a bd.Record"),
    (dict(mu=[0.1, 0.0]), "mu must be positive"),
    (dict(mu=[-0.1]), "mu must be positive"),
    (dict(pga=[0.5, -1.0]), "pga must be positive"),
    (dict(pga=[np.nan]), "pga must be positive"),
    (dict(pga=[0.3, 9.81]), r"pga=9\.81 g is implausible .* looks like m/s² \(9\.81 m/s² = 1 g\): give pga in g"),
    (dict(pga=None), "give pga"),
    (dict(scale=[1.0]), "give pga"),
    (dict(where=["roof"]), "where must hold"),
    (dict(where=[]), "where is empty"),
    (dict(mu=np.linspace(0.01, 1, 10**4), pga=np.linspace(0.01, 1, 10**4)), "free memory"),
])
def test_bad_input_fails_before_work(records, kwargs, match, monkeypatch):
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    args = dict(records=records, mu=MU, pga=PGA) | kwargs
    with pytest.raises((ValueError, TypeError), match=match):
        bd.study(**args)


def test_a_record_with_nan_fails_before_work(records, monkeypatch):
    bad = bd.Record(np.ones(3), 0.01, name="nan", units="m/s2")
    object.__setattr__(bad, "acceleration_samples", np.array([0.0, np.nan, 1.0]))  # past Record's own check
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    with pytest.raises(ValueError, match="not finite"):
        bd.study([records[0], bad], mu=MU, pga=PGA)


def test_summary_follows_the_formulas(table):
    s = bd.studies.summary(table)
    assert len(s) == len(WHERE) * 2 * len(MU) * len(PGA) and (s["n_records"] == len(SHORT)).all()
    for _, row in s.sample(4, random_state=1).iterrows():
        cases = table[(table["location"] == row["location"]) & (table["mu"] == row["mu"])
                      & (table["pga_g"] == row["pga_g"]) & (table["polarity"] == row["polarity"])]
        assert row["rc_m"] == pytest.approx(cases["max_abs_displacement_m"].mean(), rel=1e-14)
        assert row["sd_m"] == pytest.approx(cases["sd_m"].mean(), rel=1e-14)
        rd = bd.sliding.newmark_rd_sd(row["sd_m"], row["pga_g"], row["mu"])
        assert row["rd_m"] == pytest.approx(rd, rel=1e-14)
        adj = bd.sliding.AdjustmentFactor()(row["pga_g"], row["mu"])
        assert row["rd_adjusted_m"] == pytest.approx(adj * rd, rel=1e-14)


def test_save_and_load_round_trip(table, tmp_path):
    pd.testing.assert_frame_equal(bd.load_study(bd.save_study(table, tmp_path / "s.csv")), table, check_exact=True)
    with pytest.raises(ValueError, match=".csv or .parquet"):
        bd.save_study(table, tmp_path / "s.xlsx")
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pyarrow"):
            bd.save_study(table, tmp_path / "s.parquet")
    else:
        pd.testing.assert_frame_equal(bd.load_study(bd.save_study(table, tmp_path / "s.parquet")), table)


def test_command(tmp_path, records, capsys):
    folder = tmp_path / "records"
    folder.mkdir()
    for path in sample_record_paths():
        if path.stem in SHORT[:2]:
            (folder / path.name).write_bytes(path.read_bytes())
    out = tmp_path / "r.csv"
    status = main(["--no-cache", "study", str(folder), "--mu", "0.1", "0.3", "--pga", "0.2:0.6:2", "--frame", "0.3",
                            "--out", str(out)])
    assert status == 0, capsys.readouterr().err
    got = bd.load_study(out)
    assert len(got) == 2 * 6 * 2 * 2 * 2 and sorted(got["pga_g"].unique()) == PGA  # two polarities by default
    assert "2 records × 6 locations × 2 polarities × 2 mu × 2 intensities" in capsys.readouterr().out
    expected = bd.study(sorted(records[:2], key=lambda r: r.name), mu=MU, pga=PGA,
                        where=["ground"] + [FRAME.floor(i) for i in range(1, 6)])
    pd.testing.assert_frame_equal(got, expected)
    rigid_ky = tmp_path / "ky.csv"
    assert main(["--no-cache", "study", str(folder), "--ky", "0.1", "0.3", "--pga", "0.2", "--out", str(rigid_ky)]) == 0
    by_ky = bd.load_study(rigid_ky)
    assert "ky_g" in by_ky and (by_ky["D_m"] >= 0).all() and set(by_ky["polarity"]) == {"normal", "inverse"}
    (folder / "bad.csv").write_text("0.0, 1.0\n0.01, nan\n")
    assert main(["--no-cache", "study", str(folder), "--mu", "0.1", "--pga", "0.5", "--out", str(out)]) == 2
    assert "bad.csv" in capsys.readouterr().err
    assert main(["--no-cache", "study", str(tmp_path / "empty"), "--mu", "0.1", "--pga", "0.5", "--out", str(out)]) == 2


def _one_record_folder(tmp_path):
    folder = tmp_path / "records"
    folder.mkdir()
    path = next(p for p in sample_record_paths() if p.stem == SHORT[0])
    (folder / path.name).write_bytes(path.read_bytes())
    return folder


def test_command_passes_no_worker_timeout(tmp_path, monkeypatch, capsys):
    seen = []

    def study(*args, no_worker_timeout, **kwargs):
        seen.append(no_worker_timeout)
        raise bd.studies.NoWorkerError("no Dask worker alive for 2.0 s")

    monkeypatch.setattr(command_module, "study", study)
    argv = ["--no-cache", "study", str(_one_record_folder(tmp_path)), "--mu", "0.1", "--pga", "0.5",
            "--out", str(tmp_path / "r.csv")]
    for flag in [[], ["--no-worker-timeout", "2.5"], ["--no-worker-timeout", "none"]]:
        assert main(argv + flag) == 1
        assert "blockdae: error: no Dask worker alive for 2.0 s" in capsys.readouterr().err
    assert seen == [60.0, 2.5, None]
    for bad in ["-1", "0", "nan", "soon"]:
        assert main(argv + ["--no-worker-timeout", bad]) == 2
        assert "argument --no-worker-timeout:" in capsys.readouterr().err
    assert len(seen) == 3 and not (tmp_path / "r.csv").exists()  # bad values never reach study


def test_command_on_a_cluster_without_workers(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    with _one_thread_cluster(distributed) as cluster:
        cluster.scale(0)
        while cluster.scheduler.workers:
            time.sleep(0.05)
        status = main(["--no-cache", "study", str(_one_record_folder(tmp_path)), "--mu", "0.1", "--pga", "0.5",
                       "--out", str(tmp_path / "r.csv"), "--scheduler", cluster.scheduler_address,
                       "--no-worker-timeout", "1"])
    assert status == 1
    assert "no_worker_timeout=1 s): 0 of 1 tasks finished" in capsys.readouterr().err


def test_benchmark_quick(monkeypatch, capsys):
    assert _load_benchmark("study", monkeypatch).main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "analyses/s" in out and "FAIL" not in out and "DIFFERS" not in out


def test_simulate_final_scale_equals_scaled_motions(records):
    block = bd.SlidingBlock(mu=np.array([0.1, 0.25]), direction="both")
    factors = [0.5, 1.5, -1.0]
    out = bd.sliding.simulate_final(block, records[:2], scale=factors)
    assert out.displacement.shape == (2, 2, 3)
    for k, factor in enumerate(factors):
        ref = bd.sliding.simulate_final(block, [r.scaled(factor) for r in records[:2]])
        for got, want in zip(out, ref):
            np.testing.assert_allclose(got[..., k], want, rtol=1e-12, atol=1e-300)
    with pytest.raises(ValueError, match="scale must be"):
        bd.sliding.simulate_final(block, records[:1], scale=[])


def test_rigid_ky_study_is_newmark_in_both_polarities(records):
    """``ky=`` on the 1-D block: the column ky_g, the rows of bd.newmark (an independent
    path: one simulate per polarity and ky), D >= 0 in each polarity; ``direction=
    "negative"`` keeps the record as given only; a two-way block's table holds signed u."""
    ky, pga = [0.05, 0.15], [0.4]
    table = bd.study(records[:2], ky=ky, pga=pga)
    assert "ky_g" in table and "mu" not in table and list(table["polarity"].unique()) == ["normal", "inverse"]
    for record in records[:2]:
        scaled = record.scaled(bd.excitation.pga_factor(record.peak_acceleration, pga[0]))
        want = bd.newmark(scaled, ky=np.array(ky))
        rows = table[table["record"] == record.name]
        for polarity in ("normal", "inverse"):
            got = rows[rows["polarity"] == polarity]["D_m"].to_numpy()
            np.testing.assert_allclose(got, getattr(want, polarity), rtol=1e-12, atol=1e-300)
            assert (got >= 0).all()
    one = bd.study(records[:2], ky=ky, pga=pga, direction="negative")
    assert list(one["polarity"].unique()) == ["normal"]
    normal = table[table["polarity"] == "normal"].drop(columns="polarity").reset_index(drop=True)
    pd.testing.assert_frame_equal(one.drop(columns="polarity"), normal)
    two_way = bd.study(records[:1], mu=[0.1], pga=pga, direction="both")
    assert "u_end_m" in two_way and "D_m" not in two_way and "n_slips" not in two_way
    with pytest.raises(ValueError, match=r"SlidingBlock sweeps mu \[-\], not ky"):
        bd.study(records[:1], ky=ky, pga=pga, block=bd.SlidingBlock(mu=0.3, bias=-0.1, direction="negative"))
