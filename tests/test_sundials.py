"""CVODE and IDA backends on the hybrid driver, checked against the exact backend.

Reference values: the exact backend (closed forms, an independent computation), seed 000
(Example 1 event times, Examples 4-6 displacements) and closed forms stated per test.
"""

import math
import re

import numpy as np
import pytest

import blockdae as bd
from blockdae.sliding import Mode
from blockdae.core import _crosscheck
from blockdae.core._driver import SolverError
from blockdae.backends import make_backend
from blockdae.sliding._model import stop_mode
from conftest import assert_same_events, load_sample_record

SUNDIALS = ("cvode", "ida")
G = 9.81

# seed 000: Example 1 (mu 0.6, A 9 m/s², T 1 s), 2 (f 0.3), 3 (A 7, bias 0.3, f 0.6 / 0.4),
# 4-6 (pulses of 9 m/s² for 0.5 s, until rest)
SEED_CASES = {
    "ex1": (bd.SlidingBlock(mu=0.6, g=G), bd.Harmonic(9.0, 1.0), 3.0),
    "ex2": (bd.SlidingBlock(mu=0.6, mu_kinetic=0.3, g=G), bd.Harmonic(9.0, 1.0), 3.0),
    "ex3a": (bd.SlidingBlock(mu=0.6, mu_kinetic=0.6, bias=0.3, g=G), bd.Harmonic(7.0, 1.0), 3.0),
    "ex3b": (bd.SlidingBlock(mu=0.6, mu_kinetic=0.4, bias=0.3, g=G), bd.Harmonic(7.0, 1.0), 3.0),
    "ex4": (bd.SlidingBlock(mu=0.6, g=G), bd.RectangularPulse(9.0, 0.5), None),
    "ex5": (bd.SlidingBlock(mu=0.6, g=G), bd.TriangularPulse(9.0, 0.5), None),
    "ex6": (bd.SlidingBlock(mu=0.6, g=G), bd.SinePulse(9.0, 0.5), None),
}
# short pySLAMMER records; two-way sliding with f < mu and a bias
RECORDS = ("Northridge_1994_PAC-175", "Cape_Mendocino_1992_PET-090", "Kobe_1995_TAK-090")
RECORD_BLOCK = bd.SlidingBlock(mu=0.15, mu_kinetic=0.12, bias=0.03)
#: backend -> (event times [s], u relative [-]): a decade above the worst measured on RECORDS
RECORD_BARS = {"cvode": (9.4e-12, 3.1e-9), "ida": (2.5e-10, 3.9e-8)}


@pytest.fixture(scope="module")
def exact_cache():
    """Exact solutions, computed once per case."""
    cache = {}

    def solve(key, block, motion, t_end):
        if key not in cache:
            cache[key] = bd.simulate(block, motion, t_end=t_end)
        return cache[key]

    return solve


def assert_agrees(sol, ref, dt_max=1e-9, rel_du_max=1e-7, scale=None):
    """Same events (modes) as ``ref``, every time within ``dt_max`` [s], displacement
    within ``rel_du_max`` relative to |u_ref(t_end)| (or to ``scale`` [m])."""
    assert_same_events(sol, ref, dt_max)
    scale = abs(ref.displacement) if scale is None else scale
    assert abs(sol.displacement - ref.displacement) <= rel_du_max * scale


