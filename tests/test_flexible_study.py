"""bd.study on the flexible sliding mass (issue 26): records x ky x PGA, its rows against
bd.flexible (an independent call on the same record, ky and target PGA), local == Dask,
checkpoints, a fragility fitted to it, and the sweep's errors before any work."""

import json

import numpy as np
import pandas as pd
import pytest

import blockdae as bd
from blockdae.studies import _study as study_module
from conftest import load_sample_record

#: ten short records of pySLAMMER's (a fragility takes at least ten)
SHORT = ("Northridge_1994_PAC-175", "Cape_Mendocino_1992_PET-090", "Duzce_1999_375-090",
         "N_Palm_Springs_1986_WWT-180", "Kobe_1995_TAK-090", "Nahanni_1985_NS1-280", "Coyote_Lake_1979_G02-050",
         "Mammoth_Lakes-2_1980_CVK-090", "Morgan_Hill_1984_CYC-285", "Mammoth_Lakes-1_1980_CVK-090")
KY = [0.1, 0.2]
PGA = [0.2, 0.4, 0.6]
COLUMN = bd.ShearColumn(height=20.0, vs=300.0)
MASS = bd.FlexibleSlidingMass(COLUMN, ky=0.15)  # its ky is not used: the study sets it
_RUN_TASK = study_module.run_task
FLEXIBLE = ["height_m", "vs_m_s", "normal_m", "inverse_m", "kmax_g", "kmax_sup_g", "vs_final_m_s", "damping_final",
            "episodes_normal", "episodes_inverse"]


@pytest.fixture(scope="module")
def records():
    return [load_sample_record(stem) for stem in SHORT]


@pytest.fixture(scope="module")
def table(records):
    return bd.study(records, ky=KY, pga=PGA, block=MASS)


@pytest.fixture(scope="module")
def by_flexible(records):
    """bd.flexible's row of every record, ky and target PGA, in the study's order."""
    return pd.concat([bd.flexible(record, ky=ky, height=COLUMN.height, vs=COLUMN.vs, pga=pga).to_dataframe()
                      .assign(pga_g=pga) for record in records for ky in KY for pga in PGA], ignore_index=True)


def test_rows_are_bd_flexible_at_the_same_record_ky_and_pga(table, by_flexible):
    assert list(table.columns) == ["record", "location", "floor", "frame_period_s", "ky_g", "pga_g", "scale",
                                   "pga_m_s2", "pgv_m_s", "sd_m"] + FLEXIBLE
    assert len(table) == len(SHORT) * len(KY) * len(PGA) and list(table["record"].unique()) == list(SHORT)
    assert list(table.loc[:5, "ky_g"]) == [0.1] * 3 + [0.2] * 3 and list(table.loc[:5, "pga_g"]) == PGA * 2
    for name in ("record", "ky_g", "pga_g", "height_m", "vs_m_s", "vs_final_m_s", "damping_final", "episodes_normal",
                 "episodes_inverse"):
        np.testing.assert_array_equal(table[name].to_numpy(), by_flexible[name].to_numpy(), err_msg=name)
    # the study scales each record to a peak of 1 g, then by the PGA; bd.flexible by pga g / peak
    # at once: the motions differ by rounding, the displacements by its size (a slide of
    # 0.2 µm by 5e-19 m on the full benchmark grid)
    for name in ("normal_m", "inverse_m"):
        np.testing.assert_allclose(table[name], by_flexible[name], rtol=1e-12, atol=1e-15, err_msg=name)
    for name in ("kmax_g", "kmax_sup_g"):
        np.testing.assert_allclose(table[name], by_flexible[name], rtol=1e-14, atol=0, err_msg=name)
    assert (table["normal_m"] > 0.01).any() and (table["inverse_m"] <= 0.01).any()  # slides and near-zeros


