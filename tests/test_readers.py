"""Record files: units from AT2 headers, a plausible peak, the time origin, errors at file lines,
gzip, binary and empty files, speed."""

import csv
import gzip
import re

import numpy as np
import pytest
from conftest import sample_record_paths

import blockdae as bd
from blockdae.cli._main import main
from blockdae.excitation._readers import STANDARD_GRAVITY, check_peak_acceleration

AT2 = ("PEER NGA STRONG MOTION DATABASE RECORD\nTest 1994, Station, 090\n"
       "ACCELERATION TIME SERIES IN UNITS OF {units}\n{npts_dt}\n"
       "  {a}  {b}  -.3E-01\n  .4E-01  .0E+00\n")


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def at2(tmp_path, name="X.AT2", units="G", npts_dt="NPTS=    5, DT=   .0050 SEC", a=".1E-01", b=".2E-01"):
    return write(tmp_path, name, AT2.format(units=units, npts_dt=npts_dt, a=a, b=b))


# --- units -------------------------------------------------------------------------

@pytest.mark.parametrize("header, scale, factor", [
    ("G", 1.0, STANDARD_GRAVITY), ("CM/SEC/SEC", 1000.0, 0.01), ("M/SEC/SEC", 10.0, 1.0),
    ("CM/S^2", 1000.0, 0.01), ("GAL", 1000.0, 0.01), ("cm/s2", 1000.0, 0.01),
])
def test_at2_units_line_is_read_and_used(tmp_path, header, scale, factor):
    """Values 0.01 ... 0.04 g, or 10 ... 40 cm/s², or 0.1 ... 0.4 m/s², as the header says."""
    values = np.array([0.01, 0.02, -0.03, 0.04, 0.0]) * scale
    path = at2(tmp_path, units=header, a=f"{values[0]:.4E}", b=f"{values[1]:.4E}")
    path.write_text(path.read_text().replace("-.3E-01", f"{values[2]:.4E}").replace(".4E-01", f"{values[3]:.4E}"))
    record = bd.read_record(path)
    np.testing.assert_allclose(record.acceleration_samples, values * factor, rtol=1e-15)


def test_explicit_units_agreeing_with_the_header_are_accepted(tmp_path):
    path = at2(tmp_path, units="CM/SEC/SEC", a="10.0", b="20.0")
    assert bd.read_record(path, units="gal").peak_acceleration == pytest.approx(0.2)
    assert bd.read_record(path, units="cm/s^2").peak_acceleration == pytest.approx(0.2)


def test_explicit_units_contradicting_the_header_raise(tmp_path):
    path = at2(tmp_path, units="CM/SEC/SEC", a="10.0", b="20.0")
    with pytest.raises(ValueError) as err:
        bd.read_record(path, units="g")
    message = str(err.value)
    assert str(path) in message and "units='g'" in message and "cm/s²" in message
    assert "line 3: 'ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC'" in message


def test_unknown_header_units_need_explicit_units(tmp_path):
    path = at2(tmp_path, units="FT/SEC/SEC")
    with pytest.raises(ValueError, match=r"X.AT2, line 3: .*FT/SEC/SEC.*units not understood"):
        bd.read_record(path)
    assert bd.read_record(path, units="g").peak_acceleration == pytest.approx(0.04 * STANDARD_GRAVITY)


def test_velocity_file_is_refused(tmp_path):
    path = write(tmp_path, "X.VT2", AT2.format(units="CM/S", npts_dt="NPTS= 5, DT= .005 SEC", a="1", b="2")
                 .replace("ACCELERATION", "VELOCITY"))
    with pytest.raises(ValueError, match="line 3: .* not an acceleration time series"):
        bd.read_record(path)


def test_files_without_units_statement_need_units(tmp_path):
    path = write(tmp_path, "r.csv", "0.0, 0.1\n0.01, -0.2\n")
    with pytest.raises(ValueError, match=re.escape(f"{path}: the units of the accelerations are not stated")):
        bd.read_record(path)
    assert bd.read_record(path, units="g").peak_acceleration == pytest.approx(0.2 * STANDARD_GRAVITY)
    assert bd.read_record(path, units="m/s2").peak_acceleration == pytest.approx(0.2)


