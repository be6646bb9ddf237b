"""``blockdae run --model MODULE:CLASS --param NAME=VALUE ... RECORD`` runs any model of the
contract (the example isolator, written outside the package; a built-in model) on any
backend, with the built-in ``run``'s table and JSON, and names the flag of a bad argument."""

import json
import pathlib

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli import main

ROOT = pathlib.Path(__file__).resolve().parents[1]
ISOLATOR = f"{ROOT / 'examples' / 'friction_isolator.py'}:FrictionIsolator"


@pytest.fixture(scope="module")
def record_file(tmp_path_factory):
    t = np.arange(0.0, 2.0, 0.01)
    a = 0.35 * np.sin(2 * np.pi * t)  # [g], two whole cycles: no offset
    path = tmp_path_factory.mktemp("records") / "shake.csv"
    np.savetxt(path, np.column_stack([t, a]), delimiter=",", header="time (s), acc (g)")
    return path


@pytest.mark.parametrize("backend", ["cvode", "ida"])
def test_json_of_a_users_model_equals_the_python_run(record_file, capsys, backend):
    assert main(["--no-cache", "run", "--model", ISOLATOR, "--param", "mu=0.05", "--param", "radius=2",
                 "--backend", backend, "--json", str(record_file)]) == 0
    out = json.loads(capsys.readouterr().out)
    import importlib.util

    spec = importlib.util.spec_from_file_location("friction_isolator", ROOT / "examples" / "friction_isolator.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    expected = bd.simulate(module.FrictionIsolator(mu=0.05, radius=2.0),
                           bd.read_record(record_file), backend=backend)
    assert out["backend"] == backend and out["parameters"] == {"mu": 0.05, "radius": 2.0}
    assert out["u_end_m"] == expected.displacement
    assert out["max_abs_displacement_m"] == expected.max_abs_displacement
    assert [e["t_s"] for e in out["events"]] == list(expected.t_events)
    assert set(out["events"][0]) == {"t_s", "from", "to", "u_m", "u_rate_m_s"}
    assert out["parameter_units"]["radius"] == "m"


def test_table_history_and_a_built_in_model(record_file, capsys, tmp_path):
    history = tmp_path / "history.csv"
    assert main(["--no-cache", "run", "--model", ISOLATOR, "--param", "mu=0.05", "--history", str(history),
                 str(record_file)]) == 0
    out = capsys.readouterr().out
    assert "model: " in out and "mu = 0.05" in out and "displacement at t_end = " in out and " m\n" in out
    assert history.read_text().splitlines()[0] == "t_s,base_acceleration_m_s2,u_m,u_rate_m_s,mode"
    assert main(["--no-cache", "run", "--model", "blockdae:SpringSupportedMass", "--param", "frequency=5",
                 "--t-end", "2", "--quiet", str(record_file)]) == 0
    expected = bd.simulate(bd.SpringSupportedMass(frequency=5.0), bd.read_record(record_file), t_end=2.0)
    assert capsys.readouterr().out.strip() == f"{expected.displacement:+.6f} m"


@pytest.mark.parametrize("argv, message", [
    (["--model", "blockdae:SpringSupportedMass", "--param", "frequncy=5"], "argument --param: SpringSupportedMass"),
    (["--model", "blockdae:no_such_class"], "argument --model: blockdae has no model class 'no_such_class'"),
    (["--model", "no_such_module_xyz:Model"], "argument --model: cannot import 'no_such_module_xyz'"),
    (["--model", "blockdae.SpringSupportedMass"], "must be package.module:Class"),
    (["--model", "blockdae:SpringSupportedMass", "--param", "frequency=5", "--mu", "0.1"], "argument --mu"),
    (["--param", "mu=0.1"], "argument --param: takes --model"),
    ([], "required: --mu (or --model"),
])
def test_errors_name_the_flag(record_file, capsys, argv, message):
    assert main(["--no-cache", "run", *argv, str(record_file)]) == 2
    assert message in capsys.readouterr().err
