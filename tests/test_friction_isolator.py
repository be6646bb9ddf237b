"""A model written outside the package (``examples/friction_isolator.py``) runs every tool
with no edit to the package: the generic backends against a closed form, a process pool,
``design.exceedance`` and an inverse on its own parameters through ``design.Simulated``."""

import concurrent.futures
import importlib.util
import math
import multiprocessing
import pathlib
import sys

import numpy as np
import pytest

import blockdae as bd
from blockdae import design

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def example():
    sys.path.insert(0, str(ROOT / "examples"))  # importable by name: a process pool's workers pickle by reference
    try:
        spec = importlib.util.spec_from_file_location("friction_isolator", ROOT / "examples" / "friction_isolator.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules["friction_isolator"] = module
        spec.loader.exec_module(module)
        yield module
    finally:
        sys.path.remove(str(ROOT / "examples"))
        sys.modules.pop("friction_isolator", None)


def test_one_slide_from_rest_against_its_closed_form(example):
    """A constant base acceleration -A (mu g < A < 3 mu g) from rest: u'' = A - (g/R) u -
    mu g, so u(t) = c (1 - cos(w t)) with c = (A - mu g) / w², w = sqrt(g/R), sliding until
    u' = 0 at t = pi / w, where u = 2c and the demand A - 2 (A - mu g) lies within mu g: it
    sticks for good (closed form)."""
    isolator = example.FrictionIsolator(mu=0.05, radius=1.5)
    w, a = math.sqrt(isolator.g / isolator.radius), 0.12 * bd.STANDARD_GRAVITY
    motion = bd.Record(np.full(401, -a), 0.01, check_peak=False)
    for backend in ("cvode", "ida"):
        solution = bd.simulate(isolator, motion, t_end=3.0, backend=backend, rtol=1e-10)
        c = (a - isolator.mu * isolator.g) / w**2
        assert [e.mode_after.name for e in solution.events] == ["SLIDE_POS", "STICK"]
        assert abs(solution.events[1].t - math.pi / w) < 1e-8
        assert abs(solution.displacement - 2 * c) < 1e-8 * 2 * c  # measured: 1.4e-9 relative on CVODE


def test_ensemble_on_a_process_pool(example):
    isolator, motion = example.FrictionIsolator(), example.record(duration=2.0)
    here = bd.simulate(isolator, [motion], scale=[0.5, 1.0], t_end=2.0)
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        there = bd.simulate(isolator, [motion], scale=[0.5, 1.0], t_end=2.0, executor=pool)
    assert there.to_dataframe().equals(here.to_dataframe())


def test_design_exceedance_and_the_inverse_on_its_own_parameters(example):
    motion, model = example.record(duration=2.0), example.design_model()
    study = design.exceedance(motion, model, {"mu": design.LogNormal(0.08, 0.2), "radius": 2.0}, threshold=0.1,
                              runs=4, runs_per_block=4)
    assert len(study.table) == 4 and "mu" not in study.table and "mu_ratio" in study.table and "radius_m" in study.table
    row = study.table.iloc[1]
    alone = bd.simulate(example.FrictionIsolator(mu=row["mu_ratio"], radius=2.0), motion)
    assert row["D_m"] == pytest.approx(alone.max_abs_displacement, rel=1e-12)
    mu = design.ky_for_displacement(motion, model, {"radius": 2.0}, allowable=0.1)
    peak = bd.simulate(example.FrictionIsolator(mu=mu, radius=2.0), motion).max_abs_displacement
    assert peak == pytest.approx(0.1, rel=1e-8)  # the inverse's D tolerance is 1e-10 relative


def test_design_contract_refuses_what_it_cannot_run(example):
    with pytest.raises(ValueError, match="holding design='ky'"):
        design.Simulated(example.FrictionIsolator(), parameters={"mu": "-"}, design="ky")
    with pytest.raises(ValueError, match="must be a design model"):
        design.exceedance(example.record(), example.FrictionIsolator(), {"mu": 0.1}, threshold=0.1, runs=4)


def test_a_start_already_sliding_against_its_closed_form(example):
    """From u = 0 sliding at v0 > 0 with no excitation: u'' = -w² u - mu g, so u(t) =
    c (cos wt - 1) + (v0 / w) sin wt with c = mu g / w²; it stops where u' = 0, at
    wt = atan(v0 / (c w)), and sticks there (|w² u| <= mu g) (closed form)."""
    isolator = example.FrictionIsolator(mu=0.05, radius=2.0, v0=0.1)
    assert isolator.initial_mode == example.IsolatorMode.SLIDE_POS
    w = math.sqrt(isolator.g / isolator.radius)
    c = isolator.mu * isolator.g / w**2
    stop = math.atan(isolator.v0 / (c * w)) / w
    quiet = bd.Record(np.zeros(301), 0.01, check_peak=False)
    for backend in ("cvode", "ida"):
        solution = bd.simulate(isolator, quiet, t_end=3.0, backend=backend, rtol=1e-10)
        assert [e.mode_after.name for e in solution.events] == ["STICK"]
        assert abs(solution.events[0].t - stop) < 1e-8
        u_stop = c * (math.cos(w * stop) - 1) + isolator.v0 / w * math.sin(w * stop)
        assert abs(solution.displacement - u_stop) < 1e-8 * abs(u_stop)


def test_a_starting_state_the_model_refuses(example):
    with pytest.raises(ValueError, match=r"u0=0.5 m: at rest there the surface pulls harder"):
        example.FrictionIsolator(mu=0.05, radius=2.0, u0=0.5)


def test_ensemble_and_design_study_on_a_dask_cluster(example):
    """The user's model on a Dask LocalCluster (one in-process worker of two threads): the
    ensemble of two scales and the design study give the local tables exactly."""
    distributed = pytest.importorskip("distributed")
    isolator, motion = example.FrictionIsolator(), example.record(duration=2.0)
    parameters = {"mu": design.LogNormal(0.08, 0.2), "radius": 2.0}
    run = lambda **kw: design.exceedance(motion, example.design_model(), parameters, threshold=0.1, runs=4,
                                         runs_per_block=2, **kw)
    here_ensemble, here_design = bd.simulate(isolator, [motion], scale=[0.5, 1.0], t_end=2.0), run()
    with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=2, dashboard_address=None) \
            as cluster, distributed.Client(cluster) as client:
        there_ensemble = bd.simulate(isolator, [motion], scale=[0.5, 1.0], t_end=2.0, executor=client)
        there_design = run(executor=client)
    assert there_ensemble.to_dataframe().equals(here_ensemble.to_dataframe())
    assert there_design.table.equals(here_design.table)


