"""The linearised rocking block in closed form on a piecewise-linear record, compiled with
numba: the engine of ``backend="exact"``.

On a piece a_x(tau) = p0 + p1 tau [m/s², m/s³] the linearised block rocking about side s
obeys theta'' = p² theta - p² (s alpha + a_x / g), whose solution is

    theta(tau) = c(tau) + A cosh(p tau) + B sinh(p tau),    c = s alpha + a_x(tau) / g,

and every guard (alpha_g theta + beta_g theta' + gamma_g) is l0 + l1 tau + E e^{p tau} +
F e^{-p tau}: monotone between its inflection (E e^{p tau} = -F e^{-p tau}) and its
extrema (a quadratic in e^{p tau}), so each root is bracketed and bisected to adjacent
floats. The rules (onset from rest, apex, impact with r, the Zeno tail summed, alpha and
pi/2) are the model's (:class:`RockingBlock`); the Zeno envelope's rate -s / K(t) is
integrated by 8-point Gauss-Legendre quadrature and its end found by Newton's method.
"""

import functools
import math

import numba
import numpy as np
from numba.extending import register_jitable

#: mode values (RockingMode)
REST, OUT, IN, BEYOND, SETTLE, OVERTURNED, RELEASE = 0, 2, 3, 4, 5, 6, 7
#: columns of the knot log: t [s], theta [rad], theta' [rad/s], mode after, mode before, is an
#: event, theta'' in the mode after [rad/s²]
KNOT_COLUMNS = 7
#: the longest closed-form step [p tau]: e^{p tau} stays far from overflow
MAX_EXPONENT = 300.0
_GL_X = np.array([-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                  0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363])
_GL_W = np.array([0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                  0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763])


@register_jitable
def _guard_form(ag, bg, gg, s, alpha, p, g, q0, q1, theta, rate):
    """(l0, l1, E, F) of guard ag theta + bg theta' + gg from (theta, theta') under
    a_x = q0 + q1 tau on side ``s``."""
    c0, c1 = s * alpha + q0 / g, q1 / g
    a, b = theta - c0, (rate - c1) / p
    return (ag * c0 + bg * c1 + gg, ag * c1, 0.5 * (ag + bg * p) * (a + b), 0.5 * (ag - bg * p) * (a - b))


@register_jitable
def _motion(theta, rate, d, c1, p, tau):
    """(theta [rad], theta' [rad/s]) at ``tau`` [s] from (theta, theta') at 0, with d =
    theta - c(0) [rad] and c1 = c' [rad/s], written around the start so that a small
    rotation keeps its relative precision: theta + theta' S + d (cosh - 1) - c1 (S - tau),
    S = sinh(p tau) / p (S - tau by its series where p tau is small)."""
    x = p * tau
    sh, cm1 = math.sinh(x), 2.0 * math.sinh(0.5 * x) ** 2
    if abs(x) < 0.1:
        x2 = x * x
        excess = x * x2 / 6.0 * (1.0 + x2 / 20.0 * (1.0 + x2 / 42.0 * (1.0 + x2 / 72.0 * (1.0 + x2 / 110.0))))
    else:
        excess = sh - x
    return (theta + rate * sh / p + d * cm1 - c1 * excess / p,
            rate + rate * cm1 + d * p * sh - c1 * cm1)


@register_jitable
def _slope(f, p, tau):
    return f[1] + p * (f[2] * math.exp(p * tau) - f[3] * math.exp(-p * tau))


@register_jitable
def _curvature(f, p, tau):
    return p * p * (f[2] * math.exp(p * tau) + f[3] * math.exp(-p * tau))


@register_jitable
def _first_down(f, p, span, row, theta, rate, d, c1):
    """The first tau in [0, span) where the guard ``row`` = (ag, bg, gg) falls through zero
    (at 0 if it is at or below zero and falls there); nan if none. ``f``: its form (l0,
    l1, E, F), which splits [0, span) where it may turn; its values come from
    :func:`_motion` (theta, theta', d, c1 at tau = 0)."""
    g0 = _guard(row, theta, rate, d, c1, p, 0.0)
    if g0 <= 0:
        slope = _slope(f, p, 0.0)
        if slope < 0 or (slope == 0 and _curvature(f, p, 0.0) < 0):
            return 0.0
    cuts = np.empty(5)
    n = 0
    cuts[n] = 0.0
    n += 1
    if f[2] != 0 and -f[3] / f[2] > 0:  # inflection
        x = math.log(-f[3] / f[2]) / (2 * p)
        if 0 < x < span:
            cuts[n] = x
            n += 1
    qa, qb, qc = p * f[2], f[1], -p * f[3]  # extrema: qa X² + qb X + qc = 0, X = e^{p tau}
    if qa != 0:
        disc = qb * qb - 4 * qa * qc
        if disc >= 0:
            root = math.sqrt(disc)
            for big in ((-qb + root) / (2 * qa), (-qb - root) / (2 * qa)):
                if big > 0:
                    x = math.log(big) / p
                    if 0 < x < span:
                        cuts[n] = x
                        n += 1
    elif qb != 0 and -qc / qb > 0:
        x = math.log(-qc / qb) / p
        if 0 < x < span:
            cuts[n] = x
            n += 1
    cuts = np.sort(cuts[:n])
    for k in range(n):
        lo = cuts[k]
        hi = cuts[k + 1] if k + 1 < n else span
        g_lo, g_hi = _guard(row, theta, rate, d, c1, p, lo), _guard(row, theta, rate, d, c1, p, hi)
        if g_lo > 0 and g_hi <= 0:
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if _guard(row, theta, rate, d, c1, p, mid) > 0:
                    lo = mid
                else:
                    hi = mid
            return hi if hi < span else math.nan
    return math.nan


