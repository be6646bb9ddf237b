"""The complete free-standing block's laws (rest, slide, rock, slide-rock, flight, impacts),
each against its own reference: closed forms (Housner's r, the frictionless r0, the
impulse ratio, D at theta = 0, Shenton's thresholds in exact rational arithmetic), the
Newton-Euler equations of a rigid body with two unilateral frictional corners solved
directly (numpy.linalg.solve of the 7 x 7 system: x'', z'', theta'' and the forces at both
corners), a brute-force enumeration of the complementarity conditions for the rest map,
and the energy balance integrated by DOP853 (rtol 1e-12)."""

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from blockdae.rocking import _slide_rock_laws as laws
from blockdae.rocking._slide_rock_laws import FLIGHT, REST, ROCK, SLIDE, SLIDE_ROCK

G = 9.80665


def geometry(b, h):
    return math.hypot(b, h), math.atan2(b, h), b / h


# ---- the reference: Newton-Euler of section 3, solved directly ------------------------
def corner(c, theta, b, h):
    """(r_cx, r_cz) written from the block's drawing: the corner at (c b, -h) in the block's
    frame, turned clockwise by theta."""
    return c * b * math.cos(theta) - h * math.sin(theta), -c * b * math.sin(theta) - h * math.cos(theta)


def newton_euler(theta, rate, ax, ge, b, h, contacts, mu_s, mu_k):
    """Solve x'' = -a_x + sum F_c, z'' = -g_e + sum N_c, (R²/3) theta'' = sum (r_cz F_c - r_cx N_c)
    with each corner c's contact ``contacts[c]``: "free" (F = N = 0), "stick" (its
    acceleration is zero) or +1 / -1 (its vertical acceleration is zero, F = -sigma mu_k N).
    Unknowns (x'', z'', theta'', F_+, N_+, F_-, N_-); returns them and each corner's
    acceleration (a_cx, a_cz) = (x'' + r_cz theta'' - r_cx theta'², z'' - r_cx theta'' - r_cz theta'²)."""
    R2 = b * b + h * h
    r = {c: corner(c, theta, b, h) for c in (1, -1)}
    col = {1: 3, -1: 5}  # F_c's column; N_c's is the next
    rows = [[1, 0, 0, -1, 0, -1, 0], [0, 1, 0, 0, -1, 0, -1],
            [0, 0, R2 / 3, -r[1][1], r[1][0], -r[-1][1], r[-1][0]]]
    rhs = [-ax, -ge, 0.0]
    for c in (1, -1):
        rx, rz = r[c]
        f, n = [0.0] * 7, [0.0] * 7
        f[col[c]], n[col[c] + 1] = 1.0, 1.0
        vertical, horizontal = [0.0, 1.0, -rx, 0, 0, 0, 0], [1.0, 0.0, rz, 0, 0, 0, 0]
        if contacts[c] == "free":
            rows += [f, n]
            rhs += [0.0, 0.0]
        elif contacts[c] == "stick":
            rows += [horizontal, vertical]
            rhs += [rx * rate ** 2, rz * rate ** 2]
        else:
            slip = list(f)
            slip[col[c] + 1] = contacts[c] * mu_k
            rows += [vertical, slip]
            rhs += [rz * rate ** 2, 0.0]
    y = np.linalg.solve(np.array(rows, dtype=float), np.array(rhs))
    acc = {c: (y[0] + r[c][1] * y[2] - r[c][0] * rate ** 2, y[1] - r[c][0] * y[2] - r[c][1] * rate ** 2)
           for c in (1, -1)}
    return y, acc


states = st.tuples(st.floats(-1.2, 1.2), st.floats(-3.0, 3.0), st.floats(-15.0, 15.0), st.floats(1.0, 15.0),
                   st.floats(0.05, 2.0), st.floats(0.05, 2.0))


