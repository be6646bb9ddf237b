"""Newmark's conventions: positive downslope displacement, both polarities, k_y helpers."""

import numpy as np
import pytest

import blockdae as bd

G = bd.STANDARD_GRAVITY


def rectangular_pulse_downslope(a, t0, ky, g=G):
    """Closed form for one rectangular pulse a [m/s²] of t0 [s] on a one-way block of
    yield acceleration ky [g]: D = (a t0² / 2) (a / (ky g) - 1) (seed 000, the
    rectangular pulse; Newmark 1965)."""
    return 0.5 * a * t0**2 * (a / (ky * g) - 1.0) if a > ky * g else 0.0


def test_rectangular_pulse_normal_and_inverse_polarity():
    pulse = bd.RectangularPulse(0.4 * G, 0.5)
    result = bd.newmark(pulse, ky=0.1)
    assert result.normal == pytest.approx(rectangular_pulse_downslope(0.4 * G, 0.5, 0.1), rel=1e-14)
    assert result.normal > 0 and result.inverse == 0.0 and str(result.inverse) == "0.0"
    assert result.maximum == result.normal and result.mean == pytest.approx(result.normal / 2, rel=1e-15)


def test_batch_over_ky_matches_the_signed_block_on_both_polarities(kobe):
    """D is -u of SlidingBlock(mu=ky, direction="negative") on the record and on its inverse."""
    ky = np.array([0.05, 0.1, 0.2])
    result = bd.newmark(kobe, ky)
    for i, k in enumerate(ky):
        block = bd.SlidingBlock(mu=k, direction="negative")
        assert result.normal[i] == pytest.approx(-bd.simulate(block, kobe).displacement, rel=1e-12)
        assert result.inverse[i] == pytest.approx(-bd.simulate(block, kobe.inverted()).displacement, rel=1e-12)
    assert np.all(np.diff(result.normal) < 0)  # a stronger slope slides less
    table = result.to_dataframe()
    assert list(table.columns) == ["ky_g", "normal_m", "inverse_m", "mean_m", "max_m"]
    np.testing.assert_array_equal(table["max_m"], np.maximum(result.normal, result.inverse))
    only = bd.newmark(kobe, 0.1, polarity="inverse")
    assert only.normal is None and only.maximum == pytest.approx(result.inverse[1], rel=1e-12)


def test_yield_acceleration_from_factor_of_safety():
    """Jibson (1993): k_y = (FS - 1) sin(alpha); FS 1.5 at 30 degrees gives 0.25 g."""
    assert bd.yield_acceleration(1.5, 30.0) == pytest.approx(0.25, rel=1e-15)
    np.testing.assert_allclose(bd.yield_acceleration([1.0, 2.0], 30.0), [0.0, 0.5], rtol=1e-15)
    with pytest.raises(ValueError, match=r"factor_of_safety=0\.9 must be >= 1"):
        bd.yield_acceleration(0.9, 30.0)
    with pytest.raises(ValueError, match=r"thrust_angle=95\.0"):
        bd.yield_acceleration(1.2, 95.0)


def test_block_on_incline_yields_at_the_jibson_acceleration():
    """On a 20 degree slope with a 35 degree friction angle, FS = tan 35 / tan 20 and the
    block slides downslope under an upslope base pulse exactly as Newmark's block of
    k_y = (FS - 1) sin 20 under the downslope pulse (same equation of motion)."""
    block = bd.SlidingBlock.on_incline(slope_angle=20.0, friction_angle=35.0)
    fs = np.tan(np.radians(35.0)) / np.tan(np.radians(20.0))
    ky = bd.yield_acceleration(fs, 20.0)
    assert block.mu - block.bias == pytest.approx(ky, rel=1e-14)
    a = 2.5 * ky * G
    sol = bd.simulate(block, bd.RectangularPulse(-a, 0.4))
    assert [e.mode_after for e in sol.events] == [bd.Mode.SLIP_POS, bd.Mode.STICK]
    assert sol.displacement == pytest.approx(rectangular_pulse_downslope(a, 0.4, ky), rel=1e-12)
    held = bd.simulate(block, bd.RectangularPulse(-0.999 * ky * G, 0.4))
    assert held.events == ()


