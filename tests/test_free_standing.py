"""The complete free-standing block (rest, slide, rock, slide-rock, flight, overturn):
closed forms and independent computations, on the compiled engine, CVODE and IDA.

References, each named in its test: the parabola of free flight (closed form, double
precision); the mu = 0 block's energy integral ½ R² (sin² phi + 1/3) theta'² + g_e R cos
phi = const integrated by mpmath's tanh-sinh quadrature (40 digits); the frictionless
impact's r0 = (1 - 3 sin² alpha)/(1 + 3 sin² alpha) and Housner's r = 1 - 3/2 sin² alpha
(closed forms); the package's sliding block and the rectangular pulse's closed form
(Sawicki & Chybicki 2005); Housner's block (RockingBlock) on its compiled engine, whose
first impact of free rocking is 1e-16 s from the quadrature; the rest map of
:func:`blockdae.rocking._slide_rock_laws.rest_mode` (Shenton 1996 with g_e). Every run's
energy balance closes to 1e-9 of its scale.
"""

import math
import warnings

import mpmath
import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import FreeMode, FreeStandingBlock, PainleveWarning, RockingBlock
from blockdae.rocking import _slide_rock_laws as laws
from conftest import load_sample_record

G = bd.STANDARD_GRAVITY
QUIET = bd.Record(np.zeros(3), 0.01, name="no shaking", units="m/s2")
BACKENDS = ("compiled", "cvode", "ida")
mpmath.mp.dps = 40


def run(block, motion, backend, t_end=None, rtol=1e-12):
    """The block's run with its energy balance checked: residual <= 1e-9 of its scale."""
    sol = bd.simulate(block, motion, t_end=t_end, backend=backend, rtol=rtol)
    assert sol.energy_residual <= 1e-9 * sol.energy_scale, (sol.energy_residual, sol.energy_scale)
    return sol


def kinds(sol):
    return [e.kind for e in sol.events]


def sticky(**kwargs):
    """A block with mu = 1e4 (Housner's limit); its Painlevé warning is expected."""
    with pytest.warns(PainleveWarning, match="Painlevé"):
        return FreeStandingBlock(mu=1e4, **kwargs)


@pytest.mark.parametrize("backend", BACKENDS)
def test_flight_is_a_parabola_and_lands_at_its_root(backend):
    """The base drops at 1.5 g for 0.2 s while pulling at 0.3 g: the flat block flies
    (x'' = -a_x, z'' = -g_e) and lands flat where z returns to h (closed form)."""
    b, h, ax, az, td = 0.3, 0.5, 0.3 * G, -1.5 * G, 0.2
    motion = bd.BaseMotion(x=bd.RectangularPulse(ax, td), z=bd.RectangularPulse(az, td))
    sol = run(FreeStandingBlock(b=b, h=h, mu=0.5), motion, backend, t_end=1.0)
    assert kinds(sol) == ["lift", "land"]
    lift, land = sol.events
    assert lift.t == 0 and lift.mode_after == FreeMode.FLIGHT_POS
    ge = G + az
    z1, v1 = h - 0.5 * ge * td**2, -ge * td  # at the end of the drop
    x1, u1 = -0.5 * ax * td**2, -ax * td
    t_land = td + (v1 + math.sqrt(v1**2 + 2 * G * (z1 - h))) / G  # z1 + v1 s - g s²/2 = h
    assert abs(land.t - t_land) <= 1e-12
    flying = (sol.t > 0) & (sol.t < land.t) & (np.abs(sol.mode) == FreeMode.FLIGHT_POS)
    t = sol.t[flying]
    early = t <= td
    s = t - td
    x = np.where(early, -0.5 * ax * t**2, x1 + u1 * s)
    z = np.where(early, h - 0.5 * ge * t**2, z1 + v1 * s - 0.5 * G * s**2)
    assert np.max(np.abs(sol.state[flying, 0] - x)) <= 1e-12
    assert np.max(np.abs(sol.state[flying, 1] - z)) <= 1e-12
    assert np.all(sol.state[flying, 2] == 0)
    assert land.state_after[3:] == (0.0, 0.0, 0.0)  # |x'| <= mu P_n: the face sticks
    assert sol.mode[-1] == FreeMode.REST


