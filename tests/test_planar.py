"""The planar block (seed 001) on the generic hybrid driver, against independent answers:
the 1-D block's exact backend (closed forms), the same problem rotated in the plane,
closed-form flight, and a Cartesian DOP853 integration written here."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import blockdae as bd
from blockdae.sliding import Mode
from blockdae.planar import PlanarMode
from conftest import load_sample_record

G = 9.81
#: this file checks the model on CVODE (IDA, the default for PlanarBlock: test_planar_ida.py)
CVODE = "cvode"


def planar_twin(block: bd.SlidingBlock, **changes) -> bd.PlanarBlock:
    """The planar block with the 1-D block's parameters (bias along x)."""
    return bd.PlanarBlock(mu=block.mu, mu_kinetic=block.mu_kinetic, bias=(block.bias, 0.0), g=block.g, **changes)


def assert_reduces(sol, ref, event_dt=1e-9, rel=1e-8):
    """The planar solution ``sol`` is the 1-D ``ref`` along x: same mode changes (slip
    of either sign is SLIP), events within ``event_dt`` [s], u_x within ``rel`` of the
    largest |u| (the 1-D CVODE backend itself is 1.5e-10 m off on Example 1, whose final
    u is 3 % of its largest)."""
    slip = lambda m: "STICK" if m == Mode.STICK else "SLIP"
    assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == \
        [(slip(e.mode_before), slip(e.mode_after)) for e in ref.events]
    np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=event_dt)
    assert abs(sol.displacement[0] - ref.displacement) <= rel * ref.max_abs_displacement


@pytest.mark.parametrize("example", bd.sliding.seed_examples(), ids=lambda e: e.name)
def test_x_only_motion_reduces_to_the_1d_block(example):
    ref = bd.simulate(example.block, example.motion, t_end=example.t_end)  # exact closed forms
    sol = bd.simulate(planar_twin(example.block), example.motion, t_end=example.t_end, backend=CVODE)
    assert_reduces(sol, ref)
    assert np.all(sol.u_y == 0.0)  # nothing pushes it off the x axis, not even rounding


@pytest.mark.parametrize("backend", ["cvode", "ida", "jax"])
@pytest.mark.parametrize("a1", [-0.5729396696, -0.5630396696])
def test_a_slide_whose_speed_dips_below_zero_within_a_sample_stops(backend, a1):
    """g = 1, mu 0.5, f 0.3 under a_x = (0, a1, -0.1, -0.4, 0, 0), dt 0.1 s: the speed of
    the slide without a stop would dip below zero (to -9e-6 and -9e-4 m/s) and come back
    within the third sample; the block must stop where the exact 1-D closed forms say
    (0.264 s, 0.242 s). Every backend stepped over it (stop 0.1 s late, u 15 % large)."""
    record = bd.Record(np.array([0.0, a1, -0.1, -0.4, 0.0, 0.0]), 0.1, units="m/s2")
    ref = bd.simulate(bd.SlidingBlock(mu=0.5, mu_kinetic=0.3, g=1.0), record, t_end=0.5)
    sol = bd.simulate(bd.PlanarBlock(mu=0.5, mu_kinetic=0.3, g=1.0), bd.BaseMotion(record), t_end=0.5,
                      backend=backend)
    assert_reduces(sol, ref)


@pytest.mark.parametrize("backend", ["cvode", "ida"])
def test_guards_that_only_touch_zero_at_a_sample_are_no_events(backend):
    """g = 1. a_x = (0, 0.5, 0, 0), mu 0.5: the demand touches the friction circle at
    0.1 s and falls back (the exact 1-D backend: no events; it was a slip and a stop at
    0.1 s). a_z = (0, -1, 0, 0): n = g + a_z touches 0 at 0.1 s and rises again, so the
    block stays on the base (it was a flight that never landed, the gap going to -0.012 m)."""
    touch = bd.Record(np.array([0.0, 0.5, 0.0, 0.0]), 0.1, units="m/s2")
    assert bd.simulate(bd.SlidingBlock(mu=0.5, g=1.0), touch).events == ()
    assert bd.simulate(bd.SlidingBlock(mu=0.5, g=1.0), touch, backend=backend).events == ()
    assert bd.simulate(bd.PlanarBlock(mu=0.5, g=1.0), bd.BaseMotion(touch), backend=backend).events == ()
    still = bd.Record(np.zeros(4), 0.1)
    unload = bd.BaseMotion(still, None, bd.Record(np.array([0.0, -1.0, 0.0, 0.0]), 0.1, units="m/s2"))
    sol = bd.simulate(bd.PlanarBlock(mu=0.5, g=1.0), unload, t_end=0.3, backend=backend)
    assert sol.events == () and np.all(sol(np.linspace(0.0, 0.3, 31))[4] == 0.0)


