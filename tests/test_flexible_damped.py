"""A coupled flexible sliding mass whose slip is overdamped or critically damped (issue
22: any total damping in (0, 1)): xi / sqrt(d1) >= 1, total damping xi >= sqrt(d1) =
0.4352; its slides run on the matrix-exponential engine (ky a flat one-piece table).
Checked against an independent DOP853 integration of section 8 (tests/test_flexible.py's
``reference``, restarted at every sample and event; its error measured there), the
closed-form no-sliding response, CVODE, the compiled engine just below the switch, and
bd.study."""

import math

import numpy as np
import pytest

import blockdae as bd
from blockdae.flexible_mass import FlexibleSlidingMass, ShearColumn
from blockdae.flexible_mass._damped_slip import COMPILED_RESPONSE_LIMIT, COMPILED_SLIP_LIMIT, slip_underdamped
from conftest import assert_same_events, load_sample_record
from test_flexible import (CLOSED_FORM_BAR, SLIDE_BAR, _compare_with_reference, _record, no_sliding_reference,
                           reference)


#: the columns here are damped beyond soil on purpose (overdamped and near-critical modes), one on a
#: rigid base (vr = 1e12 m/s): the plausibility warnings on them are expected
pytestmark = [pytest.mark.filterwarnings("ignore:damping=.* is a damping ratio of:blockdae.UnitsWarning"),
              pytest.mark.filterwarnings("ignore:vr=1e\\+12 m/s is implausible:blockdae.UnitsWarning")]


SQRT_D1 = math.sqrt(1 - 8 / math.pi**2)  # the coupled slip is critically damped at xi = sqrt(d1) = 0.43524


def _mass(total, ky=0.1):
    """A 10 m column, vs 250 m/s, total damping ``total`` (no impedance damping added)."""
    return FlexibleSlidingMass(ShearColumn(10.0, 250.0, damping=total, impedance=False), ky=ky)


@pytest.mark.parametrize("total", [0.5, 0.4353, 0.9])
def test_overdamped_slip_matches_dop853(total):
    """bd.simulate's exact backend vs DOP853 (tests/test_flexible.py's bars; the reference's
    errors here: 5.6e-14 s, 1.2e-13 of s): the same onsets and stops, s(t_end) and u(t_end)
    (0.4353 is just above critical: xi / sqrt(d1) = 1.00016)."""
    model = _mass(total, ky=0.05)
    assert not slip_underdamped(model.damping, True)
    sol, _ = _compare_with_reference(_record("Northridge_1994_PAC-175", duration=6.0), model, 6.0, min_events=8)
    assert sol.state.shape[1] == 4 and {e.kind for e in sol.events} == {"onset", "stop"}
    assert len(sol(np.array([1.0, 2.0]))) == 4  # the model's own states (u, u', s, w)


def test_flexible_rows_of_a_heavily_damped_column_match_dop853():
    """bd.flexible (SLAMMER's virtual zero sample at -dt, both polarities) vs DOP853 on the
    record with that zero sample: each polarity's displacement within SLIDE_BAR relative
    (the reference's error: 1.7e-13) and its episodes; ky_g is the constant given."""
    record = _record("Cape_Mendocino_1992_PET-090", duration=4.0)
    row = bd.flexible(record, ky=0.1, height=10.0, vs=250.0, vr=250.0, damping=0.45).rows[0]  # total 0.65
    assert row["ky_g"] == 0.1 and row["damping_final"] == pytest.approx(0.65)
    samples = np.concatenate([[0.0], record.acceleration_samples])
    for polarity, sign in (("normal", 1.0), ("inverse", -1.0)):
        events, y = reference(sign * samples, record.dt, math.pi * 250.0 / 20.0, row["damping_final"],
                                  0.1 * bd.STANDARD_GRAVITY, True, 4.0 + record.dt)
        assert row[f"{polarity}_m"] == pytest.approx(y[2], rel=SLIDE_BAR)
        assert row[f"episodes_{polarity}"] == sum(b == 0 for _, b, _ in events) >= 2