@pytest.mark.parametrize("backend", SUNDIALS)
@pytest.mark.parametrize("case", sorted(SEED_CASES))
def test_seed_examples_agree_with_exact(case, backend, exact_cache):
    """Seed-000 Examples 1-6 at rtol 1e-10: <= 1e-9 s per event, <= 1e-7 relative in u
    (measured, worst case: CVODE 1.7e-10 s and 5.1e-8, IDA 6.6e-10 s and 2.6e-8)."""
    block, motion, t_end = SEED_CASES[case]
    ref = exact_cache(case, block, motion, t_end)
    sol = bd.simulate(block, motion, t_end=t_end, backend=backend, rtol=1e-10)
    assert len(ref.events) >= 2
    assert_agrees(sol, ref)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_example1_event_times_match_the_closed_form(backend):
    """Sawicki & Chybicki's (2005) Example 1: slip from 0.113455 s to 0.535036 s and
    0.613455 s to 1.035036 s, the closed form's times to six digits (the paper prints
    0.1125 or 0.113 s, 0.535 s, 0.614 s and 1.035 s)."""
    sol = bd.simulate(*SEED_CASES["ex1"][:2], t_end=1.1, backend=backend)
    np.testing.assert_allclose(sol.t_events, [0.113455, 0.535036, 0.613455, 1.035036], atol=1e-6)


@pytest.mark.parametrize("backend", SUNDIALS)
@pytest.mark.parametrize("case, seed_u", [("ex4", -0.595), ("ex5", -0.0453), ("ex6", -0.1332)])
def test_pulse_displacements_match_seed(case, seed_u, backend):
    """Seed 000, Examples 4-6: permanent displacements to the seed's 3-4 digits."""
    block, motion, _ = SEED_CASES[case]
    assert bd.simulate(block, motion, backend=backend).displacement == pytest.approx(seed_u, abs=6e-4)


@pytest.mark.parametrize("backend", SUNDIALS)
@pytest.mark.parametrize("stem", RECORDS)
def test_records_agree_with_exact(stem, backend, exact_cache):
    """Real records, two-way, f < mu, bias, at rtol 1e-10: each backend within a decade of
    its worst agreement over the three records (CVODE 9.4e-13 s and 3.1e-10 relative in u,
    IDA 2.5e-11 s and 3.9e-9). On all 18 sample records benchmarks/cvode_records.py
    measures CVODE 5.1e-12 s and 9.3e-10, IDA 7.5e-11 s and 2.1e-8, and asserts a decade
    above (run by tests/test_benchmarks_slow.py)."""
    record = load_sample_record(stem)
    ref = exact_cache(stem, RECORD_BLOCK, record, None)
    sol = bd.simulate(RECORD_BLOCK, record, backend=backend, rtol=1e-10)
    assert len(ref.events) >= 10
    assert_agrees(sol, ref, *RECORD_BARS[backend])



@pytest.mark.parametrize("backend", SUNDIALS)
def test_long_one_way_slip_agrees_with_exact(backend, exact_cache):
    """Chi-Chi one-way, mu 0.1: a 2.4 s slip restarted at ~500 samples, where errors made
    at the restarts would add up in v. Measured: CVODE 1.4e-12 s and 2.2e-10 relative in
    u, IDA 4.1e-11 s and 1.0e-8; the bars a decade above."""
    record = load_sample_record("Chi-Chi_1999_TCU068-090")
    block = bd.SlidingBlock(mu=0.1, direction="negative")
    sol = bd.simulate(block, record, backend=backend, rtol=1e-10)
    bars = {"cvode": (1.4e-11, 2.2e-9), "ida": (4.1e-10, 1.0e-7)}[backend]
    assert_agrees(sol, exact_cache("chichi-one-way", block, record, None), *bars)


@pytest.mark.parametrize("backend", SUNDIALS)
@pytest.mark.parametrize("gap", [1e-12, 1e-8, 3e-7])
def test_onset_just_before_a_sample(backend, gap, exact_cache):
    """A restart closer to the next sample than the solver's first step: a(t) = c t
    up to 0.2 s with the onset (a = mu g) ``gap`` [s] before the sample at 0.1 s."""
    mu, dt = 0.2, 0.01
    c = mu * G / (0.1 - gap)
    k = np.arange(41)
    record = bd.Record(np.where(k <= 20, c * k * dt, c * (40 - k) * dt), dt)
    block = bd.SlidingBlock(mu=mu, g=G)
    ref = exact_cache(("ramp", gap), block, record, None)
    assert ref.events[0].t == pytest.approx(0.1 - gap, abs=1e-15)
    assert_agrees(bd.simulate(block, record, backend=backend, rtol=1e-10), ref)


