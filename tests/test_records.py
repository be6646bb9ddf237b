"""Recorded ground motions: an independent integrator, closed forms and batching."""

import re
import warnings

import numpy as np
import pytest
from conftest import assert_same_events, load_sample_record

import blockdae as bd


def newmark_one_way_fine_steps(record: bd.Record, mu: float, g: float, substeps: int) -> float:
    """Independent one-way Newmark (slides with u decreasing while a > mu g) on steps of
    h = dt/substeps: v by the trapezoid rule (exact for the linear a), u by the trapezoid
    rule on v (second order), onset and stop placed by linear interpolation in a step."""
    h = record.dt / substeps
    t = np.arange((record.acceleration_samples.size - 1) * substeps + 1) * h
    excess = np.interp(t, record.times, record.acceleration_samples) - mu * g  # a - mu g
    excess = np.concatenate([excess, np.full(int(20 / h), -mu * g)])  # a = 0 after the record
    u = v = 0.0
    for k in range(excess.size - 1):
        e0, e1 = excess[k], excess[k + 1]
        if v == 0.0:
            if e1 <= 0.0:
                continue
            s = h * e0 / (e0 - e1) if e0 < 0.0 else 0.0  # onset inside the step
            e0, step = 0.0, h - s
        else:
            step = h
        v_new = v - 0.5 * step * (e0 + e1)
        if v_new >= 0.0:  # stop: v is nearly linear over the step
            step *= v / (v - v_new)
            v_new = 0.0
        u += 0.5 * step * (v + v_new)
        v = v_new
    return u


@pytest.mark.parametrize("stem, mu", [("Northridge_1994_PAC-175", 0.15), ("Kobe_1995_TAK-090", 0.1)])
def test_one_way_newmark_matches_fine_step_integration(stem, mu):
    """At a tenth and a twentieth of the sample step the independent answers converge to
    ours: the dt/20 error is within the dt/10 - dt/20 difference (its own error
    estimate), and their Richardson extrapolation (second order) is closer still."""
    record = load_sample_record(stem)
    g = 9.80665
    exact = bd.simulate(bd.SlidingBlock(mu=mu, g=g, direction="negative"), record).displacement
    u10 = newmark_one_way_fine_steps(record, mu, g, 10)
    u20 = newmark_one_way_fine_steps(record, mu, g, 20)
    own_error = abs(u10 - u20)
    assert abs(exact) > 0.01
    assert abs(u20 - exact) <= own_error
    assert abs((4 * u20 - u10) / 3 - exact) <= 0.2 * own_error


def test_piecewise_linear_records_match_pulse_closed_forms():
    """Record([0, 9, 0], 0.25 s) is the triangular pulse and Record([9, 9], 0.5 s) the
    rectangular one of seed Examples 5 and 4: identical closed-form answers."""
    block = bd.SlidingBlock(mu=0.6, g=9.81)
    tri = bd.simulate(block, bd.Record([0.0, 9.0, 0.0], dt=0.25))
    tri_ref = bd.simulate(block, bd.TriangularPulse(9.0, 0.5))
    np.testing.assert_allclose(tri.t_events, tri_ref.t_events, rtol=1e-15)
    assert tri.displacement == pytest.approx(tri_ref.displacement, rel=1e-14)
    rect = bd.simulate(block, bd.Record([9.0, 9.0], dt=0.5))
    assert rect.displacement == pytest.approx(9 * 0.25 / 2 * (1 - 9 / (0.6 * 9.81)), rel=1e-13)


def test_one_way_agrees_with_pyslammer_within_its_discretisation():
    """pySLAMMER (the peer) integrates at the sample step without locating stops; its
    one-way result lies within a few per cent of ours on Kobe at ky = 0.1."""
    pyslammer = pytest.importorskip("pyslammer")
    record = load_sample_record("Kobe_1995_TAK-090")
    ours = bd.simulate(bd.SlidingBlock(mu=0.1, g=9.80665, direction="negative"), record).displacement
    peer = pyslammer.RigidAnalysis(0.1, pyslammer.load_sample_ground_motion("Kobe_1995_TAK-090.csv"))
    assert -ours == pytest.approx(peer.max_sliding_disp, rel=0.02)


