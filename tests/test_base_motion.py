"""Three-component base motion (BaseMotion) and the finite harmonic (Harmonic(..., cycles=n)).

References: each component's own pieces and .acceleration/.velocity (an independent
partition of the same closed forms), the closed forms of seed 000 (Harmonic: a = A sin wt,
v = -(A/w) cos wt, x = -(A/w²) sin wt; sine pulse: Eq. 18), trapezoid sums for records,
and the CVODE backend for the finite harmonic's sliding.
"""

import numpy as np
import pytest

import blockdae as bd
from blockdae.sliding import Mode
from blockdae.excitation.pieces import accel, evaluate

RNG = np.random.default_rng(6)
LONG = bd.Record(RNG.normal(0.0, 2.0, 301), 0.01, "long")  # 3 s
SHORT = bd.Record(RNG.normal(0.0, 2.0, 151), 0.01, "short")  # 1.5 s

MIXES = {
    # T/4 + k T/2 = 0.01 + 0.02 k falls on the record's samples up to rounding
    "unending harmonic, pulse, record": bd.BaseMotion(bd.Harmonic(2.0, 0.04), bd.SinePulse(1.5, 0.33), LONG),
    "records of different lengths, finite harmonic": bd.BaseMotion(LONG, SHORT, bd.Harmonic(1.0, 0.3, cycles=2.5)),
    "record, missing y, triangle": bd.BaseMotion(SHORT, None, bd.TriangularPulse(-0.7, 2.1)),
}


def _assert_reproduces(motion, t_end):
    pieces = motion.aligned_pieces(t_end)
    t0, h = pieces[0].t0, pieces[0].h
    for p in pieces:
        np.testing.assert_array_equal(p.t0, t0)
        np.testing.assert_array_equal(p.h, h)
    assert t0[0] == 0.0 and t0[-1] + h[-1] == pytest.approx(t_end, rel=1e-15) and np.all(h > 0)
    inside = np.concatenate([np.linspace(0.0, t_end, 4001)[:-1], t0, t0 + 0.5 * h])
    for p, c in zip(pieces, motion.components):
        # monotone on every piece: values in order from one end value to the other
        tau = h[:, None] * np.linspace(0.0, 1.0, 9)
        a = accel(p.p0[:, None], p.p1[:, None], p.s[:, None], p.w[:, None], p.phi[:, None], tau)
        ends = a[:, [0, -1]]
        assert np.all(a >= ends.min(axis=1, keepdims=True) - 1e-12)
        assert np.all(a <= ends.max(axis=1, keepdims=True) + 1e-12)
        assert np.all(np.diff(a, axis=1) * np.sign(ends[:, 1:] - ends[:, :1]) >= -1e-12)
        a, _, v, x = evaluate(p, inside, v0=0.0 if c is None else c.initial_velocity)
        if c is None:
            assert not np.any(a) and not np.any(v) and not np.any(x)
            continue
        np.testing.assert_allclose(a, c.acceleration(inside), rtol=0, atol=1e-12)  # peaks ~ 6 m/s²
        np.testing.assert_allclose(v, c.velocity(inside), rtol=0, atol=1e-12)
        np.testing.assert_allclose(x, c.displacement(inside), rtol=0, atol=1e-12)
    return pieces


@pytest.mark.parametrize("mix", MIXES)
@pytest.mark.parametrize("t_end", [0.8, 2.345, 3.0])
def test_aligned_pieces_reproduce_every_component(mix, t_end):
    _assert_reproduces(MIXES[mix], t_end)


@pytest.mark.parametrize("mix", ["records of different lengths, finite harmonic", "record, missing y, triangle"])
def test_aligned_pieces_beyond_the_duration(mix):
    """Past its end each component is zero and its base velocity constant, as the component says."""
    motion = MIXES[mix]
    t_end = motion.duration + 1.7
    pieces = _assert_reproduces(motion, t_end)
    after = np.linspace(motion.duration, t_end, 50)
    for p, c in zip(pieces, motion.components):
        if c is not None:
            a, _, v, _ = evaluate(p, after, v0=c.initial_velocity)
            assert not np.any(a)
            np.testing.assert_allclose(v, c.velocity(motion.duration), rtol=0, atol=1e-13)


