"""The compiled matrix-exponential engine of the flexible sliding mass's slides
(``flexible_mass/_table_kernel.py``, issue 22): a ky table and an overdamped coupled slip in
``bd.flexible``'s rows. Reference: the Python engine of the same mathematics run by the
generic driver (``solve_table_exact``), itself checked against DOP853 in
tests/test_flexible_ky_table.py and tests/test_flexible_damped.py; the no-sliding response
against its closed form. Observed on these
cases: event times within 1.4e-15 s, displacements within 6e-15 relative (on the 7,348-sample
Imperial Valley record with these tables and totals: 9e-15 s and 6e-14)."""

import numpy as np
import pytest

import blockdae as bd
from blockdae.backends import Horizon
from blockdae.flexible_mass import FlexibleSlidingMass, KyTable, ShearColumn
from blockdae.flexible_mass._analysis import with_zero_sample
from blockdae.flexible_mass._damped_slip import flat_table_model
from blockdae.flexible_mass._table_engine import (record_pieces, response_compiled, slide_compiled, solve_table_exact,
                                             system_arrays)
from blockdae.flexible_mass._table_kernel import OUTCOME_FIELDS, step_slots
from conftest import load_sample_record


#: the columns here are damped beyond soil on purpose (overdamped and near-critical modes): the
#: plausibility warning on a damping ratio above 30 % is expected
pytestmark = pytest.mark.filterwarnings("ignore:damping=.* is a damping ratio of:blockdae.UnitsWarning")


#: ky falls from 0.1 g to 0.05 g over the first 2 cm of sliding; rises from 0.08 g to 0.14 g over 4 cm
SOFTENING = KyTable([0.005, 0.01, 0.02], [0.1, 0.08, 0.05])
HARDENING = KyTable([0.0, 0.01, 0.04], [0.08, 0.1, 0.14])
#: a decade above the agreement measured on these cases (1.4e-15 s, 6e-15 relative; on
#: Imperial Valley BCR-230 9e-15 s and 6e-14)
EVENT_TOLERANCE, DISPLACEMENT_TOLERANCE = 1.4e-14, 6e-14  # [s], relative


def _record(duration=8.0):
    """Northridge PAC-175 (dt 0.02 s), its first ``duration`` [s]."""
    record = load_sample_record("Northridge_1994_PAC-175")
    return bd.Record(record.acceleration_samples[:int(round(duration / record.dt)) + 1], record.dt,
                     name=record.name, units="m/s2")


def _table_model(table, method):
    return FlexibleSlidingMass(ShearColumn(10.0, 250.0), ky=table, method=method)


def _damped_model(total, method):
    """A 10 m column, vs 250 m/s, total damping ``total`` (no impedance), ky 0.05 g, as the
    table engine takes it (a flat one-piece table)."""
    return flat_table_model(FlexibleSlidingMass(ShearColumn(10.0, 250.0, damping=total, impedance=False), ky=0.05,
                                                method=method))


def _compare(model, motion, t_end):
    """The kernel against ``solve_table_exact`` on ``motion`` to ``t_end`` [s]: the same
    events (modes, times within 1e-12 s, s within 1e-12 relative) and final s; returns
    (the Python solution, the kernel's outcome as a dict)."""
    horizon = Horizon(t_end)
    solution = solve_table_exact(model, motion, horizon, "exact")
    _, arrays = record_pieces(motion, horizon, "the test")
    outcome, log = slide_compiled(system_arrays(model), arrays, log_rows=1000)
    outcome = dict(zip(OUTCOME_FIELDS, outcome))
    assert [(int(e.mode_before), int(e.mode_after)) for e in solution.events] == \
        [(int(b), int(a)) for b, a in log[:, 1:3]]
    np.testing.assert_allclose(log[:, 0], solution.t_events, rtol=0, atol=EVENT_TOLERANCE)
    np.testing.assert_allclose(log[:, 5], [e.s for e in solution.events], rtol=DISPLACEMENT_TOLERANCE, atol=1e-15)
    assert outcome["s"] == pytest.approx(solution.sliding_displacement, rel=DISPLACEMENT_TOLERANCE)
    assert outcome["n_onsets"] == sum(e.kind == "onset" for e in solution.events)
    assert outcome["t"] == solution.t[-1]
    return solution, outcome


@pytest.mark.parametrize("table, method", [(SOFTENING, "coupled"), (SOFTENING, "decoupled"),
                                           (HARDENING, "coupled"), (HARDENING, "decoupled")])
