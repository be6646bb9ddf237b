"""One free-standing block, two contacts: ``FreeStandingBlock(..., contact="complete")`` (the
default: its pivot may slip and lift) and ``contact="housner"`` (Housner's block, a
RockingBlock of the same arguments). Where Housner's assumption breaks the solution lists
it, located (no warning), and there the complete block's run has its event."""

import copy
import pickle
import warnings

import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import ContactLimit, FreeStandingBlock, RockingBlock

G = bd.STANDARD_GRAVITY


def test_the_contact_option_chooses_the_model():
    complete = FreeStandingBlock(0.2, 1.0, 0.6, 0.5)
    assert type(complete) is FreeStandingBlock and complete.contact == "complete" and complete.mu_kinetic == 0.5
    housner = FreeStandingBlock(0.2, 1.0, 0.6, 0.5, contact="housner", restitution=0.8, linearised=True)
    assert repr(housner) == repr(RockingBlock(b=0.2, h=1.0, mu=0.6, mu_kinetic=0.5, restitution=0.8, linearised=True))
    assert type(housner) is RockingBlock and housner.contact == "housner"
    for block in (complete, housner):  # copies and pickles keep the model
        assert repr(copy.copy(block)) == repr(pickle.loads(pickle.dumps(block))) == repr(block)


def test_bad_contact_and_housners_options_on_the_complete_block_are_refused_by_name():
    with pytest.raises(ValueError, match="contact='coulomb' must be 'complete'"):
        FreeStandingBlock(b=0.2, h=1.0, mu=0.6, contact="coulomb")
    with pytest.raises(ValueError, match=r"linearised, restitution: an option of Housner's block only"):
        FreeStandingBlock(b=0.2, h=1.0, mu=0.6, restitution=0.8, linearised=True)
    with pytest.raises(ValueError, match=r"mu_kinetic=0.7 must be in \[0, mu=0.6\]"):
        FreeStandingBlock(b=0.2, h=1.0, mu=0.6, mu_kinetic=0.7, contact="housner")


def test_replace_moves_a_block_between_its_contacts():
    housner = FreeStandingBlock(b=0.2, h=1.0, mu=0.6, theta0=0.05, contact="housner")
    complete = housner.replace(contact="complete", mu=0.7)
    assert type(complete) is FreeStandingBlock and (complete.b, complete.mu, complete.theta0) == (0.2, 0.7, 0.05)
    assert repr(complete.replace(contact="housner", mu=0.6)) == repr(housner)
    with pytest.raises(ValueError, match="contact='complete': linearised belongs to Housner's block only"):
        housner.replace(linearised=True).replace(contact="complete")


def test_housners_contact_limits_are_the_complete_blocks_slip_located_without_a_warning():
    """A 0.25 m x 1 m block (mu = 0.3) under a half-sine of 0.6 g: Housner's block (CVODE at
    rtol 1e-12 and its compiled engine) lists where |F| first reaches mu N, at 0.11130204747
    s, without a warning; the complete block's first event after the uplift is its slip, at
    that time (8e-12 s apart as measured: the two runs integrate the same rocking until
    then). The complete block with mu = 1.3 never slips and gives Housner's event list, where
    Housner's contact holds."""
    pulse = bd.SinePulse(-0.6 * G, 0.4)
    housner = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, contact="housner")
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        runs = [bd.simulate(housner, pulse, t_end=3.0, backend="cvode", rtol=1e-12), bd.simulate(housner, pulse,
                                                                                                   t_end=3.0)]
    complete = bd.simulate(housner.replace(contact="complete"), pulse, t_end=3.0, rtol=1e-12)
    assert [e.kind for e in complete.events[:2]] == ["uplift", "slip"]
    for run in runs:
        first = run.contact_events[0]
        assert isinstance(first, ContactLimit) and first.kind == "slip_limit" and not run.contact_holds
        assert abs(first.t - complete.events[1].t) < 1e-10
        assert abs(abs(first.force) - 0.3 * first.normal) < 1e-9 * first.normal
    assert {limit.kind for limit in runs[0].contact_events} == {"slip_limit", "lift_limit"}
    assert str(first).startswith(f"at t = {first.t:.9f} s the contact force leaves its limits (|F| >= mu N")

    held = [bd.simulate(FreeStandingBlock(b=0.25, h=1.0, mu=1.3, contact=contact), bd.SinePulse(-0.4 * G, 0.4),
                        t_end=3.0, backend="cvode", rtol=1e-12) for contact in ("housner", "complete")]
    assert held[0].contact_holds
    assert [e.kind for e in held[1].events] == [e.kind for e in held[0].events]
    np.testing.assert_allclose([e.t for e in held[1].events], [e.t for e in held[0].events], rtol=0, atol=1e-9)


def test_strict_housner_raises_where_the_limit_is_listed():
    pulse = bd.SinePulse(-0.6 * G, 0.4)
    housner = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, contact="housner")
    first = bd.simulate(housner, pulse, t_end=3.0).contact_events[0]
    with pytest.raises(ValueError, match="strict=True stops here") as error:
        bd.simulate(housner.replace(strict=True), pulse, t_end=3.0)
    assert abs(float(str(error.value).split("at t = ")[1].split(" s")[0]) - first.t) < 1e-8


def test_the_contact_warning_is_retired():
    assert not hasattr(bd.rocking, "ContactWarning")
    assert "ContactLimit" in bd.rocking.__all__ and "FreeStandingBlock" in bd.__all__
