"""The laws of the complete free-standing block on plain numbers, written once: rest, slide,
rock, slide-rock (the pivot slips) and flight, their contact forces, the map of what a
block at rest does, the corner impacts with friction and the energy balance.

Everything is per unit mass in the base's frame: a_x [m/s²] the base's horizontal
acceleration, g_e = g + a_z [m/s²]; the block is 2b wide and 2h high (b, h [m]),
R = sqrt(b² + h²) [m], alpha = atan(b/h) [rad], lam = b/h = tan(alpha) [-]; friction
static mu_s and kinetic mu_k <= mu_s [-]. The state is the centroid's position (x, z)
relative to the base [m] (z = h standing flat) and the rotation theta [rad] (theta > 0:
leaning toward +x on the corner at +b), with rates x', z' [m/s] and theta' [rad/s].
Corners c = +1, -1 (the one at +b, -b when theta = 0); a pivot s, a slip direction
sigma (the sign of the pivot's or the block's horizontal velocity), phi = s alpha - theta.
F, N: the base's horizontal and vertical force on the block [m/s²]; impulses [m/s].

The flows take an array namespace ``xp`` for sin and cos and use plain arithmetic
otherwise (NumPy, ``jax.numpy``, :mod:`math` or, inside numba,
:mod:`blockdae.solvers.xp_scalar`); the mode decisions and the impacts are scalar. Modes
are a kind (:data:`REST`, :data:`SLIDE`, :data:`ROCK`, :data:`SLIDE_ROCK`,
:data:`FLIGHT`) with a side.
"""

import math

from ..solvers import xp_scalar
from ._rules import angular_acceleration

REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT = 0, 1, 2, 3, 4


def _sign(v):
    return 1 if v > 0 else (-1 if v < 0 else 0)


# ---- geometry (corners) ----------------------------------------------------------------
def corner_offset(c, theta, b, h, xp):
    """(r_cx, r_cz) [m]: corner ``c`` relative to the centroid at rotation ``theta``."""
    return c * b * xp.cos(theta) - h * xp.sin(theta), -c * b * xp.sin(theta) - h * xp.cos(theta)


def corner_state(c, z, theta, x_rate, z_rate, theta_rate, b, h, xp):
    """(r_cx, r_cz, z_c, v_cx, v_cz) of corner ``c``: its offset from the centroid [m], its
    height above the base [m] and its velocity relative to the base [m/s]."""
    r_cx, r_cz = corner_offset(c, theta, b, h, xp)
    return r_cx, r_cz, z + r_cz, x_rate + r_cz * theta_rate, z_rate - r_cx * theta_rate


def base_slip(x, theta, b, h, xp):
    """The slip of the block's base relative to the base [m]: the horizontal displacement
    of its lower corner from where that corner stood at rest, x - h sin theta - sgn(theta)
    b (1 - cos theta) (x [m] the centroid's, theta [rad]). Flat, it is x; on a sticking
    pivot it does not change; it moves only where a corner slips."""
    return x - h * xp.sin(theta) - xp.sign(theta) * b * (1.0 - xp.cos(theta))


# ---- flows and contact forces ----------------------------------------------------------
def rock_acceleration(s, theta, ax, ge, R, alpha, xp):
    """theta'' [rad/s²] rocking on a sticking pivot ``s``: -(3/(4R)) (g_e sin phi + a_x cos phi)."""
    return angular_acceleration(s, theta, ax, ge, alpha, 0.75 / R, 1.0, False, xp)  # p²/g = 3/(4R)


def rock_contact_force(s, theta, rate, theta_dd, ax, ge, R, alpha, xp):
    """(F, N) [m/s²] at the sticking pivot ``s`` with theta' = ``rate`` [rad/s] and theta'' =
    ``theta_dd`` [rad/s²]: F = a_x + R cos phi theta'' + R sin phi theta'²,
    N = g_e + R sin phi theta'' - R cos phi theta'²."""
    phi = s * alpha - theta
    sin, cos = xp.sin(phi), xp.cos(phi)
    return (ax + R * cos * theta_dd + R * sin * rate * rate,
            ge + R * sin * theta_dd - R * cos * rate * rate)