@settings(max_examples=200, deadline=None)
@given(states, st.sampled_from([1, -1]), st.sampled_from([1, -1]), st.floats(0.0, 1.3))
def test_slide_rock_matches_newton_euler_with_a_slipping_pivot(state, s, sigma, mu_k):
    theta, rate, ax, ge, b, h = state
    R, alpha, _ = geometry(b, h)
    D, N, theta_dd, u_dd = laws.slide_rock_acceleration(s, sigma, theta, rate, ax, ge, R, alpha, mu_k, math)
    y, acc = newton_euler(theta, rate, ax, ge, b, h, {s: sigma, -s: "free"}, mu_k, mu_k)
    scale = max(abs(ax), ge, R * rate ** 2, R * abs(theta_dd), 1.0)
    assert math.isclose(N, y[4 if s == 1 else 6], rel_tol=1e-12, abs_tol=1e-12 * scale)
    assert math.isclose(theta_dd, y[2], rel_tol=1e-12, abs_tol=1e-12 * scale / R)
    assert math.isclose(u_dd, acc[s][0], rel_tol=1e-12, abs_tol=1e-12 * scale)
    # D N = g_e - R cos(phi) theta'² = g_e + r_sz theta'²: D from the solved N
    if abs(N) > 1e-3 * scale:
        assert math.isclose(D, (ge + corner(s, theta, b, h)[1] * rate ** 2) / y[4 if s == 1 else 6], rel_tol=1e-10)


@settings(max_examples=200, deadline=None)
@given(states, st.sampled_from([1, -1]))
def test_rock_matches_newton_euler_with_a_fixed_pivot(state, s):
    theta, rate, ax, ge, b, h = state
    R, alpha, _ = geometry(b, h)
    theta_dd = laws.rock_acceleration(s, theta, ax, ge, R, alpha, math)
    F, N = laws.rock_contact_force(s, theta, rate, theta_dd, ax, ge, R, alpha, math)
    y, _ = newton_euler(theta, rate, ax, ge, b, h, {s: "stick", -s: "free"}, 0.0, 0.0)
    scale = max(abs(ax), ge, R * rate ** 2, R * abs(theta_dd), 1.0)
    assert math.isclose(theta_dd, y[2], rel_tol=1e-12, abs_tol=1e-12 * scale / R)
    assert math.isclose(F, y[3 if s == 1 else 5], rel_tol=1e-12, abs_tol=1e-12 * scale)
    assert math.isclose(N, y[4 if s == 1 else 6], rel_tol=1e-12, abs_tol=1e-12 * scale)


@pytest.mark.parametrize("b_over_h", [0.1, 0.3, 0.7, 1.0])
@pytest.mark.parametrize("s, sigma", [(1, 1), (1, -1), (-1, 1), (-1, -1)])
def test_painleve_denominator_level(b_over_h, s, sigma):
    """Closed form: D(theta = 0) = cos² alpha (1 + 4 lam² - 3 s sigma mu_k lam)."""
    R, alpha, lam = geometry(b_over_h, 1.0)
    D = laws.slide_rock_acceleration(s, sigma, 0.0, 0.7, 2.0, G, R, alpha, 0.45, math)[0]
    assert math.isclose(D, math.cos(alpha) ** 2 * (1 + 4 * lam ** 2 - 3 * s * sigma * 0.45 * lam), rel_tol=1e-14)


@pytest.mark.parametrize("sigma", [1, -1])
def test_sliding_normal_forces_balance_the_moment_of_friction(sigma):
    """Newton-Euler with both corners slipping (theta = 0): the same N_+, N_- and x''."""
    b, h, mu_k, ax, ge = 0.6, 1.1, 0.4, -3.0, 8.5
    y, _ = newton_euler(0.0, 0.0, ax, ge, b, h, {1: sigma, -1: sigma}, mu_k, mu_k)
    assert np.allclose(laws.slide_normal_forces(sigma, ge, b / h, mu_k), (y[4], y[6]), rtol=1e-13)
    assert math.isclose(laws.slide_acceleration(sigma, ax, ge, mu_k), y[0], rel_tol=1e-13)


# ---- impacts -------------------------------------------------------------------------
def rocking_return(s, w, b, h):
    """Rates on ROCK s at theta = 0 with theta' = w: x' = h w, z' = s b w (pivot still)."""
    return h * w, s * b * w, w


