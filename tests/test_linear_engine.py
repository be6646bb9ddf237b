"""The compiled linear engine (issue 21): the spring-supported mass's default exact path
against the Python closed-form path (the reference: closed-form steps on the generic
driver), against closed forms and CVODE; a second linear model on the same engine with
no engine change; bad tables refused; final numbers equal to full runs."""

import math

import numpy as np
import pytest

import blockdae as bd
from blockdae.core._linear_modes import LinearModes
from blockdae.upthrow._modes import UpthrowMode
from conftest import load_sample_record, sample_record_paths

G = 9.80665


def assert_same_run(compiled, python, dt_max=1e-12):
    """The same events (kinds, modes), each within ``dt_max`` [s], the same states at the
    events to 1e-12 relative, and the dense output within 1e-9 m."""
    assert [(e.mode_before, e.mode_after) for e in compiled.events] == \
        [(e.mode_before, e.mode_after) for e in python.events]
    np.testing.assert_allclose(compiled.t_events, python.t_events, rtol=0, atol=dt_max)
    t = np.linspace(0.0, python.t_end, 2001)
    np.testing.assert_allclose(compiled(t)[0], python(t)[0], rtol=0, atol=1e-9)


@pytest.fixture(scope="module")
def kobe_vertical():
    record = load_sample_record("Kobe_1995_TAK-090")
    return record.scaled(0.6 * G / record.peak_acceleration)


@pytest.mark.parametrize("frequency", [5.0, 10.0])
def test_compiled_equals_the_python_path_on_a_record(kobe_vertical, frequency):
    mass = bd.SpringSupportedMass(frequency, 0.05)
    compiled = bd.simulate(mass, kobe_vertical, t_end=15.0)
    python = bd.simulate(mass, kobe_vertical, t_end=15.0, linear="python")
    assert compiled.stats["n_knots"] > 0 and "n_restarts" in python.stats  # two different paths
    assert_same_run(compiled, python)


@pytest.mark.slow
@pytest.mark.parametrize("path", sample_record_paths(), ids=lambda p: p.stem)
def test_compiled_equals_the_python_path_on_every_sample_record(path):
    record = bd.read_record(path, units="g")
    motion = record.scaled(0.6 * G / record.peak_acceleration)
    for frequency in (5.0, 10.0):
        mass = bd.SpringSupportedMass(frequency, 0.05)
        t_end = min(record.duration, 15.0)
        assert_same_run(bd.simulate(mass, motion, t_end=t_end), bd.simulate(mass, motion, t_end=t_end, linear="python"))


def test_long_undamped_bouncing_matches_the_closed_form():
    """y'' = -0.55 g held for 3.5 s, 5 Hz, undamped: the step response u = (c / w²)(1 -
    cos w t) (c = 0.55 g) lifts off where u = u0 = g / w² (closed form); then every
    flight is the same ballistic arc and every contact arc the same (17 bounces): the
    liftoff times are equally spaced, the first one exact to 1e-12 s."""
    mass = bd.SpringSupportedMass(5.0)
    sol = bd.simulate(mass, bd.Record(np.full(8, -0.55 * G), dt=0.5, units="m/s2"), t_end=3.5)
    python = bd.simulate(mass, bd.Record(np.full(8, -0.55 * G), dt=0.5, units="m/s2"), t_end=3.5, linear="python")
    assert_same_run(sol, python)
    w, c = mass.omega, 0.55 * G
    first = math.acos(1 - (G / w**2) * w**2 / c) / w
    liftoffs = np.array([e.t for e in sol.events_of("liftoff")])
    assert len(liftoffs) >= 16 and abs(liftoffs[0] - first) <= 1e-12
    np.testing.assert_allclose(np.diff(liftoffs), np.diff(liftoffs)[0], rtol=0, atol=1e-11)


