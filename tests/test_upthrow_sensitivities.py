"""Sensitivities of a spring-supported mass's flights (first liftoff velocity, largest
height, total flight time) by frequency, damping and A, from the JAX twin's replay,
against central differences of the exact backend (closed forms on the generic driver,
independent of the twin) at a relative step of 1e-5."""

import numpy as np
import pytest

import blockdae as bd
from conftest import load_sample_record

G = bd.STANDARD_GRAVITY
WRT = ("frequency", "damping", "A")
QUANTITIES = ("liftoff_velocity", "height", "flight_time")
STEP = 1e-5  # relative


def flight_quantities(mass, motion, t_end):
    """(u' at the first liftoff [m/s], largest flight height [m], total flight time [s])
    from the exact backend's flights (a flight not landed counts to t_end; one still
    rising has no height)."""
    flights = bd.simulate(mass, motion, t_end=t_end).flights
    durations = [(f.landing if np.isfinite(f.landing) else t_end) - f.liftoff for f in flights]
    return np.array([flights[0].liftoff_velocity, np.nanmax([f.height for f in flights]), sum(durations)])


def central_differences(mass, motion, t_end):
    """parameter -> d(quantities)/dp: central differences, second-order one-sided
    (forward) for a damping of 0; "A" scales the motion by 1 +- STEP (d/dA = d/dk g / peak)."""
    q = lambda m, s=1.0: flight_quantities(m, motion.scaled(s), t_end)
    differences = {}
    for name in ("frequency", "damping"):
        value = getattr(mass, name)
        h = STEP * (value if value > 0 else 1.0)
        moved = lambda k: q(mass.replace(**{name: value + k * h}))
        differences[name] = ((moved(1) - moved(-1)) / (2 * h) if value > 0
                             else (4 * moved(1) - moved(2) - 3 * moved(0)) / (2 * h))
    differences["A"] = (q(mass, 1 + STEP) - q(mass, 1 - STEP)) / (2 * STEP) * G / motion.peak_acceleration
    return differences


def assert_match_differences(mass, motion, t_end, rel_max=1e-6):
    derivatives = bd.sensitivities(mass, motion, t_end, wrt=WRT)
    differences = central_differences(mass, motion, t_end)
    assert derivatives.quantities == QUANTITIES and derivatives.parameters == WRT
    for i, quantity in enumerate(QUANTITIES):
        for name in WRT:
            reference = differences[name][i]
            assert abs(derivatives.of(quantity)[name] - reference) <= rel_max * abs(reference), (quantity, name)


def test_sine_train_with_damping():
    """10 Hz, 5 %, 0.5 g at 0.13 s, 3 cycles (three flights). Measured: <= 2.5e-7 (d flight
    time / d frequency, a small sum of larger terms), the rest <= 1.2e-9."""
    assert_match_differences(bd.SpringSupportedMass(10.0, 0.05), bd.Harmonic(0.5 * G, 0.13, cycles=3), 0.39)


@pytest.mark.slow
def test_undamped_sine_train():
    """5 Hz, undamped, 0.4 g at 0.3 s (damping differenced one-sided). Measured <= 7.0e-8."""
    assert_match_differences(bd.SpringSupportedMass(5.0), bd.Harmonic(0.4 * G, 0.3, cycles=3), 0.9)


@pytest.mark.slow
def test_scaled_sample_record():
    """Kobe TAK-090 as vertical motion at 0.5 g, 5 Hz, 5 %, the first 3.2 s (four flights).
    Measured <= 3.4e-8."""
    record = load_sample_record("Kobe_1995_TAK-090")
    assert_match_differences(bd.SpringSupportedMass(5.0, 0.05), record.scaled(0.5 * G / record.peak_acceleration),
                             3.2)


def test_a_flight_still_rising_at_t_end_has_no_height():
    """y'' = -0.55 g, 5 Hz, undamped (17 equal flights): t_end 5 ms after the second
    liftoff. The height is the first flight's, as sol.flights has it (the second has
    none yet), and matches central differences; cut in the first flight, there is none."""
    mass, motion = bd.SpringSupportedMass(5.0), bd.Record(np.full(3, -0.55 * G), dt=0.5)
    lifts = [e.t for e in bd.simulate(mass, motion, t_end=0.5).events if e.kind == "liftoff"]
    assert_match_differences(mass, motion, lifts[1] + 5e-3)
    with pytest.raises(ValueError, match="no flight reaches its top"):
        bd.sensitivities(mass, motion, lifts[0] + 5e-3, of="height")


def test_a_motion_that_never_lifts_off_has_no_liftoff_velocity():
    mass, weak = bd.SpringSupportedMass(10.0), bd.Harmonic(0.2 * G, 0.13, cycles=1)
    with pytest.raises(ValueError, match="never lifts off"):
        bd.sensitivities(mass, weak, 0.2, of="liftoff_velocity")
    assert bd.sensitivities(mass, weak, 0.2, of="flight_time").of("flight_time") == dict.fromkeys(WRT, 0.0)


@pytest.mark.parametrize("kwargs, field", [(dict(wrt=("mu",)), "wrt"), (dict(of=("height", "speed")), "of"),
                                           (dict(backend="exact"), "backend")])
def test_bad_names_are_refused(kwargs, field):
    with pytest.raises(ValueError, match=field):
        bd.sensitivities(bd.SpringSupportedMass(10.0), bd.Harmonic(0.5 * G, 0.13, cycles=1), 0.2, **kwargs)


def test_of_is_refused_for_a_sliding_block():
    with pytest.raises(ValueError, match="of="):
        bd.sensitivities(bd.SlidingBlock(mu=0.2), bd.Harmonic(0.5 * G, 0.5, cycles=1), of="height")