# ---- traps measured on scikit-sundae 1.2.0 ----------------------------------------

@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap1_reused_objects_give_the_same_answer(backend):
    """scikit-sundae never clears its root history: solving twice with the same objects
    must give identical events (without the reset every root after the first reports
    a stale history and the run raises)."""
    block, motion, t_end = SEED_CASES["ex3b"]
    solver = make_backend(backend)
    first = solver.solve(block, motion, bd.backends.Horizon(t_end))
    second = solver.solve(block, motion, bd.backends.Horizon(t_end))
    assert len(first.events) >= 4
    assert first.events == second.events
    assert first.displacement == second.displacement


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap2_stops_in_both_directions(backend, exact_cache):
    """Every guard leaves its mode crossing zero downwards: stops of slip+ and of slip-
    are both found (two-way sliding, Example 2)."""
    block, motion, t_end = SEED_CASES["ex2"]
    sol = bd.simulate(block, motion, t_end=t_end, backend=backend)
    stopped = {e.mode_before for e in sol.events if e.mode_before != Mode.STICK}
    assert stopped == {Mode.SLIP_POS, Mode.SLIP_NEG}
    assert_agrees(sol, exact_cache("ex2", block, motion, t_end))


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap3_onset_not_stepped_over_in_stick(backend):
    """In stick the flow is zero and steps grow without bound; the first onset must still
    be at t* = asin(mu g / A) T / (2 pi) (closed form), also with max_step = 1000 s."""
    block, motion = bd.SlidingBlock(mu=0.6, g=G), bd.Harmonic(9.0, 1.0)
    onset = math.asin(0.6 * G / 9.0) / (2 * math.pi)
    sol = bd.simulate(block, motion, t_end=0.3, backend=backend, max_step=1000.0)
    assert sol.events[0].t == pytest.approx(onset, abs=1e-9)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap4_steps_stop_at_every_sample(backend, kobe, exact_cache):
    """A record's acceleration has kinks at its samples: no internal step may straddle
    one. Without the hard stops CVODE's u(t_end) on this record is 2 % off (measured);
    with them it agrees with the exact backend to 1e-7, and every sample is a knot."""
    ref = exact_cache("Kobe_1995_TAK-090", RECORD_BLOCK, kobe, None)
    sol = bd.simulate(RECORD_BLOCK, kobe, backend=backend)
    samples = kobe.times[kobe.times <= sol.t_end]
    assert np.isin(samples, sol.t).all()
    assert_agrees(sol, ref)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap5_restart_on_a_guard_root_fires_nothing(backend):
    """A demand exactly at the threshold (rectangular pulse of mu g): the stick guards
    are exactly zero from the restart on. The block never slides (rest_mode: a demand
    at the threshold that does not move outwards sticks) and no event fires."""
    block = bd.SlidingBlock(mu=0.5, g=G)
    sol = bd.simulate(block, bd.RectangularPulse(0.5 * G, 0.5), t_end=1.0, backend=backend)
    assert sol.events == () and sol.displacement == 0.0


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap5_no_duplicate_event_after_restart(backend, exact_cache):
    """No event repeats right after the restart it caused (Example 2: slip- and slip+
    stops with reversals)."""
    block, motion, t_end = SEED_CASES["ex2"]
    sol = bd.simulate(block, motion, t_end=t_end, backend=backend)
    for a, b in zip(sol.events, sol.events[1:]):
        assert not (b.t - a.t < 1e-6 and (a.mode_before, a.mode_after) == (b.mode_before, b.mode_after))
    assert_agrees(sol, exact_cache("ex2", block, motion, t_end))


