"""Seed 000 (rigid block on accelerating subsoil), Examples 1-6.

References: closed forms derived from the paper's equations, solved here independently
(brentq on the closed-form relative velocity; the pulses' stops and displacements in
mpmath), and the paper's printed values at the paper's precision.
"""

import mpmath as mp
import numpy as np
import pytest
from scipy.optimize import brentq

import blockdae as bd
from blockdae.sliding import Mode

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
    assert [e.mode_after for e in sol.events] == [Mode.SLIP_NEG, Mode.STICK,
                                                    Mode.SLIP_POS, Mode.STICK]
    np.testing.assert_allclose(sol.t_events, expected, rtol=0, atol=1.1e-15)  # measured 1.1e-16 s
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
    assert all(Mode.STICK not in (e.mode_before, e.mode_after) for e in late)
    times = np.array([e.t for e in late])
    periods = np.diff(times[::2])
    assert abs(periods[-1] - 1.0) < 1e-4 and abs(periods[-1] - 1.0) < abs(periods[0] - 1.0)
    assert sol.events[0].t == pytest.approx(np.arcsin(MUG / 9) / W, abs=1.1e-15)  # static onset; measured 2.8e-17 s


@pytest.mark.parametrize("f", [0.6, 0.4])
def test_example3_bias_ratchets_in_positive_x(f):
    """a0 = 7 m/s², R/Q = 0.3, mu = 0.6: slip- would need a > 0.9 g > 7, so the block only
    slides in +x and u grows every cycle (Figs. 9-10); f = 0.4 drifts faster."""
    block = bd.SlidingBlock(mu=MU, mu_kinetic=f, bias=0.3, g=G)
    sol = bd.simulate(block, bd.Harmonic(7.0, 1.0), t_end=5.0)
    assert {e.mode_after for e in sol.events} <= {Mode.SLIP_POS, Mode.STICK}
    u_cycle = sol(np.arange(6.0))[0]
    assert np.all(np.diff(u_cycle) > 0.2)
    # onset of slip+ at a - 0.3 g = -mu g
    assert sol.events[0].t == pytest.approx(0.5 + np.arcsin(0.3 * G / 7) / W, abs=1.1e-15)  # measured 1.1e-16 s
    if f == 0.4:
        faster = bd.simulate(block.replace(mu_kinetic=0.6), bd.Harmonic(7.0, 1.0), t_end=5.0)
        assert sol.displacement > 2 * faster.displacement


def test_example4_rectangular_pulse_eq14():
    """Eq. 14 with the corrected sign: u = A t0²/2 (1 - A/(mu g)) = -0.5952 m."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.RectangularPulse(9.0, 0.5))
    expected = 9 * 0.5**2 / 2 * (1 - 9 / MUG)
    assert sol.displacement == pytest.approx(expected, rel=2.2e-15)  # measured 0, the bar ten ulps
    assert round(sol.displacement, 4) == -0.5952
    assert sol.events[0].t == 0.0 and sol.events[0].mode_after == Mode.SLIP_NEG
    # stop: v(t0) = (mu g - A) t0 decays at mu g
    assert sol.events[-1].t == pytest.approx(0.5 + (9 - MUG) * 0.5 / MUG, rel=1e-14)


def triangular_slide():
    """(t_on [s], t_off [s], u [m]) of Example 5 in mpmath: the block's v_b = 18 t_on² +
    mu g (t - t_on) against v_s = 18 t² on [0, 0.25], -18 t² + 18 t - 2.25 on [0.25, 0.5]
    (Eqs. 15-17); t_off the root of a quadratic, u the integral of v_b - v_s (polynomials)."""
    with mp.workdps(30):
        mug = mp.mpf(MUG)
        t_on = mug / 36
        a, b, c = -18, 18 - mug, mug * t_on - mp.mpf(2.25) - 18 * t_on**2
        t_off = (-b - mp.sqrt(b**2 - 4 * a * c)) / (2 * a)  # the root in (0.25, 0.5)
        falling = lambda t: -6 * t**3 + 9 * t**2 - mp.mpf(2.25) * t  # an integral of v_s past 0.25
        u = (18 * t_on**2 * (t_off - t_on) + mug * (t_off - t_on) ** 2 / 2
             - 6 * (mp.mpf(0.25) ** 3 - t_on**3) - (falling(t_off) - falling(mp.mpf(0.25))))
        return float(t_on), float(t_off), float(u)


def test_example5_triangular_pulse():
    """Closed form from Eqs. 15-17 (``triangular_slide``): events within 1e-14 s (measured
    5.6e-17), u within 1e-14 relative (measured 2.2e-16; scipy's quad, the reference before
    it, was 2.2e-16 off)."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.TriangularPulse(9.0, 0.5))
    t_on, t_off, u = triangular_slide()
    np.testing.assert_allclose(sol.t_events, [t_on, t_off], rtol=0, atol=1e-14)
    assert sol.displacement == pytest.approx(u, rel=1e-14)
    assert (round(t_on, 4), round(t_off, 4), round(sol.displacement, 4)) == (0.1635, 0.4588, -0.0453)


def sine_slide():
    """(t_on [s], t_off [s], u [m]) of Example 6 in mpmath (Eqs. 18-19): a_s = 9 sin 2 pi t on
    [0, 0.5], v_s = (9/w)(1 - cos wt), constant 18/w after the pulse, so the slide at mu g
    stops at t_off = t_on + (9/w)(1 + cos w t_on) / (mu g); u the integral of mu g (t - t_on)
    - (v_s(t) - v_s(t_on))."""
    with mp.workdps(30):
        mug, w = mp.mpf(MUG), 2 * mp.pi
        t_on = mp.asin(mug / 9) / w
        v_on = 9 / w * (1 - mp.cos(w * t_on))
        t_off = t_on + 9 / w * (1 + mp.cos(w * t_on)) / mug
        half = mp.mpf(0.5)
        base = 9 / w * ((half - t_on) - (mp.sin(w * half) - mp.sin(w * t_on)) / w) + 18 / w * (t_off - half)
        u = mug * (t_off - t_on) ** 2 / 2 - (base - v_on * (t_off - t_on))
        return float(t_on), float(t_off), float(u)


def test_example6_sine_pulse():
    """Eqs. 18-19 (``sine_slide``): sliding outlasts the pulse; events within 1e-14 s
    (measured 1.4e-17), u within 1e-14 relative (measured 2.2e-16; scipy's quad, the
    reference before it, agreed with the closed form to the last bit)."""
    sol = bd.simulate(bd.SlidingBlock(mu=MU, g=G), bd.SinePulse(9.0, 0.5))
    t_on, t_off, u = sine_slide()
    np.testing.assert_allclose(sol.t_events, [t_on, t_off], rtol=0, atol=1e-14)
    assert sol.displacement == pytest.approx(u, rel=1e-14)
    # the paper: t* = 0.1135 s, t** = 0.541 s, u = -0.1332 m (its last digit is rounded up)
    np.testing.assert_allclose([t_on, t_off, sol.displacement], [0.1135, 0.541, -0.1332], atol=1e-4)