@pytest.mark.parametrize("header, factor", [
    ("time (s),Acceleration (m/s2)", 1.0), ("t [s], acc [cm/s2]", 0.01), ("time, a (gal)", 0.01),
    ("time (sec), a (g)", STANDARD_GRAVITY), ("Time [s]\tAcceleration [m/s^2]", 1.0), ("t, a (m/s²)", 1.0),
    ("t (s), a [CM/SEC/SEC]", 0.01),
])
def test_table_header_units_are_read(tmp_path, header, factor):
    """A table's header line naming the acceleration's units in brackets is read in them (was
    read as g: an m/s² file of peak 6 passed as 6 g)."""
    path = write(tmp_path, "r.csv", f"{header}\n0.0, 0.0\n0.01, 0.6\n0.02, -0.3\n")
    np.testing.assert_array_equal(bd.read_record(path).acceleration_samples, np.array([0.0, 0.6, -0.3]) * factor)


def test_table_header_units_contradicted_or_not_acceleration_are_refused(tmp_path):
    path = write(tmp_path, "r.csv", "# a comment\ntime (s),Acceleration (m/s2)\n0.0, 0.0\n0.01, 6.0\n")
    with pytest.raises(ValueError, match=re.escape(
            f"{path}: units='g' (g) contradicts the header, line 2: 'time (s),Acceleration (m/s2)', which says m/s²")):
        bd.read_record(path, units="g")
    assert bd.read_record(path, units="m/s2").peak_acceleration == 6.0
    velocity = write(tmp_path, "v.csv", "t (s), v (m/s)\n0.0, 0.0\n0.01, 0.1\n")
    with pytest.raises(ValueError, match=re.escape(f"{velocity}, line 1: 't (s), v (m/s)': the header names units "
                                                   "'m/s', not an acceleration in g, m/s2, cm/s2 or gal")):
        bd.read_record(velocity)
    mixed = write(tmp_path, "m.csv", "t (s), ax (g), ay (m/s2)\n0.0, 0.0, 0.0\n0.01, 0.1, 0.1\n")
    with pytest.raises(ValueError, match=re.escape(f"{mixed}: the header names different units, g, m/s²")):
        bd.read_motion(mixed)


def test_table_header_units_blame_the_header_for_an_implausible_peak(tmp_path):
    path = write(tmp_path, "r.csv", "time (s), a (cm/s2)\n0.0, 0.0\n0.01, 0.005\n")
    with pytest.raises(ValueError, match=r"looks like .* read as cm/s²: correct the file \(the header's line 1: "):
        bd.read_record(path)


def test_sample_records_state_g_in_a_comment():
    """pySLAMMER's CSVs state their units in a comment line, ``# Time (s),Acceleration (g's)``:
    read in g, and all pass the peak check."""
    for path in sample_record_paths():
        record = bd.read_record(path)
        assert record.metadata["units"] == "g"
        np.testing.assert_array_equal(record.acceleration_samples,
                                      bd.read_record(path, units="g").acceleration_samples)


# --- plausible peak ----------------------------------------------------------------

@pytest.mark.parametrize("body, units, message", [
    ("0.0, 50\n0.01, -400\n", "g", "peak acceleration 400 g is implausible .* looks like cm/s² read as g: "
                                    "pass units='cm/s2', or check_peak=False"),
    ("0.0, 0.01\n0.01, -0.05\n", "cm/s2", r"peak acceleration 0.05 cm/s² = 5.099e-05 g .* looks like g read as "
                                         "cm/s²: pass units='g'"),
    ("0.0, 50\n0.01, -400\n", "m/s2", r"400 m/s² = 40.79 g .* looks like cm/s² read as m/s²: pass units='cm/s2'"),
    ("0.0, 0.0\n0.01, 0.0\n", "g", "peak acceleration 0 g is implausible .* check the values and their units"),
])
def test_implausible_peak_names_it_and_the_likely_mix_up(tmp_path, body, units, message):
    path = write(tmp_path, "r.csv", body)
    with pytest.raises(ValueError, match=message) as err:
        bd.read_record(path, units=units)
    assert str(err.value).startswith(f"{path}: ")
    assert bd.read_record(path, units=units, check_peak=False).acceleration_samples.size == 2


