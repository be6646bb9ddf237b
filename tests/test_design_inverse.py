"""The design inverses of blockdae.design, each checked by the forward analysis at the
ky it returns, run independently (bd.newmark, bd.flexible called directly): the
allowable displacement reproduced to 1e-6 relative."""

import warnings

import numpy as np
import pytest

import blockdae as bd
import blockdae.design as dz
from test_design import RECORDS

ALLOWABLE = 0.05  # m
FLEXIBLE = dz.Flexible(method="coupled", equivalent_linear=True, reference_strain=5e-4)
COLUMN = {"height": 10.0, "vs": 250.0, "vr": 600.0}


def _flexible_d(record, ky, pga=0.4, **column):
    return bd.flexible(record, ky=ky, **(COLUMN | column), equivalent_linear=True, reference_strain=5e-4, pga=pga,
                       polarity="normal")["normal_m"]


@pytest.mark.slow
def test_rigid_ky_for_an_allowable_displacement_by_newton():
    """Newton on the exact dD/dky (its derivative kernel compiles once: about 10 s)."""
    ky = dz.ky_for_displacement(RECORDS["first"], dz.Rigid(), {}, ALLOWABLE, pga=0.4)
    assert 0 < ky < 0.4
    assert float(bd.newmark(RECORDS["first"], ky=ky, pga=0.4, polarity="normal").normal) == pytest.approx(
        ALLOWABLE, rel=1e-6)


def test_flexible_ky_for_an_allowable_displacement():
    ky = dz.ky_for_displacement(RECORDS["first"], FLEXIBLE, COLUMN, ALLOWABLE, pga=0.4)
    assert 0 < ky < 0.6
    assert _flexible_d(RECORDS["first"], ky)[0] == pytest.approx(ALLOWABLE, rel=1e-6)


@pytest.mark.parametrize("percentile", [50.0, 84.0])
def test_ky_whose_percentile_of_d_is_the_allowable(percentile):
    """numpy's percentile (linear interpolation) of D over the records run at the
    returned ky, rigid and flexible."""
    pga = {"first": 0.4, "second": 0.3}
    ky = dz.ky_for_percentile(RECORDS, dz.Rigid(), {}, ALLOWABLE, percentile=percentile, pga=pga)
    d = [float(bd.newmark(r, ky=ky, pga=pga[n], polarity="normal").normal) for n, r in RECORDS.items()]
    assert np.percentile(d, percentile) == pytest.approx(ALLOWABLE, rel=1e-6)
    assert min(d) < ALLOWABLE < max(d)  # the records differ: an interpolated percentile, not one record's root
    ky = dz.ky_for_percentile(RECORDS, FLEXIBLE, COLUMN, ALLOWABLE, percentile=percentile, pga=pga)
    d = [_flexible_d(r, ky, pga=pga[n])[0] for n, r in RECORDS.items()]
    assert np.percentile(d, percentile) == pytest.approx(ALLOWABLE, rel=1e-6)


def _check_mean_design(design, displacements, target):
    """At the returned mean: at most ``target`` of the samples exceed the allowable, one
    sample sits on it (to 1e-6), and just below the mean more than ``target`` exceed."""
    mean = design.mean_ky_g
    ky = design.table["ky_ratio"].to_numpy() * mean
    d = displacements(ky)
    n = d.size
    assert np.sum(d > ALLOWABLE * (1 + 1e-6)) <= np.floor(target * n)
    assert np.min(np.abs(d / ALLOWABLE - 1)) < 1e-6
    below = displacements(design.table["ky_ratio"].to_numpy() * mean * (1 - 1e-5))
    assert np.mean(below > ALLOWABLE) > target
    assert design.probability(mean) <= target < design.probability(mean * (1 - 1e-5))


def test_rigid_mean_ky_for_a_target_probability():
    """The samples rerun by bd.newmark at the returned mean (their ky ratios kept: the
    common random numbers)."""
    design = dz.mean_ky_for_probability(RECORDS, dz.Rigid(), {"ky": dz.LogNormal(mean=0.15, cov=0.3)}, ALLOWABLE,
                                        0.1, pga=0.4, runs=16, seed=3)
    records = design.table["record"].to_numpy()

    def displacements(ky):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", bd.excitation.UnitsWarning)  # a ky above the PGA: D = 0
            return np.array([float(bd.newmark(RECORDS[r], ky=k, pga=0.4, polarity="normal").normal)
                             for r, k in zip(records, ky)])

    _check_mean_design(design, displacements, 0.1)


def test_flexible_mean_ky_for_a_target_probability():
    parameters = {"ky": dz.LogNormal(mean=0.15, cov=0.2), "vs": dz.LogNormal(mean=250.0, cov=0.15),
                  "height": 10.0, "vr": 600.0}
    design = dz.mean_ky_for_probability(RECORDS, FLEXIBLE, parameters, ALLOWABLE, 0.2, pga=0.4, runs=8, seed=1)
    table = design.table

    def displacements(ky):
        return np.array([_flexible_d(RECORDS[r], k, vs=v)[0] for r, k, v in zip(table["record"], ky,
                                                                                 table["vs_m_s"])])

    _check_mean_design(design, displacements, 0.2)


def test_design_inputs_are_checked():
    with pytest.raises(ValueError, match="allowable"):
        dz.ky_for_displacement(RECORDS["first"], dz.Rigid(), {}, -0.1)
    with pytest.raises(ValueError, match="no ky is needed"):
        dz.ky_for_displacement(RECORDS["first"], FLEXIBLE, COLUMN, 50.0, pga=0.1)
    with pytest.raises(ValueError, match="target"):
        dz.mean_ky_for_probability(RECORDS, dz.Rigid(), {"ky": dz.LogNormal(mean=0.1, cov=0.2)}, 0.1, 1.5)
    with pytest.raises(ValueError, match="runs=12"):
        dz.mean_ky_for_probability(RECORDS, dz.Rigid(), {"ky": dz.LogNormal(mean=0.1, cov=0.2)}, 0.1, 0.1, runs=12)
    with pytest.raises(ValueError, match="must be a distribution"):
        dz.mean_ky_for_probability(RECORDS, dz.Rigid(), {"ky": 0.1}, 0.1, 0.1)
