"""Ordinary input mistakes end in an error or a warning, never a silent wrong number: units not
stated, m/s² read as g, a time column in milliseconds or sample numbers, a K-NET offset, a target
PGA typed in m/s². Each case through the Python API and the command line.

References: the same record read from its own file in g (pySLAMMER's Kobe TAK-090, whose comment
line states g); for the K-NET file, the raw counts times the scale factor less their mean,
computed here with numpy.
"""

import importlib.resources
import importlib.util
import json
import pathlib
import re
import warnings

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli._main import main


#: the deprecated many-motion functions keep their tests for the release they stay
pytestmark = [pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_many is deprecated:DeprecationWarning"),
              pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_final is deprecated:DeprecationWarning")]


G = bd.STANDARD_GRAVITY
KOBE = importlib.resources.files("pyslammer") / "sample_ground_motions" / "Kobe_1995_TAK-090.csv"
KNET = (pathlib.Path(importlib.util.find_spec("obspy").origin).parent / "io" / "nied" / "tests" / "data" / "test.knet"
        if importlib.util.find_spec("obspy") else None)
needs_obspy = pytest.mark.skipif(KNET is None, reason="ObsPy not installed (the optional extra blockdae[seismo])")


@pytest.fixture(scope="module")
def kobe_g():
    """Kobe TAK-090 as pySLAMMER ships it: (time [s], acceleration [g]), the record read from it."""
    table = np.loadtxt(KOBE, delimiter=",", comments="#")
    return table, bd.read_record(KOBE)


def write_table(path, time, acceleration, header=None):
    """A two-column CSV of ``time`` and ``acceleration``, with ``header`` as its first line if given."""
    np.savetxt(path, np.c_[time, acceleration], delimiter=",", fmt="%.10g")
    if header is not None:
        path.write_text(header + "\n" + path.read_text())
    return path


def run_cli(capsys, *argv):
    """(exit status, stdout, stderr) of ``blockdae argv``."""
    status = main(["--no-cache", *map(str, argv)])
    out, err = capsys.readouterr()
    return status, out, err


# --- units are stated, never assumed -----------------------------------------------------------

def test_a_table_without_units_is_refused_with_the_peak_in_each_unit(tmp_path, kobe_g):
    """Kobe in m/s², no header: no longer read as g (98 m); the error names the file and its peak
    in g (implausible), m/s² and cm/s²; units="m/s2" reads it as the g file."""
    table, reference = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0], table[:, 1] * G)
    with pytest.raises(ValueError, match=re.escape(
            f"{path}: the units of the accelerations are not stated (no header such as 'time (s), acceleration "
            "(m/s2)'); pass units= (command line: --units) g, m/s2 or cm/s2. Its peak 6.036 would be 6.036 g "
            "(implausible); 6.036 m/s² = 0.616 g; 6.036 cm/s² = 0.00616 g")):
        bd.read_record(path)
    record = bd.read_record(path, units="m/s2")
    np.testing.assert_allclose(record.acceleration_samples, reference.acceleration_samples, rtol=1e-9)


def test_m_s2_read_as_g_is_refused_naming_the_likely_units(tmp_path, kobe_g):
    """A 6.04 g peak is beyond anything recorded (4 g): refused, naming m/s²; check_peak=False accepts it."""
    table, _ = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0], table[:, 1] * G)
    with pytest.raises(ValueError, match=re.escape(
            f"{path}: peak acceleration 6.036 g is implausible (above the largest peaks recorded; plausible: "
            "0.0001 g to 4 g); looks like m/s² read as g: pass units='m/s2', or check_peak=False (command line: "
            "--accept-peak) to accept it")):
        bd.read_record(path, units="g")
    assert bd.read_record(path, units="g", check_peak=False).peak_acceleration == pytest.approx(6.036 * G, rel=1e-3)
    with pytest.raises(ValueError, match=r"^Record: peak acceleration 59.19 m/s² = 6.036 g is implausible .* "
                                         r"looks like cm/s² read as m/s²: pass units='cm/s2'"):
        bd.Record(table[:, 1] * G * G, 0.01)  # an array converted to m/s² twice: the same rule as for files