@pytest.mark.parametrize("b_over_h", [0.05, 0.2, 0.5, 1.0, 1.3])
@pytest.mark.parametrize("s", [1, -1])
def test_sticking_impact_is_housners(b_over_h, s):
    """Closed forms: theta'+ = (1 - 3/2 sin² alpha) theta'-, P_t/P_n = 3 lam/(4 + lam²), the new
    pivot still, the old one leaving upward at 2 b r |w|."""
    b, h = b_over_h, 1.0
    R, alpha, lam = geometry(b, h)
    w = -s * 1.7
    x, z, rate = rocking_return(s, w, b, h)
    assert laws.corner_state(s, h, 0.0, x, z, rate, b, h, math)[2:] == pytest.approx((0.0, 0.0, 0.0), abs=1e-15)
    xr, zr, tr, sticks, pt, pn = laws.corner_impact(-s, 0.0, x, z, rate, b, h, 3 * lam / (4 + lam ** 2) + 1e-9, 0.1)
    r = 1 - 1.5 * math.sin(alpha) ** 2
    assert sticks and pn > 0
    assert math.isclose(tr, r * w, rel_tol=1e-14)
    assert math.isclose(abs(pt) / pn, 3 * lam / (4 + lam ** 2), rel_tol=1e-13)
    assert laws.corner_state(-s, h, 0.0, xr, zr, tr, b, h, math)[3:] == pytest.approx((0.0, 0.0), abs=1e-14)
    assert math.isclose(laws.corner_state(s, h, 0.0, xr, zr, tr, b, h, math)[4], 2 * b * r * abs(w), rel_tol=1e-13)
    # just below the impulse ratio the corner slides through the impact
    assert not laws.corner_impact(-s, 0.0, x, z, rate, b, h, 3 * lam / (4 + lam ** 2) - 1e-9, 0.1)[3]


@pytest.mark.parametrize("b_over_h", [0.05, 0.2, 0.5, 1.0])
@pytest.mark.parametrize("s", [1, -1])
def test_frictionless_impact(b_over_h, s):
    """Closed form: theta'+ = r0 theta'-, r0 = (1 - 3 sin² alpha)/(1 + 3 sin² alpha), P_t = 0."""
    b, h = b_over_h, 1.0
    alpha = geometry(b, h)[1]
    w = -s * 0.9
    x, z, rate = rocking_return(s, w, b, h)
    xr, zr, tr, sticks, pt, pn = laws.corner_impact(-s, 0.0, x, z, rate, b, h, 0.0, 0.0)
    s2 = math.sin(alpha) ** 2
    assert not sticks and pt == 0.0 and xr == x
    assert math.isclose(tr, (1 - 3 * s2) / (1 + 3 * s2) * w, rel_tol=1e-14)


@settings(max_examples=300, deadline=None)
@given(st.sampled_from([1, -1]), st.floats(-1.4, 1.4), st.floats(-4.0, 4.0), st.floats(-4.0, 4.0),
       st.floats(-4.0, 4.0), st.floats(0.05, 2.0), st.floats(0.05, 2.0), st.floats(0.0, 1.3), st.floats(0.0, 1.0))
def test_impulses_satisfy_the_jump_equations(c, theta, x, z, rate, b, h, mu_s, kinetic_ratio):
    """Any strike (v_cz- < 0): v_cz+ = 0; P_n >= 0; sticking: v_cx+ = 0 inside the cone
    |P_t| <= mu_s P_n; sliding: |P_t| = mu_k P_n with the corner moving against its friction
    impulse (or stopped); the angular momentum about the corner conserved (the impulse acts
    there); no energy gained."""
    mu_k = kinetic_ratio * mu_s
    R = math.hypot(b, h)
    rx, rz = corner(c, theta, b, h)
    assume(z - rx * rate < -1e-3)  # the corner strikes
    xr, zr, tr, sticks, pt, pn = laws.corner_impact(c, theta, x, z, rate, b, h, mu_s, mu_k)
    v_cx_after, v_cz_after = xr + rz * tr, zr - rx * tr
    scale = abs(x) + abs(z) + R * abs(rate)
    assert abs(v_cz_after) <= 1e-13 * scale
    assert pn > 0
    if sticks:
        assert abs(v_cx_after) <= 1e-13 * scale and abs(pt) <= mu_s * pn
    else:
        assert math.isclose(abs(pt), mu_k * pn, rel_tol=1e-14) and v_cx_after * pt <= 1e-13 * scale * abs(pt)
    momentum = (R * R / 3 * rate + rx * z - rz * x, R * R / 3 * tr + rx * zr - rz * xr)
    assert math.isclose(*momentum, rel_tol=1e-12, abs_tol=1e-13 * R * scale)
    assert laws.kinetic_energy(xr, zr, tr, R) <= laws.kinetic_energy(x, z, rate, R) * (1 + 1e-14)