@pytest.mark.parametrize("stem", ["Kobe_1995_TAK-090", "Northridge_1994_PAC-175"])
def test_a_record_along_x_reduces_to_the_1d_block(stem):
    record = load_sample_record(stem)
    block = bd.SlidingBlock(mu=0.15, mu_kinetic=0.12, bias=0.03)
    ref = bd.simulate(block, record)
    sol = bd.simulate(planar_twin(block), bd.BaseMotion(record), backend=CVODE)
    assert_reduces(sol, ref)


@pytest.mark.parametrize("angle", [30.0, 135.0])
def test_a_motion_along_a_rotated_line_is_the_1d_block_rotated(angle):
    """Shaking along a line at ``angle`` with the bias along it is the 1-D problem in a
    rotated frame: every component of the planar code (circle, direction, both
    displacement components) is exercised, and the answer is known exactly. At 135
    degrees (a stop against the drive, where the direction is unstable) CVODE's stop was
    ~9e-6 s off before the direction's relaxation rate was capped below
    ``SLOW_SPEED``; measured since: 5.4e-12 s, 7.5e-9 of u (the bars a decade above the
    events, within one of u)."""
    example = bd.sliding.seed_examples()[3]  # Example 3b: bias 0.3, f 0.4 < mu 0.6, harmonic
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    motion = bd.BaseMotion(example.motion.scaled(c), example.motion.scaled(s))
    block = bd.PlanarBlock(mu=0.6, mu_kinetic=0.4, bias=(0.3 * c, 0.3 * s), g=G)
    ref = bd.simulate(example.block, example.motion, t_end=example.t_end)
    sol = bd.simulate(block, motion, t_end=example.t_end, backend=CVODE)
    np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=5.4e-11)
    u = np.array([c, s]) * ref.displacement
    np.testing.assert_allclose(sol.displacement, u, rtol=0, atol=1e-8 * abs(ref.displacement))


def cartesian_reference(motion_xy, mu, f, bias, g, t_on, t_end, kinks=()):
    """An independent answer written here: v' = -sigma - f g v/|v| integrated in
    Cartesian form with DOP853 (rtol 1e-12) from the onset ``t_on`` [s] (|v| = 1e-14 m/s
    along -sigma) until |v| falls to 1e-12 m/s (an approximate stop, good to ~1e-12 /
    (f g - |sigma|) s), restarted at the ``kinks`` [s] of the motion."""
    def sigma(t):
        ax, ay = motion_xy(t)
        return np.array([ax - bias[0] * g, ay - bias[1] * g])

    e0 = -sigma(t_on) / np.linalg.norm(sigma(t_on))

    def rhs(t, y):
        v = y[2:]
        speed = np.hypot(*v)
        e = v / speed if speed > 0 else e0
        return [*v, *(-sigma(t) - f * g * e)]

    def stop(t, y):
        return np.hypot(y[2], y[3]) - 1e-12

    stop.terminal, stop.direction = True, -1
    t, y = t_on, [0, 0, 1e-14 * e0[0], 1e-14 * e0[1]]
    for end in (*kinks, t_end):
        sol = solve_ivp(rhs, (t, end), y, method="DOP853", rtol=1e-12, atol=1e-15, events=stop)
        if sol.t_events[0].size:
            return sol.t_events[0][0], sol.y[:2, -1]
        t, y = end, sol.y[:, -1]
    raise AssertionError(f"no stop before t_end = {t_end} s")