@pytest.mark.parametrize("header", [
    "# time (s), acceleration (m/s2)",  # numpy's savetxt header: a comment line
    "Time,Acceleration in m/s2", "time, acc (m/s^2)", "t [s], a [m/s**2]", "time (s), a (m/s²)",
])
def test_units_in_a_header_or_comment_line_are_read(tmp_path, kobe_g, header):
    table, reference = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0], table[:, 1] * G, header)
    record = bd.read_record(path)
    assert record.metadata["units"] == "m/s2"
    np.testing.assert_allclose(record.acceleration_samples, reference.acceleration_samples, rtol=1e-9)


@pytest.mark.parametrize("header, scale", [("time (s), acc (cm/sec2)", 100 * G), ("t, a (gal)", 100 * G),
                                           ("time (s), acceleration (g)", 1.0), ("time, acc in g", 1.0),
                                           ("# Time (s),Acceleration (g's)", 1.0)])
def test_other_header_units(tmp_path, kobe_g, header, scale):
    table, reference = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0], table[:, 1] * scale, header)
    np.testing.assert_allclose(bd.read_record(path).acceleration_samples, reference.acceleration_samples, rtol=1e-9)


def test_cli_needs_units_for_a_bare_table(tmp_path, capsys, kobe_g):
    """newmark and flexible refuse the bare m/s² table (exit 2); --units m/s2 gives the D of the g file."""
    table, reference = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0], table[:, 1] * G)
    for command in (["newmark", path, "--ky", "0.1"], ["flexible", path, "--ky", "0.1", "--height", "10",
                                                       "--vs", "200"]):
        status, out, err = run_cli(capsys, *command)
        assert status == 2 and out == ""
        assert err.startswith(f"blockdae: error: {path}: the units of the accelerations are not stated")
        assert "6.036 m/s² = 0.616 g" in err
    status, out, err = run_cli(capsys, "newmark", path, "--ky", "0.1", "--units", "g")
    assert status == 2 and "looks like m/s² read as g: pass units='m/s2'" in err and "--accept-peak" in err
    status, out, _ = run_cli(capsys, "newmark", path, "--ky", "0.1", "--units", "m/s2", "--json")
    assert status == 0
    expected = bd.newmark(reference, 0.1)
    assert json.loads(out)["results"][0]["normal_m"] == pytest.approx(expected.normal, rel=1e-9)
    assert expected.normal == pytest.approx(1.942, abs=0.001)


# --- time step ---------------------------------------------------------------------------------

@pytest.mark.parametrize("time_scale, cause", [(1000.0, r"times in milliseconds \(10 ms = 0.01 s\)"),
                                               (100.0, r"a column of sample numbers")])
def test_a_time_column_in_ms_or_sample_numbers_is_refused(tmp_path, kobe_g, time_scale, cause):
    table, reference = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0] * time_scale, table[:, 1], "time, acc (g)")
    with pytest.raises(ValueError, match=rf"^{re.escape(str(path))}, lines 2-3: the time column: sample step dt = "
                                         rf"{0.01 * time_scale:g} s is implausible for an accelerogram \(above 0.1 s\):"
                                         rf" .*{cause}.*Give the times in seconds, or check_step=False \(command line: "
                                         r"--accept-step\) to accept it"):
        bd.read_record(path)
    with pytest.warns(bd.RecordWarning, match=r"resolves periods down to"):
        assert bd.read_record(path, check_step=False).dt == pytest.approx(0.01 * time_scale)


