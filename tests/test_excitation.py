"""Excitations, file readers and input validation."""

import numpy as np
import pytest

import blockdae as bd
from blockdae.excitation import STANDARD_GRAVITY


def test_harmonic_base_motion_is_seed_eqs_1_to_3():
    """a = A sin wt, v = -(A/w) cos wt, x = -(A/w²) sin wt + (A/w) t - ... integrated from v(0)."""
    m = bd.Harmonic(9.0, 1.0)
    t = np.linspace(0, 2.3, 17)
    w = 2 * np.pi
    np.testing.assert_allclose(m.acceleration(t), 9 * np.sin(w * t), atol=1e-12)
    np.testing.assert_allclose(m.velocity(t), -(9 / w) * np.cos(w * t), atol=1e-12)
    np.testing.assert_allclose(m.displacement(t), -(9 / w**2) * np.sin(w * t), atol=1e-12)


def test_pulses_base_motion_from_rest():
    """Seed Eqs. 15-16 (triangle) and 18 (sine): base at rest at t = 0."""
    tri = bd.TriangularPulse(9.0, 0.5)
    t = np.array([0.1, 0.3, 0.45])
    v = np.where(t < 0.25, 18 * t**2, -18 * t**2 + 18 * t - 2.25)
    x = np.where(t < 0.25, 6 * t**3, -6 * t**3 + 9 * t**2 - 2.25 * t + 0.1875)
    np.testing.assert_allclose(tri.velocity(t), v, rtol=1e-13)
    np.testing.assert_allclose(tri.displacement(t), x, rtol=1e-13)
    sine = bd.SinePulse(9.0, 0.5)
    w = 2 * np.pi
    np.testing.assert_allclose(sine.velocity(t), 9 / w * (1 - np.cos(w * t)), rtol=1e-13)
    np.testing.assert_allclose(sine.displacement(t), 9 / w * (t - np.sin(w * t) / w), rtol=1e-12)
    assert sine.acceleration(0.7) == 0.0 and sine.velocity(0.7) == pytest.approx(18 / w, rel=1e-14)


def test_record_is_linear_between_samples_and_zero_after():
    rec = bd.Record([0.0, 2.0, -1.0], dt=0.5)
    np.testing.assert_allclose(rec.acceleration([0.25, 0.75, 1.2]), [1.0, 0.5, 0.0])
    assert rec.duration == 1.0 and rec.peak_acceleration == 2.0
    np.testing.assert_array_equal(rec.breakpoints, [0.0, 0.5, 1.0])
    np.testing.assert_allclose(rec.scaled(2).acceleration_samples, [0, 4, -2])
    np.testing.assert_allclose(rec.inverted().acceleration_samples, [0, -2, 1])
    # v(1) = trapezoid area = 0.5 (0 + 2)/2 + 0.5 (2 - 1)/2
    assert rec.velocity(1.0) == pytest.approx(0.75, rel=1e-14)


def test_read_two_column_csv_with_bom_and_comments(tmp_path):
    path = tmp_path / "rec.csv"
    path.write_text("\ufeff# a comment\nTime (s),Acceleration (g)\n0.0,0.1\n0.01,-0.2 # inline\n0.02,0.05\n",
                    encoding="utf-8")
    rec = bd.read_record(path)
    assert rec.dt == pytest.approx(0.01) and rec.name == "rec"
    np.testing.assert_allclose(rec.acceleration_samples, np.array([0.1, -0.2, 0.05]) * STANDARD_GRAVITY)
    with pytest.raises(ValueError, match=r"units='cm/s2' \(cm/s²\) contradicts the header, line 2"):
        bd.read_record(path, units="cm/s2")  # the header's (g) is honoured or the call refused (issue 23)
    bare = tmp_path / "bare.csv"
    bare.write_text("\ufeff# a comment\nTime,Acceleration\n0.0,0.1\n0.01,-0.2 # inline\n0.02,0.05\n",
                    encoding="utf-8")
    rec_cm = bd.read_record(bare, units="cm/s2")
    np.testing.assert_allclose(rec_cm.acceleration_samples, [0.001, -0.002, 0.0005])


def test_read_one_column_needs_dt(tmp_path):
    path = tmp_path / "one.txt"
    path.write_text("0.1\n0.2\n-0.3\n")
    with pytest.raises(ValueError, match="needs the sample step dt"):
        bd.read_record(path)
    rec = bd.read_record(path, units="m/s2", dt=0.02)
    assert rec.dt == 0.02 and rec.acceleration_samples.tolist() == [0.1, 0.2, -0.3]


