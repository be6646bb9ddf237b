"""bd.sensitivities returns one type for every model, bd.Sensitivities: quantities x
parameters with units, a table, and the mapping by parameter that the derivatives were
before. Where the old derivatives are rebuilt here (the core's trajectory derivatives, a
SpringSupportedMass's flights), they come from the same building blocks the old dicts
were made of, and the result holds exactly those numbers."""

import importlib.util
import pathlib
import warnings

import numpy as np
import pytest

import blockdae as bd
from blockdae.core import Horizon, make_backend
from blockdae.core.derivatives import by_parameter, jax_context, largest_peak, trajectory_sensitivities

ROOT = pathlib.Path(__file__).resolve().parents[1]
G = bd.STANDARD_GRAVITY


def old_trajectory_derivatives(model, motion, t_end, wrt):
    """name -> d displacement(t_end) / dp as the core computed it before (an array per
    name, (n_displacement_states,)): the JAX twin's displacement Jacobian by parameter."""
    jacobian = make_backend("jax").displacement_jacobian(model, motion, Horizon.resolve(motion, t_end))
    return by_parameter(model, jacobian.T, wrt, largest_peak(motion) if "A" in wrt else None)


def assert_result(result, model, quantities, parameters, units, n_sets=None):
    """The type, names, units, shapes, table columns and mapping of ``result``."""
    assert isinstance(result, bd.Sensitivities) and result.model is model
    assert result.quantities == quantities and result.parameters == parameters
    assert result.units == units
    shape = (len(quantities), len(parameters))
    assert result.array.shape == (shape if n_sets is None else (n_sets, *shape))
    assert list(result) == list(parameters) and len(result) == len(parameters)
    table = result.to_dataframe()
    assert list(table.columns) == [f"d{q}/d{p} [{units[i][j]}]" for i, q in enumerate(quantities)
                                   for j, p in enumerate(parameters)]
    assert len(table) == (1 if n_sets is None else n_sets)
    np.testing.assert_array_equal(table.to_numpy(), result.array.reshape(len(table), -1))
    for j, name in enumerate(parameters):
        value = result[name]
        if n_sets is None and len(quantities) == 1:
            assert isinstance(value, float) and value == result.array[0, j]
        else:
            np.testing.assert_array_equal(value, np.squeeze(result.array[..., j], axis=-1)
                                          if len(quantities) == 1 else result.array[..., j])
    text = repr(result)
    assert type(model).__name__ in text and all(f" {u}" in text for row in units for u in row)


def test_a_sliding_block():
    """Units from the block's parameter_units(): mu, mu_kinetic, bias, scale [-] -> m;
    A [g] -> m/g. The mapping gives a float per name, as before."""
    block, motion = bd.SlidingBlock(mu=0.3, mu_kinetic=0.2), bd.SinePulse(6.0, 0.5)
    wrt = ("mu", "mu_kinetic", "bias", "A", "scale")
    result = bd.sensitivities(block, motion, wrt=wrt)
    assert_result(result, block, ("u",), wrt, (("m", "m", "m", "m/g", "m"),))
    assert result.backend == "exact" and result.to_dataframe().columns[3] == "du/dA [m/g]"
    assert result.of("u") == {name: result[name] for name in wrt}
    np.testing.assert_allclose(result["scale"], result["A"] * motion.peak_acceleration / block.g, rtol=1e-14)
    assert "du/dA = " in repr(result) and " m/g" in repr(result)


def test_a_batch_of_sliding_blocks():
    """A batch: (n_sets, 1, n_parameters); the mapping gives (n_sets,) per name, each set's
    derivative that of the set alone; the table has one row per set."""
    block, motion = bd.SlidingBlock(mu=np.array([0.2, 0.3, 0.4]), mu_kinetic=0.15), bd.SinePulse(6.0, 0.5)
    result = bd.sensitivities(block, motion, wrt=("mu", "A"))
    assert_result(result, block, ("u",), ("mu", "A"), (("m", "m/g"),), n_sets=3)
    assert result.to_dataframe().index.name == "set" and result.of("u")["mu"].shape == (3,)
    one = bd.sensitivities(block.item(1), motion, wrt=("mu", "A"))
    np.testing.assert_allclose(result.array[1], one.array, rtol=1e-12)


def test_finite_differences_are_the_same_type():
    from blockdae.core._sensitivities import finite_differences

    block, motion = bd.SlidingBlock(mu=0.3, mu_kinetic=0.2), bd.SinePulse(6.0, 0.5)
    differences = finite_differences(block, motion, wrt=("mu", "A"), backend="exact")
    assert_result(differences, block, ("u",), ("mu", "A"), (("m", "m/g"),))
    assert differences.backend == "exact"


def test_a_planar_block():
    """Two quantities (u_x, u_y); g [m/s²] -> m/(m/s²). The mapping gives (2,) per name,
    exactly the core's old d(u_x, u_y)/dp."""
    wave = bd.Harmonic(1.0, 2.0, cycles=1)
    block = bd.PlanarBlock(mu=0.8, mu_kinetic=0.7, bias=(-0.3, 0.0), g=1.0)
    motion = bd.BaseMotion(wave, wave.scaled(0.8))
    wrt = ("mu", "bias_x", "g", "A", "A_y")
    result = bd.sensitivities(block, motion, wrt=wrt)
    assert_result(result, block, ("u_x", "u_y"), wrt, (("m", "m", "m/(m/s²)", "m/g", "m"),) * 2)
    assert result.backend == "jax"
    old = old_trajectory_derivatives(block, motion, None, wrt)
    for name in wrt:
        assert result[name].shape == (2,)
        np.testing.assert_array_equal(result[name], old[name])
    assert result.of("u_y")["mu"] == result["mu"][1]