@register_jitable
def _guard(row, theta, rate, d, c1, p, tau):
    """The guard ag theta + bg theta' + gg at ``tau`` [s] (see :func:`_motion`)."""
    th, w = _motion(theta, rate, d, c1, p, tau)
    return row[0] * th + row[1] * w + row[2]


@register_jitable
def _accel(s, theta, a, alpha, p2, g):
    """theta'' [rad/s²] of the linearised block about side ``s`` at ``theta`` [rad] under
    a_x = ``a`` [m/s²]."""
    return -p2 * (s * alpha - theta + a / g)


@register_jitable
def _decel(s, a, alpha, p2, g):
    """-s theta'' at theta = 0 on side ``s`` [rad/s²] (the model's ``deceleration``)."""
    return -s * _accel(s, 0.0, a, alpha, p2, g)


@register_jitable
def _envelope_rate(s, q, alpha, p2, g, r):
    """1 / K [rad/s²] of the Zeno envelope on side ``s`` under a_x = ``q`` (the model's
    ``_settle_rate`` magnitude)."""
    d_s, d_o = _decel(s, q, alpha, p2, g), _decel(-s, q, alpha, p2, g)
    return (1 - r * r) / (2.0 * (1.0 / d_s + r / d_o))


@register_jitable
def _envelope_integral(s, q0, q1, alpha, p2, g, r, x):
    """The integral of 1 / K over [0, x] [rad/s] (Gauss-Legendre, 8 points)."""
    total = 0.0
    for k in range(8):
        tau = 0.5 * x * (_GL_X[k] + 1.0)
        total += _GL_W[k] * _envelope_rate(s, q0 + q1 * tau, alpha, p2, g, r)
    return 0.5 * x * total


@register_jitable
def _log(log, n, t, theta, rate, mode, before, is_event, a, alpha, p2, g, r):
    """Log a knot; theta'' [rad/s²] in ``mode`` under a_x = ``a`` [m/s²]."""
    if n < log.shape[0]:
        kind, s = abs(mode), (1 if mode > 0 else -1)
        accel = 0.0
        if kind in (OUT, IN, BEYOND):
            accel = _accel(s, theta, a, alpha, p2, g)
        elif kind == SETTLE:
            accel = -s * _envelope_rate(s, a, alpha, p2, g, r)
        log[n, 0], log[n, 1], log[n, 2] = t, theta, rate
        log[n, 3], log[n, 4], log[n, 5], log[n, 6] = mode, before, is_event, accel
    return n + 1