@pytest.mark.parametrize("backend", BACKENDS)
def test_tilted_flight_lands_on_its_lower_corner(backend):
    """Released at theta0 while the base falls at 2 g: it flies without turning and its
    lower corner lands where h cos theta0 + b sin theta0 - z = 0 (closed form), then
    rocks on that corner."""
    b, h, theta0, td = 0.2, 0.6, 0.15, 0.25
    motion = bd.BaseMotion(x=bd.RectangularPulse(0.0, td), z=bd.RectangularPulse(-2 * G, td))
    block = FreeStandingBlock(b=b, h=h, mu=1.0, theta0=theta0)
    sol = run(block, motion, backend, t_end=1.2)
    assert kinds(sol)[:3] == ["release", "land", "impact"]
    z0 = math.hypot(b, h) * math.cos(block.alpha - theta0)
    z1, v1 = z0 + 0.5 * G * td**2, G * td
    drop = z1 - (h * math.cos(theta0) + b * math.sin(theta0))
    t_land = td + (v1 + math.sqrt(v1**2 + 2 * G * drop)) / G
    land = sol.events[1]
    assert abs(land.t - t_land) <= 1e-12
    assert land.mode_after == FreeMode.ROCK_POS_IN


def mu0_first_impact(block, theta0, ge):
    """The first impact time [s] of the frictionless block released at ``theta0``: the
    quadrature of dtheta / |theta'| with ½ R² (sin² phi + 1/3) theta'² = g_e R (cos phi0 -
    cos phi), phi = alpha - theta (tanh-sinh, 40 digits)."""
    alpha, radius, ge = mpmath.mpf(block.alpha), mpmath.mpf(block.R), mpmath.mpf(ge)
    phi0 = alpha - mpmath.mpf(theta0)

    def slowness(theta):
        phi = alpha - theta
        inertia = radius * (mpmath.sin(phi) ** 2 + mpmath.mpf(1) / 3)
        return 1 / mpmath.sqrt(2 * ge * (mpmath.cos(phi0) - mpmath.cos(phi)) / inertia)

    return float(mpmath.quad(slowness, [0, mpmath.mpf(theta0)]))


@pytest.mark.parametrize("backend", BACKENDS)
def test_frictionless_block_keeps_its_centroid_still_and_falls_by_the_energy_integral(backend):
    """mu = 0: friction is the only horizontal force, so the centroid's absolute horizontal
    position stays put under a sine pulse (its base displacement in closed form); the
    first impact is at the energy integral's quadrature and its theta' ratio is r0 (rtol
    1e-13: a slide-rock's state is its pivot's, so the centroid's x = u - R sin phi carries
    theta's error, 2.7e-12 m at rtol 1e-12)."""
    b, h, theta0, A, T = 0.2, 0.6, 0.15, 0.2 * G, 0.5
    block = FreeStandingBlock(b=b, h=h, mu=0.0, theta0=theta0)
    sol = run(block, bd.SinePulse(A, T), backend, t_end=1.0, rtol=1e-13)
    t, x = sol.t, sol.state[:, 0]
    w = math.pi / T
    base = np.where(t <= T, A / w * (t - np.sin(w * t) / w), A / w * T + 2 * A / w * (t - T))
    absolute = (x + base)[sol.mode != FreeMode.RELEASE]  # from the tilt on
    assert absolute[0] == pytest.approx(b - block.R * math.sin(block.alpha - theta0), abs=1e-15)
    assert np.max(np.abs(absolute - absolute[0])) <= 1e-12
    first = sol.impacts[0]
    assert abs(first.t - mu0_first_impact(block, theta0, G)) <= 1e-11
    s2 = math.sin(block.alpha) ** 2
    assert first.state_after[5] / first.state[5] == pytest.approx((1 - 3 * s2) / (1 + 3 * s2), rel=1e-12)
    assert "chatter" in kinds(sol)  # the impacts' arcs shrink under mu_k = 0 <= b/h: it slides on