@pytest.mark.parametrize("backend", SUNDIALS)
@pytest.mark.parametrize("max_step", [None, 10.0])
def test_trap6_barely_crossing_guard_found(backend, max_step, exact_cache):
    """A = 1.0001 mu g: the demand exceeds mu g for 2 acos(1/1.0001) T / (2 pi) = 4.5 ms at
    every peak, and the block slides a few ms; found even with a large max_step."""
    block, motion = bd.SlidingBlock(mu=0.6, g=G), bd.Harmonic(1.0001 * 0.6 * G, 1.0)
    ref = exact_cache("barely", block, motion, 2.0)
    sol = bd.simulate(block, motion, t_end=2.0, backend=backend, max_step=max_step)
    windows = sol.t_events[1::2] - sol.t_events[0::2]
    assert len(sol.events) == 8
    assert np.all((windows > 2 * math.acos(1 / 1.0001) / (2 * math.pi)) & (windows < 0.01))
    assert_agrees(sol, ref, scale=ref.max_abs_displacement)  # u(t_end) is ~0 by symmetry


def _reversal_at_threshold():
    """f = mu, bias 0, T = 1 s: slip- from the onset sin(w t1) = mu g / A stops exactly
    where the demand reaches -mu g (closed form: A = mu g sqrt(1 + pi²/4))."""
    block = bd.SlidingBlock(mu=0.6)
    return block, bd.Harmonic(0.6 * G * math.sqrt(1 + math.pi**2 / 4), 1.0)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap7_stop_at_the_threshold_reverses_at_once(backend, exact_cache):
    """v returns to zero where the demand crosses the other threshold: one reversal
    event per stop, as the exact backend; chatter count reported as 1."""
    block, motion = _reversal_at_threshold()
    ref = exact_cache("reversal", block, motion, 3.0)
    sol = bd.simulate(block, motion, t_end=3.0, backend=backend)
    assert [e.mode_after for e in ref.events[1:]] == [Mode.SLIP_POS, Mode.SLIP_NEG] * 2 + [Mode.SLIP_POS]
    assert_agrees(sol, ref)
    assert sol.stats["max_events_at_one_instant"] == ref.stats["max_events_at_one_instant"] == 1


def _lobes(depth):
    """a - mu g = 0, +1, 0, -depth, 0, +1, 0 m/s² at t = 0..6 s, mu g = 5 m/s² exactly."""
    return bd.SlidingBlock(mu=0.5, g=10.0), bd.Record(5.0 + np.array([0, 1, 0, -depth, 0, 1, 0.0]), dt=1.0)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap7_tangential_graze_keeps_sliding(backend):
    """f = mu, depth 1: v = -integral(a - mu g) returns to 0 at t = 4 s exactly where a
    reaches mu g and keeps rising (v' = 0 there). The block slides on to rest at
    6.2 s (v(6) = -1 m/s decays at mu g): two events, u = -3.1 m (closed forms). The
    located stop is uncertain by sqrt(2 e / |da/dt|) ~ 1e-5 s here, more than the event
    resolution: without that allowance the run shows a stop and a restart at 4 s."""
    block, motion = _lobes(1.0)
    sol = bd.simulate(block, motion, backend=backend)
    assert [e.mode_after for e in sol.events] == [Mode.SLIP_NEG, Mode.STICK]
    assert sol.events[-1].t == pytest.approx(6.2, abs=1e-9)
    assert sol.displacement == pytest.approx(-3.1, rel=1e-7)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_trap7_stop_before_the_threshold_still_sticks(backend):
    """Depth 1.01: v crosses zero at 4 - sqrt(1 - 0.495/0.505) s, before a is back at
    mu g (closed form): the block sticks until t = 4 s. The graze allowance must not
    swallow this 0.14 s stick."""
    block, motion = _lobes(1.01)
    sol = bd.simulate(block, motion, backend=backend)
    stop = 4.0 - math.sqrt(1.0 - 0.495 / 0.505)
    assert [e.mode_after for e in sol.events] == [Mode.SLIP_NEG, Mode.STICK, Mode.SLIP_NEG,
                                                   Mode.STICK]
    np.testing.assert_allclose(sol.t_events[1:3], [stop, 4.0], atol=1e-9)


