"""``blockdae upthrow``: a mass on a spring support under a vertical record (seed 004).

Reference values: the closed-form flights under a constant downward ground acceleration
(derived below), and ``bd.simulate`` / ``bd.upthrow.upthrow_estimate`` called directly on the same
record (the CLI must print the API's numbers)."""

import json
import math

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli._main import main

G = bd.STANDARD_GRAVITY
F = 5.0  # [Hz]
OMEGA = 2 * math.pi * F


def _step_file(tmp_path, a_g, duration=3.5, name="step.csv"):
    """A record of constant vertical ground acceleration ``a_g`` [g] over ``duration`` [s]."""
    path = tmp_path / name
    path.write_text("".join(f"{t:g}, {a_g}\n" for t in np.arange(0.0, duration + 0.25, 0.5)))
    return path


def _upthrow(argv, capsys, status=0):
    """``blockdae upthrow argv`` on files in g (the step files' samples 0.5 s apart: --accept-step)."""
    assert main(["--no-cache", "upthrow", "--units", "g", "--accept-step", *map(str, argv)]) == status
    return capsys.readouterr()


def _json(argv, capsys):
    return json.loads(_upthrow([*argv, "--json"], capsys).out)


def _falling_ground_flights(a):
    """Undamped mass under y'' = -a from rest, g/2 < a < g: in contact u = (a/omega²)(1 -
    cos omega t), n = g - a (1 - cos omega t) (liftoff at u = u0 when cos theta0 = (g - a)/a,
    theta0 the phase past the top of the swing); in flight u'' = a - g, a parabola back to u0.
    Every flight repeats the first: (first liftoff [s], period [s], u'0 [m/s], duration [s],
    height [m])."""
    theta0 = math.acos((G - a) / a)
    v0 = a / OMEGA * math.sin(theta0)
    flight = 2 * v0 / (G - a)
    return (math.pi - theta0) / OMEGA, flight + (2 * math.pi - 2 * theta0) / OMEGA, v0, flight, v0**2 / (2 * (G - a))


def test_flights_under_a_falling_ground_match_the_closed_forms(tmp_path, capsys):
    """y'' = -0.55 g for 3.5 s, 5 Hz, undamped: the 17 flights equal the closed forms
    (measured: 1.8e-15 s, 7e-15 relative); the estimate's A is 2 x 0.55 = 1.1 (the
    linear oscillator's step response), with seed eqs. 5, 8, 12, 13 on it."""
    a = 0.55 * G
    t1, period, v0, duration, height = _falling_ground_flights(a)
    result = _json([_step_file(tmp_path, -0.55), "--frequency", F], capsys)
    flights = result["flights"]
    k = np.arange(len(flights))
    assert len(flights) == 17 and result["damping"] == 0.0 and result["t_end_s"] == 3.5
    np.testing.assert_allclose([f["liftoff_s"] for f in flights], t1 + k * period, rtol=0, atol=1e-13)
    np.testing.assert_allclose([f["landing_s"] for f in flights], t1 + k * period + duration, rtol=0, atol=1e-13)
    np.testing.assert_allclose([f["liftoff_velocity_m_s"] for f in flights], v0, rtol=1e-13)
    np.testing.assert_allclose([f["impact_velocity_m_s"] for f in flights], -v0, rtol=1e-13)
    np.testing.assert_allclose([f["height_m"] for f in flights], height, rtol=1e-13)
    u0 = G / OMEGA**2
    assert result["static_deflection_m"] == pytest.approx(u0, rel=1e-15)
    estimate = result["estimate"]
    assert estimate["response_acceleration_g"] == pytest.approx(1.1, rel=1e-13)
    assert estimate["liftoff_velocity_m_s"] == pytest.approx(G * math.sqrt(1.1**2 - 1) / OMEGA, rel=1e-12)
    assert estimate["height_m"] == pytest.approx(u0 * (1.1**2 - 1) / 2, rel=1e-12)
    assert estimate["time_to_top_s"] == pytest.approx(math.sqrt(1.1**2 - 1) / OMEGA, rel=1e-12)
    assert estimate["flight_duration_s"] == 2 * estimate["time_to_top_s"]


def test_long_flight_lists_are_summarised(tmp_path, capsys):
    """17 flights: the first and last five unless --flights all; rows numbered in order."""
    path = _step_file(tmp_path, -0.55)
    out = _upthrow([path, "--frequency", F], capsys).out
    rows = [line.split() for line in out.splitlines() if line.split()[:1] and line.split()[0].isdigit()]
    assert [int(r[0]) for r in rows] == [1, 2, 3, 4, 5, 13, 14, 15, 16, 17]
    assert "exact flights: 17" in out and "(7 more flights; --flights all prints them)" in out
    out = _upthrow([path, "--frequency", F, "--flights", "all"], capsys).out
    assert sum(1 for line in out.splitlines() if line.split()[:1] and line.split()[0].isdigit()) == 17
    out = _upthrow([path, "--frequency", F, "--flights", "none"], capsys).out
    assert "exact flights: 17" in out and "liftoff [s]" not in out