@pytest.mark.parametrize("backend", BACKENDS)
def test_sticking_impacts_are_housners(backend):
    """Housner's limit (mu = 1e4): every impact sticks and theta'+ = r theta'- with
    r = 1 - 3/2 sin² alpha (closed form)."""
    block = sticky(b=0.2, h=1.0, theta0=0.1)
    sol = run(block, QUIET, backend, t_end=4.0)
    assert len(sol.impacts) >= 4
    for impact in sol.impacts:
        assert impact.state_after[5] / impact.state[5] == pytest.approx(block.r, rel=1e-12)
        assert impact.via in (FreeMode.IMPACT_POS_STICK, FreeMode.IMPACT_NEG_STICK)


def test_housner_limit_reproduces_rocking_block_event_for_event():
    """mu = 1e4 on motions within the contact limits: the event list of Housner's block
    (RockingBlock on its compiled engine at rtol 1e-13, 1e-16 s from the quadrature on
    free rocking) in kind, each time within 1e-10 s, on CVODE and IDA (rtol 1e-13) over
    the first seconds; until rest, the same kinds (apexes, impacts, the Zeno tail summed,
    rest) and times within 1e-5 s: the late impacts' times are ill-conditioned (there
    RockingBlock's own CVODE is 4e-7 s from its compiled engine)."""
    cases = [(dict(b=0.2, h=1.0), bd.SinePulse(-0.3 * G, 0.6), 4.0),
             (dict(b=0.2, h=1.0, theta0=0.1), QUIET, 4.0),
             (dict(b=0.15, h=0.6), bd.SinePulse(0.35 * G, 0.5), 3.0),
             (dict(b=0.2, h=1.0), bd.SinePulse(-0.3 * G, 0.6), None)]
    for geometry, motion, t_end in cases:
        reference = bd.simulate(RockingBlock(mu=1e4, **geometry), motion, t_end=t_end, backend="compiled",
                                rtol=1e-13)
        assert not reference.contact_events
        assert len(reference.events) >= 6
        for backend in BACKENDS:
            sol = run(sticky(**geometry), motion, backend, t_end=t_end, rtol=1e-13)
            assert kinds(sol) == [e.kind for e in reference.events], (geometry, backend)
            times = np.array([e.t for e in sol.events]) - np.array([e.t for e in reference.events])
            assert np.max(np.abs(times)) <= (1e-10 if t_end else 1e-5), (geometry, backend, times)


@pytest.mark.parametrize("backend", BACKENDS)
def test_pure_sliding_is_the_sliding_block(backend):
    """mu <= b/h: the block only slides, as the package's sliding block (CVODE at rtol
    1e-12) under a sine pulse, and a rectangular pulse -A for t_d stops at A t_d / (mu g)
    having slid ½(A - mu g) t_d² + (A - mu g)² t_d² / (2 mu g) (closed form)."""
    block = FreeStandingBlock(b=0.5, h=0.5, mu=0.3)
    pulse = bd.SinePulse(-0.7 * G, 0.4)
    sol = run(block, pulse, backend)
    ref = bd.simulate(bd.SlidingBlock(mu=0.3), pulse, backend="cvode", rtol=1e-12)
    assert kinds(sol) == ["slide", "stick"]
    assert [e.t for e in sol.events] == pytest.approx([e.t for e in ref.events], abs=1e-10)
    assert sol.state[-1, 0] == pytest.approx(ref.displacement, abs=1e-10)
    A, td, mu = 0.6 * G, 0.3, 0.3
    sol = run(block, bd.RectangularPulse(-A, td), backend)
    assert abs(sol.events[-1].t - A * td / (mu * G)) <= 1e-12
    slid = 0.5 * (A - mu * G) * td**2 + (A - mu * G) ** 2 * td**2 / (2 * mu * G)
    assert sol.state[-1, 0] == pytest.approx(slid, abs=1e-12)
    assert sol.state[-1, 7] == pytest.approx(-mu * G * slid, rel=1e-10)  # friction's work


@pytest.mark.parametrize("amplitude, mu, mu_kinetic, expected", [
    (0.3, 0.3, 0.3, FreeMode.ROCK_POS_OUT), (0.6, 0.3, 0.3, FreeMode.SLIDE_ROCK_POS_POS),
    (0.3, 0.2, 0.2, FreeMode.SLIDE_POS), (0.2, 0.3, 0.3, FreeMode.REST), (0.6, 0.3, 0.2, FreeMode.SLIDE_POS)])