def test_batch_equals_one_by_one():
    """A batch of parameter sets gives, element by element, the scalar answers."""
    record = load_sample_record("Kobe_1995_TAK-090")
    mu = np.array([0.08, 0.1, 0.15, 0.2])
    block = bd.SlidingBlock(mu=mu, mu_kinetic=0.8 * mu, bias=0.02)
    batch = bd.simulate(block, record)
    assert batch.displacement.shape == (4,) and len(batch) == 4
    for i in range(4):
        one = bd.simulate(block.item(i), record)
        assert batch.displacement[i] == pytest.approx(one.displacement, rel=1e-13, abs=1e-15)
        assert batch.max_abs_displacement[i] == pytest.approx(one.max_abs_displacement, rel=1e-13)
        assert batch.n_events[i] == len(one.events)
    np.testing.assert_allclose(batch[2].t_events, bd.simulate(block.item(2), record).t_events)
    # more friction, less sliding
    assert np.all(np.diff(np.abs(batch.max_abs_displacement)) < 0)


@pytest.mark.parametrize("motion", ["record", "harmonic"])
def test_window_changes_speed_never_results(motion):
    """The exact kernel's ``window`` (pieces per search step in slip, and per block of
    the onset search in stick) only changes how far an iteration looks: windows from 1
    to beyond the whole record give the same events. Two-way, f < mu, a bias; a record
    (linear pieces) and a long harmonic (sine pieces) whose stick phases span blocks."""
    if motion == "record":
        excitation, t_end = load_sample_record("Kobe_1995_TAK-090"), None
        block = bd.SlidingBlock(mu=0.15, mu_kinetic=0.12, bias=0.03)
    else:
        excitation, t_end = bd.Harmonic(7.0, 1.0), 40.0
        block = bd.SlidingBlock(mu=0.6, mu_kinetic=0.4, bias=0.3)
    runs = [bd.simulate(block, excitation, t_end=t_end, window=w) for w in (1, 3, 64, 8192)]
    reference = runs[2]
    assert len(reference.events) >= 20
    for sol in runs:
        assert_same_events(sol, reference, 1e-12)
        assert sol.displacement == pytest.approx(reference.displacement, rel=1e-12)


def test_unhashable_excitation_still_runs():
    """The exact backend keeps the kernel input of recent (hashable, immutable)
    excitations; an unhashable user subclass is prepared afresh on every call."""

    class Unhashable(bd.Record):
        __hash__ = None

    samples = load_sample_record("Northridge_1994_PAC-175").acceleration_samples
    record, plain = Unhashable(samples, 0.02), bd.Record(samples, 0.02)
    block = bd.SlidingBlock(mu=0.1, mu_kinetic=0.08)
    assert bd.simulate(block, record).displacement == bd.simulate(block, plain).displacement
    grid = bd.SlidingBlock(mu=np.array([0.1, 0.2]))
    np.testing.assert_array_equal(bd.simulate(grid, record).displacement, bd.simulate(grid, plain).displacement)


def test_start_time_is_kept_by_scaling_and_records_hash_by_identity():
    """``start_time`` [s] labels the first sample on the file's axis: kept by scaled and
    inverted, validated finite, shown in repr; records stay hashable by identity (eq=False)
    as the exact backend's cache needs."""
    record = bd.Record([0.0, 2.0, -1.0], dt=0.5, name="r", start_time=5.0)
    for other in (record.scaled(2.0), record.inverted()):
        assert (other.name, other.start_time) == ("r", 5.0)
    assert "start_time=5 s" in repr(record) and bd.Record([0.0, 1.0], 0.5, units="m/s2").start_time == 0.0
    twin = bd.Record([0.0, 2.0, -1.0], dt=0.5, name="r", start_time=5.0)
    assert record != twin and len({record, twin}) == 2 and hash(record) == hash(record)
    with pytest.raises(ValueError, match="start_time must be finite"):
        bd.Record([0.0, 1.0], 0.5, start_time=float("nan"))


# ---- units of an array -----------------------------------------------------------------

G0 = bd.STANDARD_GRAVITY
IN_G = np.array([0.0, 0.3, -0.2, 0.1, 0.0])  # a 0.3 g record, in g


