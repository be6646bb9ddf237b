"""Seed 000 (rigid block on accelerating subsoil), Examples 1-6.

References: closed forms derived from the paper's equations, solved here independently
with scipy/numpy (brentq on the closed-form relative velocity, polynomial roots and
quadrature), and the paper's printed values at the paper's precision.
"""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

import blockdae as bd

G = 9.81
MU = 0.6
MUG = MU * G
W = 2 * np.pi  # T = 1 s


def _harmonic_slip_end(t_start, c):
    """Root of the closed-form relative velocity c (t - ts) + (9/w)(cos wt - cos wts)."""
    v_rel = lambda t: c * (t - t_start) + (9 / W) * (np.cos(W * t) - np.cos(W * t_start))
    return brentq(v_rel, t_start + 1e-6, t_start + 1.0, xtol=1e-15, rtol=1e-15)


def test_example1_event_times_exact_and_paper():
    """A = 9 m/s², T = 1 s, mu = f = 0.6: four events per cycle (seed Table 1)."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.Harmonic(9.0, 1.0), t_end=1.1)
    t_onset = np.arcsin(MUG / 9.0) / W  # a_s = mu g
    t_stop = _harmonic_slip_end(t_onset, MUG)
    expected = [t_onset, t_stop, t_onset + 0.5, t_stop + 0.5]  # half-period symmetry
    assert [e.mode_after for e in sol.events] == [bd.Mode.SLIP_NEG, bd.Mode.STICK,
                                                    bd.Mode.SLIP_POS, bd.Mode.STICK]
    np.testing.assert_allclose(sol.t_events, expected, rtol=0, atol=1e-13)
    np.testing.assert_allclose(sol.t_events, [0.113, 0.535, 0.614, 1.035], atol=6e-4)  # paper
    # the paper's text says t* = 0.1125 s; the exact onset is 0.11346 s
    assert abs(sol.events[0].t - 0.11346) < 5e-6 and abs(sol.events[0].t - 0.1125) > 9e-4


def test_example1_block_motion_matches_table1():
    """Table 1, interval AB: v_b = -1.7514 + 5.886 t, so v_rel = v_b - v_s."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.Harmonic(9.0, 1.0), t_end=1.1)
    t = np.linspace(0.12, 0.53, 7)
    v_base = -(9 / W) * np.cos(W * t)
    np.testing.assert_allclose(sol(t)[1], (-1.7514 + 5.886 * t) - v_base, atol=2e-4)
    # BC: the block sticks at u = -0.133 m (Table 1, displacement column)
    assert sol(np.array(0.58))[0] == pytest.approx(-0.133, abs=5e-4)


def test_example2_kinetic_friction_no_common_motion():
    """f = 0.3: after the first cycle the block never moves with the base again and its
    motion settles to a periodic one (the paper's Figs. 7-8)."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, mu_kinetic=0.3, g=G), bd.Harmonic(9.0, 1.0), t_end=8.0)
    late = [e for e in sol.events if e.t > 1.0]
    assert all(bd.Mode.STICK not in (e.mode_before, e.mode_after) for e in late)
    times = np.array([e.t for e in late])
    periods = np.diff(times[::2])
    assert abs(periods[-1] - 1.0) < 1e-4 and abs(periods[-1] - 1.0) < abs(periods[0] - 1.0)
    assert sol.events[0].t == pytest.approx(np.arcsin(MUG / 9) / W, abs=1e-13)  # static onset


@pytest.mark.parametrize("f", [0.6, 0.4])
def test_example3_bias_ratchets_in_positive_x(f):
    """a0 = 7 m/s², R/Q = 0.3, mu = 0.6: slip- would need a > 0.9 g > 7, so the block only
    slides in +x and u grows every cycle (Figs. 9-10); f = 0.4 drifts faster."""
    block = bd.SlidingBlock(mu=MU, mu_kinetic=f, bias=0.3, g=G)
    sol = bd.simulate(block, bd.Harmonic(7.0, 1.0), t_end=5.0)
    assert {e.mode_after for e in sol.events} <= {bd.Mode.SLIP_POS, bd.Mode.STICK}
    u_cycle = sol(np.arange(6.0))[0]
    assert np.all(np.diff(u_cycle) > 0.2)
    # onset of slip+ at a - 0.3 g = -mu g
    assert sol.events[0].t == pytest.approx(0.5 + np.arcsin(0.3 * G / 7) / W, abs=1e-13)
    if f == 0.4:
        faster = bd.simulate(block.replace(mu_kinetic=0.6), bd.Harmonic(7.0, 1.0), t_end=5.0)
        assert sol.displacement > 2 * faster.displacement


def test_example4_rectangular_pulse_eq14():
    """Eq. 14 with the corrected sign: u = A t0²/2 (1 - A/(mu g)) = -0.5952 m."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.RectangularPulse(9.0, 0.5))
    expected = 9 * 0.5**2 / 2 * (1 - 9 / MUG)
    assert sol.displacement == pytest.approx(expected, rel=1e-13)
    assert round(sol.displacement, 4) == -0.5952
    assert sol.events[0].t == 0.0 and sol.events[0].mode_after == bd.Mode.SLIP_NEG
    # stop: v(t0) = (mu g - A) t0 decays at mu g
    assert sol.events[-1].t == pytest.approx(0.5 + (9 - MUG) * 0.5 / MUG, rel=1e-14)


def test_example5_triangular_pulse():
    """Closed form from Eqs. 15-17: v_s = -18t² + 18t - 2.25 on [0.25, 0.5]."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.TriangularPulse(9.0, 0.5))
    t_on = MUG / 36.0
    # block: v_b = 18 t_on² + mu g (t - t_on) meets v_s on the falling half
    roots = np.roots([-18.0, 18.0 - MUG, -2.25 - 18 * t_on**2 + MUG * t_on])
    t_off = roots[(roots > 0.25) & (roots < 0.5)].real[0]
    v_s = lambda t: 18 * t**2 if t < 0.25 else -18 * t**2 + 18 * t - 2.25
    u = quad(lambda t: 18 * t_on**2 + MUG * (t - t_on) - v_s(t), t_on, t_off, points=[0.25],
             epsabs=1e-15, epsrel=1e-14)[0]
    np.testing.assert_allclose(sol.t_events, [t_on, t_off], atol=1e-13)
    assert sol.displacement == pytest.approx(u, rel=1e-11)
    assert (round(t_on, 4), round(t_off, 4), round(sol.displacement, 4)) == (0.1635, 0.4588, -0.0453)


def test_example6_sine_pulse():
    """Eqs. 18-19: a_s = 9 sin 2 pi t on [0, 0.5]; sliding outlasts the pulse."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.SinePulse(9.0, 0.5))
    t_on = np.arcsin(MUG / 9) / W
    v_s = lambda t: 9 / W * (1 - np.cos(W * min(t, 0.5)))
    v_rel = lambda t: MUG * (t - t_on) - (v_s(t) - v_s(t_on))
    t_off = brentq(v_rel, 0.5, 1.0, xtol=1e-15, rtol=1e-15)
    u = quad(v_rel, t_on, t_off, points=[0.5], epsabs=0, epsrel=1e-13)[0]
    np.testing.assert_allclose(sol.t_events, [t_on, t_off], atol=1e-13)
    assert sol.displacement == pytest.approx(u, rel=1e-11)
    # the paper: t* = 0.1135 s, t** = 0.541 s, u = -0.1332 m (its last digit is rounded up)
    np.testing.assert_allclose([t_on, t_off, sol.displacement], [0.1135, 0.541, -0.1332], atol=1e-4)