def _pulse():
    """One half-sine pulse of 0.3 g over 0.4 s, then 0.6 s at rest, sampled at 0.02 s."""
    t = np.arange(0.0, 1.0, 0.02)
    return bd.Record(np.where(t < 0.4, 0.3 * bd.STANDARD_GRAVITY * np.sin(np.pi * t / 0.4), 0.0), 0.02, units="m/s2")


def _newton_model(example, **options):
    """A nearly flat surface (R = 1 km) read at t = 1 s: the final D falls as mu rises
    (a slide that lasts longer the less the friction), as the inverses need."""
    return design.Simulated(example.FrictionIsolator(radius=1000.0), parameters={"mu": "-", "radius": "m"},
                            design="mu", t_end=1.0, **options)


@pytest.mark.parametrize("polarity, pga", [("normal", None), ("inverse", 0.25), ("larger", 0.25)])
def test_the_design_derivative_against_central_differences(example, polarity, pga):
    """dD/dmu of design.Simulated (the isolator's JAX twin through bd.sensitivities) against
    central differences of D with a relative step of 1e-4 (their own error, measured with
    steps 1e-3 and 1e-4: 1.1e-6 and 1.1e-8 relative, falling as the step squared)."""
    model, motion = _newton_model(example, polarity=polarity), _pulse()
    assert model.has_derivative and not example.design_model().has_derivative  # the peak has no derivative here
    d, slope = model.displacements(motion, pga, {"mu": 0.1, "radius": 1000.0}, derivative=True)
    step = 1e-4 * 0.1
    up, down = (model.displacements(motion, pga, {"mu": 0.1 + s, "radius": 1000.0}) for s in (step, -step))
    assert d[0] > 0.05 and slope[0] < 0
    assert slope[0] == pytest.approx((up[0] - down[0]) / (2 * step), rel=1e-7)