@pytest.mark.parametrize("slip_rate, sigma_rate, allow_pos, after_exact, after_tol", [
    (2 * 0.6 * G - 1e-9, -1.0, True, 0, 1),  # other threshold 1e-9 s away: reverse
    (2 * 0.6 * G - 1e-9, -1.0, False, 0, 0),  # ... unless slip+ is not allowed
    (1e-9, 1.0, True, 0, -1),  # same threshold 1e-9 s away (f = mu): graze, keep sliding
    (1e-9, -1.0, True, 0, 0),  # demand turning back: stick
])
def test_stop_mode_within_time_tolerance(slip_rate, sigma_rate, allow_pos, after_exact, after_tol):
    """The model's stop rule for a slip- stop with f = mu = 0.6: sigma = f g - dv/dt.
    A threshold crossed outwards within time_tol counts as at the threshold."""
    args = (-1, slip_rate, sigma_rate, 1.0, 0.6, 0.6, G, True, allow_pos, np)
    assert stop_mode(*args, time_tol=0.0) == after_exact
    assert stop_mode(*args, time_tol=1e-8) == after_tol


def test_trap7_chatter_cap_raises_instead_of_looping():
    """Consecutive events within event_resolution are capped: with a resolution of
    1 s every event of Example 1 counts as one instant."""
    block, motion, _ = SEED_CASES["ex1"]
    with pytest.raises(RuntimeError, match=r"2 events at t = 0\.535\d* s .*chatter"):
        bd.simulate(block, motion, t_end=1.0, backend="cvode", event_resolution=1.0,
                    max_events_at_one_instant=1)


@pytest.mark.parametrize("backend, label", [("cvode", "CVODE"), ("ida", "IDA")])
def test_trap8_solver_failure_names_time_mode_flag(backend, label):
    """max_num_steps = 1 cannot reach the first hard stop: the error names the solver,
    the time [s], the mode and the flag."""
    block, motion, _ = SEED_CASES["ex1"]
    with pytest.raises(SolverError, match=rf"{label} failed at t = [0-9.e-]+ s in mode \w+: flag -1 "):
        bd.simulate(block, motion, t_end=1.0, backend=backend, max_num_steps=1)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_inverting_the_record_flips_u(backend):
    """Mirror symmetry (bias 0): a(t) -> -a(t) gives u -> -u and mirrored events. The
    first sample is beyond -mu g, so the block slides + from t = 0 and reverses at the
    second sample. By hand (f = 0): slip+ under a = -1 + 100 t, v = t - 50 t², back to 0
    at 0.02 s with u = 2/30000 m; slip- under a = 1 m/s² to 0.94 s (v = -0.92 m/s), then
    coasting (a = 0) to 1.5 s: u = 2/30000 - 0.92²/2 - 0.92 * 0.56 = -0.9383333 m (the
    exact backend's answer too, to 3.3e-16 m)."""
    block = bd.SlidingBlock(mu=0.0625, mu_kinetic=0.0)
    record = bd.Record([-1.0] + [1.0] * 47, dt=0.02, units="m/s2")
    sol = bd.simulate(block, record, t_end=1.5, backend=backend)
    inv = bd.simulate(block, record.inverted(), t_end=1.5, backend=backend)
    assert [(e.t, e.mode_after) for e in sol.events] == [(0.0, Mode.SLIP_POS), (pytest.approx(0.02), Mode.SLIP_NEG)]
    assert [(e.t, -e.mode_after) for e in inv.events] == [(e.t, e.mode_after) for e in sol.events]
    assert inv.displacement == pytest.approx(-sol.displacement, rel=1e-12)
    by_hand = 2 / 30000 - 0.92**2 / 2 - 0.92 * 0.56  # [m]
    assert sol.displacement == pytest.approx(by_hand, rel=1e-10)
    assert bd.simulate(block, record, t_end=1.5).displacement == pytest.approx(by_hand, rel=0, abs=3.3e-15)