def test_scale_grid_gives_bd_flexible_bit_for_bit(records):
    """With scale= the study's motion is the motion of bd.flexible(..., pga=) (the record times
    pga g / peak): the same rows to the last bit."""
    kobe = records[SHORT.index("Kobe_1995_TAK-090")]
    factors = bd.excitation.pga_factor(kobe.peak_acceleration, PGA)
    table = bd.study(kobe, ky=KY, scale=factors, block=MASS)
    for (ky, pga), row in zip([(k, p) for k in KY for p in PGA], table.itertuples()):
        ref = bd.flexible(kobe, ky=ky, height=COLUMN.height, vs=COLUMN.vs, pga=pga).rows[0]
        assert [getattr(row, name) for name in FLEXIBLE] == [ref[name] for name in FLEXIBLE]
        assert row.ky_g == ky and row.pga_g == pytest.approx(pga, rel=1e-15)


def test_local_equals_dask(records, table):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) \
            as cluster, distributed.Client(cluster) as client:
        on_dask = bd.study(records, ky=KY, pga=PGA, block=MASS, executor=client)
    pd.testing.assert_frame_equal(on_dask, table)


def test_checkpoint_resumes_bit_identical(records, table, tmp_path, monkeypatch):
    monkeypatch.setattr(study_module, "TASK_ANALYSES", 2 * len(KY) * len(PGA))  # two records a task: five tasks
    folder = tmp_path / "ck"
    first = bd.study(records, ky=KY, pga=PGA, block=MASS, checkpoint=folder)
    pd.testing.assert_frame_equal(first, table)
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["ky"] == KY and "mu" not in manifest and manifest["block"]["column"]["vs"] == COLUMN.vs
    (folder / "task-000002.csv").unlink()
    ran = []

    def counting(chunk, grid):
        ran.append(len(chunk))
        return _RUN_TASK(chunk, grid)
    monkeypatch.setattr(study_module, "run_task", counting)
    pd.testing.assert_frame_equal(bd.study(records, ky=KY, pga=PGA, block=MASS, checkpoint=folder), table)
    assert ran == [2]  # only the deleted task ran again
    with pytest.raises(ValueError, match=r"holds another study: ky was \[0.1, 0.2\], now \[0.1\]"):
        bd.study(records, ky=KY[:1], pga=PGA, block=MASS, checkpoint=folder)


def test_fragility_of_a_flexible_study_is_that_of_bd_flexible_runs(table, by_flexible):
    """fit_fragility on one ky of the study, and on bd.flexible's rows of the same
    analyses: the same fit (the rows differ by rounding; the probit's Newton steps stop
    below 1e-10)."""
    worse = ("normal_m", "inverse_m")
    fits = [bd.hazard.fit_fragility(t[t["ky_g"] == 0.1], im="pga_g", displacement=worse, n_boot=0)
            for t in (table, by_flexible)]
    assert fits[0].n_records == len(SHORT) and fits[0].n_rows == len(SHORT) * len(PGA)
    np.testing.assert_allclose(fits[0].params, fits[1].params, rtol=1e-8)
    assert np.isfinite(fits[0].b0) and fits[0].b1 > 0  # some rows below d0: the probit is fitted
    assert fits[0].c1 > 0  # the median displacement grows with the PGA
    with pytest.raises(ValueError, match="2 values of ky_g: fit one slope at a time"):
        bd.hazard.fit_fragility(table, im="pga_g", displacement=worse, n_boot=0)


@pytest.mark.parametrize("kwargs, match", [
    (dict(mu=[0.1]), r"mu=\[0.1\]: FlexibleSlidingMass sweeps ky \[g\], not mu; give ky= instead"),
    (dict(block=bd.SlidingBlock(mu=0.3, bias=-0.1), ky=[0.1]),
     r"ky=\[0.1\]: SlidingBlock sweeps mu \[-\], not ky; give mu= instead"),  # with a bias, ky is not mu
    (dict(block=bd.PlanarBlock(mu=0.3), ky=[0.1]), r"PlanarBlock sweeps mu \[-\], not ky"),
    (dict(ky=None), r"give ky= \(FlexibleSlidingMass's swept parameter \[g\]"),
    (dict(ky=[0.1, -0.05]), r"ky must be positive and finite \[g\], got -0.05"),
])
def test_bad_input_fails_before_work(records, kwargs, match, monkeypatch):
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    with pytest.raises(ValueError, match=match):
        bd.study(records, **(dict(ky=KY, pga=PGA, block=MASS) | kwargs))


