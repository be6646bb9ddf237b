"""COSMOS V1/V2, K-NET/KiK-net, ESM, SAC and miniSEED records (issue 24): found by content,
the header's step and units honoured, each header field that contradicts the data refused
naming the file and line, truncated files refused. Reference values: the numbers the
fixtures (tests/record_formats.py) write, and the real files in ObsPy's wheel."""

import gzip
import importlib.util
import pathlib
import sys

import numpy as np
import pytest
from record_formats import COUNTS, SAMPLES, cosmos_block, cosmos_v2, esm, knet

import blockdae as bd

HAS_OBSPY = importlib.util.find_spec("obspy") is not None
needs_obspy = pytest.mark.skipif(not HAS_OBSPY, reason="ObsPy not installed (the optional extra blockdae[seismo])")
CM = 0.01  # m/s² per cm/s²
PEAK = float(np.max(np.abs(SAMPLES)))  # the fixtures' peak [cm/s²]


def obspy_data(*parts):
    """A test file shipped in ObsPy's wheel, read where it is installed."""
    return pathlib.Path(importlib.util.find_spec("obspy").origin).parent.joinpath(*parts)


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def line_of(path, text):
    """1-based number of the first line of ``path`` containing ``text``."""
    return next(n for n, line in enumerate(path.read_text().split("\n"), 1) if text in line)


# --- COSMOS V1/V2 ---------------------------------------------------------------------

def test_cosmos_v2_acceleration_read_with_its_step_units_and_metadata(tmp_path):
    path = write(tmp_path, "CE12345.V2", cosmos_v2())
    record = bd.read_record(path)
    np.testing.assert_allclose(record.acceleration_samples, SAMPLES * CM, rtol=1e-15)
    assert record.dt == 0.01 and record.name == "CE12345"
    meta = record.metadata
    assert (meta["format"], meta["units"], meta["station"], meta["component"], meta["azimuth_deg"]) == (
        "COSMOS V2 (v01.20)", "cm/s2", "CE.12345", "360", 0.0)
    assert meta["event"] == "Test Earthquake January 1, 2000 00:00 UTC"


def test_cosmos_units_in_g_and_gzip(tmp_path):
    path = tmp_path / "g.v1"
    path.write_bytes(gzip.compress(cosmos_block(SAMPLES / 1000, units_code=2, units_text="g", stage=1).encode()))
    record = bd.read_record(path)
    np.testing.assert_allclose(record.acceleration_samples, SAMPLES / 1000 * bd.STANDARD_GRAVITY, rtol=1e-12)
    assert record.metadata["format"] == "COSMOS V1 (v01.20)"


def test_cosmos_wrong_sample_count(tmp_path):
    path = write(tmp_path, "n.v2", cosmos_block(count=199))
    data_line = line_of(path, "acceleration pts")
    with pytest.raises(ValueError, match=rf"n.v2, line {data_line + 25}: .*more values than the 199 that line "
                                         rf"{data_line} states"):
        bd.read_record(path)
    path = write(tmp_path, "m.v2", cosmos_block(count=201))
    with pytest.raises(ValueError, match=rf"m.v2, line {data_line + 26}: 'End-of-data.*is not a number"):
        bd.read_record(path)


def test_cosmos_wrong_step(tmp_path):
    path = write(tmp_path, "dt.v2", cosmos_block(dt_ms=20.0, approx=2))
    data_line = line_of(path, "acceleration pts")
    # the real header (line 25) lists 6 values a line from line 26: value 62 is on line 36
    with pytest.raises(ValueError, match=rf"dt.v2, line 36, real-header value 62: a step of 20 ms gives 200 samples "
                                         rf"4 s, not the approximately 2 s of line {data_line}"):
        bd.read_record(path)


def test_cosmos_units_code_contradicting_the_data_line(tmp_path):
    path = write(tmp_path, "u.v2", cosmos_block(header_units=2))
    with pytest.raises(ValueError, match=rf"u.v2, line {line_of(path, 'acceleration pts')}: .*: units code 4, but the "
                                         r"integer header \(line 15, value 3\) says 2"):
        bd.read_record(path)


def test_cosmos_peak_contradicting_the_data(tmp_path):
    path = write(tmp_path, "p.v2", cosmos_block(peak=1.0))
    with pytest.raises(ValueError, match=rf"p.v2, line 36, real-header value 64: the header's peak 1 is not the "
                                         rf"data's, {np.max(np.abs(SAMPLES)):g} \(units: line 45: .*cm/sec2"):
        bd.read_record(path)


