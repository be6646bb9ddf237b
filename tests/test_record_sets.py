"""Record sets: bd.read_records over folders of files in every format, the metadata table,
lazy reading, filtering and the files that fail."""

import gzip
import json
import math
import pathlib

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli import main
from blockdae.excitation._readers import RECORD_SUFFIXES, record_files
from record_formats import SAMPLES, cosmos_block, cosmos_v2, esm, knet


def station_folder(tmp_path):
    """A folder of one K-NET station (two files), an ESM file, a COSMOS V2 file, a table and a bad table."""
    (tmp_path / "s.NS").write_text(knet(direction="N-S"))
    (tmp_path / "s.EW").write_text(knet(direction="E-W"))
    (tmp_path / "e.ASC").write_text(esm())
    (tmp_path / "c.v2").write_text(cosmos_v2())
    (tmp_path / "t.csv").write_text("time (s), acc (g)\n0,0.1\n0.01,0.25\n0.02,-0.1\n0.03,-0.25\n")
    (tmp_path / "bad.csv").write_text("0,1\n0.01,x\n")
    return tmp_path


def test_record_files_lists_every_suffix_a_reader_handles(tmp_path):
    names = ["a.V1", "b.V2", "c.v2c", "d.V1C", "e.NS", "f.EW", "g.UD", "h.NS1", "i.EW2", "j.UD1", "k.ASC", "l.sac",
             "m.mseed", "n.miniseed", "o.AT2", "p.csv", "q.txt", "r.dat", "s.EW.gz", "t.pdf", "u"]
    for name in names:
        (tmp_path / name).write_text("")
    with pytest.warns(UserWarning, match=r"2 files left out: t.pdf \(not a record file: suffix .pdf\); "
                                         r"u \(not a record file: suffix none\)"):
        assert [p.name for p in record_files(tmp_path)] == sorted(names[:-2])
    assert {".v1", ".v2", ".v1c", ".v2c", ".ns", ".ew", ".ud", ".asc", ".sac", ".mseed"} <= set(RECORD_SUFFIXES)


def test_read_records_table_from_the_headers_and_the_failed_file_listed_once(tmp_path):
    with pytest.warns(UserWarning, match=r"1 of 6 files could not be read.*bad\.csv, line 2") as caught:
        records = bd.read_records(station_folder(tmp_path))
    assert len(caught) == 1
    assert records.failed == ((str(tmp_path / "bad.csv"), f"{tmp_path / 'bad.csv'}, line 2: not a number in '0.01,x'"),)
    table = records.table
    assert list(table.columns) == ["name", "path", "format", "component", "station", "event", "magnitude",
                                   "epicentral_distance_km", "vs30_m_s", "dt_s", "samples", "pga_g"]
    # K-NET's two files of one station share the stem "s": each takes its file's name
    assert table["name"].tolist() == ["c", "e", "s.EW", "s.NS", "t"]
    row = table.set_index("name")
    assert row.loc["s.NS", "format"] == "K-NET" and row.loc["s.NS", "component"] == "N-S"
    assert row.loc["s.NS", "station"] == "MYG004" and row.loc["s.NS", "magnitude"] == 9.0
    assert (row.loc["e", "format"], row.loc["e", "component"], row.loc["e", "station"]) == ("ESM", "HNE", "IT.NRC")
    assert row.loc["c", "station"] == "CE.12345" and row.loc["c", "component"] == "360"
    assert math.isnan(row.loc["c", "magnitude"]) and math.isnan(row.loc["t", "vs30_m_s"])  # not in their headers
    assert row.loc["t", "format"] == "table" and row.loc["t", "pga_g"] == pytest.approx(0.25)
    assert row.loc["c", "dt_s"] == 0.01 and row.loc["c", "samples"] == SAMPLES.size
    assert row.loc["c", "pga_g"] == pytest.approx(np.max(np.abs(SAMPLES)) / 100 / bd.STANDARD_GRAVITY)


def test_the_records_are_read_on_first_access_and_kept(tmp_path, monkeypatch):
    from blockdae.excitation import _record_set

    folder = station_folder(tmp_path)
    with pytest.warns(UserWarning):
        records = bd.read_records(folder)
    calls = []
    real = _record_set.read_file_records
    monkeypatch.setattr(_record_set, "read_file_records", lambda path, **o: calls.append(path) or real(path, **o))
    subset = records.query("format == 'K-NET'")
    assert calls == []  # filtering reads nothing
    first = subset["s.NS"]
    assert subset["s.NS"] is first and records[3] is first  # kept, and shared with the full set
    assert calls == [folder / "s.NS"]
    np.testing.assert_allclose(first.acceleration_samples, bd.read_record(folder / "s.NS").acceleration_samples)
    assert first.name == "s.NS"
    assert [r.metadata["component"] for r in subset] == ["E-W", "N-S"]


def test_filtering_by_mask_query_and_slice(tmp_path):
    with pytest.warns(UserWarning):
        records = bd.read_records(station_folder(tmp_path))
    assert records[records.table["magnitude"] > 7].names == ["s.EW", "s.NS"]
    assert records.query("format in ['ESM', 'table']").names == ["e", "t"]
    assert records[1:3].names == ["e", "s.EW"]
    assert len(records.query("magnitude > 10")) == 0
    assert records.query("magnitude > 7").failed == records.failed
    with pytest.raises(TypeError, match="boolean mask of 5 values"):
        records[[True, False]]
    with pytest.raises(KeyError, match="no record named 'x'"):
        records["x"]


