"""Paths of the complete free-standing block between its modes that the closed forms reach:
a slide that stops into rocking, leaving the summed Zeno tail (SETTLE) by an uplift or a
lift-off, overturning in flight, a sliding flat landing with mu_k > b/h, Painlevé's paradox
met inside a slide-rock. Each reference is named in its test; every run's energy balance
closes to 1e-9 of its scale."""

import math

import mpmath
import numpy as np
import pytest

import blockdae as bd
from blockdae.excitation import AbstractExcitation, Pieces
from blockdae.rocking import FreeMode, FreeStandingBlock, PainleveWarning
from test_free_standing import kinds, run  # the run with its energy balance checked

G = bd.STANDARD_GRAVITY
BACKENDS = ("compiled", "cvode", "ida")
mpmath.mp.dps = 40


class Steps(AbstractExcitation):
    """a(t) piecewise constant: ``values[i]`` [m/s²] until ``ends[i]`` [s], zero after."""

    def __init__(self, ends, values):
        self.ends, self.values = list(map(float, ends)), list(map(float, values))

    @property
    def duration(self):
        return self.ends[-1]

    @property
    def peak_acceleration(self):
        return max(map(abs, self.values))

    def scaled(self, factor):
        return Steps(self.ends, [factor * v for v in self.values])

    def _pieces_until(self, t_end):
        t0, h = np.array([0.0] + self.ends[:-1]), np.diff([0.0] + self.ends)
        keep = t0 < t_end
        return Pieces.linear(t0[keep], np.minimum(h[keep], t_end - t0[keep]), np.array(self.values)[keep], 0.0)


def pivot_forces(b, h, s, ax, ge):
    """(F, N) [m/s²] on the sticking pivot s of the block standing flat and still under a_x,
    g_e [m/s²], from Newton-Euler written here: moments about the pivot give
    theta'' = -(3/(4 R)) (g_e sin phi + a_x cos phi) with phi = s alpha, and the centroid's
    acceleration R theta'' (cos phi, sin phi) is (F - a_x, N - g_e)."""
    R, alpha = math.hypot(b, h), math.atan2(b, h)
    phi = s * alpha
    accel = -0.75 / R * (ge * math.sin(phi) + ax * math.cos(phi))
    return ax + R * math.cos(phi) * accel, ge + R * math.sin(phi) * accel


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("second, after", [(0.5, FreeMode.ROCK_NEG_OUT), (1.6, FreeMode.SLIDE_NEG)])
def test_a_slide_that_stops_rocks_where_static_friction_holds_the_pivot(backend, second, after):
    """mu_s = 0.5 > b/h = 1/4 >= mu_k = 0.2: a step -1.6 g (beyond the pivot's hold, Shenton's
    a_SR = 1.46 g) slides the block toward +x; a step +``second`` g from 0.1 s stops it at
    0.1 + 1.4 g 0.1 / ((second + 0.2) g) s, 0.021 g m along (closed forms). At 0.5 g the
    pivot -b holds there (|F| <= mu_s N with F, N written in this test): it rocks; at 1.6 g
    it does not: the slide reverses."""
    block = FreeStandingBlock(b=0.25, h=1.0, mu=0.5, mu_kinetic=0.2)
    sol = run(block, Steps([0.1, 0.5], [-1.6 * G, second * G]), backend, t_end=0.45)
    assert kinds(sol)[:2] == ["slide", "uplift" if after == FreeMode.ROCK_NEG_OUT else "reverse"]
    stop = sol.events[1]
    t_stop = 0.1 + 1.4 * 0.1 / (second + 0.2)
    assert abs(stop.t - t_stop) <= 1e-12 and stop.mode_after == after
    slid = 0.5 * 1.4 * G * 0.1**2 + 1.4 * G * 0.1 * (t_stop - 0.1) - 0.5 * (second + 0.2) * G * (t_stop - 0.1) ** 2
    assert abs(stop.state[0] - slid) <= 1e-12 and stop.state_after[3] == 0.0
    force, normal = pivot_forces(0.25, 1.0, -1, second * G, G)
    assert (abs(force) <= 0.5 * normal) == (after == FreeMode.ROCK_NEG_OUT)


