"""The physics rules of the 1-D block, each pinned by a case with a closed-form answer."""

import numpy as np
import pytest

import blockdae as bd
from blockdae.sliding import Mode

G = 10.0  # makes mu g exact in binary for mu = 0.5


def test_onset_is_strict_at_threshold():
    """stick -> slip- only when a - bias g exceeds mu g; exactly at it the block holds."""
    block = bd.SlidingBlock(mu=0.5, g=G)
    at = bd.simulate(block, bd.RectangularPulse(5.0, 1.0))
    above = bd.simulate(block, bd.RectangularPulse(5.0 * (1 + 1e-9), 1.0))
    assert at.events == () and at.displacement == 0.0
    assert [e.mode_after for e in above.events] == [Mode.SLIP_NEG, Mode.STICK]


def test_bias_shifts_both_thresholds():
    """With bias R/Q the onset is at a - (R/Q) g = +-mu g: here a = -2 m/s² < (0.3-0.5) g."""
    block = bd.SlidingBlock(mu=0.5, bias=0.3, g=G)
    held = bd.simulate(block, bd.RectangularPulse(-1.9, 1.0))
    slides = bd.simulate(block, bd.RectangularPulse(-2.1, 1.0))
    assert held.events == ()
    assert slides.events[0].t == 0.0 and slides.events[0].mode_after == Mode.SLIP_POS