def test_elms_one_sine_wave_with_lateral_shaking_against_a_cartesian_integration():
    """Seed 001 set-up (g = 1, accelerations in g): C_x = A sin(pi t) for one wave,
    C_y = R C_x, bias P = mu - N in -x; here N/A = 0.5, mu = 0.8, R = 0.8, f = 0.7. The
    stop within 1e-8 s and u within 1e-9 m of the Cartesian reference (CVODE measured
    1.8e-10 s, 5.1e-11 m; the reference's own error, against the same integration at rtol
    2.5e-14 stopped at 1e-13 m/s: 2.3e-12 s, 4.0e-14 m)."""
    amplitude, mu, f, ratio = 1.0, 0.8, 0.7, 0.8
    bias = (-(mu - 0.5 * amplitude), 0.0)
    wave = bd.Harmonic(amplitude, 2.0, cycles=1)
    sol = bd.simulate(bd.PlanarBlock(mu=mu, mu_kinetic=f, bias=bias, g=1.0),
                      bd.BaseMotion(wave, wave.scaled(ratio)), backend=CVODE)
    assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == [("STICK", "SLIP"), ("SLIP", "STICK")]
    onset = brentq(lambda t: math.hypot(amplitude * math.sin(math.pi * t) - bias[0],
                                        ratio * amplitude * math.sin(math.pi * t)) - mu, 0.0, 0.5, xtol=1e-15)
    assert abs(sol.t_events[0] - onset) <= 1e-12
    def motion_xy(t):
        a_x = amplitude * math.sin(math.pi * t) * (t < 2)
        return a_x, ratio * a_x
    t_stop, u = cartesian_reference(motion_xy, mu, f, bias, 1.0, onset, 10.0, kinks=(2.0,))
    assert abs(sol.t_events[1] - t_stop) <= 1e-8
    np.testing.assert_allclose(sol.displacement, u, rtol=0, atol=1e-9)
    assert sol.displacement[1] < 0 and sol.displacement[0] < 0  # it slides away from +x and +y shaking


def flight_closed_form(depth, duration, g):
    """Base falling with a_z = -depth sin(pi t / T): liftoff where g + a_z = 0, then
    w'' = -(g + a_z) from w = w' = 0 integrated in closed form; landing at w = 0."""
    w_ = math.pi / duration
    t1 = math.asin(g / depth) / w_
    az_int1 = lambda t: depth / w_ * (math.cos(w_ * t) - math.cos(w_ * t1))  # integral of a_z from t1
    def gap(t):  # valid while the pulse lasts and after it (a_z = 0 past T)
        tau = min(t, duration)
        inside = (-g * (tau - t1) ** 2 / 2 - depth / w_ * ((math.sin(w_ * tau) - math.sin(w_ * t1)) / w_
                                                          - math.cos(w_ * t1) * (tau - t1)))
        rate_at_end = -g * (tau - t1) - az_int1(tau)
        return inside + rate_at_end * (t - tau) - g * (t - tau) ** 2 / 2
    t2 = brentq(gap, t1 + 1e-6, 10.0, xtol=1e-15)
    return t1, t2


def test_flight_under_a_falling_base_lands_where_the_closed_form_says():
    """CVODE against the closed form: measured 7.6e-11 s, the bar a decade above."""
    depth, duration = 1.5 * G, 0.3
    sol = bd.simulate(bd.PlanarBlock(mu=0.3, g=G), bd.BaseMotion(bd.RectangularPulse(0.0, duration), None,
                                                                   bd.SinePulse(-depth, duration)), backend=CVODE)
    t1, t2 = flight_closed_form(depth, duration, G)
    assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == [("STICK", "FLIGHT"), ("FLIGHT", "STICK")]
    np.testing.assert_allclose(sol.t_events, [t1, t2], rtol=0, atol=7.6e-10)
    assert sol.events[1].v_z < 0  # the impact velocity
    assert np.all(sol.gap >= -1e-12)


def test_bounces_shrink_by_the_restitution_and_end_in_contact():
    restitution, threshold = 0.5, 1e-3
    motion = bd.BaseMotion(bd.SinePulse(2.0, 0.5), None, bd.SinePulse(-15.0, 0.3))
    sol = bd.simulate(bd.PlanarBlock(mu=0.3, g=G, restitution=restitution, bounce_threshold=threshold), motion, backend=CVODE)
    landings = [e for e in sol.events if e.mode_before == PlanarMode.FLIGHT]
    rebounds = [e for e in landings if e.mode_after == PlanarMode.FLIGHT]
    assert len(rebounds) >= 3 and landings[-1].mode_after != PlanarMode.FLIGHT
    # after the base stops moving vertically, each flight is ballistic: the next impact
    # is as fast as the last rebound, which is restitution times the impact
    late = [e for e in landings if e.t > 0.3]
    for first, second in zip(late, late[1:]):
        assert second.v_z == pytest.approx(restitution * first.v_z, rel=1e-6)
    # finitely many bounces: the rebound falls below the threshold after at most this many
    assert len(late) <= 1 + math.ceil(math.log(threshold / -late[0].v_z) / math.log(restitution)) + 1
    assert sol.mode[-1] != PlanarMode.FLIGHT and sol.gap[-1] == 0.0


