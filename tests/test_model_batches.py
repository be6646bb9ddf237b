"""Every built-in model that takes parameter arrays runs as a batch of parameter sets under
many records and scales into one Ensemble type, each row equal to that set's own run of the
scaled record (the single-set model, run alone); the study picks its polarities through the
contract."""

import numpy as np
import pytest

import blockdae as bd


def _records():
    t = np.arange(0.0, 3.0, 0.01)
    return [bd.Record(peak * bd.STANDARD_GRAVITY * np.sin(2 * np.pi * f * t) * np.exp(-t), 0.01, name=f"r{i}")
            for i, (peak, f) in enumerate(((0.4, 1.5), (0.6, 2.0), (0.8, 3.0)))]


#: the backend of each (None: the model's default); the plane's compiled engine (its
#: default, IDA on the Python driver, takes seconds a run)
BACKENDS = {"planar": "compiled"}
BATCHES = {
    "sliding": bd.SlidingBlock(mu=np.array([0.1, 0.2])),
    "planar": bd.PlanarBlock(mu=np.array([0.1, 0.2])),
    "upthrow": bd.SpringSupportedMass(frequency=np.array([5.0, 10.0]), damping=0.05),
    "flexible": bd.FlexibleSlidingMass(bd.ShearColumn(10.0, 200.0), ky=np.array([0.1, 0.2])),
}


@pytest.mark.parametrize("name", BATCHES)
def test_a_two_set_batch_under_three_records_and_two_scales(name):
    model, records, scales = BATCHES[name], _records(), (1.0, 2.0)
    backend = BACKENDS.get(name)
    ensemble = bd.simulate(model, records, t_end=3.0, scale=scales, backend=backend)
    assert type(ensemble) is bd.Ensemble
    table = ensemble.to_dataframe()
    assert len(table) == 3 * 2 * 2
    assert ensemble.max_abs_displacement.size == 12
    for row in (0, 5, 11):  # record i, scale k, set j in that order
        i, k, j = row // 4, (row // 2) % 2, row % 2
        alone = bd.simulate(model.item(j), records[i].scaled(scales[k]), t_end=3.0, backend=backend)
        np.testing.assert_allclose(ensemble.max_abs_displacement.ravel()[row], alone.max_abs_displacement,
                                   rtol=1e-12, atol=1e-15)
        assert ensemble.n_events.ravel()[row] == len(alone.events)


@pytest.mark.parametrize("name", ["upthrow", "flexible"])
def test_batch_items_and_parameters(name):
    model = BATCHES[name]
    assert model.batch_shape == (2,)
    assert all(model.item(j).batch_shape == () for j in range(2))
    values = model.batch_parameters()
    assert all(np.shape(v) == (2,) for v in values.values())


def test_batch_values_are_checked_per_set():
    with pytest.raises(ValueError, match=r"parameter set 1: .*damping"):
        bd.SpringSupportedMass(frequency=np.array([5.0, 10.0]), damping=np.array([0.05, 1.5]))
    with pytest.raises(ValueError, match=r"ky\[1\]: ky=-0.2 must be a yield acceleration >= 0"):
        bd.FlexibleSlidingMass(bd.ShearColumn(10.0, 200.0), ky=np.array([0.1, -0.2]))
    with pytest.raises(ValueError, match="differ in size"):
        bd.SpringSupportedMass(frequency=np.array([5.0, 10.0]), damping=np.array([0.0, 0.1, 0.2]))
