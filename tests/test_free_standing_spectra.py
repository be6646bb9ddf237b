"""Overturning spectra and fragility of the complete free-standing block
(``overturning_spectrum``/``overturning_fragility`` given a FreeStandingBlock): where
friction holds the pivot (mu large) they are Housner's block's (RockingBlock, whose
sticking impacts the complete block's equal: tests/test_free_standing.py); the decision
after the motion of Housner's block counts an impact that still overturns it."""

import math

import numpy as np
import pytest

import blockdae as bd
from blockdae import rocking
from blockdae.rocking import FreeStandingBlock, RockingBlock
from conftest import load_sample_record

G = bd.STANDARD_GRAVITY
SEARCH = dict(max_factor=4.0, steps=7, rtol=1e-3)


def test_a_sine_spectrum_of_the_complete_block_with_large_friction_is_housners():
    """b/h = 0.2, mu = 1.3 (the pivot holds): the smallest overturning amplitude of a
    one-sine pulse at omega_p / p = 2 is Housner's, to the search's rtol."""
    housner = rocking.overturning_spectrum(RockingBlock(b=0.2, h=1.0, mu=1.3), [2.0], "sine", backend="cvode",
                                           **SEARCH)
    complete = rocking.overturning_spectrum(FreeStandingBlock(b=0.2, h=1.0, mu=1.3), [2.0], "sine", **SEARCH)
    assert 1.0 < housner.amplitude[0] < SEARCH["max_factor"]
    assert complete.amplitude[0] == pytest.approx(housner.amplitude[0], rel=SEARCH["rtol"])
    assert complete.to_dataframe()["amplitude_g"].iloc[0] == complete.amplitude[0] * 0.2


@pytest.mark.slow
def test_cosine_spectra_and_fragility_agree_with_housners_and_slip_lowers_them():
    """One-cosine pulses at omega_p / p = 2 and 4 (mu = 1.3: Housner's amplitudes to the
    search's rtol); a fragility over Kobe TAK-090 (first 8 s, both signs) at 0.3 and 0.6 g:
    the same records overturn."""
    housner = rocking.overturning_spectrum(RockingBlock(b=0.2, h=1.0, mu=1.3), [2.0, 4.0], "cosine",
                                           backend="cvode", **SEARCH)
    complete = rocking.overturning_spectrum(FreeStandingBlock(b=0.2, h=1.0, mu=1.3), [2.0, 4.0], "cosine", **SEARCH)
    assert np.allclose(complete.amplitude, housner.amplitude, rtol=SEARCH["rtol"], atol=0)
    kobe = load_sample_record("Kobe_1995_TAK-090")
    kobe = bd.Record(kobe.acceleration_samples[:800], kobe.dt, name="Kobe TAK-090, 0-8 s", units="m/s2")
    records = [kobe, kobe.scaled(-1.0)]
    fragility = rocking.overturning_fragility(FreeStandingBlock(b=0.2, h=1.0, mu=1.3), records, [0.3, 0.6])
    reference = rocking.overturning_fragility(RockingBlock(b=0.2, h=1.0, mu=1.3), records, [0.3, 0.6],
                                              backend="cvode")
    assert np.array_equal(fragility.overturned, reference.overturned)


def test_housners_block_falling_back_after_the_motion_may_still_overturn():
    """Under a one-cosine pulse of 1.3 g b/h at omega_p / p = 2 Housner's block (b/h = 0.2)
    is falling back toward the base when the pulse ends, strikes, and overturns on its
    other corner (the run until rest); overturns() says so, as the complete block with
    large friction does."""
    block = RockingBlock(b=0.2, h=1.0, mu=1.3)
    motion = rocking.pulse("cosine", 1.3 * G * 0.2, 2 * math.pi / (2.0 * block.frequency))
    at_end = bd.simulate(block, motion, t_end=motion.duration, backend="cvode")
    until_rest = bd.simulate(block, motion, backend="cvode")
    assert abs(int(at_end.mode[-1])) == 3 and until_rest.overturned  # falling in at the end, overturned later
    assert until_rest.events_of("impact")[-1].t > motion.duration
    assert rocking.overturns(block, motion, backend="cvode")
    assert rocking.overturns(FreeStandingBlock(b=0.2, h=1.0, mu=1.3), motion)


def test_a_slide_rock_beyond_alpha_does_not_restart_itself_at_one_instant():
    """b/h = 0.2, mu = 1.3 under a one-sine pulse of 1.2221578 g b/h at omega_p / p = 2 (an
    amplitude the overturning spectrum's bisection tries): at t = 3.368 s the block goes
    ROCK_POS_BEYOND -> SLIDE_ROCK_POS_POS, which restarted itself at that instant until the
    driver's cap ("chatter") while the slide-rock's state was the centroid's; it runs on."""
    block = FreeStandingBlock(b=0.2, h=1.0, mu=1.3)
    motion = rocking.pulse("sine", 1.222157844209278 * G * 0.2, 2 * math.pi / (2.0 * block.frequency))
    assert bd.simulate(block, motion).events[-1].kind in ("overturn", "rest")