def test_a_grazing_touch_and_events_at_samples():
    """A touch of u0 with u' = 0 (y'' = -g/2, 5 Hz, undamped: u = (g / 2 w²)(1 - cos w t)
    reaches u0 at w t = pi, 3 pi, ...) is no liftoff, also when the touch falls on a
    record sample (dt = the touch's time / 2)."""
    mass = bd.SpringSupportedMass(5.0)
    touch = math.pi / mass.omega
    for motion in (bd.RectangularPulse(-G / 2, 10.0), bd.Record(np.full(13, -G / 2), dt=touch / 2, units="m/s2")):
        sol = bd.simulate(mass, motion, t_end=0.55)
        assert sol.events == ()
        expected = G / (2 * mass.omega**2) * (1 - math.cos(mass.omega * 0.55))
        assert sol.u[-1] == pytest.approx(expected, rel=1e-12, abs=1e-15)


def test_the_compiled_engine_agrees_with_cvode(kobe_vertical):
    """CVODE at rtol 1e-12 as the reference: events within 1e-10 s (measured 8.4e-12 s;
    CVODE's own error, against CVODE at rtol 1e-13: 5.9e-12 s; at rtol 1e-10 it was
    3.7e-10 s off, too close to a bar of 1e-9 s)."""
    mass = bd.SpringSupportedMass(5.0, 0.05)
    compiled = bd.simulate(mass, kobe_vertical, t_end=15.0)
    cvode = bd.simulate(mass, kobe_vertical, t_end=15.0, backend="cvode", rtol=1e-12)
    assert_same_run(compiled, cvode, dt_max=1e-10)


class BilinearOscillator(bd.core.contract.LinearModesModel):
    """A second model on the engine, unknown to it: an oscillator whose stiffness is k_pos
    for u > 0 and k_neg for u < 0 (modes POS, NEG; guards u and -u); its tables are the
    contract's, from its linear flows and affine guards."""

    import enum as _enum

    class Modes(_enum.IntEnum):
        POS = 0
        NEG = 1

    state_names = ("u", "u_rate")
    modes = Modes
    initial_mode = Modes.POS
    engines = {"exact": "linear"}
    default_backend = "exact"

    def __init__(self, k_pos, k_neg, zeta):
        self.k_pos, self.k_neg, self.zeta = k_pos, k_neg, zeta

    def linear_flow(self, mode):
        k = self.k_pos if mode == self.Modes.POS else self.k_neg
        return k, 2 * self.zeta * math.sqrt(k), 0.0

    def affine_guards(self, mode):
        return ((1.0, 0.0, 1e-3),) if mode == self.Modes.POS else ((-1.0, 0.0, -1e-3),)

    def flow(self, mode, t, y, excitation, xp=np):
        k, c, b = self.linear_flow(mode)
        return xp.stack([y[1], b - k * y[0] - c * y[1] - excitation.acceleration(t)])

    def guards(self, mode, t, y, excitation, xp=np):
        alpha, beta, gamma = self.affine_guards(mode)[0]
        return xp.stack([alpha * y[0] + beta * y[1] + gamma])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        return self.Modes.POS

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        return self.Modes.NEG if mode == self.Modes.POS else self.Modes.POS

    def is_static(self, mode):
        return False

    def at_rest(self, mode, y):
        return False

    def rest_state(self, y):
        return np.array([y[0], 0.0])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        return y

    def turn_rate(self, mode, t, y, excitation, xp=np):
        return None

    def guard_rates(self, mode, guard_index, t, y, excitation):
        alpha, beta, _ = self.affine_guards(mode)[guard_index]
        accel = float(self.flow(mode, t, y, excitation)[1])
        return alpha * y[1] + beta * accel, alpha * accel

    def output_step(self):
        return 1.0 / (32 * math.sqrt(max(self.k_pos, self.k_neg)))

    def speed(self, y):
        return abs(float(y[1]))

    def time_to_rest(self, mode, y):
        raise ValueError("give t_end [s]")