def slide_rock_acceleration(s, sigma, theta, rate, ax, ge, R, alpha, mu_k, xp):
    """(D, N, theta'', u'') on pivot ``s`` slipping toward ``sigma`` (F = -sigma mu_k N):
    D = 1 + 3 sin phi (sin phi - sigma mu_k cos phi) [-] (Painlevé's denominator: no
    consistent force where D <= 0), N = (g_e - R cos phi theta'²) / D [m/s²],
    theta'' = -(3/R)(sin phi - sigma mu_k cos phi) N [rad/s²] and the pivot's acceleration
    u'' = -a_x - sigma mu_k N - R cos phi theta'' - R sin phi theta'² [m/s²]."""
    phi = s * alpha - theta
    sin, cos = xp.sin(phi), xp.cos(phi)
    lever = sin - sigma * mu_k * cos
    denominator = 1.0 + 3.0 * sin * lever
    normal = (ge - R * cos * rate * rate) / denominator
    theta_dd = -(3.0 / R) * lever * normal
    return denominator, normal, theta_dd, -ax - sigma * mu_k * normal - R * cos * theta_dd - R * sin * rate * rate


def centroid_from_pivot(s, theta, rate, u, u_rate, R, alpha, xp):
    """(x, z [m], x', z' [m/s]) of the centroid on pivot ``s`` at u [m] moving at u' [m/s]:
    x = u - R sin phi, z = R cos phi, x' = u' + R cos phi theta', z' = R sin phi theta'."""
    phi = s * alpha - theta
    sin, cos = xp.sin(phi), xp.cos(phi)
    return u - R * sin, R * cos, u_rate + R * cos * rate, R * sin * rate


def flight_acceleration(ax, ge):
    """(x'', z'' [m/s²], theta'' [rad/s²]) of the block in flight: (-a_x, -g_e, 0)."""
    return -ax, -ge, 0.0


def slide_acceleration(sigma, ax, ge, mu_k):
    """x'' [m/s²] of the flat block sliding toward ``sigma``: -a_x - sigma mu_k g_e."""
    return -ax - sigma * mu_k * ge


def slide_normal_forces(sigma, ge, lam, mu_k):
    """(N_+, N_-) [m/s²] on the corners at +b and -b of the flat block sliding toward
    ``sigma``: (g_e/2)(1 + c sigma mu_k / lam); the leading corner carries more, and the
    trailing one would need N < 0 where mu_k > lam."""
    return 0.5 * ge * (1.0 + sigma * mu_k / lam), 0.5 * ge * (1.0 - sigma * mu_k / lam)


def rest_normal_forces(ax, ge, lam):
    """(N_+, N_-) [m/s²] on the corners of the block at rest: (g_e -+ a_x/lam)/2."""
    return 0.5 * (ge - ax / lam), 0.5 * (ge + ax / lam)


# ---- leaving rest (Shenton 1996, with g_e) ---------------------------------------------
def slide_rock_threshold(mu, ge, lam):
    """a_SR [m/s²]: the demand |a_x| above which a block that starts to rock from rest
    slips at its pivot under friction ``mu`` (> lam):
    g_e [mu (4 + lam²) - 3 lam] / (1 + 4 lam² - 3 mu lam); infinite (the pivot always
    holds) where the denominator is <= 0. Exact on fractions."""
    denominator = 1 + 4 * lam * lam - 3 * mu * lam
    if denominator <= 0:
        return math.inf
    return ge * (mu * (4 + lam * lam) - 3 * lam) / denominator


def critical_friction(a, ge, lam):
    """mu_cr [-]: the least friction (mu_s = mu_k) with which a block at rest under the demand
    |a_x| = ``a`` > lam g_e [m/s²] rocks rather than slide-rocks:
    [(a/g_e)(1 + 4 lam²) + 3 lam] / [4 + lam² + 3 lam (a/g_e)]. Exact on fractions."""
    ratio = a / ge
    return (ratio * (1 + 4 * lam * lam) + 3 * lam) / (4 + lam * lam + 3 * lam * ratio)


def rest_mode(ax, ge, lam, mu_s, mu_k, ax_rate=0.0, ge_rate=0.0):
    """(kind, d): the mode a block at rest takes under a_x = ``ax`` and g_e = ``ge``
    [m/s²] (section 6's map, Shenton 1996 with g_e), d = -sgn(a_x) the side toward which
    it is driven (the pivot and the slip direction; 0 at REST and in FLIGHT).

    REST while |a_x| <= min(mu_s, lam) g_e; then, for mu_s <= lam, SLIDE; for mu_s > lam,
    ROCK while the pivot's static friction holds (|a_x| <= :func:`slide_rock_threshold` of
    mu_s), else SLIDE_ROCK (d, d) if mu_k > lam, else SLIDE; FLIGHT where g_e < 0. Static
    friction holds if it can. On a threshold the rates ``ax_rate`` and ``ge_rate``
    [m/s³] decide: the demand leaves it (a motion starts, the pivot slips, the block
    lifts) only if it is crossing outward, so a touch that turns back starts nothing."""
    if ge < 0 or (ge == 0 and ge_rate < 0):
        return FLIGHT, 0
    d = -_sign(ax) if ax != 0 else -_sign(ax_rate)
    a, a_rate = abs(ax), -d * ax_rate  # |a_x| and its rate
    limit = min(mu_s, lam)
    excess = a - limit * ge
    if excess < 0 or (excess == 0 and a_rate - limit * ge_rate <= 0):
        return REST, 0
    if mu_s <= lam:
        return SLIDE, d
    # the pivot's margin in (S): g_e [mu_s (4 + lam²) - 3 lam] - a (1 + 4 lam² - 3 mu_s lam), and its rate
    held, pushed = mu_s * (4.0 + lam * lam) - 3.0 * lam, 1.0 + 4.0 * lam * lam - 3.0 * mu_s * lam
    margin = ge * held - a * pushed
    if margin > 0 or (margin == 0 and ge_rate * held - a_rate * pushed >= 0):
        return ROCK, d
    return (SLIDE_ROCK, d) if mu_k > lam else (SLIDE, d)


