"""The block on a plane in blockdae.design (design.Planar): each sample against
bd.simulate of a PlanarBlock run alone, the friction coefficient above which nothing
slides against its closed form, a study that stops by its rule, and the inverses over mu
checked by the forward analysis at the mu they return (the allowable reproduced to 1e-6
relative, as for the rigid block and the flexible mass)."""

import numpy as np
import pytest

import blockdae as bd
import blockdae.design as dz
from test_design import RECORDS

ALLOWABLE = 0.05  # m
BIAS = -0.03  # a downslope pull along -x of 3 % of the weight [-]: the block slides one way


def _alone(record, mu, pga, polarity="normal", bias_x=BIAS, final_only=True):
    """D [m], the final |u|, of one PlanarBlock run alone by bd.simulate (compiled engine)."""
    block = bd.PlanarBlock(mu=float(mu), bias=(float(bias_x), 0.0))
    if final_only:
        u = bd.simulate(block, [record], pga=[pga], polarity=polarity, final_only=True,
                        backend="compiled").displacement[0, 0, 0]
    else:
        u = bd.simulate(block, record, pga=pga, polarity=polarity, backend="compiled").displacement
    return float(np.hypot(*u))


def test_each_sample_is_the_block_run_alone():
    """A study's D of a few samples equal, to the last bit, the final |u| of a PlanarBlock
    of that mu and bias run alone by bd.simulate, with final numbers only and as a full
    solution (the same compiled engine: a batch runs each set as it runs one)."""
    parameters = {"mu": dz.LogNormal(mean=0.15, cov=0.3), "bias_x": dz.Uniform(-0.03, 0.0)}
    result = dz.exceedance(RECORDS, dz.Planar(polarity="larger"), parameters, pga=0.4, threshold=0.05, runs=8,
                           runs_per_block=8)
    assert list(result.table.columns) == ["run", "record", "pga_g", "mu", "bias_x", "D_m"]
    assert result.table["mu"].nunique() == len(result.table)
    for row in result.table.iloc[[0, 5, 11]].itertuples():
        both = [_alone(RECORDS[row.record], row.mu, 0.4, p, row.bias_x) for p in ("normal", "inverse")]
        assert row.D_m == max(both) > 0
        full = max(_alone(RECORDS[row.record], row.mu, 0.4, p, row.bias_x, final_only=False)
                   for p in ("normal", "inverse"))
        assert full == row.D_m
    assert "friction coefficient mu" in result.ky_figure().axes[0].get_xlabel()


def test_nothing_slides_above_the_largest_friction_demand():
    """Closed form: the block sticks while |a(t) - bias g| <= mu g (a level plane, no
    vertical shaking), a(t) linear between samples: D = 0 at mu = max_i |s a_i - b_x g| / g
    and D > 0 just below it."""
    record = RECORDS["first"]
    model = dz.Planar()
    s = 0.4 * bd.STANDARD_GRAVITY / np.max(np.abs(record.acceleration_samples))
    limit = np.max(np.abs(s * record.acceleration_samples - BIAS * bd.STANDARD_GRAVITY)) / bd.STANDARD_GRAVITY
    values = {"mu": np.array([0.1]), "bias_x": np.array([BIAS])}
    assert model.sliding_limit(record, 0.4, values)[0] == pytest.approx(limit, rel=1e-15)
    d = model.displacements(record, 0.4, {"mu": np.array([limit, limit * (1 - 1e-6)]), "bias_x": np.full(2, BIAS)})
    assert d[0] == 0 and d[1] > 0


def test_a_planar_study_stops_by_its_rule():
    """The relative standard error of the mean D falls to the bar at the last block, not before."""
    parameters = {"mu": dz.LogNormal(mean=0.15, cov=0.3), "bias_x": BIAS}
    result = dz.exceedance(RECORDS, dz.Planar(), parameters, pga=0.4, threshold=0.05, rse=0.1, runs_per_block=8)
    history = result.history
    assert result.converged and history["rse"].iloc[-1] <= 0.1
    assert (history["rse"].iloc[:-1] > 0.1).all()
    assert len(result.table) == history["analyses"].iloc[-1] == 2 * history["runs"].iloc[-1]


def test_mu_for_an_allowable_displacement_and_a_percentile():
    """The mu of one record, and the mu whose median and 84th percentile of D over the
    records (numpy's linear interpolation) equal the allowable, rerun alone."""
    mu = dz.ky_for_displacement(RECORDS["first"], dz.Planar(), {"bias_x": BIAS}, ALLOWABLE, pga=0.4)
    assert abs(BIAS) < mu < 0.45
    assert _alone(RECORDS["first"], mu, 0.4) == pytest.approx(ALLOWABLE, rel=1e-6)
    pga = {"first": 0.4, "second": 0.3}
    for percentile in (50.0, 84.0):
        mu = dz.ky_for_percentile(RECORDS, dz.Planar(), {"bias_x": BIAS}, ALLOWABLE, percentile=percentile, pga=pga)
        d = [_alone(r, mu, pga[n]) for n, r in RECORDS.items()]
        assert np.percentile(d, percentile) == pytest.approx(ALLOWABLE, rel=1e-6)
        assert min(d) < ALLOWABLE < max(d)


