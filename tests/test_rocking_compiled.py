"""The free-standing block's compiled engine (``backend="compiled"``): the exact equation
and the linearised one by DOP853 with located events.

References: the exact block's energy integral theta'² / 2 = p² [cos(alpha - theta0) -
cos(alpha - theta)] integrated by mpmath's tanh-sinh quadrature (40 digits); the
linearised block's free rocking in closed form (mpmath, tests/test_rocking.py); CVODE at
rtol 1e-12, atol 1e-14 and the JAX twin at its default rtol 1e-10, whose own errors are
measured in tests/test_rocking.py and tests/test_conformance.py.
"""

import math

import mpmath
import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import RockingBlock, RockingMode
from conftest import load_sample_record, sample_record_paths
from test_rocking import QUIET, free_rocking_times

G = bd.STANDARD_GRAVITY
mpmath.mp.dps = 40


@pytest.fixture(scope="module")
def kobe():
    return load_sample_record("Kobe_1995_TAK-090")


@pytest.fixture(scope="module")
def kobe_six(kobe):
    """Kobe TAK-090, its first 6 s at 0.7 times: a 0.6 m x 1.8 m block rocks with impacts."""
    return bd.Record(0.7 * kobe.acceleration_samples[:600], kobe.dt, name="Kobe TAK-090, 0-6 s, x 0.7", units="m/s2")


def against_cvode(block, motion, **options):
    """(compiled run, CVODE run at rtol 1e-12, largest event-time difference [s]); the
    mode changes must be the same."""
    mine = bd.simulate(block, motion, backend="compiled", **options)
    reference = bd.simulate(block, motion, backend="cvode", rtol=1e-12, atol=1e-14, **options)
    assert [(e.mode_before, e.mode_after) for e in mine.events] == [(e.mode_before, e.mode_after)
                                                                    for e in reference.events]
    return mine, reference, float(np.max(np.abs(mine.t_events - reference.t_events), initial=0.0))


def test_exact_free_rocking_first_impact_quadrature():
    """Released at theta0 = 0.2 rad: the first impact time is the quadrature of dtheta /
    theta' (measured 1.1e-16 s) and the rate before it sqrt(2 p² [cos(alpha - theta0) -
    cos alpha]) (2.2e-16 relative); the release is an event at t = 0."""
    block = RockingBlock(b=0.3, h=0.9, mu=0.7, theta0=0.2)
    sol = bd.simulate(block, QUIET, t_end=1.5, backend="compiled")
    p, alpha, theta0 = (mpmath.mpf(v) for v in (block.frequency, block.alpha, block.theta0))
    rate = lambda theta: p * mpmath.sqrt(2 * (mpmath.cos(alpha - theta0) - mpmath.cos(alpha - theta)))
    t1 = float(mpmath.quad(lambda theta: 1 / rate(theta), [0, theta0]))
    assert sol.events[0].kind == "release" and sol.events[0].t == 0.0
    assert abs(sol.impact_times[0] - t1) < 1e-14
    assert sol.impacts[0].rate == pytest.approx(-float(rate(0)), rel=1e-14)


def test_linearised_free_rocking_closed_form():
    """The linearised block released at alpha/2 until rest: its 186 impacts before the Zeno
    tail within 1e-11 s of the closed form (measured 5.6e-12 s), the rest time within
    1e-11 s of the series' accumulation point (6.2e-12 s)."""
    block = RockingBlock(b=0.2, h=1.0, mu=0.5, linearised=True)
    block = block.replace(theta0=block.alpha / 2)
    times, rest = free_rocking_times(block, block.theta0)
    sol = bd.simulate(block, QUIET, backend="compiled")
    n = len(sol.impact_times)
    assert n >= 150 and sol.events[-1].kind == "rest"
    assert np.max(np.abs(sol.impact_times - times[:n])) < 1e-11
    assert abs(sol.rest_time - rest) < 1e-11


