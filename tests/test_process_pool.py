"""Results cross process boundaries: a Record (its read-only metadata), every solution and
an ensemble pickle, and a study and an ensemble run on a ProcessPoolExecutor give the
numbers of the same run here."""

import concurrent.futures
import multiprocessing
import pickle

import numpy as np
import pytest

import blockdae as bd


def _records():
    t = np.arange(0.0, 2.0, 0.01)
    return [bd.Record(0.4 * bd.STANDARD_GRAVITY * np.sin(2 * np.pi * f * t), 0.01, name=name,
                      metadata={"station": name, "component": "090"})
            for name, f in (("a", 1.5), ("b", 2.5))]


def test_record_pickles_with_its_metadata_read_only():
    record = _records()[0]
    copy = pickle.loads(pickle.dumps(record))
    assert dict(copy.metadata) == {"station": "a", "component": "090"}
    with pytest.raises(TypeError):
        copy.metadata["station"] = "x"
    assert not copy.acceleration_samples.flags.writeable
    np.testing.assert_array_equal(copy.acceleration_samples, record.acceleration_samples)
    assert (copy.dt, copy.name, copy.start_time) == (record.dt, record.name, record.start_time)


@pytest.mark.parametrize("model", [bd.SlidingBlock(mu=0.1), bd.SlidingBlock(mu=np.array([0.1, 0.2])),
                                   bd.SpringSupportedMass(frequency=5.0),
                                   bd.FlexibleSlidingMass(bd.ShearColumn(10.0, 200.0), ky=0.1)],
                         ids=["sliding", "sliding batch", "upthrow", "flexible"])
def test_solutions_pickle_and_keep_their_dense_output(model):
    record = _records()[0]
    solution = bd.simulate(model, record, t_end=2.0)
    copy = pickle.loads(pickle.dumps(solution))
    np.testing.assert_array_equal(copy.displacement, solution.displacement)
    if not model.batch_shape:
        times = np.array([0.5, 1.5])
        np.testing.assert_array_equal(np.asarray(copy(times)), np.asarray(solution(times)))
    else:  # a batch's full solution of one set runs again in the copy
        np.testing.assert_array_equal(copy[1].displacement, solution[1].displacement)


def test_study_and_ensemble_on_a_process_pool():
    records = _records()
    block = bd.SlidingBlock(mu=0.1)
    here = bd.simulate(block, records, scale=[0.5, 1.0])
    table_here = bd.study(records, mu=[0.1, 0.2], scale=[1.0])
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        there = bd.simulate(block, records, scale=[0.5, 1.0], executor=pool)
        table_there = bd.study(records, mu=[0.1, 0.2], scale=[1.0], executor=pool)
    assert there.to_dataframe().equals(here.to_dataframe())
    assert there[3].motion.metadata["station"] == "b"  # rows: record x scale
    assert table_there.equals(table_here)