def test_read_peer_at2(tmp_path):
    path = tmp_path / "X.AT2"
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nTest 1994, Station, 090\n"
                    "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    5, DT=   .0050 SEC\n"
                    "  .1E-01  .2E-01 -.3E-01\n  .4E-01  .0E+00\n")
    rec = bd.read_record(path)
    assert rec.dt == 0.005
    np.testing.assert_allclose(rec.acceleration_samples / STANDARD_GRAVITY, [0.01, 0.02, -0.03, 0.04, 0.0])
    path.write_text(path.read_text().replace("NPTS=    5", "NPTS=    6"))
    with pytest.raises(ValueError, match="NPTS=6, found 5"):
        bd.read_record(path)


@pytest.mark.parametrize("body, message", [
    ("0.0,0.1\n0.01,0.2\n0.03,0.1\n", "line 3: time column is not uniform"),
    ("0.0,0.1\n0.01,0.2\n0.01,0.1\n", "line 3: time column is not increasing"),
    ("0.0,0.1\n0.01,abc\n", "line 2: not a number"),
    ("0.0,0.1\n0.01,0.2,0.3\n", "line 2: 3 columns"),
    ("# nothing\n", "no data rows"),
    ("0.0,0.1\n0.01,nan\n", "line 2: value nan is not finite"),
])
def test_reader_errors_name_file_and_place(tmp_path, body, message):
    path = tmp_path / "bad.csv"
    path.write_text(body)
    with pytest.raises(ValueError, match=message) as err:
        bd.read_record(path)
    assert "bad.csv" in str(err.value) or "sample" in message


def test_unknown_units():
    with pytest.raises(ValueError, match="units='ft/s2' is unknown"):
        bd.read_record("whatever.csv", units="ft/s2")


@pytest.mark.parametrize("kwargs, message", [
    (dict(acceleration=[], dt=0.01), "at least 2 samples"),
    (dict(acceleration=[1.0], dt=0.01), "at least 2 samples"),
    (dict(acceleration=[1.0, np.inf], dt=0.01), r"sample 1 \(0-based\) is inf"),
    (dict(acceleration=[1.0, 2.0], dt=0.0), "dt must be a positive"),
    (dict(acceleration=[1.0, 2.0], dt=-0.1), "dt must be a positive"),
    (dict(acceleration=[[1.0, 2.0]], dt=0.1), "1-D array"),
])
def test_record_validation(kwargs, message):
    with pytest.raises(ValueError, match=message):
        bd.Record(**kwargs)


@pytest.mark.parametrize("kwargs, message", [
    (dict(mu=-0.1), "mu=-0.1 must be >= 0"),
    (dict(mu=0.5, mu_kinetic=-0.1), "mu_kinetic=-0.1 must be >= 0"),
    (dict(mu=0.5, mu_kinetic=0.6), "mu_kinetic=0.6 must not exceed mu=0.5"),
    (dict(mu=0.5, bias=0.5), r"bias=0.5 must satisfy \|bias\| < mu=0.5"),
    (dict(mu=0.5, bias=-0.7), r"bias=-0.7 must satisfy"),
    (dict(mu=np.array([0.5, 0.2]), bias=0.3), r"bias=0.3 must satisfy \|bias\| < mu=0.2"),
    (dict(mu=float("nan")), "mu must be finite"),
    (dict(mu=0.5, g=0.0), "g must be a positive"),
    (dict(mu=0.5, direction="up"), "direction must be one of"),
    (dict(mu=np.array([0.5, 0.4]), mu_kinetic=np.array([0.1, 0.2, 0.3])), "broadcast"),
])
def test_block_validation(kwargs, message):
    with pytest.raises(ValueError, match=message):
        bd.SlidingBlock(**kwargs)


@pytest.mark.parametrize("make, message", [
    (lambda: bd.Harmonic(1.0, 0.0), "period must be a positive"),
    (lambda: bd.Harmonic(float("nan"), 1.0), "amplitude must be finite"),
    (lambda: bd.RectangularPulse(1.0, -1.0), "duration must be a positive"),
    (lambda: bd.simulate(bd.SlidingBlock(mu=0.5), bd.Harmonic(1.0, 1.0), t_end=-1), "t_end must be"),
    (lambda: bd.simulate(bd.SlidingBlock(mu=0.5), bd.Harmonic(1.0, 1.0), t_end=1, backend="rk4"),
     "backend='rk4' is unknown"),
])
def test_other_validation(make, message):
    with pytest.raises(ValueError, match=message):
        make()