def sliding_kind(lam, mu_k):
    """The kind a flat block that slides is in: SLIDE, or SLIDE_ROCK on its leading corner
    (s = sigma) where mu_k > lam (the trailing corner would need N < 0)."""
    return SLIDE_ROCK if mu_k > lam else SLIDE


def pivot_mode(s, theta, rate, ax, ge, R, alpha, mu_s, mu_k):
    """(kind, sigma) on pivot ``s`` at rest relative to the base (a slip that stops, an impact
    that sticks) at (theta [rad], theta' [rad/s]): ROCK (sigma 0) if N >= 0 and
    |F| <= mu_s N with ROCK's forces, else SLIDE_ROCK toward -sgn F if its N > 0, else
    FLIGHT (sigma 0)."""
    theta_dd = rock_acceleration(s, theta, ax, ge, R, alpha, math)
    force, normal = rock_contact_force(s, theta, rate, theta_dd, ax, ge, R, alpha, math)
    if normal >= 0 and abs(force) <= mu_s * normal:
        return ROCK, 0
    sigma = -_sign(force)
    if sigma != 0 and slide_rock_acceleration(s, sigma, theta, rate, ax, ge, R, alpha, mu_k, math)[1] > 0:
        return SLIDE_ROCK, sigma
    return FLIGHT, 0


# ---- impacts ---------------------------------------------------------------------------
def corner_impact(c, theta, x_rate, z_rate, theta_rate, b, h, mu_s, mu_k):
    """The plastic impact of corner ``c`` (v_cz -> 0) with friction, the other corner
    releasing: (x'+, z'+ [m/s], theta'+ [rad/s], sticks, P_t, P_n [m/s]).

    Sticking (v_cx+ = 0) is tried first and kept if |P_t| <= mu_s P_n; otherwise the
    corner slides through the impact with P_t = tau P_n, tau = sgn(P_t of sticking) mu_k
    (needs mu_k < 4/3, as D > 0 does)."""
    jump = impact_jump(c, True, theta, x_rate, z_rate, theta_rate, b, h, mu_k, xp_scalar)
    sticks = abs(jump[3]) <= mu_s * jump[4]
    if not sticks:
        jump = impact_jump(c, False, theta, x_rate, z_rate, theta_rate, b, h, mu_k, xp_scalar)
    return (*jump[:3], sticks, *jump[3:])


def impact_jump(c, sticks, theta, x_rate, z_rate, theta_rate, b, h, mu_k, xp):
    """The jump of corner ``c``'s plastic impact on the branch given (``sticks``: v_cx+ = 0;
    else slipping through with P_t = sgn(P_t of sticking) mu_k P_n): (x'+, z'+ [m/s],
    theta'+ [rad/s], P_t, P_n [m/s]); xp-generic (the JAX twin differentiates it)."""
    r_cx, r_cz, _, v_cx, v_cz = corner_state(c, 0.0, theta, x_rate, z_rate, theta_rate, b, h, xp)
    k = 3.0 / (b * b + h * h)
    w11, w12, w22 = 1.0 + k * r_cz * r_cz, -k * r_cx * r_cz, 1.0 + k * r_cx * r_cx
    det = w11 * w22 - w12 * w12
    p_t = (-w22 * v_cx + w12 * v_cz) / det
    p_n = (w12 * v_cx - w11 * v_cz) / det
    if not sticks:
        tau = xp.sign(p_t) * mu_k
        p_n = -v_cz / (w12 * tau + w22)
        p_t = tau * p_n
    return x_rate + p_t, z_rate + p_n, theta_rate + k * (r_cz * p_t - r_cx * p_n), p_t, p_n