def test_a_step_from_rest_starts_the_rest_maps_mode(amplitude, mu, mu_kinetic, expected):
    """A step a_x = -amplitude g on the block with b/h = 1/4: the mode it starts is that of
    the rest map (Shenton 1996 with g_e: :func:`rest_mode`'s (kind, side))."""
    block = FreeStandingBlock(b=0.25, h=1.0, mu=mu, mu_kinetic=mu_kinetic)
    sol = run(block, bd.RectangularPulse(-amplitude * G, 0.05), "cvode", t_end=0.05)
    kind, d = laws.rest_mode(-amplitude * G, G, 0.25, mu, mu_kinetic)
    assert block._mode_of(kind, d) == expected
    assert (sol.events[0].mode_after if sol.events else FreeMode.REST) == expected
    assert not sol.events or sol.events[0].t == 0


@pytest.mark.parametrize("backend", BACKENDS)
def test_rocking_slips_sticks_and_overturns_with_friction(backend):
    """b/h = 1/4, mu = 0.3 under a half-sine of 0.6 g: it tips at a_x = g b/h, its pivot
    slips where |F| reaches mu N (located: the margin is zero there), sticks again,
    passes alpha, slips back and overturns; friction only takes energy."""
    block = FreeStandingBlock(b=0.25, h=1.0, mu=0.3)
    sol = run(block, bd.SinePulse(-0.6 * G, 0.4), backend, t_end=3.0)
    assert kinds(sol) == ["uplift", "slip", "stick", "beyond_alpha", "slip", "reverse", "overturn"]
    assert sol.events[0].t == pytest.approx(math.asin(0.25 / 0.6) * 0.4 / math.pi, abs=1e-12)
    slip = sol.events[1]
    y = np.array(slip.state + (0.0, 0.0))
    ax = -0.6 * G * math.sin(math.pi * slip.t / 0.4)
    _, force, normal = block.rock_forces(1, y, ax, G)
    assert abs(0.3 * normal - abs(force)) <= 1e-9 * G
    assert sol.overturned and np.all(np.diff(sol.state[:, 7]) <= 1e-15)
    table = sol.to_dataframe()
    assert list(table["kind"]) == kinds(sol) and table["theta_rad"][1] == slip.state[2]
    assert table.columns[-1] == "theta_rate_rad_s_after" and len(sol.event_table().splitlines()) == 8