def test_agrees_with_cvode_and_jax_under_a_record(kobe_six):
    """Under Kobe TAK-090 (0-6 s, x 0.7) the exact block rocks with impacts: the same mode
    changes as CVODE (rtol 1e-12) within 1e-9 s (measured 7.6e-11 s) and as the JAX twin
    within 1e-9 s; the dense motion within 1e-9 rad."""
    block = RockingBlock(b=0.3, h=0.9, mu=0.8)
    mine, reference, dt = against_cvode(block, kobe_six, t_end=6.0)
    assert len(mine.impacts) >= 4 and not mine.overturned
    assert dt < 1e-9
    twin = bd.simulate(block, kobe_six, t_end=6.0, backend="jax")
    assert [e.kind for e in twin.events] == [e.kind for e in mine.events]
    assert np.max(np.abs(twin.t_events - mine.t_events)) < 1e-9
    t = np.linspace(0.0, 6.0, 3001)
    assert np.max(np.abs(mine(t)[0] - reference(t)[0])) < 1e-9


def test_overturns_after_the_record_ends(kobe_six):
    """Until rest, the same block under the same record passes alpha and overturns after
    the record's end (6 s), at CVODE's times within 1e-9 s (measured 7.6e-11 s)."""
    mine, _, dt = against_cvode(RockingBlock(b=0.3, h=0.9, mu=0.8), kobe_six)
    assert mine.overturned and kobe_six.duration < mine.time_beyond_alpha < mine.overturn_time
    assert mine.state[-1, 0] == pytest.approx(math.pi / 2, abs=0)
    assert dt < 1e-9


def test_overturns_under_a_pulse():
    """A one-sine pulse of 1 g overturns a 0.2 m x 1 m block: uplift, alpha, pi/2 at CVODE's
    times within 1e-10 s (measured 1.1e-12 s)."""
    mine, _, dt = against_cvode(RockingBlock(b=0.1, h=0.5, mu=0.6), bd.SinePulse(-1.0 * G, 0.6))
    assert [e.kind for e in mine.events] == ["uplift", "beyond_alpha", "overturn"]
    assert dt < 1e-10


def test_never_rocks_below_the_threshold():
    """A pulse below g b/h leaves the block at rest: no event, theta = 0 throughout."""
    block = RockingBlock(b=0.3, h=0.9, mu=0.8)
    sol = bd.simulate(block, bd.SinePulse(-0.3 * G, 0.6), t_end=2.0, backend="compiled")
    assert sol.events == () and sol.max_theta_over_alpha == 0.0
    assert np.all(sol.state == 0.0) and sol.t_end == 2.0


def test_vertical_shaking(kobe_six):
    """With a vertical component (half the horizontal record) the block rocks under g + a_z:
    CVODE's mode changes within 1e-9 s (measured 1.7e-11 s)."""
    motion = bd.BaseMotion(kobe_six, None, kobe_six.scaled(0.5))
    mine, _, dt = against_cvode(RockingBlock(b=0.3, h=0.9, mu=0.8), motion, t_end=6.0)
    assert len(mine.impacts) >= 4
    assert dt < 1e-9


def test_the_base_falling_faster_than_g_is_an_error():
    """a_z below -g while the block rests stops the run with the model's message."""
    motion = bd.BaseMotion(bd.SinePulse(0.1 * G, 0.5), None, bd.SinePulse(-1.2 * G, 0.5))
    with pytest.raises(ValueError, match="falls faster than g"):
        bd.simulate(RockingBlock(b=0.3, h=0.9, mu=0.8), motion, t_end=1.0, backend="compiled")


def test_backends_by_variant():
    """The exact equation runs on "compiled" (not on "exact", the linearised block's closed
    form); a block that slides on neither."""
    assert "compiled" in bd.backends.available(RockingBlock(b=0.3, h=0.9, mu=0.8))
    assert "exact" not in bd.backends.available(RockingBlock(b=0.3, h=0.9, mu=0.8))
    assert {"exact", "compiled"} <= set(bd.backends.available(RockingBlock(b=0.3, h=0.9, mu=0.8, linearised=True)))
    assert not {"exact", "compiled"} & set(bd.backends.available(RockingBlock(b=0.5, h=0.6, mu=0.3)))