def flat_landing(x_rate, z_rate, mu_s, mu_k):
    """The whole face lands (z' -> 0, theta' -> 0): (x'+ [m/s], sticks, P_t, P_n [m/s]) with
    P_n = -z'; the face sticks (x'+ = 0) if |x'| <= mu_s P_n, else slides on with
    x'+ = x' - sgn(x') mu_k P_n."""
    p_n = -z_rate
    if abs(x_rate) <= mu_s * p_n:
        return 0.0, True, -x_rate, p_n
    p_t = -_sign(x_rate) * mu_k * p_n
    return x_rate + p_t, False, p_t, p_n


def lands_flat(c, theta, z_rate, theta_rate, b, h):
    """Whether the impact of corner ``c`` that left (z'+, theta'+) [m/s, rad/s] is a flat
    landing: the block is level (theta = 0) and theta'+ = 0 or the other corner would
    move down (v_{-c,z}+ < 0)."""
    if theta != 0:
        return False
    return theta_rate == 0 or corner_state(-c, 0.0, theta, 0.0, z_rate, theta_rate, b, h, math)[4] < 0


def landing(theta, x_rate, z_rate, theta_rate, b, h, mu_s, mu_k):
    """A block in flight reaching the base: (c, x'+, z'+, theta'+, sticks, P_t, P_n), c the
    corner struck (0: a flat landing, :func:`flat_landing`, z'+ = theta'+ = 0).

    theta != 0: the lowest corner c = sgn(theta) strikes. Level with theta' != 0: the corner
    that falls faster, c = sgn(theta'). Level and not turning: the leading corner
    c = sgn(x') is tried, then the other; the first single-corner impact that turns the block
    onto that corner (c theta'+ > 0) without driving the other one down is kept."""
    if theta != 0 or theta_rate != 0:
        c = _sign(theta) if theta != 0 else _sign(theta_rate)
        after = corner_impact(c, theta, x_rate, z_rate, theta_rate, b, h, mu_s, mu_k)
        if not lands_flat(c, theta, after[1], after[2], b, h):
            return (c,) + after
    else:
        lead = _sign(x_rate) if x_rate != 0 else 1
        for c in (lead, -lead):
            after = corner_impact(c, theta, x_rate, z_rate, theta_rate, b, h, mu_s, mu_k)
            if c * after[2] > 0 and corner_state(-c, 0.0, theta, 0.0, after[1], after[2], b, h, math)[4] >= 0:
                return (c,) + after
    x_after, sticks, p_t, p_n = flat_landing(x_rate, z_rate, mu_s, mu_k)
    return 0, x_after, 0.0, 0.0, sticks, p_t, p_n


def mode_after_impact(c, theta, x_rate, z_rate, theta_rate, sticks, ax, ge, b, h, mu_s, mu_k):
    """(kind, s, sigma) after a single-corner impact of corner ``c`` that is not a flat
    landing (:func:`lands_flat`), from the rates after it and ``sticks``
    (:func:`corner_impact`): a corner still slipping goes on slide-rocking toward
    sgn(v_cx+) (FLIGHT, s = sigma = 0, where its N < 0); one at rest relative to the base
    takes :func:`pivot_mode` (ROCK with sigma = 0, SLIDE_ROCK, or FLIGHT)."""
    R, alpha = math.sqrt(b * b + h * h), math.atan2(b, h)
    slip = 0.0 if sticks else corner_state(c, 0.0, theta, x_rate, z_rate, theta_rate, b, h, math)[3]
    if slip == 0:
        kind, sigma = pivot_mode(c, theta, theta_rate, ax, ge, R, alpha, mu_s, mu_k)
    else:
        sigma = _sign(slip)
        normal = slide_rock_acceleration(c, sigma, theta, theta_rate, ax, ge, R, alpha, mu_k, math)[1]
        kind = SLIDE_ROCK if normal >= 0 else FLIGHT
    if kind == FLIGHT:
        return FLIGHT, 0, 0
    return kind, c, sigma


# ---- energy (section 9) ----------------------------------------------------------------
def kinetic_energy(x_rate, z_rate, theta_rate, R):
    """½ (x'² + z'²) + (R²/6) theta'² [J/kg]."""
    return 0.5 * (x_rate * x_rate + z_rate * z_rate) + R * R / 6.0 * theta_rate * theta_rate


def energy(x_rate, z_rate, theta_rate, z, R, g):
    """E = kinetic + g z [J/kg], relative to the base, ``g`` [m/s²] (not g_e)."""
    return kinetic_energy(x_rate, z_rate, theta_rate, R) + g * z


def base_power(ax, az, x_rate, z_rate):
    """The power of the base's inertial force [W/kg]: -a_x x' - a_z z'."""
    return -ax * x_rate - az * z_rate


def friction_power(force, slip_rate):
    """The power of friction [W/kg] (<= 0): F u', u' the slip velocity [m/s] (x' sliding,
    the pivot's u' slide-rocking)."""
    return force * slip_rate