def test_records_of_different_lengths_end_separately():
    """y has 3 samples (ends at 1 s), x has 5 (ends at 2 s): trapezoid sums give v."""
    motion = bd.BaseMotion.from_samples([0.0, 1.0, 2.0, -1.0, 0.0], [0.0, 4.0, 0.0], dt=0.5, name="r")
    assert motion.duration == 2.0 and motion.z is None
    assert (motion.x.name, motion.y.name) == ("r x", "r y")
    t = np.array([0.25, 0.75, 1.5, 2.5])
    np.testing.assert_allclose(motion.acceleration(t), [[0.5, 1.5, -1.0, 0.0], [2.0, 2.0, 0.0, 0.0], [0, 0, 0, 0]])
    # v_y(1.5) = 0.5 (0 + 4)/2 + 0.5 (4 + 0)/2 = 2; v_x(2.5) = 0.5 (0.5 + 1.5 + 0.5 - 0.5) = 1
    assert motion.velocity(1.5)[1] == pytest.approx(2.0, rel=1e-14)
    assert motion.velocity(2.5)[0] == pytest.approx(1.0, rel=1e-14)
    px, py, pz = motion.aligned_pieces(2.0)
    np.testing.assert_array_equal(px.t0, [0.0, 0.5, 1.0, 1.5])
    np.testing.assert_array_equal(py.p0[2:], [0.0, 0.0])  # y is zero after its last sample
    np.testing.assert_array_equal(py.p1[2:], [0.0, 0.0])


def test_no_sliver_pieces_where_breakpoints_coincide_up_to_rounding():
    """The harmonic's extrema 0.01 + 0.02 k are the record's samples k dt up to rounding:
    the common partition is the record's grid, no pieces of 1e-17 s."""
    motion = MIXES["unending harmonic, pulse, record"]
    harmonic_only = bd.BaseMotion(bd.Harmonic(2.0, 0.04))
    px = motion.aligned_pieces(3.0)[0]
    assert harmonic_only.aligned_pieces(3.0)[0].h.size == 151  # 0, 0.01, 0.03, ..., 2.99
    # the record's 300 steps, one of them cut at the pulse's middle, 0.165 s (its end, 0.33 s, is a sample)
    assert px.h.size == 301 and px.h.min() == pytest.approx(0.005, rel=1e-9)


def test_values_match_closed_forms_with_shape_3_by_t():
    A, T, P, t0 = 2.0, 0.8, 1.5, 0.6
    motion = bd.BaseMotion(bd.Harmonic(A, T), None, bd.SinePulse(P, t0))
    t = np.array([[0.1, 0.37], [0.55, 0.9]])
    w, wp = 2 * np.pi / T, np.pi / t0
    inside = t < t0
    a_z = np.where(inside, P * np.sin(wp * t), 0.0)
    v_z = P / wp * (1 - np.cos(wp * np.minimum(t, t0)))  # seed Eq. 18
    x_z = np.where(inside, P / wp * (t - np.sin(wp * t) / wp), P / wp * t0 + 2 * P / wp * (t - t0))
    assert motion.acceleration(t).shape == (3, 2, 2) and motion.acceleration(0.3).shape == (3,)
    np.testing.assert_allclose(motion.acceleration(t), [A * np.sin(w * t), 0 * t, a_z], rtol=0, atol=1e-14)
    np.testing.assert_allclose(motion.velocity(t), [-(A / w) * np.cos(w * t), 0 * t, v_z], rtol=0, atol=1e-14)
    np.testing.assert_allclose(motion.displacement(t), [-(A / w**2) * np.sin(w * t), 0 * t, x_z], rtol=0,
                               atol=1e-14)
    assert motion.initial_velocity == (pytest.approx(-A * T / (2 * np.pi), rel=1e-15), 0.0, 0.0)
    assert motion.peak_acceleration == (A, 0.0, P)