def test_kobe_as_vertical_motion_prints_the_apis_numbers(tmp_path, capsys):
    """Kobe TAK-090 used as vertical motion, scaled to 0.6 g, 5 Hz, 5 %: the JSON holds the
    numbers of bd.simulate and bd.upthrow.upthrow_estimate called directly (same floats), the text
    prints them to its digits with units, --quiet and --plot."""
    from conftest import load_sample_record, sample_record_paths

    path = next(p for p in sample_record_paths() if p.stem == "Kobe_1995_TAK-090")
    record = load_sample_record("Kobe_1995_TAK-090")
    record = record.scaled(0.6 * G / record.peak_acceleration)
    block = bd.SpringSupportedMass(F, damping=0.05)
    solution = bd.simulate(block, record, t_end=record.duration)
    estimate = bd.upthrow.upthrow_estimate(block, record)
    flights = solution.flights
    assert len(flights) == 5 and all(math.isfinite(f.landing) for f in flights)

    argv = [path, "--frequency", F, "--damping", 0.05, "--pga", 0.6]
    result = _json(argv, capsys)
    old = _upthrow([path, "--frequency", F, "--damping", 0.05, "--scale-to", 0.6, "--json"], capsys)
    assert json.loads(old.out)["flights"] == result["flights"] and json.loads(old.out)["scale"] == result["scale"]
    assert "blockdae: warning: --scale-to is deprecated; use --pga" in old.err
    assert result["peak_acceleration_g"] == pytest.approx(0.6, rel=1e-15)
    assert result["t_end_s"] == record.duration and result["backend"] == "exact"
    assert result["static_deflection_m"] == block.static_deflection
    assert result["estimate"] == {"response_acceleration_g": estimate.response_acceleration,
                                  "liftoff_velocity_m_s": estimate.liftoff_velocity, "height_m": estimate.height,
                                  "time_to_top_s": estimate.time_to_top,
                                  "flight_duration_s": estimate.flight_duration}
    assert result["flights"] == [{"liftoff_s": f.liftoff, "liftoff_velocity_m_s": f.liftoff_velocity,
                                  "height_m": f.height, "landing_s": f.landing,
                                  "impact_velocity_m_s": f.impact_velocity} for f in flights]

    png = tmp_path / "upthrow.png"
    out = _upthrow([*argv, "--plot", png], capsys).out
    assert f"static deflection u0 = g / omega² = {block.static_deflection * 1e3:.6f} mm" in out
    assert f"A = {estimate.response_acceleration:.6f} g" in out
    assert f"eq. 12 liftoff velocity u'0 = {estimate.liftoff_velocity:.6f} m/s" in out
    assert f"eq. 13 height z = {estimate.height * 1e3:.6f} mm" in out
    assert f"eq. 8 time to the top Delta t = {estimate.time_to_top:.6f} s" in out
    for k, f in enumerate(flights, 1):
        row = [f"{k}", f"{f.liftoff:.6f}", f"{f.liftoff_velocity:+.6f}", f"{f.height * 1e3:+.6f}",
               f"{f.landing:.6f}", f"{f.impact_velocity:+.6f}"]
        assert row in [line.split() for line in out.splitlines()]
    assert "liftoff velocity [m/s]" in out and "largest height [mm]" in out and "impact velocity [m/s]" in out
    assert f"figure: {png}" in out and png.stat().st_size > 10_000
    quiet = _upthrow([*argv, "--quiet"], capsys).out.strip()
    assert quiet == f"5 flights, largest height {max(f.height for f in flights) * 1e3:+.6f} mm"


def test_a_record_that_never_lifts_off_says_so(tmp_path, capsys):
    """Closed forms: under y'' = -a the support force falls to g - 2a (no liftoff for
    a = 0.45 g: A = 0.9); under y'' = +a it is g + a (1 - cos omega t) > 0 for any a, though
    A = 1.1 (the seed's estimate looks at |acceleration| only)."""
    down = _step_file(tmp_path, -0.45, duration=1.0)
    out = _upthrow([down, "--frequency", F], capsys).out
    assert "A = 0.900000 g" in out and "A <= 1 g: no liftoff predicted" in out
    assert "exact flights: none (no liftoff until t_end = 1.0000 s)" in out
    assert _upthrow([down, "--frequency", F, "--quiet"], capsys).out.strip() == "no liftoff"
    up = _step_file(tmp_path, 0.55, duration=1.0, name="up.csv")
    result = _json([up, "--frequency", F], capsys)
    assert result["flights"] == [] and result["estimate"]["response_acceleration_g"] == pytest.approx(1.1, rel=1e-13)
    flipped = _json([up, "--frequency", F, "--scale", -1], capsys)  # upside down: the falling ground flies
    t1, _, v0, _, _ = _falling_ground_flights(0.55 * G)
    assert flipped["scale"] == -1.0 and len(flipped["flights"]) == 5
    assert flipped["flights"][0]["liftoff_s"] == pytest.approx(t1, abs=1e-13)
    assert flipped["flights"][0]["liftoff_velocity_m_s"] == pytest.approx(v0, rel=1e-13)


