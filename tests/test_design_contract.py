"""design.Simulated makes a design model of any model: on a BatchedModel (the block on a
plane, every set in one call) its D equals design.Planar's, which runs the same engine
through its own path; Rigid, Flexible and Planar declare the contract."""

import numpy as np

import blockdae as bd
from blockdae import design


def test_simulated_batch_equals_the_planar_design_model():
    t = np.arange(0.0, 3.0, 0.01)
    record = bd.Record(0.5 * bd.STANDARD_GRAVITY * np.sin(2 * np.pi * 1.5 * t) * np.exp(-t), 0.01, name="r")
    mu = np.array([0.15, 0.2, 0.3])
    wrapped = design.Simulated(bd.PlanarBlock(mu=0.2), parameters={"mu": "-"}, design="mu", backend="compiled",
                               polarity="larger")
    own = design.Planar(polarity="larger")
    np.testing.assert_allclose(wrapped.displacements(record, 0.4, {"mu": mu}),
                               own.displacements(record, 0.4, {"mu": mu}), rtol=1e-12, atol=1e-15)
    assert wrapped.PARAMETERS == {"mu": "-"} and wrapped.REQUIRED == ("mu",) and wrapped.kind == "PlanarBlock"


def test_the_built_in_design_models_declare_the_contract():
    assert all(isinstance(m, design.DesignModel) for m in (design.Rigid(), design.Flexible(), design.Planar()))
    assert design.Rigid.has_derivative and not design.Flexible.has_derivative


def test_simulated_sliding_block_is_newmarks_rigid_block_with_its_inverse():
    """A one-way SlidingBlock with mu = ky and no bias is Newmark's rigid block
    (design.Rigid, the closed-form integration of bd.newmark): same D, and the same ky
    for an allowable D, found by Newton steps on bd.sensitivities by mu."""
    t = np.arange(0.0, 3.0, 0.01)
    record = bd.Record(0.5 * bd.STANDARD_GRAVITY * np.sin(2 * np.pi * 1.5 * t) * np.exp(-t), 0.01, name="r")
    block = bd.SlidingBlock(mu=0.1, direction="negative")
    assert block.parameters() == {"mu": 0.1, "mu_kinetic": 0.1, "bias": 0.0}
    assert set(block.parameters()) <= set(block.parameter_units())
    wrapped = design.Simulated(block, parameters={"mu": "-"}, design="mu")
    assert wrapped.has_derivative and wrapped.kind == "SlidingBlock"
    ky = np.array([0.05, 0.1, 0.2])
    d = wrapped.displacements(record, 0.4, {"mu": ky})
    assert np.all(d > 0)
    np.testing.assert_allclose(d, design.Rigid().displacements(record, 0.4, {"ky": ky}), rtol=1e-12)
    allowable = float(d[1])
    np.testing.assert_allclose(design.ky_for_displacement(record, wrapped, {}, allowable, pga=0.4), 0.1, rtol=1e-9)


def test_a_sliding_block_takes_its_parameters_back():
    block = bd.SlidingBlock(mu=0.3, bias=0.1)
    moved = block.with_parameters({"mu": 0.4, "bias": 0.2})
    assert moved.parameters() == {"mu": 0.4, "mu_kinetic": 0.4, "bias": 0.2} and moved.mu_kinetic is None
    assert block.with_parameters({"mu_kinetic": 0.2}).parameters() == {"mu": 0.3, "mu_kinetic": 0.2, "bias": 0.1}
    assert block.with_parameters({"mu": np.array([0.3, 0.4])}).batch_shape == (2,)