def test_a_second_linear_model_runs_on_the_same_engine(kobe_vertical):
    """With no engine change: compiled equals the Python path (1e-12 s) and CVODE at rtol
    1e-10 (1e-8 s; measured 9.3e-10 s)."""
    model = BilinearOscillator(k_pos=(2 * np.pi * 2) ** 2, k_neg=(2 * np.pi * 6) ** 2, zeta=0.05)
    motion = kobe_vertical.scaled(0.2)
    compiled = bd.simulate(model, motion, t_end=10.0)
    assert len(compiled.events) > 10
    assert_same_run(compiled, bd.simulate(model, motion, t_end=10.0, linear="python"))
    cvode = bd.simulate(model, motion, t_end=10.0, backend="cvode", rtol=1e-10)
    np.testing.assert_allclose(compiled.t_events, cvode.t_events, rtol=0, atol=1e-8)


def test_chatter_is_capped_and_reported():
    """Two modes whose guards are both u' (each left at once where u' = 0 and u'' < 0):
    at rest under a(t) > 0 they switch forever at t = 0; the engine stops as the Python
    path does."""
    flows = np.zeros(2)
    guards = np.array([[[0.0, 1.0, 0.0]], [[0.0, 1.0, 0.0]]])
    resets = np.tile([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], (2, 1, 1, 1))
    tables = LinearModes(flows, flows, flows, guards, np.array([[1], [0]]), resets, 0)

    class Switching(BilinearOscillator):
        def linear_modes(self):
            return tables

    with pytest.raises(RuntimeError, match="chatter"):
        bd.simulate(Switching(0.0, 0.0, 0.0), bd.Record([1.0, 1.0], dt=0.1, units="m/s2"), t_end=0.1)


@pytest.mark.parametrize("change, match", [
    (dict(stiffness=[1.0, np.nan, 0.0]), r"LinearModes.stiffness must be finite"),
    (dict(guards=np.zeros((3, 2, 4))), r"LinearModes.guards must have shape \(3, 2, 3\)"),
    (dict(next_mode=np.full((3, 2), 3)), r"LinearModes.next_mode must be \(3, 2\) integers in \[0, 3\)"),
    (dict(damping=[100.0, 0.0, 0.0]), r"mode 0: .*damping ratio .* has no closed form here"),
    (dict(initial_mode=5), r"LinearModes.initial_mode must be an integer in \[0, 3\)"),
])
def test_bad_tables_are_refused_naming_the_field(change, match):
    base = bd.SpringSupportedMass(5.0, 0.05).linear_modes()
    fields = {f: getattr(base, f) for f in ("stiffness", "damping", "offset", "guards", "next_mode", "resets",
                                             "initial_mode")}
    with pytest.raises(ValueError, match=match):
        LinearModes(**(fields | change))


def test_final_numbers_equal_full_runs(kobe_vertical):
    """simulate_linear_final over masses × scales equals each full run's final state,
    event count, first liftoff and highest top."""
    masses = [bd.SpringSupportedMass(5.0, 0.05), bd.SpringSupportedMass(8.0, 0.1)]
    scales = [0.8, 1.0]
    table = bd.solvers.simulate_linear_final(masses, {"kobe": kobe_vertical}, 15.0, scales)
    assert len(table) == 4 and list(table.scale) == [0.8, 1.0, 0.8, 1.0]
    for row in table.itertuples():
        sol = bd.simulate(masses[row.model], kobe_vertical.scaled(row.scale), t_end=15.0)
        assert (row.u_m, row.u_rate_m_s) == pytest.approx((sol.u[-1], sol.u_rate[-1]), rel=1e-12, abs=1e-15)
        assert row.n_events == len(sol.events) and row.mode == UpthrowMode(sol.mode[-1]).name
        if sol.events:
            assert row.t_first_event_s == pytest.approx(sol.events[0].t, abs=1e-12)
            tops = [e.u for e in sol.events]
            assert row.max_u_at_events_m == pytest.approx(max(tops), rel=1e-12)


def test_final_numbers_refuse_other_models_and_sine_motions():
    with pytest.raises(ValueError, match="models on the linear engine"):
        bd.solvers.simulate_linear_final([bd.SlidingBlock(0.2)], [bd.Record([0.0, 1.0], 0.1, units="m/s2")], 0.1)
    with pytest.raises(ValueError, match="has sine pieces"):
        bd.solvers.simulate_linear_final([bd.SpringSupportedMass(5.0)], [bd.Harmonic(1.0, 0.2)], 0.5)
