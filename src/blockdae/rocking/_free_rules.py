"""The complete free-standing block's flow and guards in its state layout, written once for
:class:`FreeStandingBlock` (floats, NumPy, JAX) and its compiled engine (numba, with
:mod:`blockdae.solvers.xp_scalar` for ``xp``), on the laws of :mod:`._slide_rock_laws`.

``mode`` is a :class:`FreeMode` value as an int (its sign the side); ``y`` the state (x,
z, theta, x', z', theta', base work, friction work) [m, m, rad, m/s, m/s, rad/s, J/kg,
J/kg] (a slide-rock's x, x' its pivot's u, u'; a flight's x, z and rates its reference
corner's); a_x and g_e = g + a_z [m/s²] at the time; b, h [m] the half-width and
half-height, R [m] and alpha [rad] from them (computed by the caller, as a JAX trace needs).
"""

import math

from . import _rules as rules
from . import _slide_rock_laws as laws

X, Z, THETA, X_RATE, Z_RATE, THETA_RATE, BASE_WORK, FRICTION_WORK = range(8)
#: guards of each mode kind (|mode|): rest, slide, rock out/in/beyond, settle, overturned,
#: slide-rock (2), flight, and the instant modes (10-13)
GUARD_COUNTS = (3, 2, 4, 4, 4, 4, 1, 5, 5, 3, 1, 1, 1, 1)


def _side(mode):
    return 1 if mode > 0 else -1


def flow_values(mode, y, ax, ge, g, b, h, R, alpha, mu_k, xp):
    """dy/dt in ``mode`` (8 values; zero at rest, overturned and in the instant modes);
    ``g`` [m/s²] the gravity of the work of a_z = g_e - g, ``mu_k`` kinetic friction [-]."""
    kind, s = abs(mode), _side(mode)
    zero = 0.0 * y[X]
    power = laws.base_power(ax, ge - g, y[X_RATE], y[Z_RATE])
    if kind == 1:
        x_accel = laws.slide_acceleration(s, ax, ge, mu_k)
        friction = laws.friction_power(-s * mu_k * ge, y[X_RATE])
        return y[X_RATE], zero, zero, zero + x_accel, zero, zero, power, zero + friction
    if 2 <= kind <= 4 or kind == 7 or kind == 8:
        phi = s * alpha - y[THETA]
        if kind <= 4:
            accel = laws.rock_acceleration(s, y[THETA], ax, ge, R, alpha, xp)
            x_accel = R * (xp.cos(phi) * accel + xp.sin(phi) * y[THETA_RATE] ** 2)
            friction = zero
        else:  # the state's x, x' are the pivot's u, u' (the slip)
            sigma = s if kind == 7 else -s
            _, normal, accel, x_accel = laws.slide_rock_acceleration(s, sigma, y[THETA], y[THETA_RATE], ax, ge, R,
                                                                     alpha, mu_k, xp)
            friction = laws.friction_power(-sigma * mu_k * normal, y[X_RATE])
            centroid_rate = y[X_RATE] + R * xp.cos(phi) * y[THETA_RATE]
            power = laws.base_power(ax, ge - g, centroid_rate, y[Z_RATE])
        z_accel = R * (xp.sin(phi) * accel - xp.cos(phi) * y[THETA_RATE] ** 2)
        return y[X_RATE], y[Z_RATE], y[THETA_RATE], x_accel, z_accel, accel, power, zero + friction
    if kind == 9:  # the state's position is corner s's: x_c'' = -a_x - r_cx theta'², z_c'' = -g_e - r_cz theta'²
        r_cx, r_cz = laws.corner_offset(s, y[THETA], b, h, xp)
        rate = y[THETA_RATE]
        power = laws.base_power(ax, ge - g, y[X_RATE] - r_cz * rate, y[Z_RATE] + r_cx * rate)
        return y[X_RATE], y[Z_RATE], rate, -ax - r_cx * rate**2, -ge - r_cz * rate**2, zero, power, zero
    if kind == 5:
        r = 1.0 - 1.5 * xp.sin(alpha) ** 2
        ahead, behind = restoring_decelerations(s, ax, ge, R, alpha, xp)
        return zero, zero, zero, zero, zero, zero + rules.settle_rate(s, ahead, behind, r), zero, zero
    return zero, zero, zero, zero, zero, zero, zero, zero