def test_a_coarse_step_is_warned_about(tmp_path, kobe_g):
    """dt = 0.04 s: under 4 samples a 0.1 s period; read, with a warning."""
    table, _ = kobe_g
    path = write_table(tmp_path / "k.csv", table[::4, 0], table[::4, 1], "time (s), acc (g)")
    with pytest.warns(bd.RecordWarning, match=r"sample step dt = 0.04 s resolves periods down to 0.16 s only"):
        assert bd.read_record(path).dt == pytest.approx(0.04)
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.RecordWarning)
        bd.read_record(KOBE)  # dt = 0.01 s: silent


def test_cli_refuses_a_step_in_ms_and_accepts_it_when_told(tmp_path, capsys, kobe_g):
    table, _ = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0] * 1000, table[:, 1], "time, acc (g)")
    status, _, err = run_cli(capsys, "newmark", path, "--ky", "0.1")
    assert status == 2 and "sample step dt = 10 s is implausible" in err and "milliseconds" in err
    status, _, err = run_cli(capsys, "newmark", path, "--ky", "0.1", "--accept-step")
    assert status == 0 and "blockdae: warning:" in err and "resolves periods down to 40 s" in err


# --- offsets -----------------------------------------------------------------------------------

@needs_obspy
def test_knet_mean_removed_by_default_and_said_so():
    """ObsPy's test.knet: its mean is 51 % of the raw peak. Removed by default: D at 0.3 g equals
    that of the raw samples less their mean (numpy), not the 5378 m of the offset record."""
    record = bd.read_record(KNET)
    with pytest.warns(bd.RecordWarning, match=r"test.knet: the samples' mean is 51 % of their peak \(above 5 %\): "
                                              r"an offset .* remove_mean=True .*--remove-mean"):
        raw = bd.read_record(KNET, remove_mean=False)
    assert record.metadata["mean_removed"] is True and raw.metadata["mean_removed"] is False
    assert record.metadata["mean_m_s2"] == pytest.approx(raw.acceleration_samples.mean(), rel=1e-12)
    centred = bd.Record(raw.acceleration_samples - raw.acceleration_samples.mean(), raw.dt)
    np.testing.assert_allclose(record.acceleration_samples, centred.acceleration_samples, rtol=0, atol=1e-15)
    d = bd.newmark(record, [0.05, 0.1], pga=0.3)
    np.testing.assert_allclose(d.inverse, bd.newmark(centred, [0.05, 0.1], pga=0.3).inverse, rtol=1e-12)
    assert d.inverse[0] == pytest.approx(0.522, abs=0.001) and d.inverse[1] == pytest.approx(0.0488, abs=0.0002)


def test_a_table_with_an_offset_is_warned_about_with_the_fix(tmp_path, kobe_g):
    """Kobe plus 0.1 g: mean 14 % of the peak, warned about; remove_mean=True subtracts it, silently."""
    table, reference = kobe_g
    shifted = table[:, 1] + 0.1
    path = write_table(tmp_path / "k.csv", table[:, 0], shifted, "time (s), acc (g)")
    fraction = abs(shifted.mean()) / np.max(np.abs(shifted))
    with pytest.warns(bd.RecordWarning, match=rf"k.csv: the samples' mean is {100 * fraction:.3g} % of their peak "
                                              r"\(above 5 %\): an offset .* remove_mean=True"):
        bd.read_record(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.RecordWarning)
        centred = bd.read_record(path, remove_mean=True)
    own = reference.acceleration_samples
    np.testing.assert_allclose(centred.acceleration_samples, own - own.mean(), rtol=0, atol=1e-12)


@needs_obspy
def test_cli_knet_offset_removed_reported_and_kept_on_request(capsys):
    status, out, err = run_cli(capsys, "newmark", KNET, "--ky", "0.05", "0.1", "--pga", "0.3", "--json")
    assert status == 0 and "warning" not in err
    rows = {round(r["ky_g"], 2): r for r in json.loads(out)["results"]}
    expected = bd.newmark(bd.read_record(KNET), [0.05, 0.1], pga=0.3)
    assert rows[0.05]["inverse_m"] == pytest.approx(expected.inverse[0], rel=1e-12)
    status, out, err = run_cli(capsys, "newmark", KNET, "--ky", "0.05", "--pga", "0.3", "--no-remove-mean")
    assert status == 0 and "blockdae: warning:" in err and "51 % of their peak" in err
    status, out, _ = run_cli(capsys, "info", KNET)
    assert status == 0 and re.search(r"offset +mean -0.04293 m/s² removed on reading", out)
    status, out, _ = run_cli(capsys, "info", "--no-remove-mean", KNET)
    assert re.search(r"offset +mean -0.04293 m/s² = 51 % of the peak: an offset \(above 5 %\)", out)