def settling_run(backend):
    """A block b/h = 1/2 (r = 0.7) released from 0.2 rad, zeno_arc = 0.05 s: its impacts are
    summed from the one whose arc is shorter (event "zeno", SETTLE) to rest at the
    geometric sum t + arc/(1 - r), arc = 2|theta'+|/(p² sin alpha) (closed form; 1e-13 s, a
    located root: measured 2.6e-14 s on IDA)."""
    block = FreeStandingBlock(b=0.5, h=1.0, mu=1.0, theta0=0.2, zeno_arc=0.05)
    quiet = Steps([3.0], [0.0])
    sol = run(block, quiet, backend, t_end=3.0)
    zeno = sol.events_of("zeno")[0]
    arc = 2 * abs(zeno.state_after[5]) / (block.frequency**2 * math.sin(block.alpha))
    assert abs(sol.rest_time - (zeno.t + arc / (1 - block.r))) <= 1e-13
    assert arc < block.zeno_arc and kinds(sol)[-2:] == ["zeno", "rest"]
    return block, zeno.t, sol.rest_time


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_settling_block_that_the_demand_tips_rocks_as_one_at_rest(backend):
    """While the Zeno tail is summed (SETTLE), a step a_x = 0.6 g > (b/h) g for 0.2 s tips the block
    onto its corner -b at the step (event "uplift", flat and still there); from then on it
    moves as the block standing at rest under the same step (a run from REST: the rest
    map's rock, mu = 1 holding the pivot), event for event within 1e-12 s."""
    block, start, rest = settling_run(backend)
    t_step = 0.5 * (start + rest)
    sol = run(block, Steps([t_step, t_step + 0.2, 3.0], [0.0, 0.6 * G, 0.0]), backend, t_end=t_step + 1.0)
    uplift = sol.events[kinds(sol).index("zeno") + 1]
    assert uplift.kind == "uplift" and uplift.t == t_step and uplift.mode_after == FreeMode.ROCK_NEG_OUT
    assert uplift.state_after[2:] == (0.0, 0.0, 0.0, 0.0)
    standing = run(block.replace(theta0=0.0), Steps([t_step, t_step + 0.2, 3.0], [0.0, 0.6 * G, 0.0]), backend, t_end=t_step + 1.0)
    after = sol.events[kinds(sol).index("uplift"):]
    assert [e.kind for e in after] == kinds(standing) and len(after) >= 3
    assert np.max(np.abs([a.t - b.t for a, b in zip(after, standing.events)])) <= 1e-12


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_settling_block_lifts_off_when_the_base_falls_and_lands_flat(backend):
    """While the Zeno tail is summed, a_z = -1.5 g for d = 0.05 s: g_e < 0, the block lifts
    off at the step (event "lift") flat and still, rises under 0.5 g for d and falls under
    g: its face lands at t + d + d (1/2 + sqrt(3/4)) (closed form: h + g d²/4 + (g d/2) tau
    - g tau²/2 = h), flat and still: it rests (a flat landing)."""
    block, start, rest = settling_run(backend)
    t_step, d = 0.5 * (start + rest), 0.05
    motion = bd.BaseMotion(x=Steps([3.0], [0.0]), z=Steps([t_step, t_step + d, 3.0], [0.0, -1.5 * G, 0.0]))
    sol = run(block, motion, backend, t_end=t_step + 0.5)
    assert kinds(sol)[-3:] == ["zeno", "lift", "land"]
    lift, land = sol.events_of("lift")[0], sol.events_of("land")[0]
    assert lift.t == t_step and lift.state_after[2:] == (0.0, 0.0, 0.0, 0.0)
    assert abs(land.t - (t_step + d + d * (0.5 + math.sqrt(0.75)))) <= 1e-12
    assert land.via == FreeMode.LANDING_FLAT and land.mode_after == FreeMode.REST


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_block_that_lifts_off_beyond_alpha_overturns_in_flight(backend):
    """Released from 0.3 rad > alpha on a sticking pivot (mu = 1), the block falls outward
    by the energy integral theta'²/2 = p² [cos(alpha - theta0) - cos(alpha - theta)]
    (closed form, 1e-10 rad/s); at 0.9 s the base drops at 2 g (g_e = -g): it lifts off and
    flies, theta' constant, x' constant, z under +g, until |theta| = pi/2 at
    0.9 + (pi/2 - theta)/theta' (closed forms: 1e-12 s, 1e-10 m)."""
    block = FreeStandingBlock(b=0.25, h=1.0, mu=1.0, theta0=0.3)
    motion = bd.BaseMotion(x=Steps([3.0], [0.0]), z=Steps([0.9, 3.0], [0.0, -2 * G]))
    sol = run(block, motion, backend, t_end=3.0)
    assert kinds(sol) == ["release", "lift", "overturn"]
    lift, over = sol.events[1:]
    assert lift.t == 0.9 and lift.mode_after == FreeMode.FLIGHT_POS
    theta, rate = lift.state[2], lift.state[5]
    p2, alpha = block.frequency**2, block.alpha
    assert abs(rate - math.sqrt(2 * p2 * (math.cos(alpha - 0.3) - math.cos(alpha - theta)))) <= 1e-10
    tau = (0.5 * math.pi - theta) / rate
    assert abs(over.t - (0.9 + tau)) <= 1e-12 and over.mode_after == FreeMode.OVERTURNED_POS
    assert abs(over.state[0] - (lift.state[0] + lift.state[3] * tau)) <= 1e-10
    assert abs(over.state[1] - (lift.state[1] + lift.state[4] * tau + 0.5 * G * tau**2)) <= 1e-10
    # the flight's state is its corner's, whose rates turn with theta: integrated at rtol 1e-12 (IDA: 5e-12 m/s)
    assert abs(over.state[3] - lift.state[3]) <= 1e-11 and abs(over.state[5] - rate) <= 1e-11


