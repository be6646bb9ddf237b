"""The model contract (blockdae.core.contract): a model written in the test, not
subclassing a built-in model, declares its capabilities and the package chooses by them:
its default parameters and their units reach bd.sensitivities and bd.crosscheck, and a
model without turn points whose slide starts at v = 0 runs on the JAX twin."""

import dataclasses
import enum
import math
import warnings

import numpy as np
import pytest

import blockdae as bd
from blockdae.core.contract import SCALAR

G = 9.80665


class SlideMode(enum.IntEnum):
    NEGATIVE = -1
    STICK = 0
    POSITIVE = 1


class FrictionRules:
    """A rigid block on a base accelerating at a(t) [m/s²], Coulomb friction mu [-] (static
    and kinetic alike), written against the contract alone: state (u [m], v [m/s]) relative
    to the base; in a slide dv/dt = -mode mu g - a(t). It declares no turn points
    (``turn_rate`` None)."""

    state_names = ("u", "v")
    modes = SlideMode
    initial_mode = SlideMode.STICK

    def flow(self, mode, t, y, excitation, xp=np):
        a = excitation.acceleration(t)
        dv = -int(mode) * self.mu * self.g - a
        return xp.stack([y[1], dv if mode != SlideMode.STICK else 0.0 * a])

    def guards(self, mode, t, y, excitation, xp=np):
        """Stick: mu g - a -> NEGATIVE, mu g + a -> POSITIVE; a slide: mode v -> stop."""
        if mode == SlideMode.STICK:
            a = excitation.acceleration(t)
            return xp.stack([self.mu * self.g - a, self.mu * self.g + a])
        return xp.stack([int(mode) * y[1]])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        a, rate, limit = excitation.acceleration(t), excitation.acceleration_rate(t), self.mu * self.g
        if a > limit or (a == limit and rate > 0):
            return SlideMode.NEGATIVE
        if a < -limit or (a == -limit and rate < 0):
            return SlideMode.POSITIVE
        return SlideMode.STICK

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        if mode == SlideMode.STICK:
            return SlideMode.NEGATIVE if guard_index == 0 else SlideMode.POSITIVE
        return self.mode_at_rest(t, excitation)

    def is_static(self, mode):
        return mode == SlideMode.STICK

    def at_rest(self, mode, y):
        return mode == SlideMode.STICK or y[1] == 0

    def rest_state(self, y):
        return np.array([y[0], 0.0])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        return y if mode == SlideMode.STICK else xp.stack([y[0], 0.0 * y[1]])

    def turn_rate(self, mode, t, y, excitation, xp=np):
        return None

    def guard_rates(self, mode, guard_index, t, y, excitation):
        rate = excitation.acceleration_rate(t)
        if mode == SlideMode.STICK:
            return (-rate, 0.0) if guard_index == 0 else (rate, 0.0)
        return int(mode) * float(self.flow(mode, t, y, excitation)[1]), -int(mode) * rate

    def contradiction(self, mode, y, velocity_error):
        if mode != SlideMode.STICK and int(mode) * y[1] < -velocity_error:
            return f"v = {y[1]:+.6g} m/s points against the slide"
        return None

    def speed(self, y):
        return abs(float(y[1]))

    def time_to_rest(self, mode, y):
        return 2 * abs(float(y[1])) / (self.mu * self.g)

    def parameters(self):
        return {"mu": self.mu, "g": self.g}

    def with_parameters(self, values):
        return dataclasses.replace(self, **values)

    def replace(self, **changes):
        return dataclasses.replace(self, **changes)


@dataclasses.dataclass(frozen=True)
class FrictionBlock(FrictionRules, bd.core.contract.DifferentiableModel):
    """The block, differentiable: by mu alone unless asked otherwise."""

    mu: float
    g: float = G

    def default_wrt(self):
        return ("mu",)

    def parameter_units(self):
        return {"mu": "-", "g": "m/s²", "A": "g", "A_x": "-"}