def test_pga_scales_the_record_to_a_peak_in_g(kobe):
    """newmark(rec, ky, pga=0.3) is newmark on the record scaled to a peak of 0.3 g; with
    pga_rounding="slammer" the record's own peak is first rounded to 0.001 g (SLAMMER)."""
    ky = np.array([0.05, 0.1])
    scaled = bd.newmark(kobe, ky, pga=0.3)
    direct = bd.newmark(kobe.scaled(0.3 * G / kobe.peak_acceleration), ky)
    np.testing.assert_array_equal(scaled.normal, direct.normal)
    np.testing.assert_array_equal(scaled.inverse, direct.inverse)
    assert np.all(scaled.normal > 0)
    own = round(kobe.peak_acceleration / G, 3)
    assert own != kobe.peak_acceleration / G  # the rounding changes the factor here
    slammer = bd.newmark(kobe, ky, pga=0.3, pga_rounding="slammer")
    np.testing.assert_array_equal(slammer.normal, bd.newmark(kobe.scaled(0.3 / own), ky).normal)
    assert not np.array_equal(slammer.normal, scaled.normal)
    with pytest.raises(TypeError, match=r"target_pga=0\.3 is called pga here: the target peak ground "
                                        r"acceleration \[g\], newmark\(motion, ky, pga=\.\.\.\)"):
        bd.newmark(kobe, 0.1, target_pga=0.3)
    with pytest.raises(ValueError, match=r"pga=9\.81 g is implausible .*looks like m/s² \(9\.81 m/s² = 1 g\)"):
        bd.newmark(kobe, 0.1, pga=9.81)


def test_ky_in_m_s2_is_refused_and_ky_above_the_peak_warns():
    """ky = 9.81 (m/s² meant as 1 g) under a 0.4 g pulse is refused; ky = 0.5 g >= PGA 0.4 g
    warns that D = 0 (and D is 0); ky = 1.5 g under a 2 g pulse slides, no warning."""
    pulse = bd.RectangularPulse(0.4 * G, 0.5)
    with pytest.raises(ValueError, match=r"ky=9\.81 g is above 1 g and the motion's peak \(0\.4 g\): it looks "
                                         r"like m/s² \(9\.81 m/s² = 1 g\); give ky in g"):
        bd.newmark(pulse, ky=[0.1, 9.81])
    with pytest.warns(bd.UnitsWarning, match=r"ky=0\.4, 0\.5 g >= PGA = 0\.4 g: the block does not slide, D = 0 m"):
        result = bd.newmark(pulse, ky=[0.1, 0.4, 0.5])
    assert result.maximum[0] > 0 and result.maximum[1] == result.maximum[2] == 0.0
    strong = bd.newmark(bd.RectangularPulse(2.0 * G, 0.5), ky=1.5, polarity="normal")
    assert strong.normal == pytest.approx(rectangular_pulse_downslope(2.0 * G, 0.5, 1.5), rel=1e-14)


@pytest.mark.parametrize("kwargs, message", [
    ({"ky": 0.0}, r"ky=0\.0 must be a positive yield acceleration \[g\]"),
    ({"ky": 0.1, "polarity": "up"}, r"polarity must be one of"),
])
def test_bad_newmark_input_names_the_field(kwargs, message):
    with pytest.raises(ValueError, match=message):
        bd.newmark(bd.RectangularPulse(3.0, 0.5), **kwargs)


def test_incline_steeper_than_friction_angle_is_an_error():
    with pytest.raises(ValueError, match=r"slope_angle=40\.0 must be below friction_angle=35\.0"):
        bd.SlidingBlock.on_incline(40.0, 35.0)
