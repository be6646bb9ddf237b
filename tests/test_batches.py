"""Batches from Python: results that remember their inputs, tables, simulate_many,
plots of a batch, crosscheck on batches and at bounds."""

import numpy as np
import pytest

import blockdae as bd
from blockdae.core import _crosscheck
from blockdae.core._sensitivities import finite_differences, step_difference
from blockdae.backends import make_backend


#: the deprecated many-motion functions keep their tests for the release they stay
pytestmark = [pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_many is deprecated:DeprecationWarning"),
              pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_final is deprecated:DeprecationWarning")]


G = 9.81
RESULT_COLUMNS = ["u_end_m", "max_abs_displacement_m", "n_events", "t_end_s"]


def synthetic_records(n=2, samples=300, dt=0.01):
    """Short accelerograms [m/s²] of one length (one compiled shape), named rec0, rec1, ..."""
    rng = np.random.default_rng(7)
    t = dt * np.arange(samples)
    return [bd.Record(3.0 * np.sin(2 * np.pi * (1.5 + k) * t) * np.exp(-t) + rng.normal(0, 0.3, samples),
                      dt, f"rec{k}") for k in range(n)]


GRID = bd.SlidingBlock(np.array([0.1, 0.15, 0.2]), np.array([0.08, 0.15, 0.12]), bias=np.array([0.0, 0.02, -0.03]))


# ---- results remember their inputs ----------------------------------------------------

def test_solution_and_batch_remember_block_and_motion():
    block, motion = bd.SlidingBlock(0.2, bias=0.05), bd.SinePulse(5.0, 0.5)
    sol = bd.simulate(block, motion)
    assert sol.block is block and sol.motion is motion
    batch = bd.simulate(GRID, motion)
    assert batch.block is GRID and batch.motion is motion
    one = batch[1]
    assert (one.block.mu, one.block.mu_kinetic, one.block.bias) == (0.15, 0.15, 0.02) and one.motion is motion
    assert one.displacement == pytest.approx(bd.simulate(GRID.item(1), motion).displacement, rel=1e-12)


def test_backends_called_directly_still_build_results_without_block():
    """The constructors keep their keyword signatures: block and motion default to None."""
    from blockdae.backends import Horizon

    motion = bd.SinePulse(5.0, 0.5)
    sol = make_backend("exact").solve(bd.SlidingBlock(0.2), motion, Horizon(None))
    batch = make_backend("exact").solve_batch(GRID, motion, Horizon(None))
    assert sol.block is None and batch.block is None and batch[0].block is None
    assert list(batch.to_dataframe().columns) == RESULT_COLUMNS
    assert batch.parameters() == {}


# ---- tables -------------------------------------------------------------------------

def test_solution_table_has_one_row_per_event():
    sol = bd.simulate(bd.SlidingBlock(0.2, 0.15), bd.Harmonic(3.0, 1.0), t_end=3.0)
    df = sol.to_dataframe()
    assert list(df.columns) == ["t_s", "mode_before", "mode_after", "u_m", "v_m_s"]
    assert len(df) == len(sol.events) > 4
    np.testing.assert_array_equal(df["t_s"], sol.t_events)
    np.testing.assert_array_equal(df["u_m"], [e.u for e in sol.events])
    assert list(df["mode_after"]) == [e.mode_after.name for e in sol.events]
    empty = bd.simulate(bd.SlidingBlock(0.9), bd.SinePulse(1.0, 0.5)).to_dataframe()
    assert len(empty) == 0 and list(empty.columns) == list(df.columns)


def test_batch_table_rows_equal_one_by_one_runs():
    motion = bd.Harmonic(2.0, 1.0)
    df = bd.simulate(GRID, motion, t_end=4.0).to_dataframe()
    assert list(df.columns) == ["mu", "mu_kinetic", "bias", "g_m_s2", "direction"] + RESULT_COLUMNS
    for i, row in df.iterrows():
        sol = bd.simulate(GRID.item(i), motion, t_end=4.0)
        assert (row["mu"], row["mu_kinetic"], row["bias"]) == (GRID.mu[i], GRID.mu_kinetic[i], GRID.bias[i])
        assert row["n_events"] == len(sol.events)
        assert row["u_end_m"] == pytest.approx(sol.displacement, rel=1e-12, abs=1e-15)
        assert row["max_abs_displacement_m"] == pytest.approx(sol.max_abs_displacement, rel=1e-12, abs=1e-15)
        assert row["t_end_s"] == 4.0
    assert set(df["g_m_s2"]) == {GRID.g} and set(df["direction"]) == {"both"}


def test_kinetic_column_is_the_friction_in_effect():
    df = bd.simulate(bd.SlidingBlock(np.array([0.1, 0.2])), bd.SinePulse(3.0, 0.5)).to_dataframe()
    np.testing.assert_array_equal(df["mu_kinetic"], [0.1, 0.2])


# ---- simulate_many ------------------------------------------------------------------

def test_records_times_scales_times_grid_equal_one_by_one_runs():
    records = synthetic_records()
    sweep = bd.sliding.simulate_many(GRID, records, scale=[1.0, 2.0, -1.0])
    assert sweep.shape == (2, 3, 3) and sweep.names == ("rec0", "rec1")
    df = sweep.to_dataframe()
    assert list(df.columns) == ["record", "scale", "pga_m_s2", "mu", "mu_kinetic", "bias", "g_m_s2",
                                "direction"] + RESULT_COLUMNS
    assert len(df) == 18
    for i, record in enumerate(records):
        for j, k in enumerate([1.0, 2.0, -1.0]):
            for n in range(3):
                row = df.iloc[(i * 3 + j) * 3 + n]
                sol = bd.simulate(GRID.item(n), record.scaled(k))
                assert (row["record"], row["scale"], row["mu"]) == (record.name, k, GRID.mu[n])
                assert row["pga_m_s2"] == pytest.approx(abs(k) * record.peak_acceleration, rel=1e-15)
                assert row["u_end_m"] == pytest.approx(sol.displacement, rel=1e-12, abs=1e-15)
                assert row["n_events"] == len(sol.events)
                assert sweep.displacement[i, j, n] == row["u_end_m"]
    assert np.all(sweep.n_events > 0)
    assert sweep[1, 2].motion.peak_acceleration == pytest.approx(records[1].peak_acceleration)


def test_target_pga_against_the_rectangular_pulse_closed_form():
    """Seed 000 Eq. 14 (f = mu, no bias): u = A g t0²/2 (1 - A/mu) for a pulse of A g;
    the motions are scaled to each target peak A g (pga [g], one g = the block's g) whatever
    their own amplitude."""
    t0, mu = 0.5, np.array([0.2, 0.3, 0.4])
    motions = {"small": bd.RectangularPulse(1.0, t0), "large": bd.RectangularPulse(-7.0, t0)}
    A = np.array([0.5, 0.8])
    sweep = bd.sliding.simulate_many(bd.SlidingBlock(mu, g=G), motions, pga=A)
    assert sweep.names == ("small", "large")
    np.testing.assert_allclose(sweep.scale, [A * G / 1.0, A * G / 7.0], rtol=1e-15)
    expected = A[:, None] * G * t0**2 / 2 * (1 - A[:, None] / mu)
    np.testing.assert_allclose(sweep.displacement[0], expected, rtol=1e-12)
    np.testing.assert_allclose(sweep.displacement[1], -expected, rtol=1e-12)  # the pulse points the other way
    np.testing.assert_allclose(sweep.to_dataframe()["pga_m_s2"], np.repeat(np.tile(A * G, 2), 3), rtol=1e-15)


def test_pga_is_in_g_and_equals_scaling_the_record():
    """simulate_many(pga=[0.3]) is the record scaled to a peak of 0.3 g (was m/s²: 0 m);
    pga_rounding="slammer" scales by 0.3 / (the record's peak rounded to 0.001 g)."""
    record, block = synthetic_records(n=1)[0], bd.SlidingBlock(0.1, g=bd.STANDARD_GRAVITY)
    sweep = bd.sliding.simulate_many(block, [record], pga=[0.3])
    scaled = record.scaled(0.3 * bd.STANDARD_GRAVITY / record.peak_acceleration)
    assert sweep.displacement[0, 0, 0] == bd.simulate(block, scaled).displacement != 0.0
    assert sweep[0, 0].motion.peak_acceleration == pytest.approx(0.3 * bd.STANDARD_GRAVITY, rel=1e-15)
    own = round(record.peak_acceleration / bd.STANDARD_GRAVITY, 3)
    assert own != record.peak_acceleration / bd.STANDARD_GRAVITY  # the rounding matters here
    slammer = bd.sliding.simulate_many(block, [record], pga=0.3, pga_rounding="slammer")
    assert slammer.scale[0, 0] == 0.3 / own
    assert slammer.displacement[0, 0, 0] == bd.simulate(block, record.scaled(0.3 / own)).displacement


def test_one_parameter_set_is_a_grid_of_one():
    motion = bd.SinePulse(5.0, 0.5)
    sweep = bd.sliding.simulate_many(bd.SlidingBlock(0.2), [motion])
    assert sweep.shape == (1, 1, 1)
    assert sweep.displacement[0, 0, 0] == pytest.approx(bd.simulate(bd.SlidingBlock(0.2), motion).displacement,
                                                         rel=1e-12)
    assert sweep.names == (repr(motion),)


@pytest.mark.parametrize("args, kwargs, error, match", [
    ((bd.SinePulse(5.0, 0.5),), {}, TypeError, "sequence"),
    (([],), {}, ValueError, "empty"),
    (([np.zeros(3)],), {}, TypeError, "ndarray"),
    (([bd.SinePulse(5.0, 0.5)],), dict(scale=1.0, pga=2.0), ValueError, "not both"),
    (([bd.SinePulse(5.0, 0.5)],), dict(pga=[2.0, -1.0]), ValueError, "positive"),
    (([bd.SinePulse(5.0, 0.5)],), dict(scale=[[1.0]]), ValueError, "1-D"),
    (([bd.SinePulse(0.0, 0.5)],), dict(pga=2.0), ValueError, "motion 0: pga needs a motion with a nonzero peak"),
    (([bd.SinePulse(5.0, 0.5)],), dict(pga=[0.3, 9.81]), ValueError,
     r"pga=9\.81 g is implausible .* looks like m/s² \(9\.81 m/s² = 1 g\): give pga in g"),
    (([bd.SinePulse(5.0, 0.5)],), dict(pga=0.3, pga_rounding="nearest"), ValueError,
     r"pga_rounding must be one of \('exact', 'slammer'\), got 'nearest'"),
])
def test_bad_sweeps_are_named(args, kwargs, error, match):
    with pytest.raises(error, match=match):
        bd.sliding.simulate_many(bd.SlidingBlock(0.2), *args, **kwargs)


# ---- plot of a batch ----------------------------------------------------------------

@pytest.fixture
def pyplot():
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    yield plt
    plt.close("all")


def test_plot_of_a_batch_is_against_the_varied_parameter(pyplot):
    mu = np.array([0.1, 0.2, 0.3])
    batch = bd.simulate(bd.SlidingBlock(mu, bias=0.02), bd.SinePulse(5.0, 0.5))  # mu_kinetic follows mu
    ax = bd.plot(batch, title="grid").axes[0]
    assert ax.get_xlabel() == "static friction coefficient mu [-]"
    assert ax.get_ylabel() == "relative displacement (signed) [m]"
    line = next(line for line in ax.lines if line.get_label() == "u(t_end)")
    np.testing.assert_array_equal(line.get_xdata(), mu)
    np.testing.assert_array_equal(line.get_ydata(), batch.displacement)


def test_plot_of_a_batch_with_several_varied_parameters_is_against_the_index(pyplot):
    batch = bd.simulate(GRID, bd.SinePulse(5.0, 0.5))
    ax = bd.plot(batch).axes[0]
    assert ax.get_xlabel() == "parameter set (mu, mu_kinetic, bias vary)"
    line = next(line for line in ax.lines if line.get_label() == "max |u|")
    np.testing.assert_array_equal(line.get_xdata(), [0, 1, 2])
    np.testing.assert_array_equal(line.get_ydata(), batch.max_abs_displacement)


# ---- crosscheck -----------------------------------------------------------------------

def test_one_sided_difference_is_second_order_exact():
    """On a quadratic, u(x) = 3 x² - 2 x, a second-order difference is exact: from
    either side of a bound, and central away from one."""
    u = lambda x: 3 * x**2 - 2 * x
    x0, h = 0.7, 0.01

    def bounded(limit_side):
        def change(s):
            if s * limit_side > 0:
                raise ValueError("beyond the bound")
            return (x0 + s * h,)
        return change

    for change in (bounded(+1), bounded(-1), lambda s: (x0 + s * h,)):
        assert step_difference(u, change) / h == pytest.approx(6 * x0 - 2, rel=1e-12)

    def never_valid(s):
        if s:
            raise ValueError("beyond the bound")
        return (x0,)

    with pytest.raises(ValueError, match="no step"):
        step_difference(u, never_valid)


def test_kinetic_friction_at_its_bound_is_differenced_from_below():
    """mu_kinetic = mu: the step above mu is refused, so the difference is one-sided.
    Reference: the differentiated exact kernel."""
    block, motion = bd.SlidingBlock(0.3, 0.3, bias=0.05), bd.SinePulse(6.0, 0.5)
    kernel = bd.sensitivities(block, motion, wrt=("mu", "mu_kinetic", "bias"))
    differences = finite_differences(block, motion, wrt=("mu", "mu_kinetic", "bias"), backend="exact", step=1e-5)
    assert kernel["mu_kinetic"] > 1.0
    np.testing.assert_allclose(differences["mu_kinetic"], kernel["mu_kinetic"], rtol=1e-8)
    np.testing.assert_allclose(differences["bias"], kernel["bias"], rtol=1e-8)
    assert abs(differences["mu"]) < 1e-8 and abs(kernel["mu"]) < 1e-12  # f = mu held: mu only sets the onset


def test_crosscheck_at_the_kinetic_bound():
    block, motion = bd.SlidingBlock(0.3, 0.3, bias=0.05), bd.SinePulse(6.0, 0.5)
    table = bd.crosscheck(block, motion, backends=("exact", "cvode", "ida"), wrt=("mu_kinetic",), rtol=1e-11)
    for backend in ("cvode", "ida"):
        assert table.row(backend)["rel_dsens"] < 1e-6


def test_crosscheck_times_a_first_and_a_warm_call(monkeypatch):
    calls = []

    def counting(*args, **kwargs):
        calls.append(kwargs["backend"])
        return bd.simulate(*args, **kwargs)

    monkeypatch.setattr(_crosscheck, "simulate", counting)
    table = bd.crosscheck(bd.SlidingBlock(0.3), bd.SinePulse(6.0, 0.5), backends=("exact", "cvode"))
    assert calls == ["exact", "exact", "cvode", "cvode"]
    for row in table.rows:
        assert row["first"] > 0 and row["warm"] > 0 and "wall" not in row
    head = str(table).splitlines()[0]
    assert "first [s]" in head and "warm [s]" in head and "wall" not in head


def test_crosscheck_of_a_batch_is_one_table_per_parameter_set():
    motion = bd.SinePulse(6.0, 0.5)
    tables = bd.crosscheck(GRID, motion, backends=("exact", "cvode"))
    assert isinstance(tables, list) and len(tables) == 3
    for i, table in enumerate(tables):
        assert isinstance(table, bd.core.CrossCheck)
        assert table.row("exact")["displacement"] == bd.simulate(GRID.item(i), motion).displacement
        assert table.row("cvode")["rel_du"] < 1e-7

