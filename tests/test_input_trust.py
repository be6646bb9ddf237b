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
    centred = bd.Record(raw.acceleration_samples - raw.acceleration_samples.mean(), raw.dt, units="m/s2")
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


# --- the plausibility rules: ky, the column, peaks, results --------------------------------

def test_flexible_refuses_a_ky_in_m_s2_and_warns_about_a_ky_not_reached_as_newmark_does(kobe_g, capsys):
    """ky=9.81 (one g typed in m/s²) is refused and ky=0.98 (above kmax, D = 0) warned about, as
    bd.newmark does against the PGA; the flexible mass's sliding is driven by kmax, the peak of its
    average acceleration (0.8427 g for Kobe TAK-090 under H = 20 m, vs = 300 m/s)."""
    _, record = kobe_g
    with pytest.raises(ValueError, match=re.escape("ky=9.81 g is above 1 g and kmax (0.8427 g): it looks like m/s² "
                                                   "(9.81 m/s² = 1 g); give ky in g")):
        bd.flexible(record, ky=9.81, height=20.0, vs=300.0)
    with pytest.raises(ValueError, match=r"ky=9.81 g is above 1 g and the motion's peak \(0.6155 g\)"):
        bd.newmark(record, 9.81)
    with pytest.warns(bd.UnitsWarning, match=re.escape("ky=0.98 g >= kmax = 0.8427 g: the mass does not slide, "
                                                       "D = 0 m")):
        result = bd.flexible(record, ky=0.98, height=20.0, vs=300.0)
    assert result.rows[0]["normal_m"] == 0 and result.rows[0]["inverse_m"] == 0
    with pytest.warns(bd.UnitsWarning, match=r"ky >= kmax in 1 of 2 analyses: the mass does not slide there, D = 0 m: "
                                             r"Kobe_1995_TAK-090 \(kmax 0.8427 g\): ky=0.98 g"):
        bd.flexible(record, ky=[0.1, 0.98], height=20.0, vs=300.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.UnitsWarning)
        assert bd.flexible(record, ky=0.8, height=20.0, vs=300.0).rows[0]["normal_m"] > 0  # below kmax: slides
    status, out, err = run_cli(capsys, "flexible", KOBE, "--ky", "9.81", "--height", "20", "--vs", "300")
    assert status == 2 and out == "" and "ky=9.81 g is above 1 g and kmax (0.8427 g): it looks like m/s²" in err
    status, out, err = run_cli(capsys, "flexible", KOBE, "--ky", "0.98", "--height", "20", "--vs", "300")
    assert status == 0 and "blockdae: warning: ky=0.98 g >= kmax = 0.8427 g: the mass does not slide, D = 0 m" in err


@pytest.mark.parametrize("given, message", [
    (dict(vs=0.3), "vs=0.3 m/s is implausible for a soil's or rock's shear-wave velocity (plausible: 30 m/s to "
                   "5000 m/s); in other units? 0.3 km/s = 300 m/s; give vs in m/s"),
    (dict(vr=0.6), "vr=0.6 m/s is implausible for a soil's or rock's shear-wave velocity (plausible: 30 m/s to "
                   "5000 m/s); in other units? 0.6 km/s = 600 m/s"),
    (dict(height=20000.0), "height=20000 m is implausible for a sliding mass's height (plausible: 0.5 m to 500 m); "
                           "in other units? 20000 cm = 200 m or 20000 mm = 20 m; give height in m"),
    (dict(height=0.02), "height=0.02 m is implausible for a sliding mass's height (plausible: 0.5 m to 500 m); in "
                        "other units? 0.02 km = 20 m"),
    (dict(damping=0.5), "damping=0.5 is a damping ratio of 50 %, above the 30 % a soil reaches: if it is a "
                        "percentage, give damping=0.005"),
])
def test_flexible_warns_about_a_column_in_other_units(kobe_g, given, message):
    """Vs typed in km/s gave D = 0.0005 m and a column period of 267 s without a word; each column value
    outside the range of slopes is warned about, naming the unit that brings it in."""
    _, record = kobe_g
    parameters = dict(ky=0.1, height=20.0, vs=300.0) | given
    with pytest.warns(bd.UnitsWarning, match=re.escape(message)):
        bd.flexible(record, **parameters)


