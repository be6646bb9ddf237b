"""A model written outside the package plugs in (issue 20): ``examples/custom_model.py``
runs on CVODE, IDA and the JAX twin with no edit in ``src/``."""

import importlib.util
import pathlib

import numpy as np
import pytest

import blockdae as bd

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def example():
    spec = importlib.util.spec_from_file_location("custom_model", ROOT / "examples" / "custom_model.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_example_runs_on_every_solver_backend_and_they_agree(example, capsys):
    """The backends against each other at rtol 1e-10: the same events, within 1e-8 s."""
    check = example.main()
    assert [row["backend"] for row in check.rows] == ["cvode", "ida", "jax"]
    assert check.agrees and check.rows[0]["n_events"] >= 10
    assert max(row["max_dt"] for row in check.rows) <= 1e-8
    assert "largest event-time disagreement between backends" in capsys.readouterr().out


def test_free_flight_matches_the_closed_form_oscillator(example):
    """Before the first contact the model is a damped oscillator under a(t) = A (a
    rectangular pulse from rest): u = -(A / omega²) (1 - e^{-zeta omega t}(cos wd t +
    zeta omega / wd sin wd t)); the first contact is where u = -gap (brentq, an
    independent computation)."""
    from scipy.optimize import brentq

    omega, zeta, gap, a = 2 * np.pi, 0.1, 0.01, 1.0
    model = example.OscillatorOnStop(omega=omega, zeta=zeta, omega_c=4 * omega, gap=gap)
    wd = omega * np.sqrt(1 - zeta**2)
    decay = lambda t: np.exp(-zeta * omega * t) * (np.cos(wd * t) + zeta * omega / wd * np.sin(wd * t))
    u = lambda t: -(a / omega**2) * (1 - decay(t))
    t_contact = brentq(lambda t: u(t) + gap, 0.05, 0.5)
    for backend in ("cvode", "ida", "jax"):
        sol = bd.simulate(model, bd.RectangularPulse(a, 2.0), t_end=1.0, backend=backend)
        first = sol.events[0]
        assert (first.mode_before, first.mode_after) == (example.StopMode.FREE, example.StopMode.CONTACT)
        assert abs(first.t - t_contact) <= 1e-9
        assert first.state[0] == -gap


def test_a_custom_model_gets_the_default_backend_and_a_clear_refusal(example):
    model = example.OscillatorOnStop(omega=2 * np.pi, zeta=0.1, omega_c=8 * np.pi, gap=0.01)
    sol = bd.simulate(model, bd.RectangularPulse(1.0, 2.0), t_end=1.0)
    assert sol.backend == "cvode" and isinstance(sol, bd.core.DriverSolution)
    assert "t [s]" in sol.event_table() and list(sol.to_dataframe().columns) == [
        "t_s", "mode_before", "mode_after", "u", "u_rate"]
    with pytest.raises(ValueError, match=r"backend='exact' does not run a OscillatorOnStop; choose one of "
                                         r"\['cvode', 'ida', 'jax'\]"):
        bd.simulate(model, bd.RectangularPulse(1.0, 2.0), t_end=1.0, backend="exact")


def test_a_custom_model_is_plotted_by_its_solution(example):
    """bd.plot draws any DriverSolution as its states against time, events marked."""
    import matplotlib

    matplotlib.use("Agg")
    model = example.OscillatorOnStop(omega=2 * np.pi, zeta=0.1, omega_c=8 * np.pi, gap=0.01)
    sol = bd.simulate(model, bd.RectangularPulse(1.0, 2.0), t_end=1.0)
    fig = bd.plot(sol, n_points=200)
    assert [ax.get_ylabel() for ax in fig.axes] == ["u", "u_rate"]
    events = fig.axes[0].lines[1]
    np.testing.assert_array_equal(events.get_xdata(), sol.t_events)
