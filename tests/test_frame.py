"""The uniform shear frame (seed 002, Fig. 3) and the absolute accelerations of its floors.

References, each independent of the code under test:
- the closed form of the uniform shear building (n storeys, mass m, stiffness k):
  ω_j = 2√(k/m) sin((2j - 1)π / (2(2n + 1))), φ_j(i) = sin((2j - 1) i π / (2n + 1));
- the closed-form step response of a damped oscillator, summed over those modes;
- the closed form of each mode under a record (linear between samples) summed over the
  modes, in mpmath at the samples (tests/closed_forms.py);
- the exact response spectrum (``bd.motions.response_spectrum``) of a one-storey frame.
"""

import numpy as np
import pytest

import blockdae as bd
from closed_forms import oscillator_samples
from conftest import load_sample_record


def closed_form(n, k_over_m):
    """(ω [rad/s] shape (n,), φ shape (n floors, n modes)) of the uniform shear building."""
    j = np.arange(1, n + 1)
    omega = 2.0 * np.sqrt(k_over_m) * np.sin((2 * j - 1) * np.pi / (2 * (2 * n + 1)))
    phi = np.sin(np.outer(j, 2 * j - 1) * np.pi / (2 * n + 1))
    return omega, phi


def modal_weights(phi):
    """φ_ij Γ_j with Γ_j = φ_jᵀ 1 / φ_jᵀ φ_j (uniform mass), shape (n floors, n modes)."""
    return phi * (phi.sum(axis=0) / np.einsum("ij,ij->j", phi, phi))


@pytest.mark.parametrize("n", [1, 2, 5, 12])
def test_periods_and_mode_shapes_match_the_closed_form(n):
    frame = bd.ShearFrame(storeys=n, period=0.3, damping=0.05)
    omega, phi = closed_form(n, frame.stiffness_ratio)
    assert frame.periods[0] == pytest.approx(0.3, rel=1e-14)
    assert omega[0] == pytest.approx(2 * np.pi / 0.3, rel=1e-14)  # k/m gives T_1 by the closed form too
    np.testing.assert_allclose(frame.omegas, omega, rtol=1e-13)
    np.testing.assert_allclose(frame.periods, 2 * np.pi / omega, rtol=1e-13)
    unit = phi / np.linalg.norm(phi, axis=0) * np.sign(phi[-1])
    np.testing.assert_allclose(frame.mode_shapes, unit, rtol=0, atol=1e-13)
    np.testing.assert_allclose(frame.participation * frame.mode_shapes, modal_weights(phi), rtol=0, atol=1e-13)
    np.testing.assert_allclose((frame.mode_shapes * frame.participation).sum(axis=1), 1.0, rtol=1e-13)


def step_floor_accelerations(n, k_over_m, zeta, a0, t, t_off):
    """Floor accelerations [m/s²], shape (n, len(t)), under a_g = a0 on [0, t_off), 0 after:
    the step response of each mode, D = -(a0/ω²)[1 - e^(-ζωt)(cos ω_d t + ζ/√(1-ζ²) sin ω_d t)],
    D' = -(a0/ω_d) e^(-ζωt) sin ω_d t, minus the same step started at t_off."""
    omega, phi = closed_form(n, k_over_m)

    def absolute(s):  # -2ζω D' - ω² D of each mode, shape (n modes, len(s))
        s = np.maximum(s, 0.0)[None, :]
        w = omega[:, None]
        wd = w * np.sqrt(1 - zeta**2)
        e = np.exp(-zeta * w * s)
        d = -(a0 / w**2) * (1 - e * (np.cos(wd * s) + zeta / np.sqrt(1 - zeta**2) * np.sin(wd * s)))
        dv = -(a0 / wd) * e * np.sin(wd * s)
        return np.where(s > 0, -2 * zeta * w * dv - w**2 * d, 0.0)

    return modal_weights(phi) @ (absolute(t) - absolute(t - t_off))


@pytest.mark.parametrize("refine", [1, 3])
def test_floor_accelerations_under_a_step_match_the_closed_form(refine):
    """A constant record 2 m/s² for 1 s, then the free vibration to 2.5 s: every sample of
    every floor equals the modal step response (to 1e-13 of the peak; measured 4e-15)."""
    frame = bd.ShearFrame(storeys=4, period=0.25, damping=0.07)
    record = bd.Record(np.full(101, 2.0), dt=0.01, name="step")
    floors = frame.floor_motions(record, refine=refine, t_end=2.5)
    assert [f.name for f in floors] == [f"step floor {i}" for i in range(1, 5)]
    assert all(f.dt == pytest.approx(0.01 / refine, rel=1e-15) and f.duration == pytest.approx(2.5) for f in floors)
    t = floors[0].times
    expected = step_floor_accelerations(4, frame.stiffness_ratio, 0.07, 2.0, t, 1.0)
    got = np.array([f.acceleration_samples for f in floors])
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-13 * np.abs(expected).max())


def modal_floor_accelerations(frame, record):
    """Absolute floor accelerations [m/s²] at the samples, shape (n, samples): each
    closed-form mode q_j'' + 2ζω_j q_j' + ω_j² q_j = -a_g by the oscillator's closed form on
    each sample interval (states in mpmath, tests/closed_forms.py), floor i the sum over
    modes of φ_ij Γ_j (-2ζω_j q_j' - ω_j² q_j)."""
    omega, phi = closed_form(frame.storeys, frame.stiffness_ratio)
    absolute = []
    for w in omega:
        q, q_rate = oscillator_samples(record.acceleration_samples, record.dt, w, frame.damping).T
        absolute.append(-2 * frame.damping * w * q_rate - w**2 * q)
    return modal_weights(phi) @ np.array(absolute)