@pytest.mark.parametrize("backend", BACKENDS)
def test_vertical_drop_lifts_a_rocking_block_off_and_it_lands(backend):
    """A rocking block whose base starts to fall faster than g (a_z ramps to -2 g) slips
    where |F| reaches mu N and lifts off where N falls to 0 (both located: the margins are
    zero there); from the lift-off state its flight is a parabola that lands its lower
    corner at the root of z - h cos theta + b |sin theta| (mpmath: Cauchy's formula for
    the double integral of the ramps of a_z, findroot), within 1e-12 s."""
    b, h = 0.2, 0.6
    block = FreeStandingBlock(b=b, h=h, mu=1.0, theta0=0.15)
    ramps = np.array([0.0, 0.0, -2 * G, -2 * G, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    z = bd.Record(ramps, 0.1, name="drop", units="m/s2")
    sol = run(block, bd.BaseMotion(x=bd.Record(np.zeros(10), 0.1, name="none", units="m/s2"), z=z), backend,
              t_end=0.9, rtol=1e-13)
    assert kinds(sol) == ["release", "slip", "lift", "land", "impact"]
    slip, lift, land = sol.events[1:4]
    a_z = lambda t: float(np.interp(t, 0.1 * np.arange(10), ramps))
    y = np.array(slip.state + (0.0, 0.0))
    _, force, normal = block.rock_forces(1, y, 0.0, G + a_z(slip.t))
    assert abs(1.0 * normal - abs(force)) <= 1e-9 * G
    y = np.array(lift.state + (0.0, 0.0))
    assert lift.mode_before == FreeMode.SLIDE_ROCK_POS_NEG
    assert abs(block.slide_rock(1, -1, y, 0.0, G + a_z(lift.t))[1]) <= 1e-9 * G
    mpmath.mp.dps = 30
    t0, (x0, z0, theta0, u0, w0, rate) = mpmath.mpf(lift.t), map(mpmath.mpf, lift.state)
    knots = [t0] + [mpmath.mpf(k) / 10 for k in range(2, 5)]

    def lower_corner(t):  # the corner -b's height in flight
        drop = mpmath.quad(lambda s: (t - s) * a_z(float(s)), [k for k in knots if k < t] + [t])
        theta = theta0 + rate * (t - t0)
        return z0 + w0 * (t - t0) - G * (t - t0) ** 2 / 2 - drop + b * mpmath.sin(theta) - h * mpmath.cos(theta)

    t_land = mpmath.findroot(lower_corner, land.t)
    assert abs(land.t - float(t_land)) <= 1e-12
    assert land.mode_after == FreeMode.ROCK_NEG_IN and land.state[0] == pytest.approx(float(x0 + u0 * (t_land - t0)),
                                                                                        abs=1e-12)


def chatter_slide_rate(block, event):
    """The slide's x' [m/s] after a chatter, from the state before its last impact by
    momentum and impulse written here in mpmath: the corner c = side of the impact strikes
    (theta = 0: r_cx = c b, r_cz = -h) plastically, v_cz+ = z'+ - r_cx theta'+ = 0, slipping
    with P_t = -sigma mu_k P_n (sigma the slide's direction); over the arcs after it the
    base's normal impulse is g_e T - z'+ (z' ends at 0) and friction's -sigma mu_k times it,
    while a slide from the impact's time gets -sigma mu_k g_e T: it starts at x'+ + sigma mu_k z'+."""
    c = 1 if int(event.via) > 0 else -1
    sigma = 1 if event.mode_after == FreeMode.SLIDE_POS else -1
    b, h, mu = (mpmath.mpf(v) for v in (block.b, block.h, block.friction_kinetic))
    x_rate, z_rate, w = (mpmath.mpf(v) for v in (event.state[3], event.state[4], event.state[5]))
    r_cx, r_cz, k = c * b, -h, 3 / (b * b + h * h)
    # z'+ - r_cx theta'+ = 0 with z'+ = z' + P_n, theta'+ = w + k (r_cz P_t - r_cx P_n), P_t = -sigma mu P_n
    p_n = -(z_rate - r_cx * w) / (1 - r_cx * k * (-r_cz * sigma * mu - r_cx))
    return float(x_rate - sigma * mu * p_n + sigma * mu * (z_rate + p_n))


@pytest.mark.parametrize("backend", BACKENDS)
def test_slide_rock_chatter_ends_in_a_slide_that_sticks(backend):
    """mu_k = 0.2 <= b/h = 1/4 < mu_s = 0.3: the rocking block's pivot slips, its impacts
    on alternate corners come ever faster while it slips (each arc restoring), and once an
    arc would be shorter than zeno_arc the chatter ends in a slide (event "chatter", the
    face down), which sticks: friction only takes energy. The slide's x' is the impulse
    balance's over the summed arcs (:func:`chatter_slide_rate`, 1e-15 m/s); the stick after
    the pulse is at the slide's closed form (x' = v + ∫ (0.6 g sin(pi t/0.4) - mu_k g) dt = 0;
    3e-12 s: the slide's x' integrated at rtol 1e-12, measured 1.2e-12 s) and does not depend on zeno_arc: with 1e-4 s and 1e-7 s (1000 times more
    arcs resolved) it is the same within 1e-11 s (the pivot's slip velocity for x' puts it
    2.3e-5 s off at zeno_arc = 1e-5 s, the centroid's x' 1.2e-6 s)."""
    pulse = bd.SinePulse(-0.6 * G, 0.4)
    block = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, mu_kinetic=0.2)
    sol = run(block, pulse, backend, t_end=1.5)
    assert kinds(sol)[:3] == ["uplift", "slip", "impact"] and kinds(sol)[-2:] == ["chatter", "stick"]
    chatter = sol.events_of("chatter")[0]
    assert chatter.mode_after == FreeMode.SLIDE_POS and chatter.via in (FreeMode.IMPACT_POS_SLIP,
                                                                       FreeMode.IMPACT_NEG_SLIP)
    assert chatter.state_after[1:3] == (block.h, 0.0) and chatter.state_after[4:] == (0.0, 0.0)
    slide_rate = chatter_slide_rate(block, chatter)
    assert abs(chatter.state_after[3] - slide_rate) <= 1e-15
    assert abs(slide_rate - chatter.state[3]) > 1e-3 * block.R * abs(chatter.state[5])  # the tail's impulse counts
    t_c, w = mpmath.mpf(chatter.t), mpmath.pi / mpmath.mpf(0.4)
    a, mu_g = 0.6 * mpmath.mpf(G), mpmath.mpf(0.2) * mpmath.mpf(G)
    at_end = slide_rate + a / w * (mpmath.cos(w * t_c) + 1) - mu_g * (mpmath.mpf(0.4) - t_c)
    assert at_end > 0 and t_c < 0.4
    stick = sol.events_of("stick")[-1]
    assert abs(stick.t - float(mpmath.mpf(0.4) + at_end / mu_g)) <= 3e-12
    assert 2 * abs(chatter.state[5]) / G < 10 * block.zeno_arc
    assert np.all(np.diff(sol.state[:, 7]) <= 1e-15)
    resolved = [run(block.replace(zeno_arc=arc), pulse, backend, t_end=1.5).events_of("stick")[-1].t
                for arc in (1e-4, 1e-7)]
    assert abs(resolved[0] - stick.t) <= 1e-11 and abs(resolved[1] - stick.t) <= 1e-11


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_squat_block_lands_flat(backend):
    """b/h = 2 (r = 1 - 3/2 sin² alpha < 0): released from a tilt, its other corner would be
    driven down at the impact, so the face lands flat and the block rests (closed form:
    z'+ = theta'+ = 0; no rebound)."""
    block = FreeStandingBlock(b=0.8, h=0.4, mu=2.5, mu_kinetic=1.0, theta0=0.2)
    assert block.r < 0
    sol = run(block, QUIET, backend, t_end=1.0)
    assert kinds(sol) == ["release", "land"]
    land = sol.events[1]
    assert land.via == FreeMode.LANDING_FLAT and land.mode_after == FreeMode.REST
    assert land.state_after[1:] == (block.h, 0.0, 0.0, 0.0, 0.0)


def test_painleves_paradox_stops_the_run_naming_the_time():
    """mu_k = 2 >= 4/3: where the pivot of a rocking block starts to slip into a slide-rock
    with D = 1 + 3 sin phi (sin phi - sigma mu_k cos phi) <= 0, no contact force is
    consistent: an error naming the time and D."""
    with pytest.warns(PainleveWarning):
        block = FreeStandingBlock(b=0.3, h=0.5, mu=2.0)
    with pytest.raises(ValueError, match=r"at t = 0\.2537\d+ s Painlevé's paradox.*D = -0\.108"):
        bd.simulate(block, bd.SinePulse(-3 * G, 0.5), t_end=2.0, backend="cvode")


@pytest.mark.slow
@pytest.mark.parametrize("backend", ["ida", "compiled"])
@pytest.mark.parametrize("mu", [0.3, 0.2])
def test_cvode_and_the_others_agree_on_a_record(mu, backend):
    """Coalinga 1983 PVB-045 scaled to 0.8 g, b/h = 1/4: rocking, an impact, a stick, a slip
    and the overturn (mu = 0.3), or 37 slides, reversals and sticks (mu = 0.2): CVODE, IDA
    and the compiled engine (three integrators, rtol 1e-12) give the same events within
    1e-9 s (measured: IDA 5e-11 s, the compiled engine 1.2e-11 s)."""
    record = load_sample_record("Coalinga_1983_PVB-045")
    record = record.scaled(0.8 * G / np.max(np.abs(record.acceleration_samples)))
    block = FreeStandingBlock(b=0.2, h=0.8, mu=mu)
    sol, ref = run(block, record, backend), run(block, record, "cvode")
    assert kinds(sol) == kinds(ref) and len(ref.events) >= 7
    assert ref.overturned == (mu == 0.3)
    assert np.max(np.abs([a.t - b.t for a, b in zip(sol.events, ref.events)])) <= 1e-9


@pytest.mark.slow
@pytest.mark.parametrize("backend", ["ida", "compiled"])
def test_gentle_lift_offs_under_vertical_shaking(backend):
    """Kocaeli ATS-090 at 0.8 g along x with Landers LCN-345 at 1.2 g vertical: the pivot
    lifts off where N falls slowly through 0 (its corner then rises as t³, below the
    rounding of the centroid's height for about 1e-5 s: the flight's state is the
    corner's); CVODE agrees with IDA and with the compiled engine on the events (kinds,
    and times within 1e-8 s over the first lift-off and landing; the compiled engine
    measured 1e-12 s) and each run's energy balance closes."""
    x, z = load_sample_record("Kocaeli_1999_ATS-090"), load_sample_record("Landers_1992_LCN-345")
    n = min(x.acceleration_samples.size, z.acceleration_samples.size)
    scaled = [bd.Record(r.acceleration_samples[:n] * peak * G / np.max(np.abs(r.acceleration_samples)), r.dt,
                        name=r.name, units="m/s2", check_peak=False) for r, peak in ((x, 0.8), (z, 1.2))]
    motion = bd.BaseMotion(x=scaled[0], z=scaled[1])
    block = FreeStandingBlock(b=0.3, h=0.6, mu=0.7, mu_kinetic=0.4)
    sol, ref = run(block, motion, backend, t_end=12.0), run(block, motion, "cvode", t_end=12.0)
    assert "lift" in kinds(ref) and "land" in kinds(ref)
    first = kinds(ref).index("land") + 1
    assert kinds(sol)[:first] == kinds(ref)[:first]
    assert np.max(np.abs([a.t - b.t for a, b in zip(sol.events[:first], ref.events[:first])])) <= 1e-8


@pytest.mark.slow
def test_the_jax_twin_runs_the_same_automaton():
    """backend="jax" (diffrax, compiled: about a minute of compilation): the flight's
    landing at its closed form (1e-12 s), and the slip-stick-overturn run's events as
    CVODE's at rtol 1e-12 (1e-10 s), energy residuals within 1e-9 of their scale."""
    motion = bd.BaseMotion(x=bd.RectangularPulse(0.3 * G, 0.2), z=bd.RectangularPulse(-1.5 * G, 0.2))
    sol = run(FreeStandingBlock(b=0.3, h=0.5, mu=0.5), motion, "jax", t_end=1.0)
    assert kinds(sol) == ["lift", "land"] and abs(sol.events[1].t - (0.3 + math.sqrt(0.03))) <= 1e-12
    block, pulse = FreeStandingBlock(b=0.25, h=1.0, mu=0.3), bd.SinePulse(-0.6 * G, 0.4)
    sol, ref = run(block, pulse, "jax", t_end=3.0), run(block, pulse, "cvode", t_end=3.0)
    assert kinds(sol) == kinds(ref)
    assert np.max(np.abs([a.t - b.t for a, b in zip(sol.events, ref.events)])) <= 1e-10


def test_bad_input_is_refused_by_name():
    for kwargs, field in [(dict(b=0.0, h=1.0, mu=0.5), "b"), (dict(b=0.2, h=-1.0, mu=0.5), "h"),
                          (dict(b=0.2, h=1.0, mu=-0.1), "mu"),
                          (dict(b=0.2, h=1.0, mu=0.5, mu_kinetic=0.6), "mu_kinetic"),
                          (dict(b=0.2, h=1.0, mu=0.5, mu_kinetic=-0.1), "mu_kinetic"),
                          (dict(b=0.2, h=1.0, mu=0.5, theta0=2.0), "theta0"),
                          (dict(b=float("nan"), h=1.0, mu=0.5), "b")]:
        with pytest.raises(ValueError, match=field):
            FreeStandingBlock(**kwargs)
    with pytest.warns(PainleveWarning, match="Painlevé's paradox"):
        FreeStandingBlock(b=0.2, h=1.0, mu=1.5, mu_kinetic=4 / 3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        FreeStandingBlock(b=0.2, h=1.0, mu=1.5, mu_kinetic=1.3)