def test_a_file_of_three_channels_gives_three_rows(tmp_path):
    three = cosmos_block(orientation=360) + cosmos_block(orientation=90) + cosmos_block(orientation=400)
    (tmp_path / "three.v2").write_text(three)
    records = bd.read_records(tmp_path / "three.v2")
    assert records.names == ["three 360", "three 090", "three Up"]
    assert records["three Up"].metadata["vertical"] is True
    assert records.failed == ()


def test_a_list_of_files_and_folders_gzip_included(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "e.ASC.gz").write_bytes(gzip.compress(esm().encode()))
    (tmp_path / "k.NS").write_text(knet())
    records = bd.read_records([tmp_path / "k.NS", tmp_path / "sub"])
    assert records.names == ["k", "e"] and records.table["format"].tolist() == ["K-NET", "ESM"]
    with pytest.raises(ValueError, match="nope: no such file or folder"):
        bd.read_records([tmp_path / "nope"])
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError, match="empty: no record files"):
        bd.read_records(tmp_path / "empty")


def test_subfolders_are_read_when_asked_and_named_when_not(tmp_path):
    """A folder's subfolders (a station per folder, as downloaded) are searched with
    recursive=True; without it, the record files left in them are counted and named in a
    warning, as is every file that is not a record; hidden files are not looked at."""
    (tmp_path / "top.NS").write_text(knet())
    for station in ("s1", "s2"):
        (tmp_path / station).mkdir()
        (tmp_path / station / f"{station}.EW").write_text(knet(direction="E-W"))
    (tmp_path / "s2" / "notes.pdf").write_text("")
    (tmp_path / ".cache").mkdir()
    (tmp_path / ".cache" / "old.NS").write_text(knet())
    with pytest.warns(UserWarning, match=r"2 files left out: 2 record files in subfolders \(s1, s2\): not searched, "
                                         r"recursive=True \(--recursive\) reads them"):
        assert bd.read_records(tmp_path).names == ["top"]
    with pytest.warns(UserWarning, match=r"1 file left out: s2/notes.pdf \(not a record file: suffix .pdf\)"):
        records = bd.read_records(tmp_path, recursive=True)
    assert records.names == ["s1", "s2", "top"]
    assert [pathlib.Path(p).relative_to(tmp_path).as_posix() for p in records.table["path"]] == \
        ["s1/s1.EW", "s2/s2.EW", "top.NS"]


def test_the_command_line_searches_subfolders_with_recursive(tmp_path, capsys):
    """blockdae newmark on a folder: --recursive reads the subfolders' records; without it
    they are named on stderr as left out."""
    station_folder = tmp_path / "records"
    (station_folder / "s1").mkdir(parents=True)
    (station_folder / "top.NS").write_text(knet())
    (station_folder / "s1" / "s1.EW").write_text(knet(direction="E-W"))
    arguments = ["--no-cache", "newmark", str(station_folder), "--ky", "0.01", "--json"]
    with pytest.warns(UserWarning, match=r"1 record file in subfolders \(s1\): not searched"):
        assert main(arguments) == 0
    assert [r["record"] for r in json.loads(capsys.readouterr().out)["results"]] == ["top"]
    assert main([*arguments, "--recursive"]) == 0
    assert sorted({r["record"] for r in json.loads(capsys.readouterr().out)["results"]}) == ["s1", "top"]


def test_a_header_number_that_is_not_a_number_fails_that_file_naming_field_and_value(tmp_path):
    (tmp_path / "m.NS").write_text(knet().replace("Mag.              9.0", "Mag.              big"))
    (tmp_path / "k.EW").write_text(knet(direction="E-W"))
    with pytest.warns(UserWarning, match="1 of 2"):
        records = bd.read_records(tmp_path)
    assert records.names == ["k"]
    assert records.failed[0][1] == f"{tmp_path / 'm.NS'}: the header's magnitude 'big' is not a number"


def test_reader_options_apply_to_every_file(tmp_path):
    (tmp_path / "one.txt").write_text("0.1\n-0.2\n0.05\n")
    records = bd.read_records(tmp_path, dt=0.02, units="g")
    assert records.table.loc[0, "dt_s"] == 0.02 and records[0].dt == 0.02
    assert records[0].peak_acceleration == pytest.approx(0.2 * bd.STANDARD_GRAVITY)


def test_a_record_set_of_records_and_its_metadata_for_results():
    a = bd.Record([0.0, 1.0, -2.0], 0.01, "a", units="m/s2", metadata={"station": "X", "magnitude": "6.1"})
    b = bd.Record([0.0, 3.0, 0.0], 0.01, "b", units="m/s2")
    records = bd.RecordSet([a, b])
    assert records[0] is a and list(records) == [a, b]
    assert records.table["path"].isna().all()
    meta = records.metadata
    assert list(meta.index) == ["a", "b"] and meta.loc["a", "magnitude"] == 6.1 and meta.loc["a", "station"] == "X"
    assert "pga_g" not in meta.columns and "path" not in meta.columns
    with pytest.raises(ValueError, match=r"repeated: \['a'\]"):
        bd.RecordSet([a, a])
    with pytest.raises(TypeError, match=r"records\[1\] must be a bd.Record"):
        bd.RecordSet([a, "b.csv"])
