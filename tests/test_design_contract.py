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