def test_floor_accelerations_match_the_modal_closed_form():
    """Northridge PAC-175 (1000 samples) through the 5-storey frame of T_1 = 0.3 s: every
    floor at every sample within 1e-13 of its peak of the modal closed form (measured
    1.4e-14; DOP853 and CVODE at rtol 1e-12 on the whole frame, restarted at every sample,
    the references before it, are 2.0e-11 and 3.4e-10 off), on the grid dt (m = 1) and on
    dt/4 (every 4th sample)."""
    record = load_sample_record("Northridge_1994_PAC-175")
    frame = bd.ShearFrame(storeys=5, period=0.3, damping=0.05)
    reference = modal_floor_accelerations(frame, record)
    scale = np.abs(reference).max(axis=1)
    for refine in (1, 4):
        got = np.array([f.acceleration_samples[::refine] for f in frame.floor_motions(record, refine=refine)])
        assert np.all(np.abs(got - reference).max(axis=1) <= 1e-13 * scale)


def test_one_storey_frame_peak_approaches_the_spectral_acceleration(kobe):
    """A one-storey frame's floor is the oscillator's absolute acceleration: its sampled
    peak never exceeds Sa (located exactly between samples by the spectrum) and falls
    short by at most (ωh)²/4 on the grid h = dt/m (twice the (ωh)²/8 of a pure sinusoid
    of frequency ω sampled within h/2 of its crest)."""
    frame = bd.ShearFrame(storeys=1, period=0.4, damping=0.05)
    sa = bd.motions.response_spectrum(kobe, 0.4, 0.05).sa
    for m in (1, 4, 16, 64):
        gap = 1 - frame.floor_motions(kobe, refine=m)[0].peak_acceleration / sa
        assert -1e-14 <= gap <= 0.25 * (frame.omegas[0] * kobe.dt / m) ** 2


def test_sliding_on_a_floor_converges_as_the_grid_is_refined(kobe):
    """The error of the refined-grid representation, measured on a block's largest relative
    displacement on the roof (scale fixed from the m = 64 motion): falls as m⁻² and is
    below 1e-3 relative from m = 4 (benchmarks/floor_refinement.py: all records)."""
    roof = bd.ShearFrame(storeys=5, period=0.3, damping=0.05).floor(5)
    scale = bd.STANDARD_GRAVITY / roof.motion(kobe, refine=64).peak_acceleration
    block = bd.SlidingBlock(mu=np.array([0.1, 0.2, 0.3]))
    exact = bd.simulate(block, roof.motion(kobe, refine=64).scaled(scale)).max_abs_displacement
    err = np.array([np.abs(bd.simulate(block, roof.motion(kobe, refine=m).scaled(scale)).max_abs_displacement
                           / exact - 1) for m in (1, 2, 4, 8)])
    assert np.all(err[2] < 1e-3)
    order = np.log2(err[:-1].max(axis=1) / err[1:].max(axis=1))
    assert np.all(order > 1.5), order


def test_floor_selector_and_spectra_of_ground_and_floors(kobe):
    frame = bd.ShearFrame()
    floors = frame.floor_motions(kobe)
    roof = frame.floor(5)
    assert roof == bd.structures.Floor(frame, 5) and roof.level == 5
    np.testing.assert_array_equal(roof.motion(kobe).acceleration_samples, floors[4].acceleration_samples)
    spectra = bd.motions.response_spectrum([kobe, *floors], periods=[0.3, 1.0], damping=0.05)
    assert spectra.sa.shape == (6, 2) and spectra.names[1] == "Kobe_1995_TAK-090 floor 1"
    assert spectra.sa[5, 0] > spectra.sa[0, 0]  # the roof amplifies at the frame's period


@pytest.mark.parametrize("kwargs, message", [
    ({"storeys": 0}, r"storeys must be an integer >= 1, got 0"),
    ({"storeys": 2.5}, r"storeys must be an integer >= 1, got 2\.5"),
    ({"storeys": True}, r"storeys must be an integer"),
    ({"period": 0.0}, r"period must be a positive finite number \[s\], got 0\.0"),
    ({"period": np.nan}, r"period must be a positive finite number"),
    ({"damping": 1.0}, r"damping must lie in \[0, 1\) \[-\]"),
    ({"damping": -0.01}, r"damping must lie in \[0, 1\)"),
])
def test_bad_frame_names_the_field(kwargs, message):
    with pytest.raises(ValueError, match=message):
        bd.ShearFrame(**kwargs)


def test_bad_floor_and_motion_input(kobe):
    frame = bd.ShearFrame(storeys=3)
    with pytest.raises(ValueError, match=r"level must lie in 1\.\.3 .* got 4"):
        frame.floor(4)
    with pytest.raises(ValueError, match=r"level must lie in 1\.\.3 .* got 0"):
        frame.floor(0)
    with pytest.raises(ValueError, match=r"level must be an integer floor number, got 1\.5"):
        frame.floor(1.5)
    with pytest.raises(TypeError, match=r"frame must be a bd\.ShearFrame"):
        bd.structures.Floor("frame", 1)
    with pytest.raises(ValueError, match=r"refine must be an integer >= 1 .* got 0"):
        frame.floor_motions(kobe, refine=0)
    with pytest.raises(ValueError, match=r"t_end must be a positive finite time \[s\], got -1\.0"):
        frame.floor_motions(kobe, t_end=-1.0)
    with pytest.raises(TypeError, match=r"record must be a bd\.Record .* got Harmonic"):
        frame.floor_motions(bd.Harmonic(1.0, 1.0))