def test_mean_mu_for_a_target_probability():
    """At the returned mean mu (each sample's mu its ratio times the mean: the common
    random numbers), rerun alone: at most the target fraction exceed the allowable, one
    sample sits on it (to 1e-6), and just below the mean more than the target exceed."""
    target = 0.2
    design = dz.mean_ky_for_probability(RECORDS, dz.Planar(), {"mu": dz.LogNormal(mean=0.15, cov=0.3),
                                                               "bias_x": BIAS},
                                        ALLOWABLE, target, pga=0.4, runs=8, seed=2)
    assert design.parameter == "mu" and "critical_mean_mu" in design.table
    records, ratio = design.table["record"].to_numpy(), design.table["mu_ratio"].to_numpy()

    def displacements(mean):
        return np.array([_alone(RECORDS[r], k, 0.4) for r, k in zip(records, ratio * mean)])

    d = displacements(design.mean)
    assert np.sum(d > ALLOWABLE * (1 + 1e-6)) <= np.floor(target * d.size)
    assert np.min(np.abs(d / ALLOWABLE - 1)) < 1e-6
    assert np.mean(displacements(design.mean * (1 - 1e-5)) > ALLOWABLE) > target
    assert design.probability(design.mean) <= target < design.probability(design.mean * (1 - 1e-5))
    with pytest.raises(AttributeError, match="read .mean"):
        design.mean_ky_g


def test_planar_inputs_are_checked():
    with pytest.raises(ValueError, match="mu_kinetic=0.02 must exceed"):
        dz.Planar().displacements(RECORDS["first"], 0.4, {"mu": np.array([0.1]), "mu_kinetic": np.array([0.02]),
                                                          "bias_x": np.array([BIAS])})
    with pytest.raises(ValueError, match="'ky' is not one of the planar model's"):
        dz.exceedance(RECORDS, dz.Planar(), {"ky": 0.1}, threshold=0.1, runs=2)
    with pytest.raises(ValueError, match="no mu is needed"):
        dz.ky_for_displacement(RECORDS["first"], dz.Planar(), {"bias_x": BIAS}, 50.0, pga=0.1)
    with pytest.raises(ValueError, match="polarity"):
        dz.Planar(polarity="both")


def _three_components():
    """Decaying sines along x, y and z [m/s²] (peaks 3, 2 and 1.5 m/s²: the base never
    falls faster than g), one step of 0.01 s."""
    t = np.arange(600) * 0.01
    return bd.BaseMotion.from_samples(3.0 * np.sin(2 * np.pi * 1.5 * t) * np.exp(-0.4 * t),
                                      2.0 * np.sin(2 * np.pi * 1.1 * t + 0.7) * np.exp(-0.3 * t),
                                      1.5 * np.sin(2 * np.pi * 3.0 * t) * np.exp(-0.5 * t), dt=0.01, name="three")


def test_a_base_motion_of_three_components():
    """Each sample against the PlanarBlock run alone on the same BaseMotion (bit for bit);
    the friction limit against its closed form |(a_x - b_x g, a_y - b_y g)| / (g + a_z) at
    the samples (D = 0 there, D > 0 just below); the mu for an allowable D rerun alone
    (1e-6 relative)."""
    motion, bias = _three_components(), (BIAS, 0.01)
    result = dz.exceedance({"three": motion}, dz.Planar(), {"mu": dz.LogNormal(mean=0.15, cov=0.3), "bias_x": bias[0],
                                                             "bias_y": bias[1]}, threshold=0.05, runs=4,
                           runs_per_block=4)
    for row in result.table.itertuples():
        solution = bd.simulate(bd.PlanarBlock(mu=row.mu, bias=bias), motion, backend="compiled")
        assert row.D_m == float(np.hypot(*solution.displacement)) > 0
    g = bd.STANDARD_GRAVITY
    a_x, a_y, a_z = (c.acceleration_samples for c in motion.components)
    limit = np.max(np.hypot(a_x - bias[0] * g, a_y - bias[1] * g) / (g + a_z))
    values = {"mu": np.array([limit, limit * (1 - 1e-6)]), "bias_x": np.full(2, bias[0]), "bias_y": np.full(2, bias[1])}
    assert dz.Planar().sliding_limit(motion, None, values)[0] == pytest.approx(limit, rel=1e-15)
    d = dz.Planar().displacements(motion, None, values)
    assert d[0] == 0 and d[1] > 0
    mu = dz.ky_for_displacement(motion, dz.Planar(), {"bias_x": bias[0], "bias_y": bias[1]}, ALLOWABLE)
    solution = bd.simulate(bd.PlanarBlock(mu=mu, bias=bias), motion, backend="compiled")
    assert float(np.hypot(*solution.displacement)) == pytest.approx(ALLOWABLE, rel=1e-6)


def test_a_base_motion_is_taken_as_given_and_by_the_plane_only():
    motion = _three_components()
    with pytest.raises(ValueError, match="a target PGA scales a record of one component"):
        dz.exceedance(motion, dz.Planar(), {"mu": 0.2}, pga=0.3, threshold=0.1, runs=2)
    with pytest.raises(ValueError, match="must be a Record, got BaseMotion"):
        dz.exceedance(motion, dz.Rigid(), {"ky": 0.2}, threshold=0.1, runs=2)