def test_record_units_convert_to_m_s2():
    """units="g", "cm/s2", "gal", "m/s2" convert the samples to m/s² (g from ``g``)."""
    reference = IN_G * G0
    np.testing.assert_array_equal(bd.Record(IN_G, 0.01, units="g").acceleration_samples, reference)
    np.testing.assert_array_equal(bd.Record(IN_G, 0.01, units="g", g=9.81).acceleration_samples, IN_G * 9.81)
    np.testing.assert_allclose(bd.Record(reference * 100, 0.01, units="cm/s2").acceleration_samples, reference,
                               rtol=1e-15)
    np.testing.assert_allclose(bd.Record(reference * 100, 0.01, units="gal").acceleration_samples, reference,
                               rtol=1e-15)
    np.testing.assert_array_equal(bd.Record(reference, 0.01, units="m/s2").acceleration_samples, reference)
    with pytest.raises(ValueError, match=r"units='ft/s2' is unknown"):
        bd.Record(IN_G, 0.01, units="ft/s2")


def test_arrays_are_m_s2_unless_units_say_otherwise():
    """Numbers from Python are SI: an array without units is m/s², with a warning where its peak
    (at most 2) reads as g too, silently where units= states them; a weak record in cm/s² given
    without units (49 m/s² = 5 g) is refused naming cm/s², and read with units="cm/s2"."""
    with pytest.warns(bd.UnitsWarning, match=r"Record 'r': no units given, .* pass units='g'"):
        np.testing.assert_array_equal(bd.Record(IN_G, 0.01, "r").acceleration_samples, IN_G)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        np.testing.assert_array_equal(bd.Record(IN_G, 0.01, "r", units="m/s2").acceleration_samples, IN_G)
        bd.Record(IN_G, 0.01, units="g")
        bd.Record(np.zeros(3), 0.01)  # no peak, no units to get wrong
    weak_in_cm_s2 = IN_G / 6 * G0 * 100  # a 0.05 g record in cm/s²
    with pytest.raises(ValueError, match=re.escape(
            "Record: peak acceleration 49.03 m/s² = 5 g is implausible (above the largest peaks recorded; plausible: "
            "0.0001 g to 4 g); looks like cm/s² read as m/s²: pass units='cm/s2', or check_peak=False")):
        bd.Record(weak_in_cm_s2, 0.01)
    assert bd.Record(weak_in_cm_s2, 0.01, units="cm/s2").peak_acceleration == pytest.approx(0.05 * G0, rel=1e-14)


@pytest.mark.parametrize("samples, units, message", [
    (IN_G * G0 * 100, None, r"Record: peak acceleration 294\.2 m/s² = 30 g is implausible \(above the largest peaks "
                            r"recorded; plausible: 0\.0001 g to 4 g\); looks like cm/s² read as m/s²: pass "
                            r"units='cm/s2', or check_peak=False"),
    (IN_G * G0 * 100, "g", r"Record: peak acceleration 294\.2 g is implausible .* looks like cm/s² read as g: "
                           r"pass units='cm/s2'"),
    (IN_G / 1000, "m/s2", r"peak acceleration 0\.0003 m/s² = 3\.059e-05 g is implausible .* looks like g read "
                          r"as m/s²: pass units='g'"),
])
def test_implausible_array_peak_is_refused_naming_the_value_and_unit(samples, units, message):
    """An array in cm/s² given as m/s² (peak > 4 g), ..., is an error naming peak and units."""
    with pytest.raises(ValueError, match=message):
        bd.Record(samples, 0.01, units=units)
    assert bd.Record(samples, 0.01, units=units, check_peak=False).acceleration_samples.size == 5


def test_derived_records_are_not_rechecked_and_from_samples_takes_units():
    """scaled/inverted keep m/s² without a warning; BaseMotion.from_samples passes units on (m/s² without)."""
    record = bd.Record(IN_G, 0.01, units="g")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert record.scaled(0.01).peak_acceleration == pytest.approx(0.003 * G0, rel=1e-15)
        motion = bd.BaseMotion.from_samples(IN_G, IN_G, dt=0.01, units="g")
    np.testing.assert_array_equal(motion.x.acceleration_samples, record.acceleration_samples)
    np.testing.assert_array_equal(bd.BaseMotion.from_samples(IN_G, dt=0.01).x.acceleration_samples, IN_G)  # m/s²


