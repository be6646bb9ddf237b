"""Every solution has ``history()`` and ``to_dataframe()``; a model's declared state units
go into their column names and onto the axes of its figure."""

import importlib.util
import pathlib

import numpy as np
import pytest

import blockdae as bd
from blockdae.core.contract import AbstractHybridModel

ROOT = pathlib.Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("friction_isolator", ROOT / "examples" / "friction_isolator.py")
isolator = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(isolator)


def _motion():
    t = np.arange(0.0, 2.0, 0.01)
    return bd.Record(0.4 * bd.STANDARD_GRAVITY * np.sin(2 * np.pi * 1.5 * t), 0.01, name="s")


MODELS = {
    "isolator": isolator.FrictionIsolator(),
    "sliding": bd.SlidingBlock(mu=0.1),
    "upthrow": bd.SpringSupportedMass(frequency=5.0),
    "flexible": bd.FlexibleSlidingMass(bd.ShearColumn(10.0, 200.0), ky=0.1),
    "rocking": bd.RockingBlock(b=0.2, h=0.6, mu=0.7),
}


@pytest.mark.parametrize("name", MODELS)
def test_history_samples_the_dense_output(name):
    model, motion = MODELS[name], _motion()
    solution = bd.simulate(model, motion, t_end=2.0)
    history = solution.history()
    assert history["t_s"].iloc[0] == 0.0 and history["t_s"].iloc[-1] == pytest.approx(solution.t_end)
    np.testing.assert_allclose(history["base_acceleration_m_s2"], motion.acceleration(history["t_s"].to_numpy()))
    assert set(solution.t_events) <= set(history["t_s"])
    assert "t_s" in solution.to_dataframe().columns
    if isinstance(solution, bd.core.DriverSolution):
        states = solution.dense_state(history["t_s"].to_numpy())[0]
        columns = [c for c in history.columns if c not in ("t_s", "base_acceleration_m_s2", "mode")]
        np.testing.assert_array_equal(history[columns].to_numpy(), states)


def test_declared_units_name_the_columns_and_label_the_figure():
    solution = bd.simulate(isolator.FrictionIsolator(), _motion(), t_end=2.0)
    assert list(solution.history().columns) == ["t_s", "base_acceleration_m_s2", "u_m", "u_rate_m_s", "mode"]
    assert list(solution.to_dataframe().columns) == ["t_s", "mode_before", "mode_after", "u_m", "u_rate_m_s"]
    figure = bd.plot(solution)
    assert [ax.get_ylabel() for ax in figure.axes] == ["u [m]", "u_rate [m/s]"]


def test_rocking_units_follow_what_the_block_does():
    assert bd.RockingBlock(b=0.2, h=0.6, mu=0.7).state_units == ("rad", "rad/s")
    assert bd.RockingBlock(b=0.2, h=0.6, mu=0.1).state_units == ("m", "m/s")
    assert AbstractHybridModel.state_units is None  # not declared: the names alone
