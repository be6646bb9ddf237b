"""The finite harmonic (Harmonic(..., cycles=n)).

References: the closed forms of seed 000 (Harmonic: a = A sin wt, v = -(A/w) cos wt,
x = -(A/w²) sin wt), the unending harmonic, and the CVODE backend for the sliding.
"""

import numpy as np
import pytest

import blockdae as bd


# --- the finite harmonic -------------------------------------------------------------------

@pytest.mark.parametrize("cycles", [0.5, 1, 2.25])
def test_finite_harmonic_is_the_unending_one_until_it_ends(cycles):
    A, T = 3.0, 0.7
    finite, unending = bd.Harmonic(A, T, cycles=cycles), bd.Harmonic(A, T)
    end = cycles * T
    assert finite.duration == end and unending.duration == np.inf
    t = np.linspace(0.0, end, 1001)[:-1]
    np.testing.assert_array_equal(finite.acceleration(t), unending.acceleration(t))
    np.testing.assert_allclose(finite.velocity(t), unending.velocity(t), rtol=0, atol=1e-15)
    np.testing.assert_allclose(finite.displacement(t), unending.displacement(t), rtol=0, atol=1e-15)
    # after n T: a = 0, the base keeps v(nT) = -(A T/2 pi) cos(2 pi n) and moves on linearly
    after = end + np.array([0.0, 0.3, 2.0])
    v_end = -(A * T / (2 * np.pi)) * np.cos(2 * np.pi * cycles)
    x_end = -(A * T**2 / (4 * np.pi**2)) * np.sin(2 * np.pi * cycles)
    assert not np.any(finite.acceleration(after))
    np.testing.assert_allclose(finite.velocity(after), v_end, rtol=0, atol=1e-14)
    np.testing.assert_allclose(finite.displacement(after), x_end + v_end * (after - end), rtol=0, atol=1e-14)


def test_one_sine_wave_of_seed_001():
    """Elms: C_x = A sin(pi t) on 0 <= t <= 2, i.e. Harmonic(A, period=2, cycles=1)."""
    wave = bd.Harmonic(0.4, period=2.0, cycles=1)
    t = np.linspace(0.0, 3.0, 31)
    np.testing.assert_allclose(wave.acceleration(t), np.where(t < 2.0, 0.4 * np.sin(np.pi * t), 0.0),
                               rtol=0, atol=1e-15)
    assert wave.initial_velocity == pytest.approx(-0.4 / np.pi, rel=1e-15)
    np.testing.assert_allclose(wave.velocity(t), np.where(t < 2.0, -0.4 / np.pi * np.cos(np.pi * t), -0.4 / np.pi),
                               rtol=0, atol=1e-15)
    np.testing.assert_array_equal(wave.breakpoints, [0.0, 0.5, 1.5, 2.0])  # ends and extrema


def test_finite_harmonic_keeps_cycles_and_unending_repr_is_unchanged():
    assert repr(bd.Harmonic(3.0, 1.0)) == "Harmonic(amplitude=3.0, period=1.0)"
    assert repr(bd.Harmonic(3.0, 1.0, cycles=2)) == "Harmonic(amplitude=3.0, period=1.0, cycles=2.0)"
    assert bd.Harmonic(3.0, 1.0, cycles=2).scaled(-2.0) == bd.Harmonic(-6.0, 1.0, cycles=2.0)
    assert bd.Harmonic(3.0, 1.0).inverted().cycles is None


@pytest.mark.parametrize("cycles", [0, -1.0, np.nan, np.inf])
def test_cycles_must_be_positive_and_finite(cycles):
    with pytest.raises(ValueError, match=rf"cycles must be a positive finite number \[-\], got {cycles!r}"):
        bd.Harmonic(1.0, 1.0, cycles=cycles)


def test_finite_harmonic_slides_until_rest_on_both_backends():
    """Until rest (no t_end): exact agrees with CVODE, and at t = 2 s with the unending harmonic."""
    block, motion = bd.SlidingBlock(mu=0.2, g=9.81), bd.Harmonic(3.0, 1.0, cycles=2)
    exact = bd.simulate(block, motion)
    cvode = bd.simulate(block, motion, backend="cvode")
    assert exact.t_events[-1] > 2.0  # the last slip ends after the shaking
    assert exact.displacement == pytest.approx(cvode.displacement, abs=1e-8)
    np.testing.assert_allclose(exact.t_events, cvode.t_events, rtol=0, atol=1e-8)
    assert exact.events[-1].mode_after == bd.Mode.STICK and exact.t_end == exact.t_events[-1]
    unending = bd.simulate(block, bd.Harmonic(3.0, 1.0), t_end=2.0)
    assert exact(2.0)[0] == pytest.approx(unending.displacement, abs=1e-14)