def test_resample_is_exact_at_the_new_samples_and_keeps_name_start_and_units():
    """Issue 23 item 4. Independent: a(t) of the old record by hand (linear between samples)."""
    record = bd.Record([0.0, 2.0, -1.0, 3.0, 0.5], 0.02, "r", start_time=1.5, units="g")
    new = bd.excitation.resample(record, 0.015)
    assert (new.name, new.start_time, new.dt) == ("r", 1.5, 0.015)
    assert new.acceleration_samples.size == 6  # t = 0, 0.015, ..., 0.075 <= duration 0.08; the tail is dropped
    g = bd.STANDARD_GRAVITY
    by_hand = g * np.array([0.0, 1.5, 0.5, 0.0, 3.0, 1.125])  # e.g. t = 0.015 s: 3/4 of the way 0 -> 2
    np.testing.assert_allclose(new.acceleration_samples, by_hand, rtol=1e-14, atol=1e-14)
    # a step dividing the old one gives a(t) itself: the same pieces, so the same sliding
    fine = bd.excitation.resample(record, 0.005)
    t = np.linspace(0.0, record.duration, 97)
    np.testing.assert_allclose(fine.acceleration(t), record.acceleration(t), rtol=0, atol=1e-12)
    # between new samples the result is linear in them: the old peak 3 g at t = 0.06 s is cut
    coarse = bd.excitation.resample(record, 0.025)
    np.testing.assert_allclose(coarse.acceleration_samples, g * np.array([0.0, 1.25, 1.0, 1.125]), rtol=1e-14)
    assert coarse.peak_acceleration == pytest.approx(1.25 * g, rel=1e-14)


@pytest.mark.parametrize("dt, message", [(0.0, r"dt must be a finite sample step > 0 \[s\], got 0.0"),
                                         (-0.01, r"got -0.01"), (float("nan"), r"got nan"),
                                         (float("inf"), r"got inf"), ("x", r"got 'x'"),
                                         (1.0, r"dt = 1.0 s leaves fewer than 2 samples of record 'r'")])
def test_resample_refuses_a_bad_step_naming_it(dt, message):
    record = bd.Record([0.0, 2.0, -1.0], 0.02, "r", units="m/s2")
    with pytest.raises(ValueError, match=message):
        bd.excitation.resample(record, dt)


def test_resample_joins_records_of_mixed_steps_into_one_base_motion():
    """The BaseMotion error points to bd.excitation.resample; resampling the motion's Records (not its
    other components) to the finer step makes one motion with the same a(t)."""
    x = bd.Record([0.0, 1.0, 0.0, -1.0, 0.0], 0.01, "x", units="m/s2", check_peak=False)
    y = bd.Record([0.0, 2.0, 0.0], 0.02, "y", units="m/s2", check_peak=False)
    with pytest.raises(ValueError, match=r"blockdae\.excitation\.resample\(record, dt\) on each in Python, --resample DT"):
        bd.BaseMotion(x, y)
    motion = bd.BaseMotion(bd.excitation.resample(x, 0.01), bd.excitation.resample(y, 0.01))
    np.testing.assert_array_equal(motion.y.acceleration_samples, [0.0, 1.0, 2.0, 1.0, 0.0])
    np.testing.assert_array_equal(motion.x.acceleration_samples, x.acceleration_samples)
    coarse = bd.excitation.resample(bd.BaseMotion(x, None, bd.Harmonic(1.0, 2.0)), 0.02)  # a whole motion: its Records
    assert coarse.x.dt == 0.02 and coarse.y is None and isinstance(coarse.z, bd.Harmonic)
    np.testing.assert_array_equal(coarse.x.acceleration_samples, [0.0, 0.0, 0.0])
    with pytest.raises(TypeError, match=r"record must be a Record or a BaseMotion, got list"):
        bd.excitation.resample([0.0, 1.0], 0.01)


def test_record_attributes_say_what_they_hold_and_in_which_unit():
    """Issue 23 item 5: the samples by names with their units; acceleration(t) is a(t)."""
    record = bd.Record([0.0, 0.25, -0.5], 0.02, "r", units="g")
    assert record.acceleration_m_s2 is record.acceleration_samples
    np.testing.assert_allclose(record.acceleration_g, [0.0, 0.25, -0.5], rtol=1e-15)
    np.testing.assert_array_equal(record.sample_times, [0.0, 0.02, 0.04])
    assert record.acceleration(0.01) == pytest.approx(0.125 * bd.STANDARD_GRAVITY, rel=1e-14)