def test_the_inverse_takes_newton_steps_on_that_derivative(example, monkeypatch):
    """ky_for_displacement on the isolator's mu steps by Newton (has_derivative): the root
    bracketing finds (Illinois), in fewer forward runs (each count with the sliding
    limit's doubling from mu = 1e-4)."""
    from blockdae.design import _inverse, _models

    runs, simulate = [], _models.simulate
    monkeypatch.setattr(_models, "simulate", lambda *a, **k: runs.append(1) or simulate(*a, **k))
    model, motion = _newton_model(example), _pulse()
    newton = design.ky_for_displacement(motion, model, {"radius": 1000.0}, allowable=0.03)
    by_newton, runs[:] = len(runs), []
    bracketed = _inverse.critical_ky(model, motion, None, {"radius": 1000.0}, 0.03, newton=False)[0]
    assert newton == pytest.approx(bracketed, rel=1e-9)  # D to 1e-10 relative at each root
    assert by_newton < len(runs)  # measured: 19 against 23
    final = bd.simulate(example.FrictionIsolator(mu=newton, radius=1000.0), motion, t_end=1.0).displacement
    assert abs(final) == pytest.approx(0.03, rel=1e-9)


def test_a_study_of_the_isolator_equals_its_single_runs(example):
    """bd.study sweeps the isolator's mu (it declares no study hooks: the keyword given is
    its parameter, one model per value through its replace, each run by bd.simulate): every
    row is that model's own run of the scaled record, bit for bit, on the ground and on a
    floor of a frame."""
    motion, frame = example.record(duration=2.0), bd.ShearFrame(period=0.3, storeys=2)
    table = bd.study([motion], mu=[0.05, 0.08], scale=[0.5, 1.0], where=("ground", frame.floor(1)),
                     block=example.FrictionIsolator(radius=2.0), t_end=2.0)
    assert len(table) == 2 * 2 * 2 and "polarity" not in table
    assert list(table.columns[-4:]) == ["u_end_m", "max_abs_displacement_m", "n_events", "t_end_s"]
    floor = frame.floor_motions(motion)[0]
    for _, row in table.iterrows():
        place = motion if row["location"] == "ground" else floor
        alone = bd.simulate(example.FrictionIsolator(mu=row["mu"], radius=2.0), place.scaled(row["scale"]), t_end=2.0)
        assert row["max_abs_displacement_m"] == alone.max_abs_displacement
        assert row["u_end_m"] == alone.displacement
        assert row["n_events"] == len(alone.events)
    assert table["mu"].tolist() == [0.05, 0.05, 0.08, 0.08] * 2 and table["scale"].tolist() == [0.5, 1.0] * 4


def test_a_study_refuses_what_the_isolator_has_not(example):
    with pytest.raises(ValueError, match=r"ky=: FrictionIsolator has no parameter 'ky' \(its parameters: \["):
        bd.study([example.record()], ky=[0.1], scale=1.0, block=example.FrictionIsolator())
    # each value checked by the model before any run: at mu = 0.01 the surface pulls harder at u0 than friction holds
    with pytest.raises(ValueError, match=r"u0=0.1 m: at rest there the surface pulls harder"):
        bd.study([example.record()], mu=[0.06, 0.01], scale=1.0, block=example.FrictionIsolator(u0=0.1, radius=2.0))