# ---- horizon, dense output, settings ----------------------------------------------

@pytest.mark.parametrize("backend", SUNDIALS)
def test_never_resting_block_raises(backend):
    """f <= bias: after the pulse the block slides along the bias for ever."""
    block = bd.SlidingBlock(mu=0.3, mu_kinetic=0.1, bias=0.2)
    with pytest.raises(ValueError, match="never comes to rest"):
        bd.simulate(block, bd.RectangularPulse(-5.0, 0.5), backend=backend)


@pytest.mark.parametrize("backend", SUNDIALS)
def test_dense_output_on_a_record(backend, kobe, exact_cache):
    """Cubic Hermite between knots reproduces the exact dense output (u is cubic, v
    quadratic on a sample interval of a record) to 1e-7 m and 1e-6 m/s."""
    ref = exact_cache("Kobe_1995_TAK-090", RECORD_BLOCK, kobe, None)
    sol = bd.simulate(RECORD_BLOCK, kobe, backend=backend)
    t = np.random.default_rng(0).uniform(0.0, min(sol.t_end, ref.t_end), 2000)
    u, v = sol(t)
    u_ref, v_ref = ref(t)
    assert np.max(np.abs(u - u_ref)) < 1e-7
    assert np.max(np.abs(v - v_ref)) < 1e-6


@pytest.mark.parametrize("backend", SUNDIALS)
def test_dense_output_on_a_harmonic(backend, exact_cache):
    """Knots every 1 / (32 w) s on sine pieces: cubic Hermite error <= h^4 max|a''| / 384
    = A / (384 32^4 w^2) = 5.7e-10 m for Example 2; with the solver's ~1e-9 m, within
    3e-9 m of the exact dense output (and 1e-8 m/s in v)."""
    block, motion, t_end = SEED_CASES["ex2"]
    ref = exact_cache("ex2", block, motion, t_end)
    sol = bd.simulate(block, motion, t_end=t_end, backend=backend)
    t = np.linspace(0.0, t_end, 3001)
    assert np.max(np.abs(sol(t)[0] - ref(t)[0])) < 3e-9
    assert np.max(np.abs(sol(t)[1] - ref(t)[1])) < 1e-8


@pytest.mark.parametrize("backend", SUNDIALS)
@pytest.mark.parametrize("field, value", [("rtol", 0.0), ("rtol", 0.5), ("atol", -1.0), ("max_step", 0.0),
                                          ("max_num_steps", 0), ("max_events_at_one_instant", 1.5),
                                          ("event_resolution", -1e-9)])
def test_bad_settings_name_field_and_value(backend, field, value):
    with pytest.raises(ValueError, match=rf"{field}={re.escape(repr(value))}|{field} must"):
        make_backend(backend, **{field: value})


def test_crosscheck_table():
    """The table: one row per backend, the reference first with zero differences,
    units in the headers; unknown options are refused."""
    block, motion, t_end = SEED_CASES["ex3b"]
    table = bd.crosscheck(block, motion, t_end=t_end, rtol=1e-10)
    assert [r["backend"] for r in table.rows] == ["exact", "cvode", "ida", "jax"]
    assert table.row("exact")["max_dt"] == 0.0 and table.row("exact")["rel_du"] == 0.0
    for name in SUNDIALS:
        assert table.row(name)["max_dt"] <= 1e-9 and table.row(name)["rel_du"] <= 1e-7
    text = str(table)
    assert "[m]" in text and "[s]" in text and "cvode" in text
    with pytest.raises(TypeError, match="rtoll"):
        bd.crosscheck(block, motion, t_end=t_end, rtoll=1e-10)