def test_kernel_matches_the_python_engine_on_a_ky_table(table, method):
    """Both polarities (the record times -1); at least two breakpoints crossed."""
    record = _record()
    for motion in (record, record.scaled(-1.0)):
        solution, outcome = _compare(_table_model(table, method), motion, 8.0)
        assert sum(e.kind == "breakpoint" for e in solution.events) >= 2 and outcome["n_onsets"] >= 3


@pytest.mark.parametrize("total", [0.4353, 0.5, 0.9])
@pytest.mark.parametrize("method", ["coupled", "decoupled"])
def test_kernel_matches_the_python_engine_on_an_overdamped_slip(total, method):
    """Totals just above the coupled slip's critical damping (sqrt(d1) = 0.43524), well
    above, and near 1; both polarities."""
    record = _record()
    for motion in (record, record.scaled(-1.0)):
        _, outcome = _compare(_damped_model(total, method), motion, 8.0)
        assert outcome["n_onsets"] >= 4


def test_kept_transitions_agree_with_transitions_applied_to_the_vector():
    """With no whole-step length kept (every slot -1) each step's transition is applied to
    the vector (Taylor passes) instead of a kept matrix: the same events within 1e-12 s."""
    motion = with_zero_sample(_record())
    horizon = Horizon(8.0 + motion.dt)
    _, arrays = record_pieces(motion, horizon, "the test")
    systems = system_arrays(_table_model(SOFTENING, "coupled"))
    kept, kept_log = slide_compiled(systems, arrays, log_rows=1000)
    applied, applied_log = slide_compiled(systems, arrays, log_rows=1000, slots=np.full(len(arrays[0]), -1))
    assert kept_log.shape == applied_log.shape and kept_log.shape[0] >= 8
    np.testing.assert_allclose(applied_log[:, 0], kept_log[:, 0], rtol=0, atol=EVENT_TOLERANCE)
    assert applied[OUTCOME_FIELDS.index("s")] == pytest.approx(kept[OUTCOME_FIELDS.index("s")], rel=1e-12)


@pytest.mark.parametrize("ky, damping", [(SOFTENING, 0.05), (0.05, 0.3)])
def test_flexible_rows_run_the_kernel(ky, damping):
    """bd.flexible's rows (SLAMMER's virtual zero sample, both polarities) of a table and
    of a coupled total damping of 0.5 (0.3 + 0.2 impedance) against solve_table_exact on
    the record with its zero sample: displacements within 1e-12 relative, the same
    episode counts."""
    record = _record()
    row = bd.flexible(record, ky=ky, height=10.0, vs=250.0, damping=damping).rows[0]
    model = FlexibleSlidingMass(ShearColumn(10.0, 250.0, damping=damping), ky=ky)
    if model.table is None:
        assert model.damping == pytest.approx(0.5)
        model = flat_table_model(model)
    padded = with_zero_sample(record)
    for polarity, motion in (("normal", padded), ("inverse", padded.scaled(-1.0))):
        solution = solve_table_exact(model, motion, Horizon(record.duration + record.dt), "exact")
        assert row[f"{polarity}_m"] == pytest.approx(solution.sliding_displacement, rel=DISPLACEMENT_TOLERANCE)
        assert row[f"episodes_{polarity}"] == sum(e.kind == "onset" for e in solution.events) >= 3


@pytest.mark.parametrize("total", [0.25, 1 - 1e-9])
def test_no_sliding_response_on_matrix_exponentials_matches_the_closed_form(total):
    """The kernel's no-sliding response (used for a total damping next to 1) vs the closed
    form (tests/test_flexible.py's ``no_sliding_reference``, mpmath at the samples, extrema
    refined by brentq) on 12 s of Northridge PAC-175 with SLAMMER's zero sample: max |HEA|
    at the samples, its supremum over time and sup |u| within 1e-13 relative (measured
    2.6e-15; DOP853, the reference before it, was 1.4e-13 off)."""
    from test_flexible import CLOSED_FORM_BAR, _with_zero_sample, no_sliding_reference

    record = _record(12.0)
    model = FlexibleSlidingMass(ShearColumn(10.0, 250.0, damping=total, impedance=False), ky=0.1)
    _, arrays = record_pieces(with_zero_sample(record), Horizon(12.0 + record.dt), "the test")
    samples, sup, u_sup = response_compiled(model, arrays, step_slots(arrays[0], arrays[1]), True)
    hea_samples, hea_sup, u_reference = no_sliding_reference(_with_zero_sample(record), record.dt, model.omega,
                                                             model.damping, 12.0 + record.dt)
    assert samples == pytest.approx(hea_samples.max(), rel=CLOSED_FORM_BAR)
    assert sup == pytest.approx(hea_sup, rel=CLOSED_FORM_BAR) and sup > samples
    assert u_sup == pytest.approx(u_reference, rel=CLOSED_FORM_BAR)