def _run(t0, h, p0, p1, alpha, p, g, r, zeno_arc, theta0, log):
    """One run over the pieces (t0 [s], h [s], p0 [m/s²], p1 [m/s³]) (the last may be
    the rest-seeking tail, h = inf); returns the number of knot rows (more than the
    log holds: it was full)."""
    p2 = p * p
    limit = g * alpha  # |a_x| that lifts a corner of the linearised block [m/s²]
    mode, theta, rate, n = REST, 0.0, 0.0, 0
    if theta0 != 0:
        s = 1 if theta0 > 0 else -1
        theta = theta0
        n = _log(log, n, 0.0, 0.0, 0.0, RELEASE, RELEASE, 0.0, p0[0], alpha, p2, g, r)
        accel = _accel(s, theta, p0[0], alpha, p2, g)
        if s * accel <= 0:
            mode = IN * s
        else:
            mode = (OUT if s * theta < alpha else BEYOND) * s
        n = _log(log, n, 0.0, theta, rate, mode, RELEASE, 1.0, p0[0], alpha, p2, g, r)
    else:
        n = _log(log, n, 0.0, 0.0, 0.0, REST, REST, 0.0, p0[0], alpha, p2, g, r)
    for i in range(t0.shape[0]):
        length, tau = h[i], 0.0
        while True:
            q0 = p0[i] + p1[i] * tau
            q1 = p1[i]
            span = length - tau
            kind = abs(mode)
            s = 1 if mode > 0 else -1
            if kind == OVERTURNED:
                break
            if mode == REST:  # onset: a_x = -limit falling (rock +) or +limit rising (rock -)
                start = 0
                if q0 < -limit or (q0 == -limit and q1 < 0):
                    start = 1
                elif q0 > limit or (q0 == limit and q1 > 0):
                    start = -1
                if start == 0:
                    best = math.inf
                    if q1 < 0 and q0 > -limit:
                        best = (-limit - q0) / q1
                        start = 1
                    if q1 > 0 and q0 < limit:
                        x = (limit - q0) / q1
                        if x < best:
                            best, start = x, -1
                    if not best < span:
                        if t0[i] + length == math.inf:
                            return n
                        break
                    tau += best
                mode = OUT * start
                n = _log(log, n, t0[i] + tau, 0.0, 0.0, mode, REST, 1.0, p0[i] + p1[i] * tau, alpha, p2, g, r)
                continue
            if kind == SETTLE:
                w = abs(rate)
                onset = math.inf
                if q1 < 0 and q0 > -limit:
                    onset = (-limit - q0) / q1
                if q1 > 0 and q0 < limit:
                    onset = min(onset, (limit - q0) / q1)
                horizon = min(span, onset)
                if _envelope_integral(s, q0, q1, alpha, p2, g, r, min(horizon, 1e6)) >= w:
                    x = w / _envelope_rate(s, q0, alpha, p2, g, r)
                    for _ in range(20):
                        step = (_envelope_integral(s, q0, q1, alpha, p2, g, r, x) - w) / _envelope_rate(
                            s, q0 + q1 * x, alpha, p2, g, r)
                        x -= step
                        if abs(step) <= 1e-16 * x:
                            break
                    tau += x
                    n = _log(log, n, t0[i] + tau, 0.0, 0.0, mode, mode, 0.0, p0[i] + p1[i] * tau, alpha, p2, g, r)
                    mode, theta, rate = REST, 0.0, 0.0
                    n = _log(log, n, t0[i] + tau, 0.0, 0.0, REST, SETTLE * s, 1.0, p0[i] + p1[i] * tau, alpha, p2, g, r)
                    continue
                if onset < span:
                    tau += onset
                    before = mode
                    mode, theta, rate = (OUT if q1 < 0 else -OUT), 0.0, 0.0
                    n = _log(log, n, t0[i] + tau, 0.0, 0.0, mode, before, 1.0, p0[i] + p1[i] * tau, alpha, p2, g, r)
                    continue
                rate -= s * _envelope_integral(s, q0, q1, alpha, p2, g, r, span)
                break
            # rocking: the guards of the mode as (ag, bg, gg)
            if kind == OUT:
                rows = ((0.0, s * 1.0, 0.0), (-s * 1.0, 0.0, alpha))
            elif kind == IN:
                rows = ((s * 1.0, 0.0, 0.0), (0.0, -s * 1.0, 0.0))
            else:
                rows = ((0.0, s * 1.0, 0.0), (-s * 1.0, 0.0, 0.5 * math.pi))
            reach = min(span, MAX_EXPONENT / p)  # e^{p tau} stays finite
            c0, c1 = s * alpha + q0 / g, q1 / g
            best, index = math.inf, -1
            for j in range(2):
                f = _guard_form(rows[j][0], rows[j][1], rows[j][2], s, alpha, p, g, q0, q1, theta, rate)
                x = _first_down(f, p, reach, rows[j], theta, rate, theta - c0, c1)
                if x < best:
                    best, index = x, j
            x = reach if index < 0 else best
            theta, rate = _motion(theta, rate, theta - c0, c1, p, x)
            if index < 0:
                if reach < span:
                    tau += reach
                    continue
                break
            tau += x
            t = t0[i] + tau
            before = mode
            if kind == OUT and index == 0 or kind == BEYOND and index == 0:
                rate = 0.0
                if kind == OUT and theta == 0:
                    mode = REST
                else:
                    mode = IN * s
            elif kind == OUT:
                theta, mode = s * alpha, BEYOND * s
            elif kind == BEYOND:
                theta, mode = s * 0.5 * math.pi, OVERTURNED * s
            elif index == 1:  # IN, turning outward again
                rate = 0.0
                mode = (OUT if s * theta < alpha else BEYOND) * s
            else:  # IN: impact
                theta = 0.0
                w = r * rate
                a = q0 + q1 * x
                d_new, d_old = _decel(-s, a, alpha, p2, g), _decel(s, a, alpha, p2, g)
                if w == 0:
                    mode = REST
                elif d_new > 0 and d_old > 0 and 2 * abs(w) / d_new < zeno_arc:
                    mode = -SETTLE * s
                else:
                    mode = -OUT * s
            n = _log(log, n, t, theta, rate, before, before, 0.0, p0[i] + p1[i] * tau, alpha, p2, g, r)
            if abs(before) == IN and index == 0:
                rate = r * rate
            if abs(mode) == OVERTURNED:
                rate = 0.0
            n = _log(log, n, t, theta, rate, mode, before, 1.0, p0[i] + p1[i] * tau, alpha, p2, g, r)
        end = h[i] if h[i] < math.inf else tau
        n = _log(log, n, t0[i] + end, theta, rate, mode, mode, 0.0, p0[i] + p1[i] * end, alpha, p2, g, r)
    return n


@functools.cache
def kernel():
    """The compiled run (numba, cached on disk)."""
    return numba.njit(cache=True, error_model="numpy")(_run)