def test_sliding_law_with_bias_and_kinetic_friction():
    """slip-: dv/dt = (bias + f) g - a, so under a constant pulse v = ((b + f) g - A) t."""
    block = bd.SlidingBlock(mu=0.5, mu_kinetic=0.3, bias=0.1, g=G)
    sol = bd.simulate(block, bd.RectangularPulse(8.0, 1.0))
    t = np.linspace(0.0, 1.0, 11)
    u, v = sol(t)
    rate = (0.1 + 0.3) * G - 8.0
    np.testing.assert_allclose(v, rate * t, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(u, 0.5 * rate * t**2, rtol=1e-14, atol=1e-15)
    # after the pulse it decelerates at (b + f) g and stops: v(1) + 4 (t - 1) = 0
    assert sol.events[-1].t == pytest.approx(1.0 - rate / 4.0, rel=1e-14)


def test_stop_reverses_when_demand_exceeds_static_friction():
    """A slip- that stops while a - bias g < -mu g reverses straight into slip+."""
    # a = +8 for 1 s (slip-, v = -3 at t=1), then -8: v returns to 0 at t = 1 + 3/13
    motion = bd.Record([8.0, 8.0, -8.0, -8.0, -8.0], dt=1.0)
    block = bd.SlidingBlock(mu=0.5, g=G)
    sol = bd.simulate(block, motion, t_end=2.5)
    # on [1, 2] a falls linearly from 8 to -8: v' = 5 - a(t) = 5 - 8 + 16 (t - 1)
    tau = np.roots([8.0, -3.0, -3.0]).max()  # v(1 + tau) = -3 - 3 tau + 8 tau² = 0
    transitions = [(e.mode_before, e.mode_after) for e in sol.events]
    assert transitions[:2] == [(Mode.STICK, Mode.SLIP_NEG), (Mode.SLIP_NEG, Mode.SLIP_POS)]
    assert sol.events[1].t == pytest.approx(1.0 + tau, rel=1e-14)


def test_onset_at_time_zero_is_an_event():
    sol = bd.simulate(bd.SlidingBlock(mu=0.5, g=G), bd.RectangularPulse(7.0, 0.2))
    first = sol.events[0]
    assert (first.t, first.mode_before, first.mode_after) == (0.0, Mode.STICK, Mode.SLIP_NEG)


def test_direction_restricts_sliding():
    """Harmonic forcing slides both ways; "negative" keeps u non-increasing, "positive"
    non-decreasing, each never entering the forbidden slip mode."""
    motion = bd.Harmonic(9.0, 1.0)
    for direction, forbidden, sign in (("negative", Mode.SLIP_POS, -1), ("positive", Mode.SLIP_NEG, 1)):
        sol = bd.simulate(bd.SlidingBlock(mu=0.5, g=G, direction=direction), motion, t_end=3.0)
        assert forbidden not in {e.mode_after for e in sol.events}
        u = sol(np.linspace(0, 3, 301))[0]
        assert np.all(sign * np.diff(u) >= -1e-15) and sign * sol.displacement > 0.1


def test_grazing_keeps_sliding_without_events():
    """f = mu: v returns to 0 at t = 4 s exactly where a reaches mu g and keeps rising.
    The block slides on: no stop, no re-onset, no event loop.

    a - mu g = 0, +1, 0, -1, 0, +1, 0 m/s² at t = 0..6 s (mu g = 5 exactly), so
    v = -integral(a - mu g) is 0 at t = 4 s and negative on both sides.
    """
    motion = bd.Record(5.0 + np.array([0.0, 1.0, 0.0, -1.0, 0.0, 1.0, 0.0]), dt=1.0)
    sol = bd.simulate(bd.SlidingBlock(mu=0.5, g=G), motion)
    assert [(e.t, e.mode_after) for e in sol.events][:1] == [(0.0, Mode.SLIP_NEG)]
    assert all(e.t > 6.0 for e in sol.events[1:]) and len(sol.events) == 2
    assert sol.stats["max_events_at_one_instant"] == 1
    # after the excitation, v(6) = -1 decays at mu g: rests at 6.2 s
    assert sol.events[-1].t == pytest.approx(6.2, rel=1e-14)
    # and v(4) = 0 with v < 0 on both sides
    # v(4 -+ 0.1) = -integral of (1 - s) ds over the last/first 0.1 s of the lobes = -0.005
    np.testing.assert_allclose(sol(np.array([3.9, 4.0, 4.1]))[1], [-0.005, 0.0, -0.005], rtol=1e-12, atol=1e-15)


def test_stop_just_before_threshold_sticks_then_slides_again():
    """A slightly deeper negative lobe makes v cross zero before a reaches mu g again:
    the block stops (a < mu g), sticks, and slides again when a reaches mu g at t = 4 s.

    v(3) = -1 + 0.505 and on [3, 4] s, v = -0.495 + 1.01 s - 0.505 s² with s = t - 3,
    zero at s = 1 - sqrt(1 - 0.495/0.505).
    """
    motion = bd.Record(5.0 + np.array([0.0, 1.0, 0.0, -1.01, 0.0, 1.0, 0.0]), dt=1.0)
    sol = bd.simulate(bd.SlidingBlock(mu=0.5, g=G), motion)
    stop = 3.0 + 1.0 - np.sqrt(1.0 - 0.495 / 0.505)
    assert [e.mode_after for e in sol.events] == [Mode.SLIP_NEG, Mode.STICK, Mode.SLIP_NEG,
                                                   Mode.STICK]
    np.testing.assert_allclose(sol.t_events[1:3], [stop, 4.0], rtol=1e-14)


def test_events_at_the_end_of_a_record_and_until_rest():
    """t_end inside a slip ends with v != 0; t_end=None follows the block to rest."""
    motion = bd.RectangularPulse(8.0, 1.0)
    block = bd.SlidingBlock(mu=0.5, g=G)
    cut = bd.simulate(block, motion, t_end=0.5)
    assert cut.t_end == 0.5 and cut.v[-1] == pytest.approx(-1.5, rel=1e-14)
    assert [e.mode_after for e in cut.events] == [Mode.SLIP_NEG]
    full = bd.simulate(block, motion)
    assert full.t_end == pytest.approx(1.6, rel=1e-14) and full.events[-1].mode_after == Mode.STICK
    longer = bd.simulate(block, motion, t_end=3.0)
    assert longer.t_end == 3.0 and longer.displacement == pytest.approx(full.displacement, rel=1e-14)


def test_never_resting_block_is_an_error():
    """f <= |bias| sliding along the bias never stops once the excitation ends."""
    block = bd.SlidingBlock(mu=0.5, mu_kinetic=0.2, bias=0.3, g=G)
    with pytest.raises(ValueError, match="never comes to rest"):
        bd.simulate(block, bd.RectangularPulse(-9.0, 1.0))


def test_unending_excitation_needs_t_end():
    with pytest.raises(ValueError, match="give t_end"):
        bd.simulate(bd.SlidingBlock(mu=0.5), bd.Harmonic(1.0, 1.0))


def test_dense_output_is_consistent_with_knots_and_velocity():
    """u(t) from dense output equals the integral of v(t): 10-point Gauss-Legendre on
    quarters of each interval between knots (v is smooth there), within 1e-13 m (measured
    5.6e-16 m; the trapezoid rule on a grid of 5e-5 s, the reference before it, was
    1.6e-9 m off)."""
    sol = bd.simulate(bd.SlidingBlock(mu=0.3, mu_kinetic=0.2, bias=0.05, g=G), bd.Harmonic(5.0, 0.7), t_end=3.0)
    knots = np.unique(sol.t)
    t = np.unique(np.concatenate([np.linspace(a, b, 5) for a, b in zip(knots[:-1], knots[1:])]))
    x, w = np.polynomial.legendre.leggauss(10)
    half = np.diff(t)[:, None] / 2
    nodes = (t[:-1, None] + half) + half * x
    integral = np.concatenate([[0.0], np.cumsum(half[:, 0] * (sol(nodes.ravel())[1].reshape(nodes.shape) @ w))])
    np.testing.assert_allclose(sol(t)[0], integral, rtol=0, atol=1e-13)
    np.testing.assert_allclose(sol(sol.t)[0], sol.u, atol=1e-13)
    with pytest.raises(ValueError, match="t must lie in"):
        sol(np.array(3.5))


def test_onset_at_start_wins_over_a_later_crossing_in_the_same_piece():
    """a rises from -1 to +1 m/s² over the first sample step, beyond both thresholds
    (mu g = 0.613 m/s²): the block slides + from t = 0 (a < -mu g there), reverses when
    v returns to 0 (f = 0: v = t - 50 t², at t = 0.02 s with u = 2/30000 m), and the
    result mirrors the inverted record (found by the SUNDIALS backends' tests)."""
    block = bd.SlidingBlock(mu=0.0625, mu_kinetic=0.0)
    record = bd.Record([-1.0] + [1.0] * 47, dt=0.02, units="m/s2")
    sol = bd.simulate(block, record, t_end=1.5)
    inv = bd.simulate(block, record.inverted(), t_end=1.5)
    assert [(e.t, e.mode_after) for e in sol.events] == [(0.0, Mode.SLIP_POS), (0.02, Mode.SLIP_NEG)]
    assert sol.events[1].u == pytest.approx(2 / 30000, rel=1e-12)
    assert inv.displacement == pytest.approx(-sol.displacement, rel=1e-14)
    # then slip- under a = 1 to 0.94 s (v = -0.92 m/s) and coasting to 1.5 s
    assert sol.displacement == pytest.approx(2 / 30000 - 0.92**2 / 2 - 0.92 * 0.56, rel=1e-12)


@pytest.mark.parametrize("backend, rtol", [("exact", 1e-13), ("jax", 1e-13), ("cvode", 1e-7), ("ida", 1e-7)])
def test_frictionless_block_stays_where_it_started(backend, rtol):
    """mu = 0: no force on the block, so it keeps the base's initial velocity and
    u(t) = v_b(0) t - x_b(t) (closed form), on every backend; it never rests after the
    excitation, so t_end is required."""
    block = bd.SlidingBlock(mu=0.0)
    motion = bd.Record(3.0 * np.sin(np.linspace(0, 20, 2001)) * np.linspace(1, 0, 2001), 0.01)
    sol = bd.simulate(block, motion, t_end=20.0, backend=backend)
    t = np.linspace(0.0, 20.0, 9)
    exact = motion.velocity(0.0) * t - motion.displacement(t)
    np.testing.assert_allclose(sol(t)[0], exact, rtol=rtol, atol=rtol * np.max(np.abs(exact)))
    with pytest.raises(ValueError, match="never comes to rest"):
        bd.simulate(block, motion, backend=backend)


def test_zero_friction_with_a_bias_names_bias():
    with pytest.raises(ValueError, match=r"bias=0\.1 must satisfy \|bias\| < mu=0\.0"):
        bd.SlidingBlock(mu=0.0, bias=0.1)