def reversal_record():
    """a(t) [m/s²] at 0.008 s: a slide +x that stops at 0.0163 s where a(t) is beyond mu g
    (mu = 0.2), so that the block slides back at once from v = 0; that slide stops 5.5 ms
    later within the same linear piece of a(t), beyond the other threshold: it reverses
    again."""
    return bd.Record(np.array([0.0, -8.0, 8.0, -8.0, 0.0, 0.0, 0.0]), 0.008, units="m/s2")


def test_a_slide_from_v_zero_without_turn_points_runs_on_the_jax_twin():
    """The JAX twin against CVODE at rtol 1e-10 (the same events within 1e-9 s) and
    against the exact backend's closed forms for bd.SlidingBlock(mu=0.2), the same block
    (an independent computation, exact to rounding): 4 events, u(t_end) to 1e-9 m. The
    first reversal (POSITIVE -> NEGATIVE at v = 0) and the stop of that slide share one
    segment of the twin, whose guard starts at zero."""
    model, motion = FrictionBlock(mu=0.2), reversal_record()
    jax = bd.simulate(model, motion, t_end=0.048, backend="jax", rtol=1e-10)
    cvode = bd.simulate(model, motion, t_end=0.048, backend="cvode", rtol=1e-10)
    exact = bd.simulate(bd.SlidingBlock(mu=0.2), motion, t_end=0.048)
    modes = [(e.mode_before.name, e.mode_after.name) for e in jax.events]
    assert modes == [("STICK", "POSITIVE"), ("POSITIVE", "NEGATIVE"), ("NEGATIVE", "POSITIVE"), ("POSITIVE", "STICK")]
    assert modes == [(e.mode_before.name, e.mode_after.name) for e in cvode.events]
    assert [int(e.mode_after) for e in jax.events] == [int(e.mode_after) for e in exact.events]
    assert np.max(np.abs(jax.t_events - cvode.t_events)) <= 1e-9
    assert np.max(np.abs(jax.t_events - exact.t_events)) <= 1e-9
    assert abs(jax.displacement - exact.displacement) <= 1e-9


def test_a_declared_default_wrt_and_units_reach_sensitivities_and_crosscheck():
    """bd.sensitivities without wrt differentiates by the model's default_wrt ("mu"
    alone), through the core's trajectory method; du/dmu [m] agrees with the exact kernel's
    derivative for bd.SlidingBlock (the same block; mu moves both frictions there too) to
    1e-6 relative (the twin at rtol 1e-12). The cross-check's table heads the derivatives
    with the declared units."""
    model, motion = FrictionBlock(mu=0.2), reversal_record()
    derivatives = bd.sensitivities(model, motion, t_end=0.048, rtol=1e-12, atol=1e-14)
    assert tuple(derivatives) == ("mu",)
    reference = bd.sensitivities(bd.SlidingBlock(mu=0.2), motion, t_end=0.048, wrt="mu")["mu"]
    assert abs(derivatives["mu"] - reference) <= 1e-6 * abs(reference)
    check = bd.crosscheck(model, motion, t_end=0.048, backends=("jax", "cvode"), wrt=("mu", "g"), rtol=1e-10)
    assert "du/dmu [m]" in str(check) and "du/dg [m/(m/s²)]" in str(check)
    with pytest.raises(ValueError, match=r"wrt=\('friction',\): choose among \('mu', 'g', 'A_x', 'A'\)"):
        bd.sensitivities(model, motion, t_end=0.048, wrt="friction")


@dataclasses.dataclass(frozen=True)
class PlainFrictionBlock(FrictionRules, bd.AbstractHybridModel):
    """The same block, declaring no capability."""

    mu: float
    g: float = G