@pytest.mark.slow
def test_differences_from_cvode_are_cvodes():
    """Landers LCN-345 at 0.4 g (534 events): the compiled engine at rtol 1e-12 and 1e-14
    agree within 1e-11 s (measured 2.2e-13 s), while CVODE, 8.3e-4 s away at rtol 1e-12,
    comes closer at rtol 1e-13 (1.4e-4 s): the unstable rocking amplifies CVODE's drift."""
    path = next(p for p in sample_record_paths() if p.name.startswith("Landers_1992_LCN-345"))
    record = bd.read_record(path, units="g")
    record = record.scaled(0.4 * G / record.peak_acceleration)
    block = RockingBlock(b=0.2, h=0.8, mu=0.6)
    runs = [bd.simulate(block, record, t_end=record.duration, backend=backend, **options)
            for backend, options in (("compiled", {}), ("compiled", dict(rtol=1e-14, atol=1e-16)),
                                     ("cvode", dict(rtol=1e-12)), ("cvode", dict(rtol=1e-13, atol=1e-16)))]
    assert len({tuple(e.kind for e in run.events) for run in runs}) == 1 and len(runs[0].events) > 500
    mine, finer, cvode, cvode_finer = (run.t_events for run in runs)
    assert np.max(np.abs(mine - finer)) < 1e-11
    assert np.max(np.abs(cvode_finer - finer)) < 0.5 * np.max(np.abs(cvode - finer))


@pytest.mark.parametrize("backend, linearised", [("compiled", False), ("exact", True)])
def test_final_numbers_are_the_single_runs(kobe_six, backend, linearised):
    """bd.simulate(..., final_only=True) over records and scales (factors on a(t) in the
    compiled engine) gives each single run's theta(t_end) and max |theta| (on a scaled
    copy: to the rounding of the product, amplified by the rocking: measured 2.2e-14
    relative) and its number of events; the linearised block's closed form too."""
    block = RockingBlock(b=0.3, h=0.9, mu=0.8, linearised=linearised)
    motions = [kobe_six, kobe_six.scaled(-0.8)]
    finals = bd.simulate(block, motions, scale=[0.9, 1.0], t_end=6.0, backend=backend, final_only=True)
    for i, motion in enumerate(motions):
        for k, factor in enumerate((0.9, 1.0)):
            one = bd.simulate(block, motion.scaled(factor), t_end=6.0, backend=backend)
            assert finals.displacement[i, k, 0] == pytest.approx(one.displacement, rel=1e-9, abs=1e-15)
            assert finals.max_abs_displacement[i, k, 0] == pytest.approx(one.max_abs_displacement, rel=1e-9)
            assert finals.n_events[i, k, 0] == len(one.events)
    assert finals.n_events.max() >= 10


def test_strict_stops_where_cvode_stops(kobe):
    """strict=True: the first contact limit (a 0.2 m x 1 m block with mu = 0.3 under Kobe
    TAK-090) stops the run with CVODE's error, at its time within 1e-6 s (the dense
    output's error; measured 1e-9 s at the message's 9 decimals)."""
    block = RockingBlock(b=0.1, h=0.5, mu=0.3, strict=True)
    stops = []
    for backend in ("cvode", "compiled"):
        with pytest.raises(ValueError, match="strict=True stops here") as error:
            bd.simulate(block, kobe, t_end=6.0, backend=backend)
        stops.append(float(str(error.value).split("at t = ")[1].split(" s")[0]))
    assert abs(stops[1] - stops[0]) < 1e-6


