"""IDA on the planar block: a DAE with the friction force components (F_x, F_y) as
algebraic variables, against CVODE, the 1-D block's exact backend and a reference written
here (a stiff integration of the polar slide plus the closed-form slide after the pulse).

Where a slide turns (a demand that changes direction), the direction equation is stiff
just after the onset (it relaxes at the rate |sigma| / s, s -> 0). CVODE (Adams) lost
the direction there (stops up to 2.4e-4 s off at rtol 1e-10) until the model capped
that rate below ``SLOW_SPEED``; it now agrees with IDA (numbers below).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

import blockdae as bd
from blockdae.sliding import Mode
from blockdae.planar import PlanarMode
from blockdae.backends import make_backend
from conftest import assert_same_events, load_sample_record

G = 9.81
RTOL = 1e-10


def both(block, motion, t_end=None):
    """(IDA, CVODE) at RTOL."""
    return tuple(bd.simulate(block, motion, t_end=t_end, backend=name, rtol=RTOL) for name in ("ida", "cvode"))


def assert_agrees(sol, ref, dt_max=1e-9, rel_du_max=1e-7):
    """The same events as ``ref``, each within ``dt_max`` [s]; the final displacement
    within ``rel_du_max`` of |u_ref(t_end)|."""
    assert_same_events(sol, ref, dt_max)
    assert np.hypot(*(sol.displacement - ref.displacement)) <= rel_du_max * np.hypot(*ref.displacement)


def assert_reduces(sol, ref, dt_max=1e-9, rel_du_max=1e-7):
    """The planar ``sol`` is the 1-D ``ref`` along x: slip of either sign is SLIP (a
    reversal is a stop that slides on), events within ``dt_max`` [s], u_x within
    ``rel_du_max`` of the largest |u| (a harmonic's final u is a small net of its slides),
    and u_y = 0 exactly."""
    slip = lambda m: "STICK" if m == Mode.STICK else "SLIP"
    assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == \
        [(slip(e.mode_before), slip(e.mode_after)) for e in ref.events]
    np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=dt_max)
    assert abs(sol.displacement[0] - ref.displacement) <= rel_du_max * ref.max_abs_displacement
    assert np.all(sol.u_y == 0.0)


# ---- (a) x-only motion: the 1-D problem ------------------------------------------

X_ONLY = {  # planar block, its 1-D twin, motion, t_end
    "harmonic": (bd.PlanarBlock(mu=0.2, g=G), bd.SlidingBlock(mu=0.2, g=G), bd.Harmonic(3.0, 1.0), 3.0),
    "pulse": (bd.PlanarBlock(mu=0.2, mu_kinetic=0.15, bias=(0.05, 0.0), g=G),
              bd.SlidingBlock(mu=0.2, mu_kinetic=0.15, bias=0.05, g=G), bd.SinePulse(4.0, 0.5), None),
}


def test_ida_runs_a_planar_block():
    assert make_backend("ida").runs(bd.PlanarBlock(mu=0.5))
    block, _, motion, _ = X_ONLY["pulse"]
    sol = bd.simulate(block, motion, backend="ida")
    assert isinstance(sol, bd.planar.PlanarSolution) and sol.backend == "ida"
    assert sol.state.shape[1] == 7  # the model's states; F is IDA's own
    assert sol.stats["n_restarts"] > 0


@pytest.mark.parametrize("case", sorted(X_ONLY))
def test_x_only_motion_agrees_with_cvode(case):
    """Measured: harmonic 1.4e-10 s, 5.4e-9; pulse 3.2e-11 s, 6.5e-10."""
    block, _, motion, t_end = X_ONLY[case]
    ida, cvode = both(block, motion, t_end)
    assert len(cvode.events) >= 2
    assert_agrees(ida, cvode)
    assert np.all(ida.u_y == 0.0)


@pytest.mark.parametrize("case", sorted(X_ONLY))
def test_x_only_motion_agrees_with_the_exact_1d_block(case):
    """Measured: harmonic 4.5e-11 s and 1.2e-7 of its final u (4.0e-9 of its largest
    |u|, as the 1-D IDA's 8.9e-8 of the final u); pulse 1.4e-10 s, 3.5e-11."""
    block, twin, motion, t_end = X_ONLY[case]
    ref = bd.simulate(twin, motion, t_end=t_end)  # closed forms
    assert_reduces(bd.simulate(block, motion, t_end=t_end, backend="ida", rtol=RTOL), ref)


def test_a_motion_along_a_rotated_line_is_the_1d_block_rotated():
    """Seed-000 Example 3b along a line at 135 degrees (bias along it): the 1-D problem
    rotated, with the block driven against the bias, where CVODE's stop is 8.9e-6 s off
    (tests/test_planar.py). Measured for IDA: 3.0e-10 s, 3.3e-10 of u."""
    example = bd.sliding.seed_examples()[3]
    c, s = math.cos(math.radians(135.0)), math.sin(math.radians(135.0))
    block = bd.PlanarBlock(mu=0.6, mu_kinetic=0.4, bias=(0.3 * c, 0.3 * s), g=G)
    sol = bd.simulate(block, bd.BaseMotion(example.motion.scaled(c), example.motion.scaled(s)),
                      t_end=example.t_end, backend="ida", rtol=RTOL)
    ref = bd.simulate(example.block, example.motion, t_end=example.t_end)
    np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=1e-9)
    np.testing.assert_allclose(sol.displacement, np.array([c, s]) * ref.displacement, rtol=0,
                               atol=1e-7 * abs(ref.displacement))


# ---- (b) Elms: one sine pulse in x and R times it in y, g = 1 ---------------------

MU, BIAS_X, PULSE = 0.8, -0.3, 2.0  # A = 1, N/A = 0.5: P = mu - N = 0.3 in -x; f = mu


def elms(ratio, z=None):
    motion = bd.BaseMotion(bd.SinePulse(1.0, PULSE), bd.SinePulse(ratio, PULSE), z)
    return bd.PlanarBlock(mu=MU, bias=(BIAS_X, 0.0), g=1.0), motion


def slide_reference(ratio, t_end, z=None, tau0=1e-5):
    """The slide from rest under a_x = sin(pi t / 2) on [0, 2], a_y = ratio a_x, a_z =
    ``z(t)`` (g = 1, f = mu), written here: the onset where |sigma| = mu n (brentq), then
    (s, theta, u_x, u_y) with s' = -e.sigma - f n, theta' = (e_perp.(-sigma)) / s by
    Radau (rtol 1e-12; stiff: the direction relaxes at |sigma| / s) from ``tau0`` [s] after
    the onset, where s = int (|sigma| - f n) dt and e = -sigma / |sigma| (at f = mu the lag
    of e is O(tau²), u is O(tau³)), restarted at the pulse's end (a kink of a_x). Returns
    (t_on, (s, theta, u_x, u_y) at ``t_end``).

    Its own error, measured against tau0 = 1e-6 s with Radau at rtol 1e-13 and 2.5e-14 and
    DOP853 at 2.5e-14 (the largest of them): at the pulse's end (R = 0.4 / 0.8) 8.9e-16 /
    2.0e-12 s of the stop that follows and 1.6e-14 / 1.2e-11 of u; with the vertical
    shaking, at 2.5 s, 2.6e-12 / 6.9e-12 of u and 4.7e-12 / 7.6e-12 of v."""
    def sigma(t):
        a = math.sin(math.pi * t / PULSE) if t < PULSE else 0.0
        return a - BIAS_X, ratio * a

    normal = (lambda t: 1.0) if z is None else (lambda t: 1.0 + z(t))
    margin = lambda t: math.hypot(*sigma(t)) - MU * normal(t)
    t_on = brentq(margin, 0.0, PULSE / 2, xtol=1e-16)

    def rhs(t, y):
        s, theta = y[0], y[1]
        (sx, sy), ex, ey = sigma(t), math.cos(theta), math.sin(theta)
        return [-(ex * sx + ey * sy) - MU * normal(t), (ey * sx - ex * sy) / s, s * ex, s * ey]

    t0 = t_on + tau0
    s0 = quad(margin, t_on, t0, epsabs=1e-22, epsrel=1e-14)[0]
    sx, sy = sigma(t0)
    state, first_step = [s0, math.atan2(-sy, -sx), 0.0, 0.0], tau0 / 100
    for start, end in ((t0, min(t_end, PULSE)), (PULSE, t_end)):
        if end > start:
            sol = solve_ivp(rhs, (start, end), state, method="Radau", rtol=1e-12, atol=1e-16, first_step=first_step)
            assert sol.status == 0
            state, first_step = sol.y[:, -1], None
    return t_on, state


def stop_after_the_pulse(state):
    """After the pulse sigma = (-bias_x, 0) and n = 1 are constant: with the angle phi of
    e from -sigma, s = C tan(phi/2)^beta / sin(phi) (beta = f n / |sigma|) and phi' =
    -|sigma| sin(phi) / s, so the stop (phi -> 0) and the displacement are quadratures
    (scipy's quad: within 8.9e-16 s and 1.7e-16 of u of mpmath's on the cases here).
    Returns (time from the state to the stop [s], displacement at the stop [m])."""
    s, theta, u_x, u_y = state
    size, back = abs(BIAS_X), math.copysign(1.0, BIAS_X)  # -sigma = (back |sigma|, 0)
    phi = math.atan2(back * math.sin(theta), back * math.cos(theta))
    side, phi = math.copysign(1.0, phi), abs(phi)
    beta = MU / size
    c = s * math.sin(phi) / math.tan(phi / 2) ** beta
    speed = lambda p: c * math.tan(p / 2) ** beta / math.sin(p)
    integral = lambda f: quad(f, 0.0, phi, epsabs=1e-15, epsrel=1e-13)[0]
    duration = integral(lambda p: speed(p) / (size * math.sin(p)))
    along = integral(lambda p: speed(p) ** 2 * math.cos(p) / (size * math.sin(p)))
    across = integral(lambda p: speed(p) ** 2 / size)
    return duration, np.array([u_x + back * along, u_y + back * side * across])


@pytest.mark.parametrize("ratio", [0.4, 0.8])
def test_elms_pulse_agrees_with_the_reference(ratio):
    """Measured: onset 5.6e-17 / 1.1e-16 s, stop 6.0e-11 / 4.5e-10 s, u 6.2e-11 / 8.5e-10
    (R = 0.4 / 0.8)."""
    t_on, state = slide_reference(ratio, PULSE)
    duration, u = stop_after_the_pulse(state)
    sol = bd.simulate(*elms(ratio), backend="ida", rtol=RTOL)
    assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == [("STICK", "SLIP"), ("SLIP", "STICK")]
    np.testing.assert_allclose(sol.t_events, [t_on, PULSE + duration], rtol=0, atol=1e-9)
    assert np.hypot(*(sol.displacement - u)) <= 1e-7 * np.hypot(*u)
    assert np.all(sol.displacement < 0)  # away from the +x, +y shaking


@pytest.mark.parametrize("ratio", [0.4, 0.8])
def test_elms_pulse_ida_agrees_with_cvode(ratio):
    """Measured: 1.3e-10 / 2.7e-10 s, 8.6e-11 / 7.3e-10 of u (R = 0.4 / 0.8); before
    the cap on the direction's rate CVODE's stop was 7.4e-7 s off (R = 0.4) and it
    failed mid-slide (R = 0.8)."""
    assert_agrees(*both(*elms(ratio)))


# ---- (c) a vertical component ----------------------------------------------------

def test_vertical_shaking_along_x_agrees_with_cvode():
    """n = g + a_z varies (3.0 m/s², period 0.37 s; n > 0): the kinetic friction f n and
    the circle mu n move. Measured: 1.2e-10 s, 1.4e-8 of the final u."""
    block = bd.PlanarBlock(mu=0.2, g=G)
    motion = bd.BaseMotion(bd.Harmonic(3.0, 1.0), z=bd.Harmonic(3.0, 0.37))
    ida, cvode = both(block, motion, 3.0)
    assert len(cvode.events) >= 10
    assert_agrees(ida, cvode)


VERTICAL = 0.3, 0.7  # a_z amplitude [g] and period [s]


@pytest.mark.parametrize("ratio", [0.4, 0.8])
def test_elms_pulse_with_vertical_shaking_agrees_with_the_reference(ratio):
    """Elms's pulse with a_z = 0.3 sin(2 pi t / 0.7) (n in [0.7, 1.3]), to t = 2.5 s,
    mid-slide. Measured: onset 1.1e-16 / 0 s, u 1.3e-9 / 2.8e-10, v 4.3e-9 / 1.2e-9 (R =
    0.4 / 0.8)."""
    amplitude, period = VERTICAL
    z = lambda t: amplitude * math.sin(2 * math.pi * t / period)
    t_on, (s, theta, u_x, u_y) = slide_reference(ratio, 2.5, z=z)
    sol = bd.simulate(*elms(ratio, bd.Harmonic(amplitude, period)), t_end=2.5, backend="ida", rtol=RTOL)
    assert [(e.mode_before.name, e.mode_after.name) for e in sol.events] == [("STICK", "SLIP")]
    assert abs(sol.t_events[0] - t_on) <= 1e-9
    assert np.hypot(sol.displacement[0] - u_x, sol.displacement[1] - u_y) <= 1e-7 * np.hypot(u_x, u_y)
    v_x, v_y = (v[-1] for v in sol.velocity)
    assert np.hypot(v_x - s * math.cos(theta), v_y - s * math.sin(theta)) <= 1e-7 * s


@pytest.mark.parametrize("ratio", [0.4, 0.8])
def test_elms_pulse_with_vertical_shaking_ida_agrees_with_cvode(ratio):
    """Measured against CVODE at rtol 1e-12: IDA 1.1e-9 / 7.9e-10 s, CVODE 4.5e-10 /
    2.2e-11 s (R = 0.4 / 0.8); before the cap on the direction's rate CVODE's stop was
    8.9e-5 s / 1.2e-3 s off, and with IDA's direction rows not scaled by max(s,
    SLOW_SPEED) IDA's was 1.9e-9 s off at R = 0.8."""
    assert_agrees(*both(*elms(ratio, bd.Harmonic(*VERTICAL)), 4.0))


# ---- (d) a record in x and half of it in y ----------------------------------------

@pytest.fixture(scope="module")
def record_case():
    record = load_sample_record("Kobe_1995_TAK-090")
    return record, bd.PlanarBlock(mu=0.15, g=G), bd.BaseMotion(record, record.scaled(0.5))


def test_record_agrees_with_cvode(record_case):
    """Measured: 1.8e-11 s, 2.1e-8 (as the 1-D IDA on the record: 2.0e-8)."""
    record, block, motion = record_case
    ida, cvode = both(block, motion, record.duration)
    assert len(cvode.events) >= 10
    assert_agrees(ida, cvode)


def test_record_is_the_1d_block_along_the_diagonal(record_case):
    """With no bias the demand stays on the line (2, 1): the 1-D block under
    sqrt(1.25) a(t), exactly; u_y / u_x = 1/2 to the last bit. Measured: 1.9e-11 s."""
    record, block, motion = record_case
    k = math.sqrt(1.25)
    ref = bd.simulate(bd.SlidingBlock(mu=0.15, g=G), record.scaled(k), t_end=record.duration)
    sol = bd.simulate(block, motion, t_end=record.duration, backend="ida", rtol=RTOL)
    assert len(sol.events) == len(ref.events)
    np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=1e-9)
    np.testing.assert_allclose(sol.displacement, np.array([1.0, 0.5]) / k * ref.displacement, rtol=1e-7)
    assert sol.displacement[1] == 0.5 * sol.displacement[0]


# ---- flight ----------------------------------------------------------------------

def test_flight_agrees_with_cvode():
    """a_z beyond g lifts the block off (F = 0 in flight) and lands it. Measured: 5.7e-11 s,
    5.1e-11."""
    block = bd.PlanarBlock(mu=0.3, g=G)
    motion = bd.BaseMotion(bd.Harmonic(4.0, 1.0), z=bd.Harmonic(12.0, 0.5))
    ida, cvode = both(block, motion, 2.0)
    assert any(e.mode_after == PlanarMode.FLIGHT for e in ida.events)
    assert_agrees(ida, cvode)