def test_crosscheck_verdict_ok_within_the_bar():
    """Every backend agrees with exact on seed example 3b at the default tolerances; the
    exact reference's rtol is rounding, the others' 1e-10; the table prints the verdict."""
    block, motion, t_end = SEED_CASES["ex3b"]
    table = bd.crosscheck(block, motion, t_end=t_end)
    assert table.agrees and table.disagreements == [] and table.span == t_end
    assert table.row("exact")["rtol"] == _crosscheck.ROUNDING
    assert all(table.row(name)["rtol"] == 1e-10 and table.row(name)["agrees"] for name in ("cvode", "ida", "jax"))
    head, *rows, footer = str(table).splitlines()[:-1]
    assert head.split()[-3:] == ["rtol", "[-]", "verdict"] and all(row.split()[-1] == "ok" for row in rows[1:])
    assert "DISAGREES" in footer and "DISAGREES" not in "".join(rows)


def test_crosscheck_bar_scales_with_rtol():
    """A loose rtol moves the bar with it: CVODE at rtol 1e-4 is ~1e-5 s off, and agrees."""
    table = bd.crosscheck(bd.SlidingBlock(0.3), bd.SinePulse(6.0, 0.5), backends=("exact", "cvode"), rtol=1e-4)
    assert table.row("cvode")["max_dt"] > 1e-6 and table.row("cvode")["rtol"] == 1e-4 and table.agrees


def test_crosscheck_flags_a_disagreement():
    """A loose atol (1e-3 m, m/s) that rtol does not account for: CVODE's stop is ~1e-4 s
    late, beyond 100 rtol x 1 s; the row says DISAGREES, the reference stays ok."""
    table = bd.crosscheck(bd.SlidingBlock(0.3), bd.SinePulse(6.0, 0.5), backends=("exact", "cvode"), atol=1e-3)
    assert not table.agrees and table.disagreements == [table.row("cvode")]
    lines = str(table).splitlines()
    assert lines[2].endswith(" ok") and lines[3].endswith(" DISAGREES")


def _row(backend, max_dt=0.0, rel_du=0.0, rtol=1e-10):
    row = dict(backend=backend, displacement=1.0, n_events=2, t_events=np.array([0.1, 0.5]), max_dt=max_dt,
               rel_du=rel_du, first=0.01, warm=0.01, rtol=rtol)
    return dict(row, agrees=_crosscheck.agrees(row, span=2.0))


def test_verdict_of_hand_made_rows():
    """The bars at rtol 1e-10 and a 2 s span: 100 rtol x 2 s = 2e-8 s, 1e4 rtol = 1e-6;
    on a bar agrees, beyond it (or other events: inf) disagrees."""
    bar_dt, bar_du = _crosscheck.TIME_BAR * 1e-10 * 2.0, _crosscheck.DISPLACEMENT_BAR * 1e-10
    assert (bar_dt, bar_du) == pytest.approx((2e-8, 1e-6), rel=1e-12)
    assert _row("on", bar_dt, bar_du)["agrees"]
    late, off, other = _row("late", 1.01 * bar_dt), _row("off", rel_du=1.01 * bar_du), _row("other", np.inf)
    assert not (late["agrees"] or off["agrees"] or other["agrees"])
    assert _row("loose", 1.01 * bar_dt, rtol=1e-8)["agrees"]  # a looser rtol, a wider bar
    table = bd.core.CrossCheck(rows=[_row("ref", rtol=_crosscheck.ROUNDING), late], reference="ref", span=2.0)
    assert not table.agrees and table.disagreements == [late]
    lines = str(table).splitlines()
    assert lines[2].split()[-1] == "ok" and lines[3].split()[-1] == "DISAGREES"
    assert "max |dt| [s] > 100 rtol × 2 s or rel |du| [-] > 10000 rtol" in lines[-1]