@pytest.mark.parametrize("kwargs, field", [
    (dict(mu=0.0), "mu"), (dict(mu=-0.1), "mu"), (dict(mu=0.3, mu_kinetic=0.4), "mu_kinetic"),
    (dict(mu=0.3, bias=(0.2, 0.25)), "bias"), (dict(mu=0.3, bias=(np.nan, 0.0)), "bias"),
    (dict(mu=0.3, bias=(0.1,)), "bias"), (dict(mu=0.3, restitution=1.0), "restitution"),
    (dict(mu=0.3, g=0.0), "g"), (dict(mu=np.nan), "mu"), (dict(mu=0.3, bounce_threshold=0.0), "bounce_threshold"),
])
def test_bad_parameters_name_the_field(kwargs, field):
    with pytest.raises(ValueError, match=field):
        bd.PlanarBlock(**kwargs)


def test_backends_and_motions_that_do_not_fit_say_so():
    block, motion = bd.PlanarBlock(mu=0.3), bd.BaseMotion(bd.SinePulse(4.0, 0.5))
    with pytest.raises(ValueError, match="does not run a PlanarBlock.*cvode"):
        bd.simulate(block, motion, backend="exact")
    with pytest.raises(TypeError, match="BaseMotion"):
        bd.simulate(block, np.zeros(3))
    with pytest.raises(TypeError, match="motion must be an excitation"):
        bd.simulate(bd.SlidingBlock(mu=0.3), motion)
    with pytest.raises(ValueError, match="never comes to rest"):
        bd.simulate(bd.PlanarBlock(mu=0.3, mu_kinetic=0.1, bias=(0.2, 0.0)), motion.scaled(3.0))


def test_planar_solution_tables_and_dense_output():
    wave = bd.Harmonic(1.0, 2.0, cycles=1)
    sol = bd.simulate(bd.PlanarBlock(mu=0.8, mu_kinetic=0.7, bias=(-0.3, 0.0), g=1.0),
                      bd.BaseMotion(wave, wave.scaled(0.8)), backend=CVODE)
    u_x, u_y, v_x, v_y, gap = sol(sol.t)
    np.testing.assert_allclose(u_x, sol.u_x, atol=1e-15)
    np.testing.assert_allclose(np.hypot(v_x, v_y)[sol.mode == PlanarMode.STICK], 0.0, atol=1e-15)
    table = sol.to_dataframe()
    assert list(table.mode_after) == ["SLIP", "STICK"] and "direction_deg" in table
    assert "u_x [g s²]" in sol.event_table()  # g = 1: lengths in g s²
    with pytest.raises(ValueError, match="t must lie"):
        sol(sol.t_end + 1.0)


def test_a_batch_of_planar_blocks_is_each_block_alone():
    """Arrays of mu, mu_kinetic and bias components broadcast to parameter sets; each
    row equals the block run alone (the driver backends run one set after another)."""
    wave = bd.Harmonic(1.0, 2.0, cycles=1)
    motion = bd.BaseMotion(wave, wave.scaled(0.8))
    block = bd.PlanarBlock(mu=np.array([0.8, 0.8, 0.9]), mu_kinetic=0.7, bias=(np.array([-0.3, -0.2, -0.3]), 0.05),
                           g=1.0)
    assert block.batch_shape == (3,)
    batch = bd.simulate(block, motion, backend=CVODE)
    for i in range(3):
        alone = bd.simulate(block.item(i), motion, backend=CVODE)
        assert np.array_equal(batch.displacement[i], alone.displacement)
        assert batch.max_abs_displacement[i] == alone.max_abs_displacement
        assert np.array_equal(batch[i].t_events, alone.t_events)
    table = batch.to_dataframe()
    assert list(table.columns[:5]) == ["mu", "mu_kinetic", "bias_x", "bias_y", "g_m_s2"]
    columns = ["displacement_x_gs2", "displacement_y_gs2"]  # g = 1: lengths in g s²
    np.testing.assert_array_equal(table[columns].to_numpy(), batch.displacement)
    assert table["bias_y"].tolist() == [0.05] * 3


@pytest.mark.parametrize("kwargs, message", [
    (dict(mu=np.array([0.3, 0.5]), bias=(np.array([0.1, 0.6]), 0.0)), r"bias=\(0.6, 0.0\).*mu=0.5.*parameter set 1"),
    (dict(mu=np.array([0.3, 0.5]), mu_kinetic=np.array([0.1, 0.6])), r"mu_kinetic=0.6 .*mu=0.5\].*parameter set 1"),
    (dict(mu=np.array([0.3, 0.5, 0.7]), bias=(np.array([0.1, 0.2]), 0.0)), "broadcast"),
    (dict(mu=np.ones((2, 2))), "mu must be a real number or a 1-D array"),
])
def test_a_bad_parameter_set_in_a_batch_is_named(kwargs, message):
    with pytest.raises(ValueError, match=message):
        bd.PlanarBlock(**kwargs)