def test_t_end_past_a_record_and_summary_are_refused(records, table, monkeypatch):
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    with pytest.raises(ValueError, match=r"t_end=20.0 must lie in \(0, 19.98\] s \(the record "
                                         r"'Northridge_1994_PAC-175', records\[0\]\)"):
        bd.study(records[:2], ky=KY, pga=PGA, block=MASS, t_end=20.0)
    with pytest.raises(ValueError, match=r"summary takes a study of a block over mu or ky_g.*no "
                                         r"\['max_abs_displacement_m'\] columns"):
        bd.studies.summary(table)


def test_benchmark_quick(monkeypatch, capsys):
    from conftest import load_benchmark

    assert load_benchmark("flexible_study", monkeypatch).main(["--quick", "--no-dask"]) == 0
    out = capsys.readouterr().out
    assert "10 records × 2 ky × 3 PGA = 60 analyses" in out and "bar: the study no slower" in out
    assert "smoke run, not a measurement" in out and "P(D > 5 cm | PGA 0.5 g)" in out


def test_a_three_component_motion_is_refused_before_work(records, monkeypatch):
    """A bd.BaseMotion (the block on a plane's input) is refused by name before any task runs."""
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    x = records[4]
    y = bd.Record(0.5 * x.acceleration_samples, x.dt, "half", units="m/s2")
    with pytest.raises(ValueError, match=r"records\[1\] \('Kobe_1995_TAK-090 \+ half'\) is a "
                                         r"BaseMotion: the flexible sliding mass takes records along the slope"):
        bd.study([records[0], bd.BaseMotion(x, y)], ky=KY, pga=PGA, block=MASS)


#: a hardening ky table: 0.1 g at rest, 0.2 g after 5 cm of sliding
TABLE = bd.KyTable([0.0, 0.05], [0.1, 0.2])


def test_a_ky_table_study_is_bd_flexible_and_resumes_from_its_checkpoint(records, tmp_path, monkeypatch):
    """ky= a bd.KyTable: its rows are bd.flexible's with the same table and motion (scale=
    the factors of pga: the same record, bit for bit), column ky_g its ky at D = 0;
    the manifest records the table, a rerun with it resumes, another table is refused."""
    two = records[:2]
    factors = [0.3, 0.6]
    monkeypatch.setattr(study_module, "TASK_ANALYSES", len(factors))  # one record a task: two tasks
    folder = tmp_path / "ck"
    table = bd.study(two, ky=TABLE, scale=factors, block=MASS, checkpoint=folder)
    assert list(table["ky_g"]) == [0.1] * 4 and list(table["scale"]) == factors * 2
    for record, rows in zip(two, (table.iloc[:2], table.iloc[2:])):
        for factor, row in zip(factors, rows.itertuples()):
            ref = bd.flexible(record.scaled(factor), ky=TABLE, height=COLUMN.height, vs=COLUMN.vs).rows[0]
            assert [getattr(row, name) for name in FLEXIBLE] == [ref[name] for name in FLEXIBLE]
    assert (table["normal_m"] > 0.05).any()  # some slides pass the breakpoint: the table matters
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["ky"] == [{"displacement_m": [0.0, 0.05], "ky_g": [0.1, 0.2]}]
    (folder / "task-000001.csv").unlink()
    ran = []

    def counting(chunk, grid):
        ran.append([r.name for r in chunk])
        return _RUN_TASK(chunk, grid)
    monkeypatch.setattr(study_module, "run_task", counting)
    resumed = bd.study(two, ky=bd.KyTable([0.0, 0.05], [0.1, 0.2]), scale=factors, block=MASS, checkpoint=folder)
    pd.testing.assert_frame_equal(resumed, table)
    assert ran == [[two[1].name]]  # only the deleted task ran again
    with pytest.raises(ValueError, match=r"holds another study: ky was \[\{'displacement_m': \[0.0, 0.05\], "
                                         r"'ky_g': \[0.1, 0.2\]\}\], now \[\{'displacement_m': \[0.0, 0.05\], "
                                         r"'ky_g': \[0.1, 0.3\]\}\]"):
        bd.study(two, ky=bd.KyTable([0.0, 0.05], [0.1, 0.3]), scale=factors, block=MASS, checkpoint=folder)
    with pytest.raises(ValueError, match=r"holds another study: ky was \[\{'displacement_m'.*\}\], now \[0.1\]"):
        bd.study(two, ky=0.1, scale=factors, block=MASS, checkpoint=folder)


