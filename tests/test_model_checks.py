"""The driver checks a model's hooks once per run: a flow or guards of the wrong shape, a
mode the enumeration lacks and a mode entered with a guard already below zero raise a
ModelContractError naming the hook, the mode and the values, on every generic backend
(never a silent wrong answer)."""

import dataclasses
import importlib.util
import pathlib

import numpy as np
import pytest

import blockdae as bd
from blockdae.core import ModelContractError

ROOT = pathlib.Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("custom_model", ROOT / "examples" / "custom_model.py")
example = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(example)
StopMode = example.StopMode
PARAMETERS = dict(omega=2 * np.pi * 2.0, zeta=0.2, omega_c=2 * np.pi * 8.0, gap=0.005)


class WrongFlowShape(example.OscillatorOnStop):
    def flow(self, mode, t, y, excitation, xp=np):
        return xp.stack([*super().flow(mode, t, y, excitation, xp), 0.0])


class ScalarGuards(example.OscillatorOnStop):
    def guards(self, mode, t, y, excitation, xp=np):
        return super().guards(mode, t, y, excitation, xp)[0]


class WrongGuardSign(example.OscillatorOnStop):
    """FREE's guard written as -(u + gap): negative as FREE is entered at rest."""

    def guards(self, mode, t, y, excitation, xp=np):
        clearance = y[0] + self.gap
        return xp.stack([-clearance if mode == StopMode.FREE else clearance])


class UnknownMode(example.OscillatorOnStop):
    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        return 7


def _make(cls):
    return cls(**PARAMETERS)


@pytest.mark.parametrize("backend", ["cvode", "ida", "jax"])
def test_flow_of_the_wrong_shape_names_the_hook_mode_and_shapes(backend):
    with pytest.raises(ModelContractError, match=r"WrongFlowShape\.flow in mode FREE gave shape \(3,\).*\(2,\)"):
        bd.simulate(_make(WrongFlowShape), example.record(), t_end=6.0, backend=backend)


def test_guards_of_the_wrong_shape_name_the_hook_mode_and_shape():
    with pytest.raises(ModelContractError, match=r"ScalarGuards\.guards in mode FREE gave shape \(\)"):
        bd.simulate(_make(ScalarGuards), example.record(), t_end=6.0)


@pytest.mark.parametrize("backend", ["cvode", "ida", "jax"])
def test_a_mode_entered_below_its_guard_is_an_error_not_a_snap(backend):
    with pytest.raises(ModelContractError, match=r"mode FREE entered at t = 0 s with guard 0 = -0\.005 below zero"):
        bd.simulate(_make(WrongGuardSign), example.record(), t_end=6.0, backend=backend)


def test_a_mode_the_enumeration_lacks_names_the_hook():
    with pytest.raises(ModelContractError, match=r"UnknownMode\.mode_after_guard gave the mode 7, which StopMode"):
        bd.simulate(_make(UnknownMode), example.record(), t_end=6.0)


def test_an_initial_mode_the_enumeration_lacks_names_it():
    model = dataclasses.replace(_make(example.OscillatorOnStop))
    object.__setattr__(model, "initial_mode", 3)  # an instance attribute over the class's
    with pytest.raises(ModelContractError, match=r"initial_mode gave the mode 3"):
        bd.simulate(model, example.record(), t_end=6.0)


def test_a_correct_model_runs_as_before():
    """The check passes a model whose guards start positive and are left at exact roots: the
    example's events on CVODE match IDA's (each backend's own event location)."""
    model, motion = _make(example.OscillatorOnStop), example.record()
    cvode, ida = (bd.simulate(model, motion, t_end=6.0, backend=b, rtol=1e-10) for b in ("cvode", "ida"))
    assert len(cvode.events) == len(ida.events) > 4
    np.testing.assert_allclose(cvode.t_events, ida.t_events, atol=1e-7)


class WrongInitialState(example.OscillatorOnStop):
    def initial_state(self):
        return np.zeros(3)


def test_an_initial_state_of_the_wrong_shape_names_the_hook():
    with pytest.raises(ModelContractError, match=r"WrongInitialState\.initial_state gave shape \(3,\).*\(2,\)"):
        bd.simulate(_make(WrongInitialState), example.record(), t_end=6.0)


class MinimalStop(bd.AbstractHybridModel):
    """The example's oscillator on a stop from the required hooks alone (flow, guards and
    the two mode rules): the driver's hooks take their defaults (guard rates by differences
    along the flow, the state at a guard as located, no turning points)."""

    state_names, modes, initial_mode = ("u", "u_rate"), StopMode, StopMode.FREE

    def __init__(self, full):
        self.full = full

    def flow(self, mode, t, y, excitation, xp=np):
        return self.full.flow(mode, t, y, excitation, xp)

    def guards(self, mode, t, y, excitation, xp=np):
        return self.full.guards(mode, t, y, excitation, xp)

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        return self.full.mode_at_rest(t, excitation, xp, y)

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        return self.full.mode_after_guard(mode, guard_index, t, y, excitation, xp, time_tol)

    def output_step(self):
        return self.full.output_step()


def test_the_required_hooks_alone_run_as_the_whole_model():
    """The minimal model's events and displacement match the example's (all its hooks
    explicit) on CVODE at rtol 1e-10: each event within 1e-8 s (the integrator's own
    root location; measured 7e-13 s over 22 events), the derived guard rates within 1e-6
    of the exact ones."""
    full, motion = _make(example.OscillatorOnStop), example.record()
    minimal = MinimalStop(full)
    a, b = (bd.simulate(m, motion, t_end=6.0, rtol=1e-10) for m in (full, minimal))
    assert [(e.mode_before, e.mode_after) for e in a.events] == [(e.mode_before, e.mode_after) for e in b.events]
    np.testing.assert_allclose(b.t_events, a.t_events, atol=1e-8)
    assert abs(b.displacement - a.displacement) < 1e-8
    with pytest.raises(ValueError, match="give t_end"):
        bd.simulate(minimal, motion)
    from blockdae.core.contract import difference_rates

    piece = bd.core._driver.PieceExcitation()
    piece.set(0.0, [(0.0, 2.0, 0.0, 0.0, 0.0)], 0.01)  # a(t) = 2 t [m/s²] on [0, 0.01] s
    y = np.array([0.001, 0.05])
    for mode in StopMode:
        exact = full.guard_rates(mode, 0, 0.005, y, piece)
        derived = difference_rates(full, mode, 0, 0.005, y, piece)
        np.testing.assert_allclose(derived, exact, rtol=1e-6, atol=1e-9)