def test_cosmos_units_argument_contradicting_the_header(tmp_path):
    path = write(tmp_path, "a.v2", cosmos_block())
    with pytest.raises(ValueError, match=r"units='g' \(g\) contradicts the header, line \d+: .*cm/s²"):
        bd.read_record(path, units="g")


def test_cosmos_truncated(tmp_path):
    text = cosmos_block()
    path = write(tmp_path, "t.v2", text[:len(text) // 2 + 600])
    with pytest.raises(ValueError, match=r"t.v2, line \d+: the file ends inside a block of 200 values"):
        bd.read_record(path)
    path = write(tmp_path, "h.v2", "\n".join(text.split("\n")[:20]))
    with pytest.raises(ValueError, match=r"h.v2, line 20: the file ends inside a block of 100 values"):
        bd.read_record(path)


def test_cosmos_velocity_only_is_refused(tmp_path):
    path = write(tmp_path, "v.v2", cosmos_block(SAMPLES / 10, kind="velocity", title="Velocity data", parameter=2,
                                                units_code=5, units_text="cm/sec"))
    with pytest.raises(ValueError, match=r"v.v2: a COSMOS file without acceleration \(velocity \(line 1\)\)"):
        bd.read_record(path)


def test_cosmos_three_channels_refused_by_read_record_grouped_by_read_motion(tmp_path):
    text = (cosmos_block(orientation=90) + cosmos_block(SAMPLES / 2, orientation=400)
            + cosmos_block(SAMPLES / 4, orientation=360))
    path = write(tmp_path, "three.v2", text)
    with pytest.raises(ValueError, match=r"3 acceleration channels \('090', 'Up', '360'\).*read_motion"):
        bd.read_record(path)
    motion = bd.read_motion(path)
    np.testing.assert_allclose(motion.x.acceleration_samples, SAMPLES / 4 * CM, rtol=1e-15)  # 360: north, H1
    np.testing.assert_allclose(motion.y.acceleration_samples, SAMPLES * CM, rtol=1e-15)  # 090: east, H2
    np.testing.assert_allclose(motion.z.acceleration_samples, SAMPLES / 2 * CM, rtol=1e-15)  # Up
    assert motion.x.name == "three 360"


# --- K-NET / KiK-net ------------------------------------------------------------------

def test_knet_counts_times_the_scale_factor_mean_removed_by_default(tmp_path):
    """K-NET samples carry the recorder's offset: read_record removes their mean unless told
    not to, and says so in the metadata."""
    path = write(tmp_path, "MYG0041103111446.NS", knet())
    a = COUNTS * 3920.0 / 6182761.0
    record = bd.read_record(path)
    np.testing.assert_allclose(record.acceleration_samples, (a - a.mean()) * CM, rtol=1e-12, atol=1e-15)
    meta = record.metadata
    assert (meta["format"], meta["station"], meta["component"], meta["units"], meta["mean_removed"]) == (
        "K-NET", "MYG004", "N-S", "cm/s2", True)
    assert meta["mean_m_s2"] == pytest.approx(a.mean() * CM, rel=1e-12)
    assert meta["event"] == "2011/03/11 14:46:00" and meta["magnitude"] == "9.0"
    raw = bd.read_record(path, remove_mean=False)
    np.testing.assert_allclose(raw.acceleration_samples, a * CM, rtol=1e-14)
    assert raw.metadata["mean_removed"] is False


def test_kiknet_channels(tmp_path):
    record = bd.read_record(write(tmp_path, "k.EW2", knet(direction="5")))
    assert (record.metadata["format"], record.metadata["component"], record.metadata["azimuth_deg"]) == (
        "KiK-net", "E-W surface", 90.0)


def test_knet_wrong_sample_count(tmp_path):
    path = write(tmp_path, "n.NS", knet(duration="5"))
    with pytest.raises(ValueError, match=r"n.NS, line 12: 'Duration Time\(s\)  5': 200 samples at 100Hz .* last 2 s, "
                                         "not 5 s"):
        bd.read_record(path)


def test_knet_wrong_step(tmp_path):
    path = write(tmp_path, "dt.NS", knet(frequency="50Hz"))
    with pytest.raises(ValueError, match=r"dt.NS, line 12: .*200 samples at 50Hz \(line 11: .*\) last 4 s, not 2 s"):
        bd.read_record(path)


def test_knet_wrong_units(tmp_path):
    path = write(tmp_path, "u.NS", knet(scale="3920(m/s2)/6182761"))
    with pytest.raises(ValueError, match=r"u.NS, line 15: 'Max. Acc. \(gal\).*the header's peak [\d.]+ is not the "
                                         r"data's.*line 14: 'Scale Factor"):
        bd.read_record(path)
    path = write(tmp_path, "v.NS", knet(scale="3920(kine)/6182761"))
    with pytest.raises(ValueError, match=r"v.NS, line 14: .*Scale Factor in 'kine', not an acceleration"):
        bd.read_record(path)


def test_knet_truncated(tmp_path):
    text = knet()
    path = write(tmp_path, "t.NS", text[:len(text) // 3])
    with pytest.raises(ValueError, match=r"t.NS, line 12: .*not 2 s.*truncated"):
        bd.read_record(path)
    path = write(tmp_path, "h.NS", "\n".join(text.split("\n")[:10]))
    with pytest.raises(ValueError, match=r"h.NS, line 10: the file ends inside the header"):
        bd.read_record(path)


@needs_obspy
def test_knet_file_shipped_with_obspy():
    """ObsPy's test.knet: 5900 samples at 100 Hz, Scale Factor 2000(gal)/8388608, Max. Acc. 4.383 gal."""
    path = obspy_data("io", "nied", "tests", "data", "test.knet")
    record = bd.read_record(path, remove_mean=True)
    assert record.acceleration_samples.size == 5900 and record.dt == 0.01
    assert record.peak_acceleration == pytest.approx(4.383 * CM, abs=0.0005 * CM)
    assert (record.metadata["station"], record.metadata["component"], record.metadata["memo"]) == (
        "AKT013", "E-W", "A dummy comment")


# --- ESM ------------------------------------------------------------------------------

def test_esm_read_with_its_units_and_metadata(tmp_path):
    path = write(tmp_path, "IT.NRC..HNE.D.EMSC-20161030_0000029.ACC.MP.ASC", esm(SAMPLES / 100, units="m/s^2",
                                                                                  pga=f"{PEAK:f}"))
    record = bd.read_record(path)
    np.testing.assert_allclose(record.acceleration_samples, SAMPLES / 100, rtol=1e-15)
    meta = record.metadata
    assert (meta["format"], meta["units"], meta["station"], meta["component"], meta["event"]) == (
        "ESM", "m/s2", "IT.NRC", "HNE", "EMSC-20161030_0000029")
    assert (meta["magnitude"], meta["epicentral_distance_km"], meta["vs30_m_s"]) == ("6.5", "4.6", "498")


def test_esm_wrong_sample_count(tmp_path):
    path = write(tmp_path, "n.ASC", esm(ndata=300))
    with pytest.raises(ValueError, match=r"n.ASC, line 13: 'NDATA: 300': the header says 300 samples, the data hold "
                                         r"200 \(a truncated file\?\)"):
        bd.read_record(path)


def test_esm_wrong_step(tmp_path):
    path = write(tmp_path, "dt.ASC", esm(dt="0.005000"))
    with pytest.raises(ValueError, match=r"dt.ASC, line 14: 'DURATION_S: 2.000': 200 samples at 0.005 s \(line 12: "
                                         r".*\) last 1 s, not 2 s"):
        bd.read_record(path)


def test_esm_wrong_units(tmp_path):
    path = write(tmp_path, "u.ASC", esm(units="m/s^2"))
    with pytest.raises(ValueError, match=rf"u.ASC, line 17: 'PGA_CM/S\^2: .*the header's peak {PEAK:g} is not the "
                                         rf"data's, {100 * PEAK:g} \(units: cm/s²; line 16: 'UNITS: m/s\^2'\)"):
        bd.read_record(path)
    path = write(tmp_path, "v.ASC", esm(data_type="VELOCITY"))
    with pytest.raises(ValueError, match=r"v.ASC, line 18: 'DATA_TYPE: VELOCITY': velocity, not acceleration"):
        bd.read_record(path)


def test_esm_truncated(tmp_path):
    text = esm()
    path = write(tmp_path, "t.ASC", text[:len(text) // 2])
    with pytest.raises(ValueError, match=r"t.ASC, line 13: 'NDATA: 200': the header says 200 samples, the data hold "
                                         r"\d+ \(a truncated file\?\)"):
        bd.read_record(path)


def test_esm_components_grouped_by_read_motion(tmp_path):
    paths = [write(tmp_path, f"{c}.ASC", esm(SAMPLES * k, stream=c)) for c, k in (("HNZ", 0.5), ("HNE", 1.0),
                                                                                   ("HNN", 0.25))]
    motion = bd.read_motion(*paths)
    for component, k in zip(motion.components, (0.25, 1.0, 0.5)):
        np.testing.assert_allclose(component.acceleration_samples, SAMPLES * k * CM, rtol=1e-15)


# --- SAC / miniSEED (ObsPy) -----------------------------------------------------------

@needs_obspy
def test_sac_file_shipped_with_obspy_needs_units():
    path = obspy_data("io", "sac", "tests", "data", "test.sac")
    with pytest.raises(ValueError, match=r"test.sac: a SAC file does not state the units of its samples; pass units="):
        bd.read_record(path)
    import obspy

    trace = obspy.read(str(path))[0]
    record = bd.read_record(path, units="m/s2", check_step=False)  # a test signal at 1 s steps
    np.testing.assert_array_equal(record.acceleration_samples, trace.data.astype(float))
    assert record.dt == trace.stats.delta and record.metadata["event"] == "FUNCGEN:SINE"
    assert record.metadata["format"] == "SAC"


@needs_obspy
def test_sac_in_volts_is_refused():
    with pytest.raises(ValueError, match=r"seism.sac: SAC header IDEP = 50: volts, not acceleration"):
        bd.read_record(obspy_data("io", "sac", "tests", "data", "seism.sac"), units="m/s2")


@needs_obspy
def test_miniseed_counts_need_a_gain():
    path = obspy_data("io", "mseed", "tests", "data", "BW.BGLD.__.EHE.D.2008.001.first_10_records")
    with pytest.raises(ValueError, match=r"trace BW.BGLD..EHE holds counts \(integers\); pass gain="):
        bd.read_record(path, units="cm/s2")
    import obspy

    counts = obspy.read(str(path))[0].data
    record = bd.read_record(path, units="cm/s2", gain=1000.0)
    np.testing.assert_allclose(record.acceleration_samples, counts / 1000.0 * CM, rtol=1e-15)
    assert (record.metadata["format"], record.metadata["component"], record.dt) == ("miniSEED", "EHE", 0.005)


@needs_obspy
def test_miniseed_truncated(tmp_path):
    data = obspy_data("io", "mseed", "tests", "data", "BW.BGLD.__.EHE.D.2008.001.first_record").read_bytes()
    path = tmp_path / "cut.mseed"
    path.write_bytes(data[:300])
    with pytest.raises(ValueError, match=r"cut.mseed: ObsPy cannot read this MSEED file"):
        bd.read_record(path, units="cm/s2", gain=1000.0)


def test_seismo_file_without_obspy_names_the_extra(tmp_path, monkeypatch):
    data = bytearray(632)
    data[304:308] = (6).to_bytes(4, "little")
    path = tmp_path / "x.sac"
    path.write_bytes(bytes(data))
    monkeypatch.setitem(sys.modules, "obspy", None)
    with pytest.raises(ValueError, match=r"x.sac: a SAC file; reading it needs ObsPy: pip install 'blockdae\[seismo\]'"):
        bd.read_record(path, units="m/s2")


def test_format_options_are_refused_for_other_formats(tmp_path):
    path = write(tmp_path, "e.ASC", esm())
    centred = bd.read_record(path, remove_mean=True)  # any format's mean can be removed
    assert centred.metadata["mean_removed"] and abs(centred.acceleration_samples.mean()) < 1e-15
    with pytest.raises(ValueError, match=r"r.csv: gain= is an option for SAC/miniSEED files; this one is a table"):
        bd.read_record(write(tmp_path, "r.csv", "0, 0.1\n0.01, 0.2\n"), gain=2.0)


def test_knet_station_files_grouped_and_resampled_to_the_smallest_step(tmp_path):
    ud = write(tmp_path, "s.UD", knet(COUNTS[::2], direction="U-D", frequency="50Hz"))
    ew = write(tmp_path, "s.EW", knet(direction="E-W"))
    ns = write(tmp_path, "s.NS", knet(direction="N-S"))
    with pytest.warns(UserWarning, match=r"channels of steps 0.01, 0.02 s resampled to 0.01 s"):
        motion = bd.read_motion(ud, ew, ns)
    assert [c.metadata["component"] for c in motion.components] == ["N-S", "E-W", "U-D"]
    assert motion.z.dt == 0.01
    a = COUNTS[::2] * 3920.0 / 6182761.0 * CM
    a -= a.mean()  # K-NET: the mean removed by default
    np.testing.assert_allclose(motion.z.acceleration_samples[::2], a[:motion.z.acceleration_samples[::2].size],
                               rtol=1e-12, atol=1e-15)  # the old samples, kept at the new step


def test_channels_of_two_stations_are_refused(tmp_path):
    a = write(tmp_path, "a.NS", knet(direction="N-S"))
    b = write(tmp_path, "b.EW", knet(direction="E-W", station="IWT010"))
    with pytest.raises(ValueError, match=r"channels of different stations \('IWT010', 'MYG004'\)"):
        bd.read_motion(a, b)