def test_flexible_refuses_a_damping_in_percent_and_is_silent_on_plausible_columns(kobe_g, capsys):
    _, record = kobe_g
    with pytest.raises(ValueError, match=re.escape("damping=5 is a damping ratio of 500 %: give the ratio, not a "
                                                   "percentage (5 % is damping=0.05)")):
        bd.flexible(record, ky=0.1, height=20.0, vs=300.0, damping=5)
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.UnitsWarning)
        bd.flexible(record, ky=0.1, height=[1.0, 20.0, 300.0], vs=[50.0, 300.0, 3000.0], vr=1000.0, damping=0.2)
    status, out, err = run_cli(capsys, "flexible", KOBE, "--ky", "0.1", "--height", "20", "--vs", "0.3")
    assert status == 0 and "blockdae: warning: vs=0.3 m/s is implausible" in err and "0.3 km/s = 300 m/s" in err


def test_a_column_built_anywhere_gets_the_column_rules_once(kobe_g, capsys, tmp_path):
    """bd.simulate and bd.study on FlexibleSlidingMass(ShearColumn(20, 0.3), ...) ran a column of
    267 s without a word: the column's rules apply where it is built (once per column: bd.flexible
    does not warn twice, nor per parameter set), and a damping in percent is refused there."""
    _, record = kobe_g
    message = "vs=0.3 m/s is implausible for a soil's or rock's shear-wave velocity (plausible: 30 m/s to 5000 m/s); " \
              "in other units? 0.3 km/s = 300 m/s; give vs in m/s"
    with pytest.warns(bd.UnitsWarning, match=re.escape(message)):
        bd.ShearColumn(20.0, 0.3)
    with pytest.warns(bd.UnitsWarning, match=re.escape("height=20000 m is implausible")):
        bd.FlexibleSlidingMass(bd.ShearColumn(20000.0, 300.0), ky=np.array([0.1, 0.2]))
    with pytest.raises(ValueError, match=re.escape("damping=5 is a damping ratio of 500 %: give the ratio")):
        bd.ShearColumn(20.0, 300.0, damping=5.0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bd.flexible(record, ky=0.1, height=20.0, vs=[0.3, 0.4, 300.0])
    assert [str(w.message) for w in caught if "implausible" in str(w.message)] == [message]
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.UnitsWarning)
        bd.ShearColumn(20.0, 300.0, 600.0, 0.05)  # plausible: silent
        bd.ShearColumn(20.0, 300.0, damping=-0.05)  # SLAMMER's offset of the impedance damping: the model's to check
    folder = tmp_path / "records"
    folder.mkdir()
    (folder / KOBE.name).write_bytes(KOBE.read_bytes())
    status, _, err = run_cli(capsys, "study", folder, "--pga", "0.3", "--ky", "0.1", "--height", "20", "--vs", "0.3",
                             "--out", tmp_path / "study.csv")
    assert status == 0 and err.count("blockdae: warning: vs=0.3 m/s is implausible") == 1, err


def test_simulate_and_study_refuse_a_ky_of_the_flexible_mass_in_m_s2(kobe_g):
    """bd.flexible refuses ky=9.81 (one g typed in m/s², above 1 g and kmax); bd.simulate and bd.study
    on the same mass returned D = 0. The peak named is kmax, as bd.flexible finds it (0.8427 g)."""
    _, record = kobe_g
    column = bd.ShearColumn(20.0, 300.0)
    with pytest.raises(ValueError, match=r"^ky=9.81 g is above 1 g and the peak of the mass's average acceleration HEA "
                                         r"\(0.84\d* g\): it looks like m/s² \(9.81 m/s² = 1 g\); give ky in g"):
        bd.simulate(bd.FlexibleSlidingMass(column, ky=9.81), record, t_end="motion")
    with pytest.raises(ValueError, match=r"^parameter set 1 of 2: ky=9.81 g is above 1 g"):
        bd.simulate(bd.FlexibleSlidingMass(column, ky=np.array([0.1, 9.81])), record, t_end="motion")
    with pytest.raises(ValueError, match=re.escape("Kobe_1995_TAK-090: ky=9.81 g is above 1 g and kmax (0.8427 g)")):
        bd.study([record], ky=[0.1, 9.81], scale=1.0, block=bd.FlexibleSlidingMass(column, ky=0.1))
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.UnitsWarning)
        batch = bd.simulate(bd.FlexibleSlidingMass(column, ky=np.array([0.1, 0.98])), record, t_end="motion")
    assert batch.displacement[0] > 0 and batch.displacement[1] == 0  # 0.98 g < 1 g: not refused


