"""Overturning spectra, the rest/slide/rock map and fragility of the free-standing block.

References: Housner's (1963) rectangular-pulse criterion for the linearised block (a pulse
of the rectangle's area overturns exactly above 1 / (1 - exp(-p t_d)) in units of g
alpha), the free block's energy past alpha, CVODE against the compiled closed form, and
the onset rules of rest (mu g_e, g_e b/h)."""

import math

import pytest

import blockdae as bd
from blockdae import rocking
from conftest import load_sample_record

G = bd.STANDARD_GRAVITY


def test_energy_rule_matches_running_to_rest():
    """Deciding overturning at the pulse's end by the free block's energy gives what the
    run until rest gives (overturned or at rest), on both sides of Housner's threshold."""
    block = bd.RockingBlock(b=0.25, h=1.5, mu=0.8, linearised=True)
    t_d = 0.4
    threshold = 1.0 / (1.0 - math.exp(-block.frequency * t_d))
    for ratio in (0.999 * threshold, 1.001 * threshold, 1.2 * threshold):
        pulse = bd.RectangularPulse(-ratio * G * block.alpha, t_d)
        until_rest = bd.simulate(block, pulse, backend="exact")
        assert rocking.overturns(block, pulse, backend="exact") == until_rest.overturned == (ratio > threshold)


def test_spectrum_threshold_is_a_threshold():
    """At each frequency the amplitude found overturns the block and 0.1 % less does not;
    the compiled closed form and CVODE (the linearised block) find it within 1e-3."""
    block = bd.RockingBlock(b=0.2, h=1.0, mu=0.6, linearised=True)
    spectrum = rocking.overturning_spectrum(block, [1.0, 3.0], "sine", backend="exact", rtol=1e-6)
    for ratio, amplitude in zip(spectrum.frequency_ratio, spectrum.amplitude):
        period = 2 * math.pi / (ratio * block.frequency)
        unit = G * block.alpha  # the linearised block's threshold
        assert rocking.overturns(block, rocking.pulse("sine", amplitude * unit, period), backend="exact")
        assert not rocking.overturns(block, rocking.pulse("sine", 0.999 * amplitude * unit, period), backend="exact")
    cvode = rocking.overturning_amplitude(block, "sine", 3.0, backend="cvode", rtol=1e-6)
    assert cvode == pytest.approx(spectrum.amplitude[1], rel=1e-3)
    assert 1.0 < spectrum.amplitude[0] < spectrum.amplitude[1]
    assert list(spectrum.to_dataframe().columns) == ["frequency_ratio", "amplitude_over_threshold", "amplitude_g"]


def test_rest_slide_rock_map():
    """Below min(mu, b/h) it rests; above it slides where mu < b/h, else rocks; and the
    model starts the same way under a pulse just above its threshold."""
    regime = rocking.motion_regime([0.1, 0.1, 0.5, 0.5], 0.25, [0.09, 0.11, 0.24, 0.26])
    assert regime.tolist() == ["rest", "slide", "rest", "rock"]
    named = rocking.motion_regime(mu=[0.1, 0.5, 0.5], b_over_h=0.25, demand=[0.3, 0.2, 0.3])  # as the docs call it
    assert named.tolist() == ["slide", "rest", "rock"]
    for mu, expected in ((0.1, "slide"), (0.5, "uplift")):
        block = bd.RockingBlock(b=0.25, h=1.0, mu=mu)
        sol = bd.simulate(block, bd.SinePulse(1.05 * min(mu, 0.25) * G, 0.5), t_end=0.5, backend="cvode")
        assert sol.events[0].kind == expected


def test_fragility_counts_what_overturns():
    """P(overturn) at each PGA is the fraction of records whose scaled run overturns."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    short = bd.Record(kobe.acceleration_samples[:800], kobe.dt, name="Kobe TAK-090, 0-8 s", units="m/s2")
    block = bd.RockingBlock(b=0.2, h=1.0, mu=0.6, linearised=True)
    fragility = rocking.overturning_fragility(block, [short, short.scaled(-1.0)], [0.1, 1.5], backend="exact")
    assert fragility.probability[0] == 0.0 and fragility.probability[1] > 0.0
    for i, motion in enumerate((short, short.scaled(-1.0))):
        scaled = motion.scaled(1.5 * G / motion.peak_acceleration)
        assert fragility.overturned[i, 1] == rocking.overturns(block, scaled, backend="exact")


def test_overturns_keeps_the_pivot_without_a_warning():
    """What spectra and fragility run keeps Housner's pivot: a rectangular pulse at 1.2
    times Housner's threshold makes the pivot slip and lift before the block overturns,
    which bd.simulate lists on its solution and overturns (run to the end of the same pulse
    held 2 s) passes through silently; strict still stops there; a backend that does not
    run the block is refused by name."""
    import warnings

    block = bd.rocking.FreeStandingBlock(b=0.25, h=1.5, mu=0.8, linearised=True, contact="housner")
    pulse = bd.RectangularPulse(-1.2 * G * block.alpha / (1.0 - math.exp(-block.frequency * 0.4)), 0.4)
    assert {limit.kind for limit in bd.simulate(block, pulse, backend="cvode").contact_events} == \
        {"lift_limit", "slip_limit"}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert rocking.overturns(block, bd.RectangularPulse(pulse.amplitude, 2.0), backend="cvode")
    with pytest.raises(ValueError, match="the contact force leaves its limits"):
        rocking.overturns(block.replace(strict=True), bd.RectangularPulse(pulse.amplitude, 2.0), backend="cvode")
    with pytest.raises(ValueError, match="backend='exact' does not run this RockingBlock"):
        rocking.overturns(block.replace(linearised=False), pulse, backend="exact")
