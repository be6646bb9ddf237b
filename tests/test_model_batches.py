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
    # rocks (mu >= b/h): its default backend, "compiled", runs the sets one by one
    "rocking": bd.RockingBlock(b=np.array([0.25, 0.35]), h=1.0, mu=1.0),
    # slides (mu < b/h): on its default backend, "cvode"
    "rocking-slides": bd.RockingBlock(b=0.5, h=1.0, mu=np.array([0.1, 0.2])),
    # the complete block: rocks, slide-rocks and slides, set by set on "cvode"
    "free-standing": bd.rocking.FreeStandingBlock(b=np.array([0.25, 0.35]), h=1.0, mu=np.array([0.3, 0.5])),
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


def _rows_and_single_runs(model, ensemble, records, scales):
    """(row, (record i, scale k, set j), the set's own run of the scaled record) for each
    row of a batch's ``ensemble``, its final numbers checked equal to that run's bit for bit."""
    for row in range(len(records) * len(scales) * 2):
        i, k, j = row // 4, (row // 2) % 2, row % 2
        alone = bd.simulate(model.item(j), records[i].scaled(scales[k]), t_end=3.0)
        assert ensemble.max_abs_displacement.ravel()[row] == alone.max_abs_displacement
        assert ensemble.displacement.ravel()[row] == alone.displacement
        assert ensemble.n_events.ravel()[row] == len(alone.events)
        yield row, (i, k, j), alone


def test_a_rocking_batch_equals_its_single_runs_exactly():
    """Every row of a rocking batch (the compiled engine, set by set) is its set's own run,
    bit for bit, with every case's solution and with the final numbers alone."""
    model, records, scales = BATCHES["rocking"], _records(), (1.0, 2.0)
    ensemble = bd.simulate(model, records, t_end=3.0, scale=scales)
    finals = bd.simulate(model, records, t_end=3.0, scale=scales, final_only=True)
    table = ensemble.to_dataframe()
    assert list(table["b"]) == [0.25, 0.35] * 6 and "theta_end_rad" in table
    for row, (i, k, j), alone in _rows_and_single_runs(model, ensemble, records, scales):
        assert table["max_theta_over_alpha"][row] == alone.max_abs_displacement / model.item(j).alpha
        one = bd.simulate(model.item(j), records[i], t_end=3.0, scale=[scales[k]], final_only=True)
        assert finals.max_abs_displacement.ravel()[row] == one.max_abs_displacement.ravel()[0]
        assert finals.n_events.ravel()[row] == one.n_events.ravel()[0]


def test_a_rocking_batch_that_mixes_sliding_and_rocking_sets_is_refused():
    """One batch's displacements share one unit: u [m] of a block that slides, theta [rad]
    of one that rocks."""
    with pytest.raises(ValueError, match=r"mu: parameter sets \[0\] have mu below their rocking threshold b/h "
                                         r"\(they slide: u \[m\]\) and sets \[1, 2\] at or above it"):
        bd.RockingBlock(b=np.array([0.2, 0.3, 0.5]), h=1.0, mu=np.array([0.1, 0.7, 0.9]))
    with pytest.raises(ValueError, match=r"threshold alpha = atan\(b/h\)"):
        bd.RockingBlock(b=0.2, h=1.0, mu=np.array([0.197, 0.198]), linearised=True)  # alpha = 0.1974
    with pytest.raises(ValueError, match=r"parameter set 1: b=-0.3 must be > 0"):
        bd.RockingBlock(b=np.array([0.2, -0.3]), h=1.0, mu=0.7)
    with pytest.raises(ValueError, match="differ in size"):
        bd.RockingBlock(b=np.array([0.2, 0.3]), h=np.array([1.0, 1.0, 1.0]), mu=0.7)