def test_painleves_paradox_met_inside_a_slide_rock_names_the_time_and_d():
    """b/h = 3/2, mu_s = 1.7, mu_k = 1.6 (>= 4/3): a step -3 g for 0.1 s slide-rocks the
    block onto +b; +6 g from 0.26 s throws it back, and it slide-rocks on -b slipping toward
    -x while D = 1 + 3 sin phi (sin phi + mu_k cos phi) (phi = -alpha - theta) falls to 0:
    an error naming the time and D at the located root. Its theta is D's closed-form root
    (mpmath, to the 6 digits named); CVODE and IDA (rtol 1e-12) name the same time within
    1e-10 s (measured 9e-12 s)."""
    with pytest.warns(PainleveWarning):
        block = FreeStandingBlock(b=1.5, h=1.0, mu=1.7, mu_kinetic=1.6)
    motion = Steps([0.1, 0.26, 3.0], [-3 * G, 0.0, 6 * G])
    times = []
    for backend in BACKENDS:
        with pytest.raises(ValueError, match=r"Painlevé's paradox: slide-rocking on the corner -1 b slipping toward "
                                             r"-1 x.*D = -?\d\.\d+e-1\d (<= 0|falling to 0) at theta = ") as error:
            bd.simulate(block, motion, t_end=0.6, backend=backend, rtol=1e-12)
        message = str(error.value)
        times.append(float(message.split("at t = ")[1].split(" s")[0]))
        theta = float(message.split("at theta = ")[1].split(" rad")[0])
        alpha = mpmath.atan(mpmath.mpf(1.5))
        phi = mpmath.findroot(lambda p: 1 + 3 * mpmath.sin(p) * (mpmath.sin(p) + mpmath.mpf(1.6) * mpmath.cos(p)),
                              -alpha - theta)
        assert abs(theta - float(-alpha - phi)) <= 5e-7  # half a unit of the 6th digit named
    assert abs(times[0] - times[1]) <= 1e-10 and times[0] > 0.26


class StillBase:
    """The base at rest as the model's rules read an excitation: a_x = a_z = 0 [m/s²]."""

    def component(self, index, t):
        return 0.0

    def component_rate(self, index, t):
        return 0.0


def test_a_face_that_lands_sliding_with_mu_k_above_b_over_h_tips_onto_its_leading_corner():
    """b/h = 0.3 < mu_k = 0.92 < mu_s = 1.2, the base still: a slide-rock on +b falling back
    (theta' = -1 rad/s) while its pivot slips forward (u' = 1.5 m/s) reaches theta = 0; the
    corner -b's impact would drive +b down (the face lands: x'- = u' + h theta' = 0.5 m/s,
    z'- = b theta' = -0.3 m/s, P_n = 0.3 m/s > |x'-| / mu_s is not enough to hold it), so
    the face slides on with x'+ = x'- - mu_k P_n = 0.224 m/s (closed form). Flat, its
    trailing corner would need N = (g/2)(1 - mu_k/lambda) < 0: it slide-rocks on its
    leading corner +b from theta = 0, slipping at x'+, tipping (theta'' = -(3/R)(sin alpha -
    mu_k cos alpha) N > 0, N = g / (cos² alpha (1 + 4 lambda² - 3 mu_k lambda)))."""
    block, still, t = FreeStandingBlock(b=0.3, h=1.0, mu=1.2, mu_kinetic=0.92), StillBase(), 1.0
    lam, alpha, R = 0.3, math.atan(0.3), math.hypot(0.3, 1.0)
    state = block.initial_state()
    falling = np.array(block.to_pivot(1, state, 1.5))
    falling[5], falling[4] = -1.0, -0.3  # theta' [rad/s] and the centroid's z' = R sin(alpha) theta' [m/s]
    via = block.mode_after_guard(FreeMode.SLIDE_ROCK_POS_POS, 0, t, falling, still)
    assert via == FreeMode.LANDING_FLAT
    landed = block.entry_state(FreeMode.SLIDE_ROCK_POS_POS, via, falling)
    assert landed[3] == pytest.approx(0.5 - 0.92 * 0.3, abs=1e-15) and tuple(landed[4:6]) == (0.0, 0.0)
    assert abs(landed[3]) > 0 and abs(0.5) > 1.2 * 0.3  # the face does not stick
    after = block.mode_after_guard(via, 0, t, landed, still)
    assert after == FreeMode.SLIDE_ROCK_POS_POS and 0.5 * G * (1 - 0.92 / lam) < 0
    tipping = block.entry_state(via, after, landed)
    assert tipping[2] == 0.0 and tipping[3] == pytest.approx(0.224, abs=1e-15)  # the pivot slips at x'+
    _, normal, accel, _ = block.slide_rock(1, 1, tipping, 0.0, G)
    expected = G / (math.cos(alpha) ** 2 * (1 + 4 * lam**2 - 3 * 0.92 * lam))
    assert normal == pytest.approx(expected, rel=1e-14)
    assert accel == pytest.approx(-3 / R * (math.sin(alpha) - 0.92 * math.cos(alpha)) * expected, rel=1e-13)
    assert accel > 0