def test_flat_landing():
    """The face lands: sticks while |x'| <= mu_s |z'|, else slides on at |x'| - mu_k |z'|."""
    assert laws.flat_landing(0.3, -1.0, 0.4, 0.3) == (0.0, True, -0.3, 1.0)
    assert laws.flat_landing(-0.5, -1.0, 0.4, 0.3) == pytest.approx((-0.2, False, 0.3, 1.0))


def test_landing_from_flight():
    b, h = 0.4, 1.0
    lam = b / h
    # tilted: the lowest corner strikes, a sticking impact (mu large) leaves the block on it
    c, xr, zr, tr, sticks, *_ = laws.landing(-0.1, 0.0, -1.0, 0.0, b, h, 2.0, 2.0)
    assert c == -1 and sticks and laws.corner_state(-1, h, -0.1, xr, zr, tr, b, h, math)[3:] == pytest.approx((0, 0))
    # level, not turning, sliding hard (|P_t| > lam P_n needed to stop it): tips onto its leading corner
    c, xr, zr, tr, *_ = laws.landing(0.0, 2.0, -1.0, 0.0, b, h, 2.0, 2.0)
    assert c == 1 and tr > 0
    assert laws.corner_state(-1, h, 0.0, xr, zr, tr, b, h, math)[4] >= 0
    # level, straight down: no single corner turns the block onto itself -> flat landing
    assert laws.landing(0.0, 0.0, -1.0, 0.0, b, h, 0.5, 0.5) == (0, 0.0, 0.0, 0.0, True, -0.0, 1.0)
    # level, gently sliding (|x'| <= mu_s |z'|, tangential impulse within lam P_n): flat, sticks
    landed = laws.landing(0.0, 0.1 * lam, -1.0, 0.0, b, h, 0.5, 0.5)
    assert landed[0] == 0 and landed[4] and landed[1] == 0.0
    # level and turning: the corner that falls faster strikes
    assert laws.landing(0.0, 0.0, -0.2, 1.0, b, h, 2.0, 2.0)[0] == 1