def test_slide_directions_start_on_the_friction_circle_and_end_with_the_last_velocity():
    """Seed 001 eqs. 19-20: a slide starts against the demand, e = -(C_x + P, C_y) / |.|
    (closed form at the located onset); it ends in the direction of the velocity just
    before the stop (the dense output a little earlier)."""
    wave = bd.Harmonic(1.0, 2.0, cycles=1)
    sol = bd.simulate(bd.PlanarBlock(mu=0.8, bias=(-0.3, 0.0), g=1.0), bd.BaseMotion(wave, wave.scaled(0.4)),
                      backend="ida")
    slides = sol.slide_directions()
    onset, stop = sol.events[0], sol.events[1]
    c_x = math.sin(math.pi * onset.t)
    assert slides[0] == pytest.approx(math.degrees(math.atan2(-0.4 * c_x, -(c_x + 0.3))), abs=1e-9)
    _, _, v_x, v_y, _ = sol(stop.t - 1e-6)
    assert slides[1] == pytest.approx(math.degrees(math.atan2(v_y, v_x)), abs=1e-2)
    assert math.isnan(onset.direction)  # the velocity before an onset is zero: no direction
    assert "slide [deg]" in sol.event_table() and list(sol.to_dataframe().slide_deg) == pytest.approx(list(slides))


def test_event_table_fills_the_direction_only_where_the_block_moves():
    """Issue 23 item 5: a push then a falling base (the README's flight); the velocity is
    zero at the onset and the stop (blank cells, no "nan") and points along -x when the
    block lifts off and lands sliding (180 deg, the event's own atan2(v_y, v_x))."""
    g = bd.STANDARD_GRAVITY
    ax, az = np.zeros(41), np.zeros(41)
    ax[1:6], az[7:25] = 0.6 * g, -0.8 * g
    motion = bd.BaseMotion.from_samples(ax, az=az, dt=0.01)
    block = bd.PlanarBlock(0.3, support=bd.SpringSupport(8.0, damping=0.05))
    sol = bd.simulate(block, motion, t_end=0.4, backend="cvode", rtol=1e-10)
    table = sol.event_table().splitlines()
    assert "nan" not in sol.event_table() and len(table) == len(sol.events) + 1
    start = table[0].index("direction [deg]")
    cells = [line[start:start + len("direction [deg]")].strip() for line in table[1:]]
    for event, cell in zip(sol.events, cells):
        moving = event.v_x != 0.0 or event.v_y != 0.0
        assert (cell != "") == moving, (event, cell)
        if moving:
            assert float(cell) == pytest.approx(math.degrees(math.atan2(event.v_y, event.v_x)), abs=5e-4)
    assert cells[0] == "" and cells[-1] == "" and any(cells)  # onset and stop blank, the flight's filled


def test_history_and_figure_carry_the_declared_state_units():
    """history()'s columns and the figure's axes take the block's ``state_units``: m and
    m/s, or g s² and g s for a dimensionless block (g = 1)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = np.arange(0.0, 1.0, 0.01)
    motion = bd.BaseMotion(bd.Record(0.3 * G * np.sin(2 * np.pi * t), 0.01, units="m/s2"),
                           bd.Record(0.2 * G * np.cos(2 * np.pi * t), 0.01, units="m/s2"))
    for g, length, speed in ((G, "m", "m_s"), (1.0, "gs2", "gs")):
        block = bd.PlanarBlock(mu=0.1, g=g)
        scaled = motion if g == G else bd.BaseMotion(*(bd.Record(r.acceleration_samples / G, r.dt, check_peak=False)
                                                     for r in (motion.x, motion.y)))
        solution = bd.simulate(block, scaled, backend=CVODE)
        history = solution.history()
        assert list(history.columns[-8:]) == [f"u_x_{length}", f"u_y_{length}", f"s_{speed}", "c_x_ratio",
                                              "c_y_ratio", f"w_{length}", f"w_rate_{speed}", "mode"]
        assert history[f"u_x_{length}"].iloc[-1] == solution.displacement[0]
        figure = bd.plot(solution)
        label = {G: "m", 1.0: "g s²"}[g]
        assert figure.axes[0].get_xlabel() == f"u_x [{label}]"
        plt.close(figure)
