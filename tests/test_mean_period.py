"""The mean period T_m (Rathje, Abrahamson & Bray 1998). References: sines with whole
periods in the record, whose discrete Fourier transform is one line each (closed form)."""

import numpy as np
import pytest

import blockdae as bd


def _sines(parts, dt=0.01, duration=20.0):
    t = np.arange(int(round(duration / dt))) * dt
    return bd.Record(sum(amp * np.sin(2 * np.pi * f * t) for amp, f in parts), dt, name="sines", units="m/s2")


def test_one_sine_has_its_own_period():
    assert bd.motions.mean_period(_sines([(2.0, 2.0)])) == pytest.approx(0.5, rel=1e-12)


def test_two_sines_weigh_their_periods_by_squared_amplitude():
    # T_m = (A1²/f1 + A2²/f2) / (A1² + A2²) for lines at f1, f2
    amps, freqs = np.array([1.0, 3.0]), np.array([0.5, 5.0])
    expected = np.sum(amps**2 / freqs) / np.sum(amps**2)
    assert bd.motions.mean_period(_sines(zip(amps, freqs))) == pytest.approx(expected, rel=1e-12)


def test_content_outside_the_band_is_left_out():
    record = _sines([(1.0, 2.0), (5.0, 0.1), (5.0, 30.0)])  # 0.1 Hz and 30 Hz lie outside 0.25-20 Hz
    assert bd.motions.mean_period(record) == pytest.approx(0.5, rel=1e-12)
    assert bd.motions.mean_period(record, band=(0.05, 40.0)) > 0.5


def test_a_sample_record_lies_between_the_band_periods(sample_records):
    for record in sample_records[:3]:
        assert 1 / 20.0 < bd.motions.mean_period(record) < 1 / 0.25


@pytest.mark.parametrize("band", [(5.0, 1.0), (0.0, 20.0), (1.0,), (1.0, np.nan)])
def test_a_bad_band_names_itself(band):
    with pytest.raises(ValueError, match="band"):
        bd.motions.mean_period(_sines([(1.0, 2.0)]), band=band)


def test_a_band_between_two_fourier_frequencies_is_refused():
    with pytest.raises(ValueError, match="holds no Fourier frequency"):  # 20 s: frequencies 0.05 Hz apart
        bd.motions.mean_period(_sines([(1.0, 2.0)]), band=(1.01, 1.04))


def test_a_record_at_rest_is_refused():
    with pytest.raises(ValueError, match="zero Fourier amplitude"):
        bd.motions.mean_period(bd.Record(np.zeros(100), 0.01, units="m/s2"))


def test_an_analytic_excitation_is_refused():
    with pytest.raises(TypeError, match="sampled record"):
        bd.motions.mean_period(bd.Harmonic(1.0, 2.0))