def test_implausible_peak_with_header_units_blames_the_header(tmp_path):
    path = at2(tmp_path, units="CM/SEC/SEC")  # values 0.01 ... 0.04: in g really
    with pytest.raises(ValueError, match=r"looks like g read as cm/s²: correct the file \(the header's line 3: "):
        bd.read_record(path)


def test_peak_check_helper_bounds():
    check_peak_acceleration([0.0, 1.0001e-4], "g")
    check_peak_acceleration([0.0, -4.0], "g")
    check_peak_acceleration([0.0, 39.2], "m/s2")
    with pytest.raises(ValueError, match=r"^built: peak acceleration 4.01 g is implausible \(above the largest peaks "
                                         r"recorded; plausible: 0.0001 g to 4 g\); looks like m/s² read as g"):
        check_peak_acceleration([0.0, 4.01], "g", source="built")
    with pytest.raises(ValueError, match="units='furlong' is unknown"):
        check_peak_acceleration([0.0, 1.0], "furlong")


# --- AT2 detection and headers ------------------------------------------------------

@pytest.mark.parametrize("name, npts_dt", [
    ("X.AT2", "NPTS=    5, DT=   .0050 SEC"),
    ("X.txt", "NPTS=    5, DT=   .0050 SEC"),  # found by content
    ("X.AT2", "DT=   .0050 SEC, NPTS=    5"),  # reversed
    ("X.dat", "DT= 0.005 SEC,  NPTS= 5"),
    ("X.AT2", "    5    0.0050    NPTS, DT"),  # NGA-West1
])
def test_at2_headers(tmp_path, name, npts_dt):
    record = bd.read_record(at2(tmp_path, name=name, npts_dt=npts_dt))
    assert record.dt == 0.005 and record.name == "X" and record.start_time == 0.0
    np.testing.assert_allclose(record.acceleration_samples / STANDARD_GRAVITY, [0.01, 0.02, -0.03, 0.04, 0.0])


def test_at2_without_its_header_line(tmp_path):
    with pytest.raises(ValueError, match=r"X.AT2: no 'NPTS=..., DT=...' line in the first 10 lines"):
        bd.read_record(write(tmp_path, "X.AT2", "0.1\n0.2\n"))


# --- time origin ---------------------------------------------------------------------

def test_time_column_origin_is_kept_as_start_time(tmp_path):
    """A time column from 5 s: the excitation starts at 0 as always, and start_time = 5 s
    puts its event times back on the file's axis."""
    shifted = bd.read_record(write(tmp_path, "late.csv", "t, a\n5.0, 0.0\n5.25, 0.9\n5.5, 0.0\n"),
                             units="m/s2", g=9.81, check_peak=False, check_step=False)
    assert shifted.start_time == 5.0 and shifted.dt == 0.25
    assert "start_time=5 s" in repr(shifted)
    block = bd.SlidingBlock(mu=0.06, g=9.81)
    ref = bd.simulate(block, bd.Record([0.0, 0.9, 0.0], 0.25, units="m/s2"))
    sol = bd.simulate(block, shifted)
    np.testing.assert_array_equal(sol.t_events, ref.t_events)
    assert sol.t_events[0] < 0.5  # solution times from the first sample; + 5 s on the file's axis


# --- errors at file lines ------------------------------------------------------------

@pytest.mark.parametrize("body, line, message", [
    ("# c\nt, a\n0.0, 0.1\n\n# c\n0.01, 0.2\n0.02, nan\n", 7, "value nan is not finite"),
    ("0.0, 0.1\n0.01, inf\n", 2, "value inf is not finite"),
    ("# c\n\n0.0, 0.1\n0.01, 0.2\n# c\n0.01, 0.1\n", 6,
     r"time column is not increasing \(t = 0.01 s after 0.01 s\)"),
    ("# c\n\n0.0, 0.1\n0.01, 0.2\n\n0.02, 0.1\n0.04, 0.1\n0.05, 0.1\n", 7,
     r"time column is not uniform \(step 0.02 s to t = 0.04 s, where the others are 0.01 s\)"),
    ("0.0, 0.1\n0.01, 0.2\n0.0200001, 0.1\n0.03, 0.1\n", 3,
     r"time column is not uniform \(step 0.0100001 s .* others are 0.01 s"),
    ("t, a\n0.0, 0.1\n0.01, 0.2, 0.3\n", 3, "3 columns, expected 2 as on line 2"),
    ("t, a\n0.0, 0.1\n0.01, x\n", 3, "not a number in '0.01, x'"),
    ("h\n0 1 2 3 4\n5 6 7 8 9\n", 2, "expected 1 or 2 columns .*, found 5"),
])
def test_errors_name_the_file_line(tmp_path, body, line, message):
    path = write(tmp_path, "bad.csv", body)
    with pytest.raises(ValueError, match=f"^{re.escape(str(path))}, line {line}: {message}") as err:
        bd.read_record(path)
    assert not re.search(r"\d{9,}", str(err.value).replace(str(path), ""))  # no float noise