def test_tables_and_numbers_together_are_refused(records, monkeypatch):
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    with pytest.raises(ValueError, match=r"ky\[1\]=0.2: give ky as numbers \[g\] or as ky tables \(bd.KyTable\), "
                                         "not both"):
        bd.study(records[:1], ky=[TABLE, 0.2], pga=PGA, block=MASS)


def test_cli_study_runs_the_flexible_mass(records, tmp_path, capsys, monkeypatch):
    """blockdae study --ky/--ky-table --height --vs: bd.study's table of the flexible mass
    (reference: the same bd.study call in Python), saved to --out; its misuses exit 2
    with one line naming the option, before any work."""
    from blockdae.cli._main import main
    from conftest import sample_record_paths

    folder = tmp_path / "records"
    folder.mkdir()
    for path in sample_record_paths():
        if path.stem in SHORT[:2]:
            (folder / path.name).write_bytes(path.read_bytes())
    two = sorted(records[:2], key=lambda r: r.name)
    out = tmp_path / "flexible.csv"
    argv = ["--no-cache", "study", str(folder), "--pga", "0.2", "0.4", "--out", str(out)]
    column = ["--height", "20", "--vs", "300"]
    assert main(argv + column + ["--ky", "0.1", "0.2"]) == 0, capsys.readouterr().err
    assert "8 analyses (2 records × 1 locations × 2 ky × 2 intensities)" in capsys.readouterr().out
    pd.testing.assert_frame_equal(bd.load_study(out), bd.study(two, ky=KY, pga=[0.2, 0.4], block=MASS))
    assert main(argv + column + ["--ky-table", "0:0.1", "0.05:0.2", "--method", "decoupled"]) == 0
    decoupled = bd.FlexibleSlidingMass(COLUMN, ky=0.1, method="decoupled")
    pd.testing.assert_frame_equal(bd.load_study(out), bd.study(two, ky=TABLE, pga=[0.2, 0.4], block=decoupled))
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    for bad, message in [
        (["--ky", "0.1", "--vs", "100"], "--ky and --ky-table study the flexible sliding mass: give --height"),
        (column + ["--ky", "0.1", "--direction", "both"], "--direction both: the flexible sliding mass slides "
                                                          "downslope in both polarities"),
        (column + ["--mu", "0.1"], "--height applies to the flexible sliding mass (--ky or --ky-table with "
                                   "--height and --vs), not to the rigid block of --mu"),
        (column + ["--ky", "0.1", "--summary", str(tmp_path / "s.csv")], "--summary: the paper's summaries are of "
                                                                         "a block"),
        (column + ["--ky-table", "0:0.1", "0:0.2"], "--ky-table: KyTable: displacement_m must be strictly "
                                                    "increasing"),
        (column + ["--ky", "0.1", "--soil-damping", "0.9"], "--soil-damping: damping=0.9 gives a total damping "
                                                            "ratio of 1.1"),
    ]:
        assert main(argv + bad) == 2, bad
        assert message in capsys.readouterr().err, bad