# ---- leaving rest: the map against the complementarity conditions ---------------------
def consistent_modes(ax, ge, b, h, mu_s, mu_k):
    """Every contact combination of the two corners (free, stick, slip +, slip -) at rest
    (theta = theta' = 0) whose forces and accelerations, solved from Newton-Euler, satisfy
    section 3's conditions; labelled (kind, side) as :func:`rest_mode` returns them. A motion
    needs an acceleration above the solve's rounding (1e-12 of the demand)."""
    found = []
    tol = 1e-12 * max(abs(ax), abs(ge))
    for plus, minus in itertools.product(("free", "stick", 1, -1), repeat=2):
        contacts = {1: plus, -1: minus}
        if plus == minus == "stick":
            # both stick: the block stays, x'' = z'' = theta'' = 0; only the total F = F_+ + F_- is
            # determined (F = a_x, N_+ + N_- = g_e, -h F - b N_+ + b N_- = 0), and a split within
            # both cones exists iff N_+, N_- >= 0 and |F| <= mu_s (N_+ + N_-)
            F, n_plus, n_minus = np.linalg.solve([[1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [-h, -b, b]], [ax, ge, 0.0])
            assert np.allclose((n_plus, n_minus), laws.rest_normal_forces(ax, ge, b / h), rtol=1e-13, atol=1e-13 * G)
            if n_plus >= 0 and n_minus >= 0 and abs(F) <= mu_s * ge:
                found.append((REST, 0))
            continue
        try:
            y, acc = newton_euler(0.0, 0.0, ax, ge, b, h, contacts, mu_s, mu_k)
        except np.linalg.LinAlgError:
            continue
        ok = True
        for c, col in ((1, 3), (-1, 5)):
            F, N = y[col], y[col + 1]
            if contacts[c] == "free":
                ok &= acc[c][1] > tol
            elif contacts[c] == "stick":
                ok &= N >= 0 and abs(F) <= mu_s * N
            else:
                ok &= N >= 0 and contacts[c] * acc[c][0] > tol
        if ok:
            if plus == minus == "free":
                found.append((FLIGHT, 0))
            elif plus == minus:
                found.append((SLIDE, plus))
            elif "free" in (plus, minus):
                s = 1 if minus == "free" else -1
                kind = ROCK if contacts[s] == "stick" else SLIDE_ROCK
                found.append((kind, s) if kind == ROCK or contacts[s] == s else (kind, s, contacts[s]))
            else:
                found.append(("mixed", plus, minus))
    return found


def near_a_boundary(a, ge, lam, mu):
    gap = 1e-9 * max(ge, 1.0)
    thresholds = (lam * ge, mu * ge, laws.slide_rock_threshold(mu, ge, lam))
    return min(abs(mu - lam) * ge, *(abs(a - threshold) for threshold in thresholds)) < gap


@pytest.mark.parametrize("b_over_h", [0.2, 0.45, 0.9, 1.4])
@pytest.mark.parametrize("ge", [G, 0.55 * G, -1.5])
def test_rest_map_is_the_one_consistent_mode(b_over_h, ge):
    """mu_s = mu_k: exactly one mode satisfies the complementarity conditions at each grid
    point off the boundaries (a = lam g_e, a = mu g_e, mu = lam, a = a_SR(mu), where a
    condition is an equality), and it is rest_mode's."""
    b, h = b_over_h, 1.0
    checked = set()
    for mu in np.linspace(0.031, 1.93, 23):
        for ratio in np.linspace(0.0, 2.47, 23):
            for side in (1, -1):
                ax = side * ratio * abs(ge)
                if ge > 0 and near_a_boundary(abs(ax), ge, b / h, mu):
                    continue
                found = consistent_modes(ax, ge, b, h, mu, mu)
                expected = laws.rest_mode(ax, ge, b / h, mu, mu)
                assert found == [expected], (mu, ax, ge, found, expected)
                checked.add(expected[0])
    assert checked == ({FLIGHT} if ge < 0 else {REST, SLIDE, ROCK, SLIDE_ROCK})


@pytest.mark.parametrize("b_over_h", [0.3, 0.8])
def test_rest_map_lets_static_friction_hold(b_over_h):
    """mu_s > mu_k: rest_mode's mode is consistent, and a sticking one (REST, ROCK) wherever
    one is consistent (a sliding mode may be consistent too)."""
    b, h = b_over_h, 1.0
    both = 0
    for mu_s in np.linspace(0.051, 1.63, 19):
        for ratio in np.linspace(0.0, 2.2, 23):
            ax = -ratio * G
            mu_k = 0.6 * mu_s
            if near_a_boundary(ratio * G, G, b / h, mu_s) or near_a_boundary(ratio * G, G, b / h, mu_k):
                continue
            found = consistent_modes(ax, G, b, h, mu_s, mu_k)
            expected = laws.rest_mode(ax, G, b / h, mu_s, mu_k)
            assert expected in found
            sticking = [m for m in found if m[0] in (REST, ROCK)]
            if sticking:
                assert expected in sticking and len(sticking) == 1
            both += len(found) > 1
    assert both > 10  # the rule was exercised


def test_rest_map_on_its_thresholds_the_rate_decides():
    """Exact thresholds (lam = 0.5, mu = 1, g_e = 8: lam g_e = 4, a_SR = 44 m/s²): a demand
    rising through one starts the motion, one that touches it and turns back does not."""
    lam, mu, ge = 0.5, 1.0, 8.0
    assert laws.slide_rock_threshold(mu, ge, lam) == 44.0
    assert laws.rest_mode(-4.0, ge, lam, mu, mu) == (REST, 0)
    assert laws.rest_mode(-4.0, ge, lam, mu, mu, ax_rate=-1.0) == (ROCK, 1)
    assert laws.rest_mode(4.0, ge, lam, mu, mu, ax_rate=1.0) == (ROCK, -1)
    assert laws.rest_mode(4.0, ge, lam, mu, mu, ax_rate=-1.0) == (REST, 0)
    assert laws.rest_mode(4.0, ge, lam, mu, mu, ge_rate=-1.0) == (ROCK, -1)  # g_e falling: lam g_e falls below a
    assert laws.rest_mode(-44.0, ge, lam, mu, mu) == (ROCK, 1)
    assert laws.rest_mode(-44.0, ge, lam, mu, mu, ax_rate=-1.0) == (SLIDE_ROCK, 1)
    assert laws.rest_mode(-44.0, ge, lam, mu, 0.4, ax_rate=-1.0) == (SLIDE, 1)
    assert laws.rest_mode(-44.0, ge, lam, mu, mu, ge_rate=1.0, ax_rate=-1.0) == (ROCK, 1)  # margin still rising
    assert laws.rest_mode(-2.0, ge, 1.0, 0.25, 0.25, ax_rate=-1.0) == (SLIDE, 1)  # mu g_e = 2
    assert laws.rest_mode(-2.0, ge, 1.0, 0.25, 0.25, ax_rate=0.0) == (REST, 0)
    assert laws.rest_mode(0.0, 0.0, lam, mu, mu, ge_rate=-1.0) == (FLIGHT, 0)
    assert laws.rest_mode(0.0, 0.0, lam, mu, mu, ge_rate=0.0) == (REST, 0)
    assert laws.rest_mode(1.0, -0.1, lam, mu, mu) == (FLIGHT, 0)


@pytest.mark.parametrize("ax_rate, az_rate", [(-1.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.0, -1.0), (-2.0, 0.3),
                                              (-2.0, 0.5)])
def test_on_the_slip_threshold_the_rate_decides_as_the_rocking_flow_does(ax_rate, az_rate):
    """At a_x = -a_SR(mu) the pivot's margin mu N - |F| is 0; rocking on from rest under
    a_x + a_x' t, g_e + a_z' t (ROCK's flow, DOP853) its sign soon after is ROCK's (> 0) or
    SLIDE-ROCK's (< 0): rest_mode's choice from the rates alone. The margin is linear in t
    there (its values at 1e-7 s and 1e-6 s in ratio 10 within 2 %: the rate's term)."""
    b, h, mu = 0.5, 1.0, 1.0
    R, alpha, lam = geometry(b, h)
    ge0 = 8.0
    ax0 = -laws.slide_rock_threshold(mu, ge0, lam)  # -44 m/s²: drives the block onto its +b corner

    def base(t):
        return ax0 + ax_rate * t, ge0 + az_rate * t

    def rhs(t, y):
        return [y[1], laws.rock_acceleration(1, y[0], *base(t), R, alpha, math)]

    def margin(t):
        theta, rate = solve_ivp(rhs, (0, t), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-22).y[:, -1]
        accel = laws.rock_acceleration(1, theta, *base(t), R, alpha, math)
        F, N = laws.rock_contact_force(1, theta, rate, accel, *base(t), R, alpha, math)
        return mu * N - abs(F)

    early, later = margin(1e-7), margin(1e-6)
    assert later / early == pytest.approx(10.0, rel=0.02)
    assert laws.rest_mode(ax0, ge0, lam, mu, mu, ax_rate, az_rate) == ((ROCK, 1) if later > 0 else (SLIDE_ROCK, 1))


def test_shenton_thresholds_in_exact_arithmetic():
    """a_SR(mu) - mu g_e = 3 g_e (mu - lam)(1 + mu lam)/(1 + 4 lam² - 3 mu lam); mu_cr inverts
    a_SR, equals lam at a = lam g_e and rises with a; at a = lam g_e the pivot's margin in
    (S) is 4 g_e (1 + lam²)(mu - lam). All on fractions, exactly."""
    rng = np.random.default_rng(7)
    for _ in range(200):
        lam = Fraction(int(rng.integers(1, 300)), 100)
        ge = Fraction(int(rng.integers(1, 2000)), 100)
        mu = lam + Fraction(int(rng.integers(1, 300)), 1000)
        if 1 + 4 * lam ** 2 - 3 * mu * lam <= 0:
            assert laws.slide_rock_threshold(mu, ge, lam) == math.inf
            continue
        a_sr = laws.slide_rock_threshold(mu, ge, lam)
        assert a_sr - mu * ge == 3 * ge * (mu - lam) * (1 + mu * lam) / (1 + 4 * lam ** 2 - 3 * mu * lam)
        assert laws.critical_friction(a_sr, ge, lam) == mu
        assert laws.critical_friction(lam * ge, ge, lam) == lam
        assert laws.critical_friction(a_sr * Fraction(11, 10), ge, lam) > mu
        margin = ge * (mu * (4 + lam ** 2) - 3 * lam) - lam * ge * (1 + 4 * lam ** 2 - 3 * mu * lam)
        assert margin == 4 * ge * (1 + lam ** 2) * (mu - lam)


# ---- a pivot at rest relative to the base: the mode it takes ---------------------------
def pivot_candidates(s, theta, rate, ax, ge, b, h, mu_s, mu_k):
    """Each way pivot ``s`` can go on (stick, slip +1 / -1, lift; the other corner above the
    base) with its Newton-Euler solution: ((kind, sigma), margins), consistent where every
    margin is >= 0 (the sticking cone's, N's) or > 0 (a slip's or a lift's acceleration)."""
    col = 3 if s == 1 else 5
    out = []
    for contact in ("stick", 1, -1, "free"):
        y, acc = newton_euler(theta, rate, ax, ge, b, h, {s: contact, -s: "free"}, mu_s, mu_k)
        F, N = y[col], y[col + 1]
        if contact == "stick":
            out.append(((ROCK, 0), (N, mu_s * N - abs(F))))
        elif contact == "free":
            out.append(((FLIGHT, 0), (acc[s][1],)))
        else:
            out.append(((SLIDE_ROCK, contact), (N, contact * acc[s][0])))
    return out


@settings(max_examples=300, deadline=None)
@given(st.floats(0.001, 1.4), st.floats(-4.0, 4.0), st.floats(-20.0, 20.0), st.floats(-3.0, 15.0),
       st.floats(0.05, 2.0), st.floats(0.05, 2.0), st.floats(0.0, 1.3), st.floats(0.3, 1.0), st.sampled_from([1, -1]))
def test_pivot_mode_is_the_consistent_one(s_theta, rate, ax, ge, b, h, mu_s, kinetic_ratio, s):
    """After a slip stops or a sticking impact: pivot_mode's mode satisfies the contact
    conditions, and it sticks wherever sticking does; with mu_s = mu_k it is the only one."""
    mu_k = kinetic_ratio * mu_s
    R, alpha, _ = geometry(b, h)
    theta = s * s_theta
    candidates = pivot_candidates(s, theta, rate, ax, ge, b, h, mu_s, mu_k)
    scale = max(abs(ax), abs(ge), R * rate ** 2, 1.0)
    assume(all(abs(m) > 1e-9 * scale for _, margins in candidates for m in margins))
    consistent = [mode for mode, margins in candidates if all(m > 0 for m in margins)]
    chosen = laws.pivot_mode(s, theta, rate, ax, ge, R, alpha, mu_s, mu_k)
    assert chosen in consistent, (chosen, consistent)
    if (ROCK, 0) in consistent:
        assert chosen == (ROCK, 0)
    if kinetic_ratio == 1.0:
        assert consistent == [chosen]


def test_mode_after_an_impact():
    """Housner's return (sticking): ROCK on the new pivot; frictionless: SLIDE-ROCK toward the
    corner's slip; a hard, fast strike of a squat block: flight (N < 0)."""
    b, h = 0.3, 1.0
    x, z, rate = rocking_return(1, -1.0, b, h)
    after = laws.corner_impact(-1, 0.0, x, z, rate, b, h, 0.8, 0.8)
    assert not laws.lands_flat(-1, 0.0, after[1], after[2], b, h)
    assert laws.mode_after_impact(-1, 0.0, *after[:4], 0.0, G, b, h, 0.8, 0.8) == (ROCK, -1, 0)
    after = laws.corner_impact(-1, 0.0, x, z, rate, b, h, 0.0, 0.0)
    slip = laws.corner_state(-1, h, 0.0, *after[:3], b, h, math)[3]
    assert slip != 0 and laws.mode_after_impact(-1, 0.0, *after[:4], 0.0, G, b, h, 0.0, 0.0) == (SLIDE_ROCK, -1,
                                                                                                   int(np.sign(slip)))
    x, z, rate = rocking_return(1, -30.0, b, h)
    after = laws.corner_impact(-1, 0.0, x, z, rate, b, h, 0.8, 0.8)
    assert laws.mode_after_impact(-1, 0.0, *after[:4], 0.0, G, b, h, 0.8, 0.8) == (FLIGHT, 0, 0)


@pytest.mark.parametrize("b_over_h", [0.5, 1.2, 1.5, 3.0])
def test_a_squat_block_lands_flat(b_over_h):
    """Housner's r < 0 where sin² alpha > 2/3 (b/h > sqrt 2): the sticking impact would drive
    the old pivot down through the base (v_z = 2 b r |w| < 0), a flat landing."""
    b, h = b_over_h, 1.0
    x, z, rate = rocking_return(1, -1.0, b, h)
    after = laws.corner_impact(-1, 0.0, x, z, rate, b, h, 2.0, 2.0)
    assert after[3] and laws.lands_flat(-1, 0.0, after[1], after[2], b, h) == (b_over_h > math.sqrt(2))


# ---- a slide-rock motion: the energy balance of section 9 -----------------------------
def test_energy_balance_while_slide_rocking():
    """SLIDE-ROCK (+1, +1) under constant a_x, a_z: E(t) - E(0) = the base's work + friction's
    work, all from the laws, along DOP853 at rtol 1e-12 (the balance's error measured:
    2e-13 J/kg; 1e-10 J/kg at rtol 1e-10; E ~ 17 J/kg, the works ~ 16 J/kg)."""
    b, h, mu_k, ax, az = 0.5, 1.0, 0.7, -25.0, 1.5
    R, alpha, _ = geometry(b, h)
    ge = G + az

    def rhs(t, y):
        theta, rate, u, u_rate = y[:4]
        _, N, theta_dd, u_dd = laws.slide_rock_acceleration(1, 1, theta, rate, ax, ge, R, alpha, mu_k, math)
        x_rate, z_rate = laws.centroid_from_pivot(1, theta, rate, u, u_rate, R, alpha, math)[2:]
        return [rate, theta_dd, u_rate, u_dd, laws.base_power(ax, az, x_rate, z_rate),
                laws.friction_power(-mu_k * N, u_rate)]

    def energy(y):
        _, z, x_rate, z_rate = laws.centroid_from_pivot(1, y[0], y[1], y[2], y[3], R, alpha, math)
        return laws.energy(x_rate, z_rate, y[1], z, R, G)

    y0 = [0.02, 0.4, 0.0, 0.3, 0.0, 0.0]
    sol = solve_ivp(rhs, (0, 0.25), y0, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    assert sol.success
    for t in np.linspace(0.0, 0.25, 11):
        y = sol.sol(t)
        assert y[3] > 0 and laws.slide_rock_acceleration(1, 1, y[0], y[1], ax, ge, R, alpha, mu_k, math)[1] > 0
        assert abs(energy(y) - energy(y0) - y[4] - y[5]) < 1e-11
    assert sol.y[5, -1] < -0.05  # friction did work


# ---- written once: the same numbers from floats, NumPy, JAX and numba -----------------
def test_the_flows_take_numpy_and_jax():
    jnp = pytest.importorskip("jax.numpy")
    import jax

    jax.config.update("jax_enable_x64", True)
    theta, rate = np.array([0.1, -0.3]), np.array([0.5, 1.2])
    args = (theta, rate, -3.0, G, 1.2, 0.4, 0.6)
    numpy = laws.slide_rock_acceleration(1, -1, *args, np)
    traced = jax.jit(lambda th, w: jnp.stack(laws.slide_rock_acceleration(1, -1, th, w, *args[2:], jnp)))(theta, rate)
    floats = [laws.slide_rock_acceleration(1, -1, th, w, *args[2:], math) for th, w in zip(theta, rate)]
    assert np.allclose(np.stack(numpy), traced, rtol=1e-15, atol=0)
    assert np.allclose(np.stack(numpy).T, floats, rtol=1e-15, atol=0)


@pytest.mark.slow
def test_the_laws_compile_with_numba():
    numba = pytest.importorskip("numba")
    from numba.extending import register_jitable

    from blockdae.rocking import _rules
    from blockdae.solvers import xp_scalar

    for fn in (_rules.angular_acceleration, *[f for name, f in vars(laws).items()
                                               if callable(f) and getattr(f, "__module__", "") == laws.__name__]):
        register_jitable(fn)

    @numba.njit
    def everything(theta, rate, ax, ge):
        R, alpha, lam = math.hypot(0.4, 1.0), math.atan2(0.4, 1.0), 0.4
        return (laws.slide_rock_acceleration(1, 1, theta, rate, ax, ge, R, alpha, 0.5, xp_scalar),
                laws.rest_mode(ax, ge, lam, 0.6, 0.5, 0.0, 0.0),
                laws.pivot_mode(1, theta, rate, ax, ge, R, alpha, 0.6, 0.5),
                laws.landing(0.0, 2.0, -1.0, 0.0, 0.4, 1.0, 2.0, 2.0), laws.slide_rock_threshold(0.6, ge, lam),
                laws.mode_after_impact(-1, 0.0, 0.3, -0.1, 0.2, False, ax, ge, 0.4, 1.0, 0.6, 0.5),
                laws.corner_impact(1, theta, 0.2, -1.0, rate, 0.4, 1.0, 0.6, 0.5))

    compiled, plain = everything(0.1, 0.3, -5.0, G), everything.py_func(0.1, 0.3, -5.0, G)
    assert compiled == plain