def test_onset_at_a_sample_and_at_the_record_end():
    """a_x reaching -g b/h exactly at a sample: the block lifts there if a_x goes on past it
    (the rate decides, as CVODE's driver does), not if the record ends there; until rest,
    the free rocking after the record (122 events to the Zeno rest) has CVODE's mode
    changes, the first six within 1e-9 s and all within 1e-7 s (measured 2.9e-8 s: CVODE's
    drift; the compiled engine at rtol 1e-14 gives the same times)."""
    block = RockingBlock(b=0.3, h=0.9, mu=0.8)
    edge = -block.rocking_threshold * G
    ends_there = bd.Record(np.array([0.0, 0.0, edge]), 0.1, units="m/s2")
    assert bd.simulate(block, ends_there, backend="compiled").events == ()
    goes_on = bd.Record(np.array([0.0, 0.0, edge, 1.5 * edge, 0.0]), 0.1, units="m/s2")
    mine, _, dt = against_cvode(block, goes_on)
    assert mine.events[0].kind == "uplift" and mine.events[0].t == 0.2
    assert mine.events[-1].kind == "rest" and len(mine.events) > 100
    assert dt < 1e-7
    reference = bd.simulate(block, goes_on, backend="cvode", rtol=1e-12, atol=1e-14)
    assert np.max(np.abs(mine.t_events[:6] - reference.t_events[:6])) < 1e-9


def test_the_engines_rules_are_the_models():
    """The compiled engine's flow, guards, guard rates, states on a guard, modes after it
    and states on entry (its functions run as plain Python) are the model's on the
    driver's piece of a motion
    (a sine on a line in x, a line in z), in every rocking, settling and static mode, at
    states on both sides of the base."""
    from blockdae.core._driver import PieceExcitation
    from blockdae.core.contract import SCALAR
    from blockdae.rocking import _compiled, _engine

    block = RockingBlock(b=0.3, h=0.9, mu=0.8, theta0=0.1)
    p = tuple(_engine.engine_parameters(block))
    coefficients = np.array([[-0.2 * G, 0.5 * G, 0.3 * G, 7.0, 0.4], [0.05 * G, -0.2 * G, 0.0, 0.0, 0.0]])
    t0, h = 1.0, 0.08
    driver = PieceExcitation(2)
    driver.set(t0, coefficients, h)
    piece = _compiled._piece_at(np.array([t0]), np.array([h]), coefficients[None], 0)
    modes = [m for m in RockingMode if abs(int(m)) != 1]
    checked = 0
    for mode in modes:
        for state in ((0.05, 0.3), (-0.12, -0.4), (0.0, 0.2), (0.3, 0.0)):
            for t in (t0, t0 + 0.03, t0 + h):
                y = np.array(state)
                value = int(mode)
                np.testing.assert_array_equal(_compiled._flow(value, t, *state, piece, p),
                                              block.flow(mode, t, y, driver, SCALAR))
                mine = _compiled._guards(value, t, state, piece, p)
                theirs = list(block.guards(mode, t, y, driver, SCALAR))
                indices = {0: 0} if len(theirs) == 1 else {0: 0, 1: 1, 3: len(theirs) - 1}
                if len(theirs) == 4:
                    indices[2] = 2
                for k, j in indices.items():
                    assert mine[k] == theirs[j] or (abs(int(mode)) == 6 and mine[k] == math.inf), (mode, k)
                    if value == RockingMode.RELEASE or abs(value) == 6:
                        continue
                    assert _compiled._guard_rates(value, k, t, state, piece, p) == block.guard_rates(
                        mode, j, t, y, driver), (mode, k)
                    if k == 3:
                        continue
                    on_guard = np.array(block.state_at_guard(mode, j, y, SCALAR), dtype=float)
                    mine_on_guard = y.copy()
                    _compiled._state_at_guard(value, k, mine_on_guard, p)
                    np.testing.assert_array_equal(mine_on_guard, on_guard)
                    after = block.mode_after_guard(mode, j, t, on_guard, driver, SCALAR)
                    assert _compiled._mode_after_guard(value, k, t, tuple(on_guard), piece, p) == int(after), (mode, k)
                    entered = on_guard.copy()
                    _compiled._state_on_entry(value, int(after), entered, p)
                    np.testing.assert_array_equal(entered, block.state_on_entry(mode, after, t, on_guard, driver,
                                                                                SCALAR))
                    checked += 1
    assert checked > 100
