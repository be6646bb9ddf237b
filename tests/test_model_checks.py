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


@pytest.mark.parametrize("backend", ["cvode", "ida"])
def test_flow_of_the_wrong_shape_names_the_hook_mode_and_shapes(backend):
    with pytest.raises(ModelContractError, match=r"WrongFlowShape\.flow in mode FREE gave shape \(3,\).*\(2,\)"):
        bd.simulate(_make(WrongFlowShape), example.record(), t_end=6.0, backend=backend)


def test_guards_of_the_wrong_shape_name_the_hook_mode_and_shape():
    with pytest.raises(ModelContractError, match=r"ScalarGuards\.guards in mode FREE gave shape \(\)"):
        bd.simulate(_make(ScalarGuards), example.record(), t_end=6.0)


@pytest.mark.parametrize("backend", ["cvode", "ida"])
def test_a_mode_entered_below_its_guard_is_an_error_not_a_snap(backend):
    with pytest.raises(ModelContractError, match=r"mode FREE entered at t = 0 s with guard 0 = -0\.005 below zero"):
        bd.simulate(_make(WrongGuardSign), example.record(), t_end=6.0, backend=backend)


def test_a_mode_the_enumeration_lacks_names_the_hook():
    with pytest.raises(ModelContractError, match=r"UnknownMode\.mode_after_guard gave the mode 7, which StopMode lacks"):
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