def test_a_flight_cut_by_t_end_is_said_to_be_in_flight(tmp_path, capsys):
    """t_end between the first liftoff and its top (closed forms above): no landing, no
    height yet (null in JSON)."""
    t1, _, v0, _, _ = _falling_ground_flights(0.55 * G)
    t_end = t1 + 0.5 * v0 / (G - 0.55 * G)  # halfway to the top
    path = _step_file(tmp_path, -0.55)
    result = _json([path, "--frequency", F, "--t-end", t_end], capsys)
    assert result["flights"] == [{"liftoff_s": pytest.approx(t1, abs=1e-13),
                                  "liftoff_velocity_m_s": pytest.approx(v0, rel=1e-13),
                                  "height_m": None, "landing_s": None, "impact_velocity_m_s": None}]
    out = _upthrow([path, "--frequency", F, "--t-end", t_end], capsys).out
    assert "(in flight)" in out and "(rising)" in out
    assert _upthrow([path, "--frequency", F, "--t-end", t_end, "--quiet"], capsys).out.strip() == \
        "1 flights, largest height not reached (rising at t_end)"


def test_cvode_backend_agrees_with_the_closed_forms(tmp_path, capsys):
    """CVODE at its default rtol 1e-10 on the falling ground: within 1e-9 s of the closed
    forms in all 17 flights (measured 6.9e-10 s)."""
    t1, period, _, duration, _ = _falling_ground_flights(0.55 * G)
    result = _json([_step_file(tmp_path, -0.55), "--frequency", F, "--backend", "cvode"], capsys)
    assert result["backend"] == "cvode" and len(result["flights"]) == 17
    k = np.arange(17)
    np.testing.assert_allclose([f["liftoff_s"] for f in result["flights"]], t1 + k * period, rtol=0, atol=1e-9)
    np.testing.assert_allclose([f["landing_s"] for f in result["flights"]], t1 + k * period + duration,
                               rtol=0, atol=1e-9)


@pytest.mark.parametrize("argv, message", [
    (["--frequency", "0"], "argument --frequency: must be a positive finite number, got 0"),
    (["--frequency", "-2"], "argument --frequency: must be a positive finite number, got -2"),
    (["--frequency", "nan"], "argument --frequency: must be a positive finite number, got nan"),
    (["--frequency", "5", "--damping", "1"], "argument --damping: must be in [0, 1), got 1"),
    (["--frequency", "5", "--damping", "-0.1"], "argument --damping: must be in [0, 1), got -0.1"),
    (["--frequency", "5", "--damping", "nan"], "argument --damping: must be in [0, 1), got nan"),
    (["--frequency", "5", "--scale", "0"], "argument --scale: must be a finite nonzero number, got 0"),
    (["--frequency", "5", "--scale-to", "-1"], "argument --scale-to: must be a positive finite number, got -1"),
    (["--frequency", "5", "--scale", "2", "--scale-to", "1"], "argument --scale-to: not allowed with argument --scale"),
    (["--frequency", "5", "--pga", "-1"], "argument --pga: must be a positive finite number, got -1"),
    (["--frequency", "5", "--pga", "1", "--scale-to", "1"], "argument --scale-to: not allowed with argument --pga"),
    (["--frequency", "5", "--backend", "exact-jax"], "argument --backend: invalid choice: 'exact-jax'"),
    (["--frequency", "5", "--units", "furlong"], "--units: units='furlong' is unknown"),
    (["--damping", "0.05"], "the following arguments are required: --frequency"),
])
def test_bad_arguments_exit_2_naming_the_flag(tmp_path, capsys, argv, message):
    err = _upthrow([_step_file(tmp_path, -0.55), *argv], capsys, status=2).err
    assert message in err


def test_bad_files_exit_2_naming_the_file_and_line(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("0.0, 0.1\n0.01, 0.2\n0.02, abc\n")
    assert f"{bad}, line 3" in _upthrow([bad, "--frequency", F], capsys, status=2).err
    missing = tmp_path / "none.csv"
    assert f"{missing}: no such file" in _upthrow([missing, "--frequency", F], capsys, status=2).err
    zeros = tmp_path / "zeros.csv"
    zeros.write_text("0.0, 0.0\n0.01, 0.0\n")
    err = _upthrow([zeros, "--frequency", F, "--pga", 0.5, "--accept-peak"], capsys, status=2).err
    assert err.startswith("blockdae: error: ") and f"{zeros}: --pga needs a motion with a nonzero peak" in err
    good = tmp_path / "good.csv"
    good.write_text("0.0, 0.0\n0.01, 0.3\n0.02, 0.0\n")
    err = _upthrow([good, "--frequency", F, "--pga", 9.81], capsys, status=2).err
    assert (f"{good}: --pga=9.81 g is implausible for a peak ground acceleration (above 2 g); it looks like "
            "m/s² (9.81 m/s² = 1 g): give --pga in g, or check_peak=False (command line: --accept-peak) to accept "
            "it") in err