def test_a_rocking_batch_lists_each_sets_contact_limits_as_its_run_does():
    """The contact check of a batch reads each set's run: the limits one run lists, and
    with strict the error one run raises."""
    record = _records()[2].scaled(2.0)
    batch = bd.RockingBlock(b=np.array([0.25, 0.2]), h=1.0, mu=0.7)
    alone = bd.simulate(batch.item(1), record, t_end=3.0).contact_events
    runs = bd.simulate(batch, record, t_end=3.0)
    assert alone and runs[1].contact_events == alone
    with pytest.raises(ValueError) as one:
        bd.simulate(batch.item(1).replace(strict=True), record, t_end=3.0)
    with pytest.raises(ValueError) as both:
        bd.simulate(batch.replace(strict=True), record, t_end=3.0)
    assert str(both.value) == str(one.value)


def test_a_free_standing_batch_equals_its_single_runs_exactly():
    """Every row of a batch of complete blocks (cvode, set by set) is its set's own run,
    bit for bit; its table holds the parameter sets and metres (x, the centroid's
    displacement relative to the base); each set is checked as a block of its own."""
    model, records, scales = BATCHES["free-standing"], _records(), (1.0, 2.0)
    ensemble = bd.simulate(model, records, t_end=3.0, scale=scales)
    table = ensemble.to_dataframe()
    assert list(table["b"]) == [0.25, 0.35] * 6 and list(table["mu"]) == [0.3, 0.5] * 6
    assert {"x_end_m", "max_abs_displacement_m"} <= set(table)
    assert model.parameter_labels["mu"] == "static friction coefficient mu [-]"
    for row, _, alone in _rows_and_single_runs(model, ensemble, records, scales):
        assert [(e.t, e.kind) for e in ensemble[row].events] == [(e.t, e.kind) for e in alone.events]
    assert {e.kind for row in range(12) for e in ensemble[row].events} >= {"uplift", "slip", "impact"}
    with pytest.raises(ValueError, match=r"parameter set 1: mu_kinetic=0.4 must be in \[0, mu=0.3\]"):
        bd.rocking.FreeStandingBlock(b=0.2, h=1.0, mu=np.array([0.5, 0.3]), mu_kinetic=0.4)
    with pytest.raises(ValueError, match="differ in size"):
        bd.rocking.FreeStandingBlock(b=np.array([0.2, 0.3]), h=np.array([1.0, 1.0, 1.0]), mu=0.7)


@pytest.mark.parametrize("name", ["upthrow", "flexible", "rocking", "free-standing"])
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


def test_a_study_sweeps_the_rocking_blocks_mu_by_default():
    """bd.study takes the rocking block, which declares no study hook: each mu a block of
    its own, each row its single run (bit for bit) with the block's own columns; values of
    mu that slide and rock in one study are refused before any run (their displacements
    differ in unit)."""
    record, block = _records()[1], bd.RockingBlock(b=0.25, h=1.0, mu=1.0)
    table = bd.study([record], mu=[0.5, 1.0], scale=[1.0, 2.0], block=block, t_end=3.0)
    assert list(table.columns[-6:]) == ["theta_end_rad", "max_abs_displacement_rad", "n_events", "t_end_s",
                                        "overturned", "max_theta_over_alpha"]
    for _, row in table.iterrows():
        alone = bd.simulate(block.replace(mu=row["mu"]), record.scaled(row["scale"]), t_end=3.0)
        assert row["max_abs_displacement_rad"] == alone.max_abs_displacement
        assert row["n_events"] == len(alone.events)
    with pytest.raises(ValueError, match=r"mu: the values \[0.1, 0.5\] give RockingBlocks whose displacements differ "
                                         r"\(u \[m\], theta \[rad\]\)"):
        bd.study([record], mu=[0.1, 0.2, 0.5], scale=1.0, block=block)


def test_a_rocking_batchs_solution_states_radians():
    """A batch of one record (a BatchSolution) says its unit: rad for a block that rocks."""
    batch = bd.simulate(BATCHES["rocking"], _records()[0], t_end=3.0)
    table = batch.to_dataframe()
    assert "rad (signed)" in repr(batch) and batch.unit == "rad"
    assert list(table.columns[-4:]) == ["theta_end_rad", "max_abs_displacement_rad", "n_events", "t_end_s"]
    assert batch.figure().axes[0].get_ylabel() == "relative displacement (signed) [rad]"
    assert bd.simulate(BATCHES["rocking-slides"], _records()[0], t_end=3.0).to_dataframe().columns[-4] == "u_end_m"
