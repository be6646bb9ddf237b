"""bd.simulate over many motions: every model, three records x two scales, one bd.Ensemble
with one table shape; its rows are the single runs (the reference: bd.simulate of that
one scaled motion), final numbers only from one compiled call equal to them."""

import concurrent.futures
import importlib.util
import pathlib

import matplotlib
import numpy as np
import pytest

import blockdae as bd
from conftest import load_sample_record

matplotlib.use("Agg")
G = bd.STANDARD_GRAVITY
ROOT = pathlib.Path(__file__).resolve().parents[1]


def _example_model():
    spec = importlib.util.spec_from_file_location("custom_model", ROOT / "examples" / "custom_model.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.OscillatorOnStop(omega=2 * np.pi * 2.0, zeta=0.2, omega_c=2 * np.pi * 8.0, gap=0.005)


def _segment(stem, start, seconds):
    """``seconds`` [s] of a sample record from ``start`` [s], a record of its own [m/s²]."""
    record = load_sample_record(stem)
    i = int(round(start / record.dt))
    samples = record.acceleration_samples[i:i + int(round(seconds / record.dt)) + 1]
    return bd.Record(samples, record.dt, name=f"{stem} {start:g}-{start + seconds:g} s", units="m/s2")


@pytest.fixture(scope="module")
def three():
    return [_segment("Kobe_1995_TAK-090", 3.0, 4.0), _segment("Northridge_1994_PAC-175", 2.0, 3.0),
            _segment("Imperial_Valley_1979_BCR-230", 4.0, 5.0)]


MODELS = {
    "rigid": (lambda: bd.SlidingBlock(mu=0.1, direction="negative"), None),
    "planar": (lambda: bd.PlanarBlock(mu=0.2), None),
    "spring-supported": (lambda: bd.SpringSupportedMass(frequency=5.0, damping=0.05), "motion"),
    "flexible": (lambda: bd.FlexibleSlidingMass(bd.ShearColumn(height=20.0, vs=200.0, damping=0.05), ky=0.1), "motion"),
    "example": (_example_model, "motion"),
}
#: what every ensemble's table starts with
CASE_COLUMNS = ["record", "scale", "pga_g", "polarity"]
FINAL_COLUMNS = ["max_abs_displacement_m", "n_events", "t_end_s"]


@pytest.mark.parametrize("name", list(MODELS))
def test_every_model_runs_three_records_at_two_scales_into_one_ensemble(name, three):
    """Each model under three records x two scales: an Ensemble of 6 rows whose table has
    the case columns, the displacement states at the end (<state>_end_m) and the final
    numbers; every row equals bd.simulate of that record scaled (its final displacement
    and its events, exactly), and ensemble[i] is that case's full solution."""
    make, t_end = MODELS[name]
    model = make()
    ensemble = bd.simulate(model, three, t_end=t_end, scale=[0.5, 1.5])
    assert isinstance(ensemble, bd.Ensemble) and len(ensemble) == 6 and ensemble.shape == (3, 2, 1)
    table = ensemble.to_dataframe()
    states = [f"{model.state_names[i]}_end_m" for i in model.displacement_states]
    assert list(table.columns) == CASE_COLUMNS + states + FINAL_COLUMNS
    assert list(table["record"]) == [r.name for r in three for _ in range(2)]
    np.testing.assert_array_equal(table["scale"], [0.5, 1.5] * 3)
    for row, (record, scale) in enumerate((r, k) for r in three for k in (0.5, 1.5)):
        one = bd.simulate(model, record.scaled(scale), t_end=None if t_end is None else record.duration)
        np.testing.assert_array_equal(table.loc[row, states].to_numpy(dtype=float), np.atleast_1d(one.displacement))
        assert table.loc[row, "max_abs_displacement_m"] == one.max_abs_displacement
        assert table.loc[row, "n_events"] == len(one.events)
        assert table.loc[row, "pga_g"] == pytest.approx(scale * record.peak_acceleration / G, rel=1e-15)
        np.testing.assert_array_equal(ensemble[row].t_events, one.t_events)
    assert table["max_abs_displacement_m"].max() > 0  # something moved


@pytest.mark.parametrize("grid, backend", [(bd.SlidingBlock(mu=np.array([0.05, 0.1, 0.2]), direction="negative"),
                                            "exact"),
                                           (bd.PlanarBlock(mu=np.array([0.1, 0.2])), "compiled")])
@pytest.mark.parametrize("by", ["scale", "pga"])
def test_final_numbers_from_one_compiled_call_equal_the_full_runs(grid, backend, by, three):
    """final_only=True runs every case in one call of the model's engine; with target PGAs
    (a scaled copy per motion, the polarity a factor -1) its numbers are the full runs'
    bit for bit; with scales (a factor inside the engine) to the rounding of a(t) times
    the factor. Rows index the parameter sets last, with the batch's parameters."""
    given = {"scale": [0.5, 2.0]} if by == "scale" else {"pga": [0.2, 0.4]}
    full = bd.simulate(grid, three, backend=backend, polarity="both", **given)
    final = bd.simulate(grid, three, backend=backend, polarity="both", final_only=True, **given)
    n_sets = grid.batch_shape[0]
    assert final.shape == full.shape == (3, 2, 2, n_sets) and final.solutions is None
    if by == "pga":
        np.testing.assert_array_equal(final.displacement, full.displacement)
    else:
        np.testing.assert_allclose(final.displacement, full.displacement, rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(final.n_events, full.n_events)
    table = final.to_dataframe()
    assert len(table) == 3 * 2 * 2 * n_sets
    np.testing.assert_array_equal(table["set"][:n_sets], np.arange(n_sets))
    np.testing.assert_array_equal(table["mu"][:n_sets], grid.mu)
    assert list(table["polarity"][:2 * n_sets:n_sets]) == ["normal", "inverse"]
    row = 2 * n_sets + 1  # first record, second factor, normal polarity, second set
    one = bd.simulate(grid.item(1), three[0], backend=backend, **{k: v[1] for k, v in given.items()})
    np.testing.assert_array_equal(final[row].t_events, one.t_events)
    if by == "pga":
        inverse = bd.simulate(grid.item(1), three[0], backend=backend, polarity="inverse", pga=given["pga"][1])
        np.testing.assert_array_equal(final[row + n_sets].displacement, inverse.displacement)


def test_a_record_set_carries_its_metadata_and_a_folder_reads_every_record(three, tmp_path):
    """A RecordSet's metadata columns follow the record column; a folder of record files is
    every record in it, by name, with the units its files state."""
    tagged = [bd.Record(r.acceleration_samples, r.dt, name=r.name, units="m/s2", metadata={"magnitude": m})
              for r, m in zip(three, (6.9, 6.7, 6.5))]
    table = bd.simulate(bd.SlidingBlock(mu=0.1), bd.RecordSet(tagged), pga=0.3).to_dataframe()
    columns = list(table.columns)
    assert columns[0] == "record" and columns.index("magnitude") < columns.index("scale")
    np.testing.assert_array_equal(table["magnitude"], [6.9, 6.7, 6.5])
    for name, record in zip("abc", three):
        t = record.dt * np.arange(record.acceleration_samples.size)
        (tmp_path / f"{name}.csv").write_text("time (s), acceleration (m/s2)\n" + "".join(
            f"{x:.17g}, {y:.17g}\n" for x, y in zip(t, record.acceleration_samples)))
    folder = bd.simulate(bd.SlidingBlock(mu=0.1), tmp_path, final_only=True).to_dataframe()
    assert list(folder["record"]) == ["a", "b", "c"]
    direct = bd.simulate(bd.SlidingBlock(mu=0.1), three, final_only=True).to_dataframe()
    np.testing.assert_allclose(folder["u_end_m"], direct["u_end_m"], rtol=1e-12)


def test_an_executor_runs_the_cases_and_gives_the_same_ensemble(three):
    """Cases submitted to an executor (a thread pool here; a Dask client likewise) give the
    ensemble of the run here, row for row."""
    model = bd.SlidingBlock(mu=0.08)
    here = bd.simulate(model, three, scale=[1.0, 2.0], backend="cvode")
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        there = bd.simulate(model, three, scale=[1.0, 2.0], backend="cvode", executor=pool)
    np.testing.assert_array_equal(there.displacement, here.displacement)
    np.testing.assert_array_equal(there.n_events, here.n_events)


def test_one_motion_is_the_solution_and_many_cases_are_an_ensemble(three):
    """One motion at one scale in one polarity is the model's own solution (scaled or
    inverted as asked); a list of one, several scales, both polarities or final_only make
    an ensemble; its figure draws a line per (record, polarity)."""
    block = bd.SlidingBlock(mu=0.1)
    inverted = bd.simulate(block, three[0], scale=2.0, polarity="inverse")
    assert isinstance(inverted, bd.sliding.Solution)
    assert inverted.displacement == bd.simulate(block, three[0].scaled(-2.0)).displacement
    for kwargs in ({"motion": [three[0]]}, {"scale": [1, 2]}, {"polarity": "both"}, {"final_only": True}):
        motion = kwargs.pop("motion", three[0])
        assert isinstance(bd.simulate(block, motion, **kwargs), bd.Ensemble)
    figure = bd.simulate(block, three, pga=[0.2, 0.4], polarity="both").plot()
    assert len(figure.axes[0].lines) == 6 and figure.axes[0].get_xlabel().endswith("[g]")
    assert bd.plot(bd.simulate(block, three, final_only=True)).axes[0].get_ylabel() == "max |displacement| [m]"


def test_bad_cases_are_refused_naming_what_is_wrong(three):
    block = bd.SlidingBlock(mu=0.1)
    with pytest.raises(ValueError, match="give scale or pga, not both"):
        bd.simulate(block, three, scale=1.0, pga=0.3)
    with pytest.raises(ValueError, match=r"polarity must be one of \('normal', 'inverse', 'both'\), got 'up'"):
        bd.simulate(block, three, polarity="up")
    with pytest.raises(ValueError, match=r"pga=9\.81 g is implausible"):
        bd.simulate(block, three, pga=9.81)
    with pytest.raises(ValueError, match=r"t_end must be a time \[s\], \"motion\" \(each motion's own end\) or None"):
        bd.simulate(block, three, t_end="end")
    with pytest.raises(ValueError, match="motions is empty"):
        bd.simulate(block, [])
    with pytest.raises(ValueError, match=r"never comes to rest .*: give t_end \[s\]") as refused:
        bd.simulate(bd.SpringSupportedMass(frequency=5.0, damping=0.05), three)
    assert refused.value.__notes__ == ["in the case Kobe_1995_TAK-090 3-7 s at scale 1, normal polarity"]
    motion = bd.BaseMotion(x=three[0])
    with pytest.raises(ValueError, match="pga scales a motion of one component; for a BaseMotion give scale"):
        bd.simulate(bd.PlanarBlock(mu=0.2), [motion], pga=0.3)
    with pytest.raises(IndexError, match="row 3 is out of range for 3 cases"):
        bd.simulate(block, three)[3]


def test_the_replaced_functions_warn_and_give_the_ensembles_numbers(three):
    """simulate_many and simulate_final (kept one release) warn, naming bd.simulate, and
    give the numbers of the ensemble that replaces them."""
    grid = bd.SlidingBlock(mu=np.array([0.05, 0.1]), direction="negative")
    ensemble = bd.simulate(grid, three, scale=[1.0, 2.0], final_only=True)
    with pytest.warns(DeprecationWarning, match=r"simulate_many is deprecated; use bd\.simulate\(block, motions"):
        sweep = bd.sliding.simulate_many(grid, three, scale=[1.0, 2.0])
    np.testing.assert_array_equal(sweep.displacement, ensemble.displacement[:, :, 0])
    with pytest.warns(DeprecationWarning, match=r"simulate_final is deprecated; use bd\.simulate\(block, motions, "
                                                r"scale=\.\.\., final_only=True\)"):
        final = bd.sliding.simulate_final(grid, three, scale=[1.0, 2.0])
    np.testing.assert_array_equal(np.moveaxis(final.displacement, -1, 1), ensemble.displacement[:, :, 0])