def pivot_state(s, y, theta, rate, R, alpha, xp):
    """``y`` on the sticking pivot ``s`` (kept where it is) at (theta [rad], theta' [rad/s]):
    the centroid's x, z and rates from the rotation alone (8 values)."""
    u = y[X] + R * xp.sin(s * alpha - y[THETA])
    phi = s * alpha - theta
    return (u - R * xp.sin(phi), R * xp.cos(phi), theta, R * xp.cos(phi) * rate, R * xp.sin(phi) * rate, rate,
            y[BASE_WORK], y[FRICTION_WORK])


def restoring_decelerations(c, ax, ge, R, alpha, xp):
    """The decelerations [rad/s²] at theta = 0 of rocking on corner ``c`` (ahead) and on
    the other corner (behind): both positive where gravity brings the block back."""
    return (-c * laws.rock_acceleration(c, 0.0, ax, ge, R, alpha, xp),
            c * laws.rock_acceleration(-c, 0.0, ax, ge, R, alpha, xp))


def settles(c, rate, ax, ge, R, alpha, zeno_arc, xp):
    """Whether the arc on corner ``c`` that a sticking impact starts with theta' = ``rate``
    [rad/s] is shorter than ``zeno_arc`` [s] and both corners restore (their decelerations
    at theta = 0 positive): the Zeno tail is summed."""
    ahead, behind = restoring_decelerations(c, ax, ge, R, alpha, xp)
    return ahead > 0 and behind > 0 and 2 * abs(rate) / ahead < zeno_arc


def guard_values(mode, t, y, ax, ge, b, h, R, alpha, mu, mu_k, xp):
    """The guards of ``mode`` at ``t`` [s] (each left as it falls through zero), padded to
    five with +inf (:data:`GUARD_COUNTS` of them are the mode's): REST (limit - a_x,
    limit + a_x, g_e), limit = min(mu, b/h) g_e; SLIDE sigma (sigma x', g_e); ROCK s (its two
    own: :func:`._rules.rocking_guards`, N, mu N - |F|); SLIDE_ROCK (s, sigma) (s theta,
    pi/2 - s theta, N, sigma u', D); FLIGHT (the corners' heights, pi/2 - |theta|); SETTLE s
    (s theta', the two onsets, g_e); OVERTURNED (1); an instant mode -1 - t (left at once)."""
    kind, s = abs(mode), _side(mode)
    inf = math.inf
    one = 0.0 * y[X] + 1.0
    if mode == 0:
        limit = xp.minimum(mu, b / h) * ge
        return limit - ax, limit + ax, ge, inf, inf
    if kind == 1:
        return s * y[X_RATE], ge, inf, inf, inf
    if 2 <= kind <= 4:
        own, back = rules.rocking_guards(kind, s, y[THETA], y[THETA_RATE], alpha)
        accel = laws.rock_acceleration(s, y[THETA], ax, ge, R, alpha, xp)
        force, normal = laws.rock_contact_force(s, y[THETA], y[THETA_RATE], accel, ax, ge, R, alpha, xp)
        return own, back, normal, mu * normal - xp.abs(force), inf
    if kind == 7 or kind == 8:
        sigma = s if kind == 7 else -s
        denominator, normal, _, _ = laws.slide_rock_acceleration(s, sigma, y[THETA], y[THETA_RATE], ax, ge, R, alpha,
                                                                 mu_k, xp)
        return s * y[THETA], 0.5 * math.pi - s * y[THETA], normal, sigma * y[X_RATE], denominator
    if kind == 9:  # z_c' = z_c + (c - c') b sin theta from the reference corner c
        lift = b * xp.sin(y[THETA])
        return y[Z] + (s - 1) * lift, y[Z] + (s + 1) * lift, 0.5 * math.pi - xp.abs(y[THETA]), inf, inf
    if kind == 5:
        limit = b / h * ge
        return s * y[THETA_RATE], limit - ax, limit + ax, ge, inf
    if kind >= 10:
        return -one - t, inf, inf, inf, inf
    return one, inf, inf, inf, inf