def test_a_model_that_declares_no_derivatives_is_refused_by_name():
    """The package asks the declaration, not the methods: the plain block runs on the JAX
    twin (it has parameters) but has no derivatives."""
    model, motion = PlainFrictionBlock(mu=0.2), reversal_record()
    assert bd.simulate(model, motion, t_end=0.048, backend="jax").displacement == pytest.approx(
        bd.simulate(FrictionBlock(mu=0.2), motion, t_end=0.048, backend="jax").displacement, abs=0.0)
    with pytest.raises(TypeError, match="a PlainFrictionBlock declares no derivatives"):
        bd.sensitivities(model, motion, t_end=0.048)
    with pytest.raises(ValueError, match="a PlainFrictionBlock declares no derivatives"):
        bd.crosscheck(model, motion, t_end=0.048, backends=("jax",), wrt=("mu",))


def test_the_scalar_namespace_has_numpy_s_functions_on_floats():
    """A rule written for xp (numpy, jax.numpy) runs on the driver's Python floats: each
    name gives what NumPy gives."""
    x, y = 0.3, -1.7
    for name in ("abs", "sign", "sqrt", "exp", "log", "sin", "cos", "tan", "arcsin", "arccos", "arctan", "sinh",
                 "cosh", "tanh"):
        value = abs(x) if name in ("sqrt", "log") else x
        assert getattr(SCALAR, name)(value) == pytest.approx(float(getattr(np, name)(value)), rel=1e-15), name
    assert SCALAR.sign(y) == -1.0 and SCALAR.sign(0.0) == 0.0
    assert SCALAR.arctan2(y, x) == float(np.arctan2(y, x)) and SCALAR.hypot(x, y) == float(np.hypot(x, y))
    assert SCALAR.minimum(x, y) == y and SCALAR.maximum(x, y) == x and SCALAR.pi == math.pi
    assert SCALAR.where(x > y, x, y) == x and SCALAR.stack([x, y]) == (x, y)


class RunChecked(UserWarning):
    """What the test's model warns after every run."""


@dataclasses.dataclass(frozen=True)
class CheckedFrictionBlock(FrictionBlock):
    """The differentiable block that checks its runs and declares a scalar quantity: the
    time its first slide starts [s]."""

    def check_solution(self, solution):
        warnings.warn(f"{solution.backend}: {len(solution.events)} events under {solution.motion.name}", RunChecked)

    def scalar_quantities(self):
        return {"first_slide_time": "s"}

    def scalar_quantity_jacobian(self, name, solution, final, events):
        return events[0].dt_dp


def test_a_model_checks_its_runs_and_declares_a_quantity_to_differentiate():
    """The core calls check_solution after every run, on every generic backend, for one
    motion and for each of many (with the solution's motion set); a declared scalar
    quantity is differentiated by the core through the model's jacobian: the first slide
    starts where a(t) = -1000 t [m/s²] reaches mu g, t1 = mu g / (1000 k) for a(t) scaled
    by k, so dt1/dmu = g / 1000 [s] and dt1/dA_x = -mu g / 1000 [s] (closed form, to 1e-12
    relative; measured 2e-16)."""
    model, motion = CheckedFrictionBlock(mu=0.2), reversal_record()
    for backend in ("cvode", "ida", "jax"):
        with pytest.warns(RunChecked, match=f"{backend}: 4 events"):
            bd.simulate(model, motion, t_end=0.048, backend=backend)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RunChecked)
        bd.simulate(model, [bd.Record(sign * motion.acceleration_samples, motion.dt, name=name, units="m/s2")
                            for sign, name in ((1.0, "one"), (-1.0, "two"))], t_end=0.048)
    assert sorted(str(w.message) for w in caught if w.category is RunChecked) == \
        ["cvode: 4 events under one", "cvode: 4 events under two"]
    found = bd.sensitivities(model, motion, t_end=0.048, wrt=("mu", "A_x"), of="first_slide_time", rtol=1e-12)
    assert found.units == (("s", "s"),)
    assert abs(found["mu"] - G / 1000) <= 1e-12 * G / 1000
    assert abs(found["A_x"] + 0.2 * G / 1000) <= 1e-12 * 0.2 * G / 1000