def test_a_spring_supported_mass():
    """Its flight quantities, each in its unit per the parameter's; result[quantity] (the
    nested form) still gives parameter -> float, with a DeprecationWarning naming
    result.of; the numbers are exactly the flights' derivatives."""
    from blockdae.upthrow._sensitivities import QUANTITIES, flight_quantity_jacobians

    mass, motion, t_end = bd.SpringSupportedMass(10.0, damping=0.05), bd.Harmonic(0.5 * G, 0.13, cycles=3), 0.39
    wrt = ("frequency", "damping", "g", "A")
    result = bd.sensitivities(mass, motion, t_end, wrt=wrt)
    units = (("(m/s)/Hz", "m/s", "(m/s)/(m/s²)", "(m/s)/g"), ("m/Hz", "m", "m/(m/s²)", "m/g"),
             ("s/Hz", "s", "s/(m/s²)", "s/g"))
    assert_result(result, mass, tuple(QUANTITIES), wrt, units)
    assert result.quantity_units == ("m/s", "m", "s")
    assert "dheight/dA [m/g]" in result.to_dataframe().columns
    solution, _, events = trajectory_sensitivities(mass, motion, Horizon.resolve(motion, t_end), make_backend("jax"))
    with jax_context():
        rows = flight_quantity_jacobians(mass, solution, events, tuple(QUANTITIES))
    for quantity, row in rows.items():
        old = {name: float(value) for name, value in by_parameter(mass, row, wrt, largest_peak(motion)).items()}
        assert result.of(quantity) == old
        with pytest.warns(DeprecationWarning, match=r"result\.of\('height'\)" if quantity == "height" else "of"):
            assert result[quantity] == old
    assert "height" not in result and "frequency" in result
    only = bd.sensitivities(mass, motion, t_end, wrt=wrt, of="height")
    assert only.quantities == ("height",) and only.of("height") == result.of("height")


def test_a_flexible_sliding_mass():
    """bd.sensitivities of a FlexibleSlidingMass (its displacement s, by omega [rad/s],
    ky [g], A [g]) and blockdae.flexible_mass.displacement_sensitivities (by its column's
    inputs: height [m], vs [m/s], ...) are the same type."""
    from blockdae.flexible_mass import displacement_sensitivities

    model = bd.FlexibleSlidingMass(bd.ShearColumn(10.0, 250.0, 800.0, 0.05), ky=0.1)
    motion, t_end = bd.SinePulse(0.4 * G, 0.5), 1.5
    wrt = ("omega", "ky", "A")
    result = bd.sensitivities(model, motion, t_end, wrt=wrt)
    assert_result(result, model, ("s",), wrt, (("m/(rad/s)", "m/g", "m/g"),))
    old = old_trajectory_derivatives(model, motion, t_end, wrt)
    assert all(result[name] == float(old[name][0]) for name in wrt)
    inputs = displacement_sensitivities(model, motion, t_end)
    assert_result(inputs, model, ("s",), ("ky", "height", "vs", "damping", "A"),
                  (("m/g", "m/m", "m/(m/s)", "m", "m/g"),))


def test_the_example_model():
    """A model written outside the package (examples/custom_model.py) gets the same type
    from the core's derivatives, with its own parameter units."""
    spec = importlib.util.spec_from_file_location("custom_model", ROOT / "examples" / "custom_model.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    model = example.OscillatorOnStop(omega=2 * np.pi * 2.0, zeta=0.2, omega_c=2 * np.pi * 8.0, gap=0.005)
    motion, t_end = bd.SinePulse(0.3 * G, 0.5), 1.0
    wrt = ("omega", "zeta", "gap", "A")
    result = bd.sensitivities(model, motion, t_end, wrt=wrt, rtol=1e-10)
    assert_result(result, model, ("u",), wrt, (("m/(rad/s)", "m", "m/m", "m/g"),))
    old = old_trajectory_derivatives(model, motion, t_end, wrt)
    assert all(result[name] == float(old[name][0]) for name in wrt)


def test_a_model_whose_own_method_returns_a_dict_gets_the_type():
    """The contract allows a model's own method to return name -> value; bd.sensitivities
    makes a Sensitivities of it, units from the model's parameter_units()."""
    class OwnDerivatives(bd.SlidingBlock):
        def sensitivities(self, motion, t_end, wrt, backend, of, options):
            return {name: 1.5 for name in wrt}

    block = OwnDerivatives(mu=0.3)
    result = bd.sensitivities(block, bd.SinePulse(6.0, 0.5), wrt=("mu", "A"))
    assert_result(result, block, ("u",), ("mu", "A"), (("m", "m/g"),))
    assert dict(result) == {"mu": 1.5, "A": 1.5}


def test_unknown_names_are_refused_clearly():
    result = bd.Sensitivities.make(bd.SlidingBlock(mu=0.3), {"mu": 0.5})
    with pytest.raises(KeyError, match="'bias' is none of the parameters"):
        result["bias"]
    with pytest.raises(KeyError, match="quantity 'v'"):
        result.of("v")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert result["mu"] == 0.5 and result.of("u") == {"mu": 0.5}