def test_at2_errors_name_the_file_line(tmp_path):
    with pytest.raises(ValueError, match=r"X.AT2, line 5: value nan is not finite"):
        bd.read_record(at2(tmp_path, b="NaN"))
    with pytest.raises(ValueError, match=r"X.AT2, line 5: not a number, 'x'"):
        bd.read_record(at2(tmp_path, b="x"))
    with pytest.raises(ValueError, match=r"header \(line 4\) says NPTS=6, found 5 values"):
        bd.read_record(at2(tmp_path, npts_dt="NPTS=    6, DT=   .0050 SEC"))


def test_record_nan_message_says_0_based():
    with pytest.raises(ValueError, match=r"acceleration sample 2 \(0-based\) is nan"):
        bd.Record([0.0, 1.0, np.nan], 0.01)


def test_time_step_printed_clean(tmp_path):
    """A step from a time column printed to a few digits is that step exactly."""
    path = write(tmp_path, "r.csv", "".join(f"{0.02 * k:.2f}, 0.1\n" for k in range(1000)))
    assert bd.read_record(path, units="g").dt == 0.02
    with pytest.raises(ValueError, match=r"dt=0.01 s contradicts the file's step 0.02 s"):
        bd.read_record(path, dt=0.01, units="g")


# --- separators ------------------------------------------------------------------------

def test_semicolons_with_decimal_commas_are_read(tmp_path):
    comma = bd.read_record(write(tmp_path, "eu.csv", "t;a\n0,00;0,1\n0,01;-0,25\n0,02;0,05\n"), units="g")
    point = bd.read_record(write(tmp_path, "us.csv", "t,a\n0.00,0.1\n0.01,-0.25\n0.02,0.05\n"), units="g")
    np.testing.assert_array_equal(comma.acceleration_samples, point.acceleration_samples)
    assert comma.dt == point.dt == 0.01


@pytest.mark.parametrize("body, message", [
    ("t;a\n0,00;1.5\n", r"line 2: both '.' and ',' in '0,00;1.5' with ';' separators"),
    ("0,00 0,1\n0,01 0,2\n", "line 1: expected 1 or 2 columns .*, found 4; decimal commas?"),
    ("0;0\n0,01;0,2\n", "line 2: 4 columns, expected 2 as on line 1; decimal commas?"),
])
def test_decimal_commas_never_misread(tmp_path, body, message):
    with pytest.raises(ValueError, match=message):
        bd.read_record(write(tmp_path, "eu.csv", body))


def test_blanks_tabs_crlf_and_trailing_separators(tmp_path):
    expected = np.array([0.5, 0.4]) * STANDARD_GRAVITY
    for body in ("0.0\t 0.5\r\n0.01\t0.4\r\n", "0.0, 0.5,\n0.01, 0.4,\n", "0.0;0.5\n0.01;0.4\n"):
        np.testing.assert_array_equal(bd.read_record(write(tmp_path, "r.csv", body), units="g").acceleration_samples,
                                      expected)


# --- what a file holds: gzip, BOM + CRLF, binary, other encodings, nothing (issue 27) ----

TWO_COLUMNS = "time [s], a [g]\n0.0, 0.5\n0.01, 0.4\n0.02, -0.3\n"
EXPECTED = np.array([0.5, 0.4, -0.3]) * STANDARD_GRAVITY