def test_cli_remove_mean_and_baseline_on_a_table(tmp_path, capsys, kobe_g):
    """--remove-mean subtracts the mean; --baseline mean corrects it (bd.motions.baseline_corrected), without the
    warning."""
    table, _ = kobe_g
    path = write_table(tmp_path / "k.csv", table[:, 0], table[:, 1] + 0.1, "time (s), acc (g)")
    status, _, err = run_cli(capsys, "newmark", path, "--ky", "0.1")
    assert status == 0 and "the samples' mean is" in err
    with pytest.warns(bd.RecordWarning):
        offset = bd.read_record(path)
    for flags, record in ((["--remove-mean"], bd.read_record(path, remove_mean=True)),
                          (["--baseline", "mean"], bd.motions.baseline_corrected(offset, "mean"))):
        status, out, err = run_cli(capsys, "newmark", path, "--ky", "0.1", "--json", *flags)
        assert status == 0 and "warning" not in err
        got = json.loads(out)["results"][0]["normal_m"]
        assert got == pytest.approx(bd.newmark(record, 0.1).normal, rel=1e-12)


# --- target PGA --------------------------------------------------------------------------------

def test_a_target_pga_in_m_s2_is_refused_in_every_api(kobe_g):
    _, record = kobe_g
    message = re.escape("=2.94 g is implausible for a peak ground acceleration (above 2 g); it looks like m/s² "
                        "(2.94 m/s² = 0.2998 g)")
    with pytest.raises(ValueError, match="^pga" + message):
        bd.newmark(record, 0.05, pga=2.94)
    with pytest.warns(DeprecationWarning, match="use bd.newmark"), pytest.raises(ValueError, match="^pga" + message):
        bd.newmark(record, 0.05, target_pga=2.94)  # the deprecated name, the same rule
    with pytest.raises(ValueError, match="^pga" + message):
        bd.newmark([record], 0.05, pga=[0.3, 2.94])
    with pytest.raises(ValueError, match="^pga" + message):
        bd.flexible(record, 0.05, 10.0, 200.0, pga=2.94)
    with pytest.raises(ValueError, match="^pga" + message):
        bd.study([record], mu=[0.05], pga=[2.94])
    with pytest.raises(ValueError, match="^pga" + message):
        bd.sliding.simulate_many(bd.SlidingBlock(0.05), [record], pga=2.94)
    confirmed = bd.newmark(record, 0.5, pga=2.94, check_peak=False)
    scaled = record.scaled(2.94 * G / record.peak_acceleration)
    assert confirmed.normal == pytest.approx(bd.newmark(scaled, 0.5).normal, rel=1e-12)
    assert bd.newmark(record, 0.5, pga=2.0).normal > 0  # 2 g: accepted


def test_cli_refuses_a_target_pga_in_m_s2(capsys):
    for command in (["newmark", KOBE, "--ky", "0.05", "--pga", "2.94"],
                    ["flexible", KOBE, "--ky", "0.05", "--height", "10", "--vs", "200", "--pga", "2.94"]):
        status, out, err = run_cli(capsys, *command)
        assert status == 2 and "2.94 g is implausible for a peak ground acceleration (above 2 g)" in err
        assert "--accept-peak" in err
    status, out, err = run_cli(capsys, "newmark", KOBE, "--ky", "0.5", "--pga", "2.94", "--accept-peak")
    assert status == 0 and "scaled to a peak of 2.94 g" in out
