"""bd.study on the block on a plane: three-component motions x mu x factors on the
compiled planar engine (at the study tolerance), locally and on Dask."""

import numpy as np
import pandas as pd
import pytest

import blockdae as bd
from blockdae.planar._model import STUDY_RTOL
from blockdae.studies import _study as study_module
from conftest import load_sample_record

MU = [0.15, 0.25]
SCALE = [0.5, 1.0, 1.5]
BLOCK = bd.PlanarBlock(mu=0.3, mu_kinetic=None, bias=(-0.03, 0.01))


@pytest.fixture(scope="module")
def motions():
    kobe, duzce, palm, nahanni = (load_sample_record(s) for s in (
        "Kobe_1995_TAK-090", "Duzce_1999_375-090", "N_Palm_Springs_1986_WWT-180", "Nahanni_1985_NS1-280"))
    return [bd.BaseMotion(kobe, duzce), bd.BaseMotion(palm, nahanni),
            bd.BaseMotion(duzce, kobe.scaled(0.7), kobe.scaled(0.4))]  # three components, z up to 0.4 x's peak


@pytest.fixture(scope="module")
def table(motions):
    return bd.study(motions, mu=MU, scale=SCALE, block=BLOCK)


def test_rows_are_single_simulations_at_the_study_tolerance(table, motions):
    assert len(table) == len(motions) * len(MU) * len(SCALE)
    assert list(table["record"].unique()) == ["Kobe_1995_TAK-090 + Duzce_1999_375-090",
                                              "N_Palm_Springs_1986_WWT-180 + Nahanni_1985_NS1-280",
                                              "Duzce_1999_375-090 + Kobe_1995_TAK-090 + Kobe_1995_TAK-090"]
    assert "n_slips" not in table and (table["n_events"] > 0).all()
    for row in (0, 4, 8, 11, 17):
        r = table.iloc[row]
        motion = motions[row // (len(MU) * len(SCALE))]
        sol = bd.simulate(BLOCK.replace(mu=r["mu"]), motion.scaled(r["scale"]), backend="compiled", rtol=STUDY_RTOL)
        np.testing.assert_allclose([r["displacement_x_m"], r["displacement_y_m"]], sol.displacement, rtol=1e-12,
                                   atol=1e-15)
        np.testing.assert_allclose(r["displacement_m"], np.hypot(*sol.displacement), rtol=1e-12)
        np.testing.assert_allclose(r["max_abs_displacement_m"], sol.max_abs_displacement, rtol=1e-12)
        assert r["n_events"] == len(sol.events) and r["slide_distance_m"] >= r["displacement_m"]
        peak = max(motion.scaled(r["scale"]).peak_acceleration[:2])
        np.testing.assert_allclose(r["pga_m_s2"], peak, rtol=1e-14)


def test_pga_scales_the_larger_horizontal_peak(motions):
    by_pga = bd.study(motions[2:], mu=MU[:1], pga=[0.3], block=BLOCK)
    duzce_peak = motions[2].x.peak_acceleration  # the x component has the larger peak
    np.testing.assert_allclose(by_pga["scale"], 0.3 * bd.STANDARD_GRAVITY / duzce_peak, rtol=1e-14)
    by_scale = bd.study(motions[2:], mu=MU[:1], scale=by_pga["scale"].to_numpy(), block=BLOCK)
    np.testing.assert_allclose(by_scale["displacement_x_m"], by_pga["displacement_x_m"], rtol=1e-9)


def test_local_equals_dask(motions, table):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) \
            as cluster, distributed.Client(cluster) as client:
        on_dask = bd.study(motions, mu=MU, scale=SCALE, block=BLOCK, executor=client)
    pd.testing.assert_frame_equal(on_dask, table)


@pytest.mark.parametrize("kwargs, match", [
    (dict(block=bd.PlanarBlock(mu=0.3, bias=(-0.2, 0.0))), "bias"),  # |bias| >= mu = 0.15
    (dict(block=object()), "block must be a model"),
    (dict(where=[bd.ShearFrame(5, 0.3, 0.05).floor(1)]), "ground only"),
])
def test_bad_input_fails_before_work(motions, kwargs, match, monkeypatch):
    monkeypatch.setattr(study_module, "run_task", lambda *a: pytest.fail("work started"))
    with pytest.raises((ValueError, TypeError), match=match):
        bd.study(motions, **(dict(mu=MU, scale=SCALE, block=BLOCK) | kwargs))