def test_scaling_inverting_and_scaling_components():
    motion = bd.BaseMotion(bd.Harmonic(2.0, 0.5), None, LONG)
    t = np.linspace(0.0, 3.5, 71)
    a = motion.acceleration(t)
    np.testing.assert_allclose(motion.scaled(2.5).acceleration(t), 2.5 * a, rtol=1e-15)
    np.testing.assert_allclose(motion.inverted().acceleration(t), -a, rtol=1e-15)
    split = motion.scaled_components(x=3.0, y=7.0, z=-0.5)
    assert split.y is None
    np.testing.assert_allclose(split.acceleration(t), a * np.array([[3.0], [0.0], [-0.5]]), rtol=1e-15)
    assert split.peak_acceleration == (6.0, 0.0, pytest.approx(0.5 * LONG.peak_acceleration, rel=1e-15))
    np.testing.assert_array_equal(motion.scaled_components().acceleration(t), a)


def test_breakpoints_are_the_union():
    motion = bd.BaseMotion(bd.Record([0.0, 1.0, 0.0], 0.5, units="m/s2"), bd.TriangularPulse(1.0, 0.8),
                           bd.Harmonic(1.0, 1.0))
    np.testing.assert_array_equal(motion.breakpoints, [0.0, 0.4, 0.5, 0.8, 1.0])
    assert motion.duration == np.inf


def test_repr_names_the_components():
    text = repr(bd.BaseMotion(bd.Harmonic(1.0, 2.0, cycles=1), z=bd.Record([0.0, 1.0], 0.01, "up", units="m/s2")))
    assert text.startswith("BaseMotion(x=Harmonic(amplitude=1.0, period=2.0, cycles=1.0), y=None, z=Record(name='up'")


def test_records_with_different_steps_raise():
    with pytest.raises(ValueError, match=r"components x \('a'\) and z \('c'\) are Records with different dt "
                                         r"\(x: dt=0.01 s, z: dt=0.02 s\); resample them to one sample step first"):
        bd.BaseMotion(bd.Record([0.0, 1.0], 0.01, "a", units="m/s2"), bd.Harmonic(1.0, 0.7),
                      bd.Record([0.0, 1.0], 0.02, "c", units="m/s2"))
    with pytest.raises(ValueError, match=r"components x and y are Records with different dt"):
        bd.BaseMotion(bd.Record([0.0, 1.0], 0.01, units="m/s2"), bd.Record([0.0, 1.0], 0.005, units="m/s2"))
    # other kinds mix with a record of any step
    motion = bd.BaseMotion(bd.Record([0.0, 1.0], 0.02, units="m/s2"), bd.SinePulse(1.0, 0.3), bd.Harmonic(1.0, 0.7))
    assert motion.duration == np.inf


@pytest.mark.parametrize("make, error, message", [
    (lambda: bd.BaseMotion(None), TypeError, "x must be an excitation .* got NoneType"),
    (lambda: bd.BaseMotion(bd.Harmonic(1.0, 1.0), np.zeros(3)), TypeError, "y must be an excitation .* got ndarray"),
    (lambda: bd.BaseMotion(bd.Harmonic(1.0, 1.0)).aligned_pieces(0.0), ValueError, "t_end must be a positive"),
    (lambda: bd.BaseMotion(bd.Harmonic(1.0, 1.0)).aligned_pieces(np.inf), ValueError, "t_end must be a positive"),
    (lambda: bd.BaseMotion.from_samples([0.0, np.nan], dt=0.01), ValueError, r"sample 1 \(0-based\) is nan"),
    (lambda: bd.BaseMotion.from_samples([0.0, 1.0], dt=0.0), ValueError, "dt must be a positive"),
])
def test_bad_input(make, error, message):
    with pytest.raises(error, match=message):
        make()


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
    assert exact.events[-1].mode_after == Mode.STICK and exact.t_end == exact.t_events[-1]
    unending = bd.simulate(block, bd.Harmonic(3.0, 1.0), t_end=2.0)
    assert exact(2.0)[0] == pytest.approx(unending.displacement, abs=1e-14)