@pytest.mark.parametrize("name", ["r.csv.gz", "r.CSV.GZ", "r.csv"])
def test_gzip_records_are_read_and_named_without_their_suffixes(tmp_path, name):
    path = tmp_path / name
    path.write_bytes(gzip.compress(TWO_COLUMNS.encode()))  # found by its first bytes, whatever its name
    record = bd.read_record(path)
    np.testing.assert_array_equal(record.acceleration_samples, EXPECTED)
    assert record.name == "r" and record.dt == 0.01


def test_gzip_at2_is_read_as_at2(tmp_path):
    plain = at2(tmp_path)
    packed = tmp_path / "Y.AT2.gz"
    packed.write_bytes(gzip.compress(plain.read_bytes()))
    record = bd.read_record(packed)
    np.testing.assert_array_equal(record.acceleration_samples, bd.read_record(plain).acceleration_samples)
    assert record.name == "Y" and record.dt == 0.005


def test_bom_and_crlf(tmp_path):
    path = tmp_path / "r.csv"
    path.write_bytes(b"\xef\xbb\xbf" + TWO_COLUMNS.replace("\n", "\r\n").encode())
    np.testing.assert_array_equal(bd.read_record(path).acceleration_samples, EXPECTED)
    path.write_bytes(b"\xef\xbb\xbf" + TWO_COLUMNS.replace("0.4", "x").replace("\n", "\r\n").encode())
    with pytest.raises(ValueError, match=f"^{re.escape(str(path))}, line 3: not a number"):
        bd.read_record(path)


@pytest.mark.parametrize("data, message", [
    (b"0.0, 0.5\n0.01, 0.4\n\x80\x81\x82", r", line 3: byte 0x80 is not UTF-8 text"),
    (b"t, a\n0.0\x00, 0.5\n", r": a binary file \(a NUL byte at offset 8\)"),
    ("# station Düsseldorf\n0.0, 0.5\n0.01, 0.4\n".encode("latin-1"), r", line 1: byte 0xfc is not UTF-8 text"),
    (b"", r": no data rows"),
    (b"\r\n\n# only a comment\n", r": no data rows"),
    (gzip.compress(b"\x00\x01\x02"), r": a binary file"),
    (gzip.compress(TWO_COLUMNS.encode())[:-6], r": a damaged gzip file"),
])
def test_unreadable_files_are_named(tmp_path, data, message):
    path = tmp_path / "bad.dat"
    path.write_bytes(data)
    with pytest.raises(ValueError, match=f"^{re.escape(str(path))}{message}"):
        bd.read_record(path, dt=0.01)


def test_batch_over_a_folder_of_mixed_files(tmp_path, capsys):
    """gzip, BOM + CRLF and comma-decimal files are analysed; binary, gzip-compressed binary and
    empty ones are listed, each by its path, with exit status 1."""
    folder = tmp_path / "records"
    folder.mkdir()
    (folder / "packed.csv.gz").write_bytes(gzip.compress(TWO_COLUMNS.encode()))
    (folder / "bom.csv").write_bytes(b"\xef\xbb\xbf" + TWO_COLUMNS.replace("\n", "\r\n").encode())
    (folder / "comma.csv").write_text("0,0;0,5\n0,01;0,4\n0,02;-0,3\n")
    (folder / "binary.dat").write_bytes(bytes(range(256)) * 4)
    (folder / "zipped.dat.gz").write_bytes(gzip.compress(bytes(range(256))))
    (folder / "empty.txt").write_bytes(b"")
    (folder / "notes.md").write_text("not a record suffix: skipped")
    out = tmp_path / "r.csv"
    assert main(["--no-cache", "batch", str(folder), "--mu", "0.1", "--csv", str(out), "--units", "g"]) == 1
    err = capsys.readouterr().err
    assert "3 of 6 files failed" in err
    for name in ("binary.dat", "zipped.dat.gz", "empty.txt"):
        assert f"  {folder / name}: " in err
    assert "codec can't decode" not in err
    rows = list(csv.DictReader(out.open()))
    assert [r["record"] for r in rows] == ["bom", "comma", "packed"]
    assert {r["n_samples"] for r in rows} == {"3"}


# --- speed -------------------------------------------------------------------------------