def test_an_array_without_units_whose_peak_reads_as_g_is_warned_about(kobe_g):
    """Kobe in g (peak 0.6155) given without units ran as a record of 0.063 g; it is warned about, naming
    units='g'; stating the units (either) silences it; a peak above 2 m/s² cannot be g read as m/s²."""
    table, reference = kobe_g
    with pytest.warns(bd.UnitsWarning, match=re.escape(
            "Record: no units given, the samples are read as m/s²: a peak of 0.6155 m/s² = 0.06277 g; if they are in "
            "g (a peak of 0.6155 g), pass units='g'; pass units='m/s2' to state m/s²")):
        bd.Record(table[:, 1], 0.01)
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.UnitsWarning)
        in_g = bd.Record(table[:, 1], 0.01, units="g")
        bd.Record(table[:, 1], 0.01, units="m/s2")
        bd.Record(table[:, 1] * G, 0.01)  # 6.04 m/s²: no g reading
        bd.Record(table[:, 1], 0.01, check_peak=False)
    np.testing.assert_allclose(in_g.acceleration_samples, reference.acceleration_samples, rtol=1e-12)


def test_a_peak_above_2_g_with_stated_units_is_warned_about(tmp_path, kobe_g, capsys):
    """A weak record (Kobe scaled to 0.03078 g) in cm/s² read as m/s² is a 3.078 g record (D = metres for none):
    above 2 g, warned about naming cm/s², from an array, a file and the command line."""
    table, _ = kobe_g
    weak_cm_s2 = table[:, 1] * 0.05 * G * 100
    message = "peak acceleration 30.18 m/s² = 3.078 g is above 2 g, rarer than a unit mix-up: it looks like cm/s² " \
              "read as m/s² (30.18 cm/s² = 0.03078 g)"
    with pytest.warns(bd.UnitsWarning, match=re.escape(f"Record: {message}: pass units='cm/s2'")):
        bd.Record(weak_cm_s2, 0.01, units="m/s2")
    path = write_table(tmp_path / "weak.csv", table[:, 0], weak_cm_s2, "time (s), acc (m/s2)")
    with pytest.warns(bd.UnitsWarning, match=re.escape(f"{path}: {message}: correct the file (the header's line 1: "
                                                       "'time (s), acc (m/s2)' sets the units)")):
        bd.read_record(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error", bd.UnitsWarning)
        bd.read_record(path, check_peak=False)
        assert bd.Record(weak_cm_s2, 0.01, units="cm/s2").peak_acceleration == pytest.approx(0.3018, rel=1e-3)
    status, out, err = run_cli(capsys, "newmark", path, "--ky", "0.1")
    assert status == 0 and f"blockdae: warning: {path}: {message}" in err


def test_a_result_that_overflows_is_an_error():
    """Samples of 1e300 m/s² (accepted with check_peak=False) overflowed to D = inf, returned silently."""
    t = np.arange(0.0, 10.0, 0.01)
    record = bd.Record(3.0 * np.sin(2 * np.pi * t) * 1e300, 0.01, "huge", check_peak=False)
    with pytest.raises(ValueError, match=r"^bd.simulate: u at the end \[m\] of SlidingBlock\(mu=0.1, .*\) under 'huge' "
                                         r"at scale 1, normal polarity is -inf \(not a finite number: the computation "
                                         r"overflowed\)"):
        bd.newmark(record, 0.1, check_peak=False)  # the block of bd.newmark slides the other way: u = -D
    with pytest.raises(ValueError, match=r"bd.simulate: u at the end .* under 'huge' .* is -inf"):
        bd.newmark([record], [0.1, 0.2], check_peak=False)


def test_simulate_never_returns_a_result_that_overflows():
    """The same record through bd.simulate returned u = -inf silently: on every path (one run, a
    batch of parameter sets, an ensemble of full solutions, final numbers from one compiled call)
    it is an error naming the quantity, the motion and the model."""
    t = np.arange(0.0, 10.0, 0.01)
    huge = bd.Record(3.0 * np.sin(2 * np.pi * t) * 1e300, 0.01, "huge", check_peak=False)
    block = bd.SlidingBlock(mu=0.1)
    named = r"bd.simulate: u at the end \[m\] of SlidingBlock\(mu=0.1, .*\) under 'huge' is -inf \(not a finite number"
    with pytest.raises(ValueError, match=named):
        bd.simulate(block, huge)
    with pytest.raises(ValueError, match=r"bd.simulate: u at the end \[m\] of SlidingBlock\(mu=0.2, .*\) under "
                                         r"'huge' is -inf"):
        bd.simulate(bd.SlidingBlock(mu=np.array([0.2, 0.3])), huge)
    with pytest.raises(ValueError, match=named) as caught:
        bd.simulate(block, [huge], scale=[1.0, 2.0])
    assert "in the case huge at scale 1, normal polarity" in caught.value.__notes__
    with pytest.raises(ValueError, match=r"of SlidingBlock\(mu=0.1, .*\) under 'huge' at scale 1, normal polarity "
                                         r"is -inf"):
        bd.simulate(block, [huge], scale=[1.0, 2.0], final_only=True)
    ordinary = bd.Record(3.0 * np.sin(2 * np.pi * t), 0.01, "ordinary", units="m/s2")
    assert np.isfinite(bd.simulate(block, ordinary).displacement)


def test_a_planar_run_that_overflows_in_python_floats_is_named():
    """The planar block's guards are Python floats: 1e300 m/s² on both axes squared to an
    OverflowError raised from deep inside the event search, naming neither run nor motion."""
    huge = np.array([0.0, 1e300, -1e300, 0.0])
    motion = bd.BaseMotion(bd.Record(huge, 0.01, "huge x", check_peak=False),
                           bd.Record(huge, 0.01, "huge y", check_peak=False))
    with pytest.raises(ValueError, match=r"^bd.simulate: the run of PlanarBlock\(mu=0.2, .*\) under a BaseMotion "
                                         r"overflowed \(a value beyond 1.8e308: .*\); check the motion's units") as caught:
        bd.simulate(bd.PlanarBlock(mu=0.2), motion)
    assert isinstance(caught.value.__cause__, OverflowError)


# --- readers: a cut value, a malformed first row, time units, a changed file --------------

def _at2(values):
    """The text of a PEER AT2 file of ``values`` [g] at dt = 0.01 s, five to a line as PEER writes them."""
    lines = ["".join(f"{v:15.7E}" for v in values[i:i + 5]) for i in range(0, len(values), 5)]
    return ("PEER NGA STRONG MOTION DATABASE RECORD\nTEST 1/1/2000, STATION, 090\n"
            f"ACCELERATION TIME SERIES IN UNITS OF G\nNPTS= {len(values):6d}, DT=   .0100 SEC\n" + "\n".join(lines) + "\n")


def test_an_at2_cut_inside_its_last_value_is_refused(tmp_path, kobe_g, capsys):
    """Kobe as an AT2 cut one character short ('...E-0' for '...E-01'): the count still matches and the last
    value still parses (as a value 10 times too large); refused naming the file and line."""
    table, reference = kobe_g
    values = table[:, 1].copy()
    values[-1] = -0.35901855  # written -3.5901855E-01
    intact = tmp_path / "intact.AT2"
    intact.write_text(_at2(values))
    np.testing.assert_allclose(bd.read_record(intact).acceleration_g, values, rtol=1e-7)
    cut = tmp_path / "cut.AT2"
    cut.write_text(intact.read_text().rstrip()[:-1])
    assert cut.read_text().endswith("-3.5901855E-0")
    line = len(cut.read_text().split("\n"))
    message = (f"{cut}, line {line}: the last value, '-3.5901855E-0', is written shorter than the values before it "
               f"('{values[-2]:.7E}'): the file is cut short; get it again")
    with pytest.raises(ValueError, match=re.escape(message)):
        bd.read_record(cut)
    status, out, err = run_cli(capsys, "newmark", cut, "--ky", "0.1")
    assert status == 2 and out == "" and message in err


@pytest.mark.parametrize("header", ["", "time (s), acc (g)\n"])
def test_a_malformed_first_data_row_is_not_taken_for_a_header(tmp_path, capsys, header):
    """'0.00,--1' was read as a header (one sample lost, the start time shifted); a header line names
    its columns in words, so this one is a data line that is not a number: refused naming the line."""
    path = tmp_path / "bad.csv"
    path.write_text(header + "0.00,--1\n0.01,0.2\n0.02,-0.1\n0.03,0.05\n")
    line = 2 if header else 1
    message = (f"{path}, line {line}: not a number, '--1', in '0.00,--1': a data line, not a header (a header line "
               "names the columns in words; start a comment line with '#')")
    with pytest.raises(ValueError, match=re.escape(message)):
        bd.read_record(path, units=None if header else "g")
    status, _, err = run_cli(capsys, "newmark", path, "--ky", "0.1", "--units", "g")
    assert status == 2 and message in err
    path.write_text(header + "Kobe 1995 TAK-090\n0.00,0.1\n0.01,-0.2\n0.02,0.1\n")  # a title: 3 fields, words
    record = bd.read_record(path, units=None if header else "g")
    assert record.acceleration_samples.size == 3 and record.start_time == 0


def test_a_time_column_in_ms_is_read_as_the_header_says(tmp_path, kobe_g, capsys):
    """'time (ms), acc (g)' was read in seconds (dt = 10 s, refused as milliseconds even though the header
    said so); its times are read in ms: the record of the file in seconds. An unknown time unit is refused."""
    table, reference = kobe_g
    path = write_table(tmp_path / "ms.csv", table[:, 0] * 1000, table[:, 1], "time (ms), acc (g)")
    record = bd.read_record(path)
    assert record.dt == 0.01 and record.start_time == pytest.approx(table[0, 0], abs=1e-12)
    np.testing.assert_allclose(record.acceleration_samples, reference.acceleration_samples, rtol=1e-12)
    status, out, _ = run_cli(capsys, "newmark", path, "--ky", "0.1", "--json")
    assert status == 0
    assert json.loads(out)["results"][0]["normal_m"] == pytest.approx(bd.newmark(reference, 0.1).normal, rel=1e-12)
    for header, scale in (("t_ms, a (g)", 1000), ("Time in seconds, acc (g)", 1), ("t [s], a [g]", 1)):
        path = write_table(tmp_path / "t.csv", table[:, 0] * scale, table[:, 1], header)
        assert bd.read_record(path).dt == 0.01
    path = write_table(tmp_path / "min.csv", table[:, 0] / 60, table[:, 1], "time (min), acc (g)")
    with pytest.raises(ValueError, match=re.escape(f"{path}, line 1: 'time (min), acc (g)': the header names the "
                                                   "time in 'min', not a unit read here (s or ms): convert the time "
                                                   "column to seconds")):
        bd.read_record(path)


def test_a_record_set_never_returns_a_record_its_table_does_not_describe(tmp_path, kobe_g):
    """A file changed after the set was listed: its table kept the old PGA while the record read later had
    the new data; the record is now refused, naming the file, until the set is read again."""
    table, _ = kobe_g
    write_table(tmp_path / "a.csv", table[:, 0], table[:, 1], "time (s), acc (g)")
    changed = write_table(tmp_path / "b.csv", table[:, 0], table[:, 1], "time (s), acc (g)")
    records = bd.read_records(tmp_path)
    assert records.table["pga_g"].tolist() == pytest.approx([0.6155] * 2, abs=1e-4)
    write_table(changed, table[:, 0], 0.5 * table[:, 1], "time (s), acc (g)")
    assert records["a"].peak_acceleration == pytest.approx(0.6155 * G, abs=1e-3)  # unchanged: read
    with pytest.raises(ValueError, match=re.escape(f"{changed}: the file changed after the record set was read")):
        records["b"]
    again = bd.read_records(tmp_path)
    assert again.table["pga_g"].tolist()[1] == pytest.approx(again["b"].peak_acceleration / G, rel=1e-12)