def test_continuous_across_the_switch_of_engines():
    """Totals just below and just above the switch (xi / sqrt(d1) = 1 - 2e-6 on the
    compiled engine, 1 - 5e-7 on the matrix-exponential one) give displacements within
    1e-5 relative of each other (their damping differs by 1.5e-6 relative)."""
    record = _record("Northridge_1994_PAC-175", duration=6.0)
    below, above = SQRT_D1 * (1 - 2e-6), SQRT_D1 * (1 - 5e-7)
    assert slip_underdamped(below, True) and not slip_underdamped(above, True)
    assert (1 - 2e-6) < COMPILED_SLIP_LIMIT < (1 - 5e-7)
    rows = bd.flexible(record, ky=0.1, height=10.0, vs=250.0, vr=1e12, damping=[below, above]).rows
    for name in ("normal_m", "inverse_m"):
        assert rows[0][name] > 1e-3
        assert rows[1][name] == pytest.approx(rows[0][name], rel=1e-5)
    assert rows[0]["episodes_normal"] == rows[1]["episodes_normal"]


def test_cvode_agrees_with_exact_on_an_overdamped_slip():
    """CVODE on the generic driver (rtol 1e-10): the same onsets and stops within 1.5e-10 s
    and s(t_end) within 3e-9 relative of exact (measured, CVODE and IDA: 1.5e-11 s, 3e-10;
    the bars a decade above)."""
    record = _record("Northridge_1994_PAC-175", duration=6.0)
    model = _mass(0.6)
    exact = bd.simulate(model, record, t_end=6.0)
    sol = bd.simulate(model, record, t_end=6.0, backend="cvode", rtol=1e-10)
    assert len(exact.events) >= 6
    assert_same_events(sol, exact, 1.5e-10)
    assert sol.displacement == pytest.approx(exact.displacement, rel=3e-9)


@pytest.mark.parametrize("damping, message", [(0.8, r"damping=0\.8 gives a total damping ratio of 1\.0"),
                                              (-0.2, r"damping=-0\.2 gives a total damping ratio of 0\.0")])
def test_a_total_damping_outside_0_1_is_still_refused(damping, message):
    """vr = vs adds the impedance damping 0.2: totals 1.0 and 0.0 are refused, naming the field."""
    with pytest.raises(ValueError, match=message):
        bd.flexible(_record("Northridge_1994_PAC-175", duration=2.0), ky=0.1, height=10.0, vs=250.0, damping=damping)


def test_study_runs_a_heavily_damped_column():
    """bd.study with a total damping of 0.5 (0.3 + impedance 0.2): its rows are
    bd.flexible's at the same record, ky and target PGA (independent calls)."""
    record = load_sample_record("Northridge_1994_PAC-175")
    mass = FlexibleSlidingMass(ShearColumn(20.0, 300.0, damping=0.3), ky=0.15)
    table = bd.study([record], ky=[0.1], pga=[0.4], block=mass)
    row = bd.flexible(record, ky=0.1, height=20.0, vs=300.0, damping=0.3, pga=0.4).rows[0]
    assert table["damping_final"][0] == pytest.approx(0.5)
    for name in ("normal_m", "inverse_m"):
        assert table[name][0] == pytest.approx(row[name], rel=1e-12) and row[name] > 0
    assert table["episodes_normal"][0] == row["episodes_normal"]


NEAR_CRITICAL = 1 - 1e-9  # a total damping in [1 - 5e-9, 1): no underdamped closed form for STICK either
assert NEAR_CRITICAL > COMPILED_RESPONSE_LIMIT > 1 - 2e-6


@pytest.mark.parametrize("method", ["coupled", "decoupled"])
def test_a_total_damping_next_to_1_matches_dop853(method):
    """Total damping 1 - 1e-9 (the column critically damped to 1e-9): bd.simulate's exact
    backend (the matrix-exponential engine in both modes) vs DOP853 (tests/test_flexible.py's
    bars; the reference's errors here: 6.8e-14 s, 6.4e-14 of s)."""
    model = FlexibleSlidingMass(ShearColumn(10.0, 250.0, damping=NEAR_CRITICAL, impedance=False), ky=0.05,
                                method=method)
    _compare_with_reference(_record("Northridge_1994_PAC-175", duration=6.0), model, 6.0, min_events=6)


def test_flexible_rows_of_a_total_damping_next_to_1_match_the_references():
    """bd.flexible at a total of 1 - 1e-9 (0.8 - 1e-9 + impedance 0.2): the no-sliding
    response on matrix exponentials (kmax at the samples and its supremum over time within
    CLOSED_FORM_BAR relative of the closed form; measured 8.9e-16, DOP853 before it 1.8e-14
    off) and both polarities' slides (DOP853, SLIDE_BAR relative; the reference's error
    4.2e-14; the same episodes) on the record with SLAMMER's zero sample."""
    record = _record("Northridge_1994_PAC-175", duration=8.0)
    row = bd.flexible(record, ky=0.05, height=10.0, vs=250.0, damping=NEAR_CRITICAL - 0.2).rows[0]
    assert row["damping_final"] == pytest.approx(NEAR_CRITICAL, abs=1e-15)
    samples = np.concatenate([[0.0], record.acceleration_samples])
    omega, t_end = math.pi * 250.0 / 20.0, 8.0 + record.dt
    for polarity, sign in (("normal", 1.0), ("inverse", -1.0)):
        events, y = reference(sign * samples, record.dt, omega, row["damping_final"], 0.05 * bd.STANDARD_GRAVITY,
                              True, t_end)
        assert row[f"{polarity}_m"] == pytest.approx(y[2], rel=SLIDE_BAR)
        assert row[f"episodes_{polarity}"] == sum(b == 0 for _, b, _ in events) >= 2
    hea_samples, hea_sup, _ = no_sliding_reference(samples, record.dt, omega, row["damping_final"], t_end)
    assert row["kmax_g"] == pytest.approx(hea_samples.max() / bd.STANDARD_GRAVITY, rel=CLOSED_FORM_BAR)
    assert row["kmax_sup_g"] == pytest.approx(hea_sup / bd.STANDARD_GRAVITY, rel=CLOSED_FORM_BAR)


def test_equivalent_linear_and_study_from_a_total_damping_next_to_1():
    """The equivalent-linear iteration's first pass at a total of 1 - 1e-9 (sup |u| on
    matrix exponentials): the same final column and rows as a start on the compiled
    response (total 1 - 2e-6; measured 1.0e-8 relative apart) to 1e-7 relative; bd.study
    of that column gives bd.flexible's rows (independent calls)."""
    record = _record("Northridge_1994_PAC-175", duration=8.0)
    rows = bd.flexible(record, ky=0.05, height=10.0, vs=250.0, damping=[NEAR_CRITICAL - 0.2, 1 - 2e-6 - 0.2],
                       equivalent_linear=True, reference_strain=5e-4, method="decoupled").rows
    for name in ("vs_final_m_s", "damping_final", "normal_m", "inverse_m", "kmax_sup_g"):
        assert rows[0][name] == pytest.approx(rows[1][name], rel=1e-7)
    mass = FlexibleSlidingMass(ShearColumn(10.0, 250.0, damping=NEAR_CRITICAL - 0.2), ky=0.1)
    table = bd.study([record], ky=[0.05], pga=[0.3], block=mass)
    row = bd.flexible(record, ky=0.05, height=10.0, vs=250.0, damping=NEAR_CRITICAL - 0.2, pga=0.3).rows[0]
    for name in ("normal_m", "inverse_m", "kmax_g", "kmax_sup_g"):
        assert table[name][0] == pytest.approx(row[name], rel=1e-12) and row[name] > 0
