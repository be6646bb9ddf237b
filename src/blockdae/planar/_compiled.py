"""The compiled planar engine: the hybrid driver's loop for a block on a plane on a rigid
support (:class:`~blockdae.PlanarBlock`), compiled with numba.

Per mode:

* stick: the state is constant (the block moves with the base); the guards
  (n = g + a_z, mu n - |sigma|) are functions of time alone, located by bisection to
  adjacent floats on the parts where they are monotone (split where the model's turn
  rate changes sign), as :meth:`blockdae.core._driver._Run.static_root` does; a piece
  with linear a(t) and both guards positive at both ends has none (:func:`_quiet_stick`);
* flight: a ballistic arc in closed form (the integrals of a(t) on the piece:
  cubics under a linear piece); the landing (w = 0 falling) is bracketed on the
  monotone parts of w (w'' = -n is monotone on a piece, so w' has at most one
  extremum) and located by bisection to adjacent floats;
* slip: DOP853 (:mod:`blockdae.solvers.dop853`), Dormand and Prince's explicit 8th-order pair with its
  7th-order dense output, where its step is stable; else RODAS (:mod:`blockdae.solvers.rodas4`), a
  linearly implicit (Rosenbrock) method of order 4 with the flow's exact derivatives
  (:func:`_slip_derivatives`). The flow is stiff only in the direction's relaxation at
  |sigma| / max(s, SLOW_SPEED) [1/s] near a slide's start and end, where DOP853's step
  would be bounded by stability (:data:`STABLE_PRODUCT`); RODAS takes over while its own
  steps are longer. 8th order elsewhere, because rtol 1e-12 on a smooth flow then takes
  one or two steps per sample of a record. The error is measured on the vectors whatever
  the axes (:func:`_error_scale`): u by |u|, the direction by the velocity error s |dc|
  it makes. A stop (s = 0 falling) is bracketed by the step (s > 0 -> s <= 0, or a dip
  below zero between a falling and a rising end, found at the minimum of the dense s),
  located by bisection on the step's dense output to adjacent floats, then confirmed on
  the flow (a step of the same method from the step's start to the located time and to
  the float before it; else bisection on that step). A liftoff (n reaching 0) is a time
  alone.

The model's rules (flows, guards, which mode follows a guard, what a mode starts with)
are :mod:`._rules`, which :class:`~blockdae.PlanarBlock` calls too; this module only
evaluates the forces they take from the piece's coefficients. The driver's event rules
(the graze rule, bisections, turning points, a static mode's first root, the stop's
uncertainty from the tolerances) are :mod:`blockdae.core.events`, which the driver
calls too; its loop (events at the end of a piece left to the next, chatter, the tail
to rest) is restated here on floats. The knots (piece ends, events, 1 / (32 w) apart on
sine pieces) are the driver's, so the dense output is its cubic Hermite one.

State (8,): the model's (u_x, u_y, s, c_x, c_y, w, w') and the slide's path length
[m] (the integral of s while sliding).
"""

import functools
import hashlib
import inspect
import math
import pathlib
import sys

import numba
import numpy as np
from numba.extending import register_jitable

from ..core.contract import KNOTS_PER_RADIAN
from ..excitation import accel, accel_int1, accel_int2, accel_rate, monotone_rate, pieces as _pieces, rebase
from ..solvers import dop853 as _dop853, rodas4 as _rodas4, xp_scalar as xp
from ..core import events as events
from . import _rules as rules
from ._rules import FLIGHT, SLIP, SLOW_SPEED, STICK

_UX, _UY, _S, _CX, _CY, _W, _WD, _PATH = range(8)
N_STATE = 8
_EPS = float(np.finfo(float).eps)
#: entries of ``params``: mu, f [-], bias (x, y) [-], g [m/s²], restitution [-],
#: bounce threshold [m/s], factor on a(t) [-]
PARAM_FIELDS = ("mu", "mu_kinetic", "bias_x", "bias_y", "g", "restitution", "bounce_threshold", "scale")
#: entries of ``options``: rtol [-], atol [m, m/s], event resolution [s], most events at
#: one instant [-], until rest (1) or not (0)
OPTION_FIELDS = ("rtol", "atol", "event_resolution", "max_events_at_one_instant", "until_rest")
#: entries of a run's outcome
OUTCOME_FIELDS = ("u_x", "u_y", "max_abs_u", "slide_distance", "n_events", "n_flights", "t_final", "mode",
                  "status", "max_events_at_one_instant", "steps", "rejected_steps", "rhs_calls")
#: outcome ``status``: finished; chatter; the state contradicts its mode; a step below
#: rounding; no rest within the model's bound; f <= |bias| (never rests)
FINISHED, CHATTER, INCONSISTENT, STEP_TOO_SMALL, NO_REST, NEVER_RESTS = range(6)


# ---- the piece's excitation: pe = (t0 [s], h [s], P (3, 5) scaled (p0, p1, s, w, phi), directions (3,))
def _a_local(P, i, tau):
    """Component ``i`` at the piece's local time ``tau`` [s] (coefficients ``P``)."""
    if P[i, 2] == 0:  # a linear piece: no sine to evaluate
        return accel(P[i, 0], P[i, 1], None, None, None, tau, xp)
    return accel(P[i, 0], P[i, 1], P[i, 2], P[i, 3], P[i, 4], tau, xp)


def _a_rate(pe, i, t):
    """Its rate [m/s³], rounding against the piece's direction projected out (as the
    driver's decisions see it)."""
    return monotone_rate(_raw_rate(pe, i, t), pe[3][i], xp)


def _raw_rate(pe, i, t):
    """Component ``i``'s rate at ``t`` [m/s³] as is."""
    P = pe[2]
    if P[i, 2] == 0:  # a linear piece: no cosine to evaluate
        return accel_rate(P[i, 0], P[i, 1], None, None, None, min(t - pe[0], pe[1]), xp)
    return accel_rate(P[i, 0], P[i, 1], P[i, 2], P[i, 3], P[i, 4], min(t - pe[0], pe[1]), xp)


def _forces(pe, p, t):
    """(n, sigma_x, sigma_y) [m/s²] at ``t`` on a rigid support, without their rates (the
    piece's local time computed once)."""
    P, tau = pe[2], min(t - pe[0], pe[1])
    sx, sy = rules.demand(_a_local(P, 0, tau), _a_local(P, 1, tau), p[2], p[3], p[4])
    return rules.rigid_normal(p[4], _a_local(P, 2, tau)), sx, sy


def _forces_and_rates(pe, p, t):
    """(n, n', sigma_x, sigma_y, sigma_x', sigma_y') [m/s², m/s³] at ``t``, as the rules
    take them (the rates as the driver's decisions see them)."""
    n, sx, sy = _forces(pe, p, t)
    return n, _a_rate(pe, 2, t), sx, sy, _a_rate(pe, 0, t), _a_rate(pe, 1, t)


def _mode_at_rest(pe, p, t):
    """:func:`~blockdae.planar._rules.mode_at_rest` at ``t``."""
    return rules.mode_at_rest(p[0], *_forces_and_rates(pe, p, t))


def _mode_after_guard(mode, index, t, y, pe, p, time_tol):
    """:func:`~blockdae.planar._rules.mode_after_guard` at ``t`` (rigid support)."""
    n, n_rate, sx, sy, rx, ry = _forces_and_rates(pe, p, t)
    return rules.mode_after_guard(mode, index, t, y, p[0], n, n_rate, sx, sy, rx, ry, p[5], p[6], True, time_tol)


def _state_on_entry(before, after, t, y, pe, p):
    """:func:`~blockdae.planar._rules.state_on_entry` (rigid support); the path length is
    kept."""
    _, _, sx, sy, rx, ry = _forces_and_rates(pe, p, t)
    entry = rules.state_on_entry(before, after, y, sx, sy, rx, ry, p[5], True, xp)
    z = y.copy()
    for i in range(N_STATE - 1):
        z[i] = entry[i]
    return z


def _flow(mode, t, y, pe, p):
    """dy/dt (:func:`~blockdae.planar._rules.flow`, rigid support) and the path's rate s
    in slip."""
    out = np.zeros(N_STATE)
    _flow_into(mode, t, y, pe, p, out)
    return out


def _flow_into(mode, t, y, pe, p, out):
    """:func:`_flow` into ``out`` (N_STATE,)."""
    n, sx, sy = _forces(pe, p, t)
    rates = rules.flow(mode, y, -sx, -sy, p[1] * n, -n, xp)
    for i in range(N_STATE - 1):
        out[i] = rates[i]
    out[_PATH] = y[_S] if mode == SLIP else 0.0


def _slip_rhs(t, y, args, out):
    """The slip flow as the steps' right-hand side (``args``: (pe, p)): :func:`_flow_into`
    in slip."""
    pe, p = args
    n, sx, sy = _forces(pe, p, t)
    u_x, u_y, s, c_x, c_y = rules.slip_flow(y, -sx, -sy, p[1] * n, xp)
    out[_UX], out[_UY], out[_S], out[_CX], out[_CY], out[_PATH] = u_x, u_y, s, c_x, c_y, y[_S]
    out[_W], out[_WD] = 0.0, 0.0


def _guards(mode, t, y, pe, p):
    """(guard 0, guard 1) [m/s², m/s or m] (:func:`~blockdae.planar._rules.guards`;
    flight has one: the second is +inf)."""
    n, sx, sy = _forces(pe, p, t)
    return rules.guards(mode, y, n, sx, sy, p[0], 1.0, xp)


def _guard_rates(mode, index, t, y, pe, p):
    """(rate, curvature) of guard ``index`` (:func:`~blockdae.planar._rules.guard_rates`)."""
    n, n_rate, sx, sy, rx, ry = _forces_and_rates(pe, p, t)
    return rules.guard_rates(mode, index, y, p[0], p[1], n, n_rate, sx, sy, rx, ry, 1.0, xp)


def _turn_rate(mode, t, y, pe, p):
    """(value, defined) (:func:`~blockdae.planar._rules.turn_rate`)."""
    n, n_rate, sx, sy, rx, ry = _forces_and_rates(pe, p, t)
    return rules.turn_rate(mode, y, p[0], p[1], n, n_rate, sx, sy, rx, ry, xp)


# ---- root finding in time --------------------------------------------------------
_guard_values, _guard_value = events.of_time(_guards)


def _turning_point(mode, t, y, end, pe, p):
    """The driver's ``turning_point`` (:func:`blockdae.core.events.turning_point`):
    where the turn rate changes sign in (t, end), else nan; none in flight, where the
    rate is y's w', constant in t."""
    if mode == FLIGHT:
        return math.nan
    return events.turning_point(_turn_value, (mode, y, pe, p), t, end)


def _turn_value(args, t):
    """:func:`_turn_rate` at ``t`` (args: (mode, y, pe, p))."""
    mode, y, pe, p = args
    return _turn_rate(mode, t, y, pe, p)


def _is_linear(pe):
    """Whether a(t) is linear on the piece (no sine in any component)."""
    P = pe[2]
    return P[0, 2] == 0 and P[1, 2] == 0 and P[2, 2] == 0


def _next_turn(mode, t, y, end, pe, p):
    """:func:`_turning_point` where the loop reads it: in slip and flight (stick finds
    its own in :func:`_static_root`)."""
    return math.nan if mode == STICK else _turning_point(mode, t, y, end, pe, p)


def _quiet_stick(pe, p, t, end, y):
    """Whether stick certainly lasts from ``t`` to ``end`` [s]: a(t) is linear on the
    piece, so n is linear and mu n - |sigma| concave (|sigma| is the norm of a linear
    function), and both guards are positive at both ends (no root between, and the
    turning point is not needed)."""
    if not _is_linear(pe):
        return False
    g0, g1 = _guards(STICK, t, y, pe, p)
    e0, e1 = _guards(STICK, end, y, pe, p)
    return g0 > 0 and g1 > 0 and e0 > 0 and e1 > 0


def _static_root(t, y, end, pe, p):
    """The driver's ``static_root`` in stick (:func:`blockdae.core.events.static_root`):
    (time, guard) or (nan, -1)."""
    if _quiet_stick(pe, p, t, end, y):
        return math.nan, -1
    turn = _turning_point(STICK, t, y, end, pe, p)
    return events.static_root(_guard_values, _guard_value, (STICK, y, pe, p), t, turn, end)


def _time_function(fa, t):
    """Functions of time the engine locates roots of: fa = (kind, t_from, y, pe, p):
    kind 0: n; 1: the flight's w; 2: the flight's w'; 3: -n (w'')."""
    kind, t_from, y, pe, p = fa
    if kind == 0:
        return _forces(pe, p, t)[0]
    if kind == 3:
        return -_forces(pe, p, t)[0]
    z = _flight_state(t_from, y, t, pe, p)
    return z[_W] if kind == 1 else z[_WD]


def _liftoff_time(t, stop, y, pe, p):
    """The first float in (t, stop) where n <= 0, n > 0 at t (monotone on the piece),
    else nan (a root at ``stop`` is no root: the piece's end is left to the next)."""
    fa = (0, t, y, pe, p)  # n depends on time alone: y is not read
    if _time_function(fa, t) > 0 and _time_function(fa, stop) <= 0:
        root = events.first_nonpositive(_time_function, fa, t, stop)
        return root if root < stop else math.nan
    return math.nan


# ---- flight in closed form ------------------------------------------------------------
def _flight_state(t_from, y, t, pe, p):
    """The state at ``t`` [s] of a flight from (``t_from``, ``y``) on the piece ``pe``:
    v' = -sigma, w'' = -(g + a_z), integrated in closed form."""
    P = pe[2]
    tau = min(t_from - pe[0], pe[1])
    d = t - t_from
    g = p[4]
    z = y.copy()
    i1 = np.empty(3)
    i2 = np.empty(3)
    for i in range(3):
        p0, p1, s, w, phi = rebase(P[i, 0], P[i, 1], P[i, 2], P[i, 3], P[i, 4], tau)
        i1[i] = accel_int1(p0, p1, s, w, phi, d, xp)
        i2[i] = accel_int2(p0, p1, s, w, phi, d, xp)
    for i, (cu, cv) in enumerate(((_UX, _CX), (_UY, _CY))):
        bg = p[2 + i] * g
        z[cu] = y[cu] + y[cv] * d - i2[i] + 0.5 * bg * d * d
        z[cv] = y[cv] - i1[i] + bg * d
    z[_W] = y[_W] + y[_WD] * d - 0.5 * g * d * d - i2[2]
    z[_WD] = y[_WD] - g * d - i1[2]
    return z


def _flight_to(t, y, stop, pe, p):
    """Fly from (t, y) to ``stop`` [s] or to the landing before it: (time, state,
    landed). w'' = -n is monotone on a piece: w' is split at its extremum (n = 0) and w
    at the roots of w'; on each part where w is monotone a fall from > 0 to <= 0 is a
    landing, located to adjacent floats."""
    knots = np.empty(4)
    knots[0] = t
    m = 1
    fa_n = (3, t, y, pe, p)
    na, nb = _time_function(fa_n, t), _time_function(fa_n, stop)
    if (na > 0) != (nb > 0) and na != 0 and nb != 0:
        knots[m] = events.sign_change(_time_function, fa_n, t, stop)
        m += 1
    knots[m] = stop
    m += 1
    parts = np.empty(6)
    k = 0
    fa_v = (2, t, y, pe, p)
    for j in range(m - 1):
        a, b = knots[j], knots[j + 1]
        parts[k] = a
        k += 1
        va, vb = _time_function(fa_v, a), _time_function(fa_v, b)
        if (va > 0 and vb < 0) or (va < 0 and vb > 0):
            parts[k] = events.sign_change(_time_function, fa_v, a, b)
            k += 1
    parts[k] = stop
    k += 1
    fa_w = (1, t, y, pe, p)
    for j in range(k - 1):
        a, b = parts[j], parts[j + 1]
        if a < b and _time_function(fa_w, a) > 0 and _time_function(fa_w, b) <= 0:
            root = events.first_nonpositive(_time_function, fa_w, a, b)
            return root, _flight_state(t, y, root, pe, p), True
    return stop, _flight_state(t, y, stop, pe, p), False


# ---- slip: DOP853, RODAS where the direction's relaxation is stiff --------------------
def _slip_derivatives(t, y, args, J, f_t):
    """df/dy (8, 8) into ``J`` and df/dt (8,) into ``f_t`` of the slip flow
    (:func:`_flow_into`; the kink of the direction's rate at s = SLOW_SPEED is taken
    from the side of s)."""
    pe, p = args
    for i in range(N_STATE):
        f_t[i] = 0.0
        for j in range(N_STATE):
            J[i, j] = 0.0
    _, sx, sy = _forces(pe, p, t)
    rx, ry = -sx, -sy
    drx, dry, dn = -_raw_rate(pe, 0, t), -_raw_rate(pe, 1, t), _raw_rate(pe, 2, t)
    s, cx, cy = y[_S], y[_CX], y[_CY]
    q = math.sqrt(cx**2 + cy**2)
    q3 = q**3
    ex, ey = cx / q, cy / q
    x = cx * ry - cy * rx  # |c| times the rate across
    fast = s > SLOW_SPEED
    slow = s if fast else SLOW_SPEED
    J[_UX, _S], J[_UX, _CX], J[_UX, _CY] = ex, s * cy * cy / q3, -s * cx * cy / q3
    J[_UY, _S], J[_UY, _CX], J[_UY, _CY] = ey, -s * cx * cy / q3, s * cx * cx / q3
    J[_S, _CX], J[_S, _CY] = -cy * x / q3, cx * x / q3
    x_cx, x_cy = ry / q - x * cx / q3, -rx / q - x * cy / q3  # d(x / q)
    J[_CX, _CX], J[_CX, _CY] = -cy * x_cx / slow, -(x / q + cy * x_cy) / slow
    J[_CY, _CX], J[_CY, _CY] = (x / q + cx * x_cx) / slow, cx * x_cy / slow
    if fast:
        J[_CX, _S], J[_CY, _S] = cy * x / (q * s * s), -cx * x / (q * s * s)
    J[_PATH, _S] = 1.0
    x_t = cx * dry - cy * drx
    f_t[_S] = ex * drx + ey * dry - p[1] * dn
    f_t[_CX], f_t[_CY] = -cy * x_t / (q * slow), cx * x_t / (q * slow)


def _error_scale(y, y_new, rtol, atol, out):
    """Each component's error scale [m, m/s, -] into ``out``: atol + rtol max(|y|,
    |y_new|) (SciPy's), save the vectors, whose errors are measured whatever the axes:
    u's components share the larger |u|, and the direction c's error counts as the
    error of the velocity v = s c / |c| it makes: both components get |c| (rtol + atol
    / s), s the larger speed (at s = 0 it makes no velocity: it relaxes at the model's
    capped rate and moves s to second order only)."""
    for i in range(N_STATE):
        out[i] = atol + rtol * max(abs(y[i]), abs(y_new[i]))
    out[_UX] = out[_UY] = atol + rtol * math.sqrt(max(y[_UX] ** 2 + y[_UY] ** 2, y_new[_UX] ** 2 + y_new[_UY] ** 2))
    size = math.sqrt(max(y[_CX] ** 2 + y[_CY] ** 2, y_new[_CX] ** 2 + y_new[_CY] ** 2))
    speed = max(y[_S], y_new[_S])
    out[_CX] = out[_CY] = size * (rtol + atol / speed) if speed > 0 else math.inf
    return out


def _slip_decompose(J, alpha, M):
    """I alpha - J of the slip flow, for :func:`_slip_solve`: its only columns besides
    the diagonal are s, c_x and c_y, so it is solved through the inverse of that 3 x 3
    block (left in M[:3, :3])."""
    a00, a01, a02 = alpha - J[_S, _S], -J[_S, _CX], -J[_S, _CY]  # the block, rows and columns (s, c_x, c_y)
    a10, a11, a12 = -J[_CX, _S], alpha - J[_CX, _CX], -J[_CX, _CY]
    a20, a21, a22 = -J[_CY, _S], -J[_CY, _CX], alpha - J[_CY, _CY]
    M[0, 0], M[0, 1], M[0, 2] = a11 * a22 - a12 * a21, a02 * a21 - a01 * a22, a01 * a12 - a02 * a11
    M[1, 0], M[1, 1], M[1, 2] = a12 * a20 - a10 * a22, a00 * a22 - a02 * a20, a02 * a10 - a00 * a12
    M[2, 0], M[2, 1], M[2, 2] = a10 * a21 - a11 * a20, a01 * a20 - a00 * a21, a00 * a11 - a01 * a10
    det = a00 * M[0, 0] + a01 * M[1, 0] + a02 * M[2, 0]
    for i in range(3):
        for j in range(3):
            M[i, j] /= det


def _slip_solve(J, alpha, M, x):
    """x <- (I alpha - J)^-1 x (see :func:`_slip_decompose`)."""
    b0, b1, b2 = x[_S], x[_CX], x[_CY]
    for i in range(3):
        x[_S + i] = M[i, 0] * b0 + M[i, 1] * b1 + M[i, 2] * b2
    for i in range(N_STATE):
        if i < _S or i > _CY:
            x[i] = (x[i] + J[i, _S] * x[_S] + J[i, _CX] * x[_CX] + J[i, _CY] * x[_CY]) / alpha


def _relaxation_rate(t, y, pe, p):
    """|sigma| / max(s, SLOW_SPEED) [1/s]: the rate at which the slip's direction relaxes
    towards the demand (the flow's stiff eigenvalue)."""
    _, sx, sy = _forces(pe, p, t)
    return math.sqrt(sx * sx + sy * sy) / max(y[_S], SLOW_SPEED)


_step, _initial_step, _dense_coefficients = _dop853.for_flow(_slip_rhs)
_jacobian, _stiff_step, _stiff_dense_coefficients = _rodas4.for_flow(_slip_rhs, _slip_derivatives, _slip_decompose,
                                                                         _slip_solve)
#: DOP853 or RODAS for a step
EXPLICIT, STIFF = 0, 1
#: DOP853's longest step times the direction's relaxation rate [-]: its stability
#: interval on the negative axis ends at -6.3 (|R| < 0.2 up to -5.5)
STABLE_PRODUCT = 4.0


def _dense_value(F, y, x, i, method):
    """Component ``i`` of the step's dense output at x in [0, 1]."""
    if method == STIFF:
        return _rodas4.dense_value(F, y, x, i)
    return _dop853.dense_value(F, y, x, i)


def _dense_state(F, y, x, out, method):
    for i in range(y.shape[0]):
        out[i] = _dense_value(F, y, x, i, method)


def _slip_to(t, y, stop, pe, p, rtol, atol, B, cnt, fl):
    """Slide from (t, y) to ``stop`` [s] or to the first stop before it: (time, state,
    1 if a stop else -1). ``B``: the work buffers (:func:`_buffers`); ``fl``: the
    steps to try (0: choose one) and the method, kept from call to call. DOP853 steps
    while its step is stable (h times the direction's relaxation rate at most
    :data:`STABLE_PRODUCT`); where the accuracy would allow a longer one, RODAS takes
    over while its own steps are longer than DOP853's stable ones."""
    K, K2, F, work, y_new, z, y_cur, _, J, M, scale = B
    args = (pe, p)
    h, h_stiff, method = fl[F_H], fl[F_H_STIFF], int(fl[F_METHOD])
    _put(y_cur, y)
    _slip_rhs(t, y_cur, args, K[0])
    cnt[C_RHS] += 1
    if h <= 0:
        h = _initial_step(args, t, y_cur, stop - t, rtol, atol, K, work)
        cnt[C_RHS] += 1
    jacobian_at = math.nan  # the time of the derivatives in J (at y_cur)
    rejected = False
    h_accepted, err_accepted = 0.0, 0.0  # DOP853's last accepted step [s] and its error [-]
    while t < stop:
        stable = STABLE_PRODUCT / _relaxation_rate(t, y_cur, pe, p)  # DOP853's longest stable step [s]
        if method == EXPLICIT and h > stable:
            if h_stiff > stable:
                method, h = STIFF, min(h, h_stiff)
            else:
                h = stable
        elif method == STIFF and h < stable:
            method = EXPLICIT
        rest = stop - t
        last = h >= rest
        hh = rest if last else h
        if not last and hh <= events.ULPS * _EPS * max(1.0, abs(t)):
            cnt[C_STATUS] = STEP_TOO_SMALL
            break
        if method == STIFF:
            if jacobian_at != t:
                _jacobian(args, t, y_cur, K, J)
                jacobian_at = t
                cnt[C_RHS] += 1
            _stiff_step(args, t, y_cur, hh, K, y_new, work, J, M)
            cnt[C_RHS] += 5
            err = _rodas4.error_norm(K, _error_scale(y_cur, y_new, rtol, atol, scale))
        else:
            _step(args, t, y_cur, hh, K, y_new, work)
            cnt[C_RHS] += 12
            err = _dop853.error_norm(K, hh, _error_scale(y_cur, y_new, rtol, atol, scale))
        accepted = err <= 1.0
        h_next = hh * (_rodas4.factor(err, accepted) if method == STIFF else _dop853.factor(err, accepted))
        if accepted and rejected:  # no longer than the step just accepted after a rejection (SciPy's)
            h_next = min(h_next, hh)
        if accepted and method == EXPLICIT:
            if h_accepted > 0 and err > 0 and err_accepted > 0:  # Gustafsson's predictive step
                predicted = _dop853.SAFETY * (hh / h_accepted) * (err_accepted / err**2) ** (1.0 / 8.0)
                h_next = min(h_next, hh * max(_dop853.MIN_FACTOR, predicted))
            h_accepted, err_accepted = hh, err
        if method == STIFF:
            h_stiff = h_next
        rejected = not accepted
        if rejected:
            h = h_next
            cnt[C_REJECTED] += 1
            continue
        cnt[C_STEPS] += 1
        t_new = stop if last else t + hh
        if method == STIFF:  # the rate at the end (DOP853's step has it in K[12])
            _slip_rhs(t_new, y_new, args, K[_dop853.N_STAGES])
            cnt[C_RHS] += 1
        upper, dense = math.nan, False
        f_start, f_end = K[0, _S], K[_dop853.N_STAGES, _S]
        if y_cur[_S] > 0 and y_new[_S] <= 0:
            upper = t_new
        elif y_cur[_S] > 0 and f_start < 0 and f_end > 0:  # s may dip below zero and come back
            cnt[C_RHS] += _dense_rows(args, t, y_cur, y_new, hh, K, F, work, method)
            dense = True
            x_min = _dense_minimum(F, y_cur, t, hh, args, work, z, method)
            if _dense_value(F, y_cur, x_min, _S, method) <= 0:
                upper = t + x_min * hh
        if not math.isnan(upper):
            if not dense:
                cnt[C_RHS] += _dense_rows(args, t, y_cur, y_new, hh, K, F, work, method)
            root = _stop_on_flow(F, args, t, y_cur, hh, upper, K, K2, work, z, cnt, B, method)
            if root > 0:
                fl[F_H], fl[F_H_STIFF], fl[F_METHOD] = h, h_stiff, method
                return root, z.copy(), 1
        h = max(h, h_next) if last else h_next
        t = t_new
        _put(y_cur, y_new)
        _put(K[0], K[_dop853.N_STAGES])
    fl[F_H], fl[F_H_STIFF], fl[F_METHOD] = h, h_stiff, method
    return t, y_cur.copy(), -1


def _dense_rows(args, t, y, y_new, hh, K, F, work, method):
    """The step's dense output into ``F``; the right-hand-side calls it took."""
    if method == STIFF:
        _stiff_dense_coefficients(y, y_new, K, F)
        return 0
    _dense_coefficients(args, t, y, y_new, hh, K, F, work)
    return 3


def _buffers():
    """Work arrays: K, K2 (16, 8), F (7, 8), then four (8,) of the slip's steps, a
    zero state (8,) (read only), J (8, 8) and M (3, 3) of RODAS's steps, the error scale (8,)."""
    n = _dop853.N_STAGES_EXTENDED
    return (np.empty((n, N_STATE)), np.empty((n, N_STATE)), np.empty((7, N_STATE)), np.empty(N_STATE),
            np.empty(N_STATE), np.empty(N_STATE), np.empty(N_STATE), np.zeros(N_STATE),
            np.empty((N_STATE, N_STATE)), np.empty((3, 3)), np.empty(N_STATE))


def _dense_minimum(F, y, t, hh, args, work, rate, method):
    """x in [0, 1] where the dense s is least (its rate from the flow at the dense state
    goes from < 0 to > 0), by bisection."""
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            break
        _dense_state(F, y, mid, work, method)
        _slip_rhs(t + mid * hh, work, args, rate)
        if rate[_S] < 0:
            lo = mid
        else:
            hi = mid
    return hi


def _dense_speed(args, t_mid):
    """s [m/s] of the step's dense output at ``t_mid`` [s] (args: (F, y, t, hh, method))."""
    F, y, t, hh, method = args
    return _dense_value(F, y, (t_mid - t) / hh, _S, method)


def _s_after(args, t, y, d, K, K2, work, z, B, method):
    """s [m/s] after a step of ``d`` [s] from (t, y) (K[0]: the rate there; for RODAS
    K[7] and B's J: the derivatives there), the state left in ``z``."""
    _put(K2[0], K[0])
    if method == STIFF:
        _put(K2[7], K[7])
        _stiff_step(args, t, y, d, K2, z, work, B[8], B[9])
    else:
        _step(args, t, y, d, K2, z, work)
    return z[_S]


def _stop_on_flow(F, args, t, y, hh, upper, K, K2, work, z, cnt, B, method):
    """The stop in (t, upper]: the first float where the dense s is <= 0, confirmed on
    the flow (a step from t to it has s <= 0, to the float before it s > 0); else the
    same bisection on steps from t. The time (0 if the flow has none), the state in ``z``."""
    calls = 6 if method == STIFF else 12
    b = events.first_nonpositive(_dense_speed, (F, y, t, hh, method), t, upper)  # on the dense output
    before = np.nextafter(b, -math.inf)
    cnt[C_RHS] += 2 * calls
    if before <= t or _s_after(args, t, y, before - t, K, K2, work, z, B, method) > 0:
        if _s_after(args, t, y, b - t, K, K2, work, z, B, method) <= 0:
            return b
    a, b = t, upper  # on the flow
    if _s_after(args, t, y, b - t, K, K2, work, z, B, method) > 0:
        return 0.0
    while True:
        mid = 0.5 * (a + b)
        if mid <= a or mid >= b:
            _s_after(args, t, y, b - t, K, K2, work, z, B, method)
            return b
        cnt[C_RHS] += calls
        if _s_after(args, t, y, mid - t, K, K2, work, z, B, method) > 0:
            a = mid
        else:
            b = mid


# ---- the loop: the driver's, on floats ---------------------------------------------------
#: counters (int64): knots, events, events in the current instant, most at one instant,
#: liftoffs, status, steps, rejected steps, right-hand-side calls, mode, restarted
C_NK, C_NE, C_RUN, C_MAX_RUN, C_FLIGHTS, C_STATUS, C_STEPS, C_REJECTED, C_RHS, C_MODE, C_RESTARTED = range(11)
#: floats: time [s], largest speed [m/s], last event [s], step to try [s], largest |u| [m],
#: RODAS's last step to try [s] (inf: none yet), the slip's method (EXPLICIT or STIFF)
F_T, F_VMAX, F_LAST, F_H, F_MAXU, F_H_STIFF, F_METHOD = range(7)
#: knot rows: t, y (7), mode after, dy/dt after (7), dy/dt before (7)
KNOT_WIDTH = 23
#: event rows: t, mode before, mode after, y before the entry (7)
EVENT_WIDTH = 10


def _put(dst, src):
    """dst[i] = src[i] for i < len(dst) (a loop: numba's slice assignment compiles a
    shape check whose error message alone takes seconds)."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


def _push(buf, n, width):
    """``buf`` with room for row ``n`` (doubled when full)."""
    if n < buf.shape[0]:
        return buf
    grown = np.empty((2 * buf.shape[0], width))
    for i in range(buf.shape[0]):
        _put(grown[i], buf[i])
    return grown


def _add_knot(kb, cnt, fl, log, t, y, mode, left, right):
    fl[F_MAXU] = max(fl[F_MAXU], math.hypot(y[_UX], y[_UY]))
    if not log:
        return kb
    n = cnt[C_NK]
    kb = _push(kb, n, KNOT_WIDTH)
    kb[n, 0], kb[n, 8] = t, mode
    _put(kb[n, 1:8], y)
    _put(kb[n, 9:16], right)
    _put(kb[n, 16:23], np.zeros(7))
    if n > 0:
        _put(kb[n - 1, 16:23], left)
    cnt[C_NK] = n + 1
    return kb


def _log_event(kb, eb, cnt, fl, log, y, t, after, pe, p, resolution, cap):
    before = cnt[C_MODE]
    same = cnt[C_NE] > 0 and abs(t - fl[F_LAST]) <= resolution
    cnt[C_RUN] = cnt[C_RUN] + 1 if same else 1
    cnt[C_MAX_RUN] = max(cnt[C_MAX_RUN], cnt[C_RUN])
    if log:
        n = cnt[C_NE]
        eb = _push(eb, n, EVENT_WIDTH)
        eb[n, 0], eb[n, 1], eb[n, 2] = t, before, after
        _put(eb[n, 3:10], y)
    cnt[C_NE] += 1
    fl[F_LAST] = t
    if after == FLIGHT and before != FLIGHT:
        cnt[C_FLIGHTS] += 1
    _put(y, _state_on_entry(before, after, t, y, pe, p))
    if cnt[C_RUN] > cap:
        cnt[C_STATUS] = CHATTER
        return kb, eb
    cnt[C_MODE], cnt[C_RESTARTED] = after, 1
    fl[F_H], fl[F_H_STIFF], fl[F_METHOD] = 0.0, math.inf, EXPLICIT  # a new mode: a fresh first step
    kb = _add_knot(kb, cnt, fl, log, t, y, after, np.zeros(N_STATE), _flow(after, t, y, pe, p))
    return kb, eb


def _on_guard(kb, eb, cnt, fl, log, y, index, pe, p, opt):
    mode, t = cnt[C_MODE], fl[F_T]
    if mode == SLIP and index == 1:
        y[_S] = 0.0
    elif mode == FLIGHT:
        y[_W] = 0.0
    after = _mode_after_guard(mode, index, t, y, pe, p, _stop_uncertainty(mode, index, t, y, pe, p, fl, opt))
    rate = _flow(mode, t, y, pe, p)
    kb = _add_knot(kb, cnt, fl, log, t, y, mode, rate, rate)
    if after != mode or mode == FLIGHT or (mode == SLIP and index == 1):  # guard_restarts
        kb, eb = _log_event(kb, eb, cnt, fl, log, y, t, after, pe, p, opt[2], int(opt[3]))
    return kb, eb


def _stop_uncertainty(mode, index, t, y, pe, p, fl, opt):
    """The driver's ``stop_uncertainty`` [s] with (rtol, atol) of this engine."""
    slope, curvature = _guard_rates(mode, index, t, y, pe, p)
    return events.stop_uncertainty(slope, curvature, events.velocity_error(opt[0], opt[1], fl[F_VMAX]), opt[2])


def _guard_left_at_once(mode, t, y, pe, p, resolution):
    """The driver's ``guard_left_at_once`` (:func:`blockdae.core.events.left_at_once`):
    the guard index, or -1."""
    return events.left_at_once(_guards(mode, t, y, pe, p), _rates_at, (mode, t, y, pe, p), resolution)


def _rates_at(args, index):
    """Guard ``index``'s (rate, curvature) (args: (mode, t, y, pe, p))."""
    mode, t, y, pe, p = args
    return _guard_rates(mode, index, t, y, pe, p)


def _output_step(pe):
    """The driver's ``output_step`` [s]: 1 / (32 w) on a sine piece, else inf."""
    w = 0.0
    for i in range(3):
        if pe[2][i, 2] != 0:
            w = max(w, pe[2][i, 3])
    return 1.0 / (KNOTS_PER_RADIAN * w) if w > 0 else math.inf


def _advance(kb, eb, cnt, fl, log, y, end, until_rest, pe, p, opt, B):
    """The driver's ``advance_to``: from ``fl[F_T]`` to ``end`` [s]."""
    turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
    while fl[F_T] < end and not (until_rest and cnt[C_MODE] == STICK):
        if cnt[C_STATUS] != FINISHED:
            return kb, eb
        mode, t = cnt[C_MODE], fl[F_T]
        if mode == STICK:
            root, index = _static_root(t, y, end, pe, p)
            if index < 0:
                fl[F_T], cnt[C_RESTARTED] = end, 1
                return _add_knot(kb, cnt, fl, log, end, y, mode, B[7], B[7]), eb
            fl[F_T] = root
            kb, eb = _on_guard(kb, eb, cnt, fl, log, y, index, pe, p, opt)
            turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
            continue
        if cnt[C_RESTARTED]:
            index = _guard_left_at_once(mode, t, y, pe, p, opt[2])
            if index >= 0:
                kb, eb = _on_guard(kb, eb, cnt, fl, log, y, index, pe, p, opt)
                turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
                if cnt[C_MODE] != mode:
                    continue
            cnt[C_RESTARTED] = 0
        target = end if math.isnan(turn) or turn <= t else turn
        if events.too_short(t, target):
            fl[F_T], cnt[C_RESTARTED] = target, 1
            continue
        t_out = min(target, t + _output_step(pe))
        if mode == FLIGHT:
            t_new, z, landed = _flight_to(t, y, t_out, pe, p)
            root = 0 if landed else -1
        else:
            lift = _liftoff_time(t, t_out, y, pe, p)
            stop = t_out if math.isnan(lift) else lift
            t_new, z, root = _slip_to(t, y, stop, pe, p, opt[0], opt[1], B, cnt, fl)
            if cnt[C_STATUS] != FINISHED:
                return kb, eb
            if root < 0 and not math.isnan(lift):
                root = 0
        if root >= 0 and t_new >= end:  # left to the next piece's right-hand limits
            root, t_new = -1, t_out
        fl[F_T] = t_new
        _put(y, z)
        fl[F_VMAX] = max(fl[F_VMAX], rules.speed(y))
        if mode == SLIP:
            error = events.velocity_error(opt[0], opt[1], fl[F_VMAX])
            if y[_S] < -(error + events.ROUNDING * fl[F_VMAX]):
                cnt[C_STATUS] = INCONSISTENT
                return kb, eb
        if root < 0:
            rate = _flow(mode, t_new, y, pe, p) if log else B[7]
            kb = _add_knot(kb, cnt, fl, log, t_new, y, mode, rate, rate)
        else:
            kb, eb = _on_guard(kb, eb, cnt, fl, log, y, root, pe, p, opt)
            turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
    return kb, eb


def _piece_excitation(T0, H, CF, scale, k, P, D):
    """(t0, h, P, directions) of piece k with a(t) times ``scale``, written into ``P``
    (3, 5) and ``D`` (3,) (no allocation per piece)."""
    for i in range(3):
        P[i, 0], P[i, 1], P[i, 2] = CF[k, i, 0] * scale, CF[k, i, 1] * scale, CF[k, i, 2] * scale
        P[i, 3], P[i, 4] = CF[k, i, 3], CF[k, i, 4]
        D[i] = np.sign(_a_local(P, i, H[k]) - _a_local(P, i, 0.0))
    return (T0[k], H[k], P, D)


def _run(T0, H, CF, p, opt, log):
    """One run: the pieces (t0 (n,), h (n,) [s], CF (n, 3, 5): (p0, p1, s, w, phi) per
    piece and component), ``p`` (``PARAM_FIELDS``), ``opt`` (``OPTION_FIELDS``), with the
    knot and event logs if ``log``. Returns (outcome, knots (k, 23), events (e, 10))."""
    n = T0.shape[0]
    cnt = np.zeros(11, dtype=np.int64)
    fl = np.zeros(7)
    fl[F_H_STIFF] = math.inf
    fl[F_LAST] = math.nan
    cnt[C_MODE], cnt[C_RESTARTED] = STICK, 1
    y = np.zeros(N_STATE)
    kb = np.empty((256 if log else 1, KNOT_WIDTH))
    eb = np.empty((64 if log else 1, EVENT_WIDTH))
    B = _buffers()
    zero = B[7]
    P, D = np.empty((3, 5)), np.empty(3)
    kb = _add_knot(kb, cnt, fl, log, 0.0, y, STICK, zero, zero)
    until_rest = opt[4] != 0
    t_end = T0[n - 1] + H[n - 1]
    for k in range(n + 1 if until_rest else n):
        if k < n:
            pe = _piece_excitation(T0, H, CF, p[7], k, P, D)
            end = T0[k + 1] if k + 1 < n else t_end
        else:  # after the excitation: a = 0
            pe = (t_end, math.inf, np.zeros((3, 5)), np.zeros(3))
            end = t_end
        if log and cnt[C_NK] > 0:  # enter_piece: dy/dt after the last knot on this piece
            _flow_into(cnt[C_MODE], fl[F_T], y, pe, p, B[3])
            _put(kb[cnt[C_NK] - 1, 9:16], B[3])
        cnt[C_RESTARTED] = 1
        if cnt[C_MODE] == STICK or (cnt[C_MODE] == SLIP and y[_S] == 0):
            rest = _mode_at_rest(pe, p, pe[0])
            if rest != cnt[C_MODE]:
                y[_S], y[_W], y[_WD] = 0.0, 0.0, 0.0
                kb, eb = _log_event(kb, eb, cnt, fl, log, y, pe[0], rest, pe, p, opt[2], int(opt[3]))
                if cnt[C_STATUS] != FINISHED:
                    break
        if k == n:
            if cnt[C_MODE] == STICK:
                break
            bound = rules.time_to_rest(cnt[C_MODE], y, p[2], p[3], p[1], p[4])
            if bound < 0:
                cnt[C_STATUS] = NEVER_RESTS
                break
            end = fl[F_T] + bound
        if cnt[C_MODE] == STICK and k < n and fl[F_T] < end and _quiet_stick(pe, p, fl[F_T], end, y):  # _advance's, short
            fl[F_T], cnt[C_RESTARTED] = end, 1
            kb = _add_knot(kb, cnt, fl, log, end, y, STICK, zero, zero)
            continue
        kb, eb = _advance(kb, eb, cnt, fl, log, y, end, k == n, pe, p, opt, B)
        if cnt[C_STATUS] != FINISHED:
            break
        if k == n and cnt[C_MODE] != STICK:
            cnt[C_STATUS] = NO_REST
    out = np.empty(len(OUTCOME_FIELDS))
    out[0], out[1], out[2], out[3], out[4] = y[_UX], y[_UY], fl[F_MAXU], y[_PATH], cnt[C_NE]
    out[5], out[6], out[7], out[8], out[9] = cnt[C_FLIGHTS], fl[F_T], cnt[C_MODE], cnt[C_STATUS], cnt[C_MAX_RUN]
    out[10], out[11], out[12] = cnt[C_STEPS], cnt[C_REJECTED], cnt[C_RHS]
    if log and cnt[C_NK] > 0:
        _put(kb[cnt[C_NK] - 1, 16:23], np.zeros(7))
    return out, kb[: cnt[C_NK]], eb[: cnt[C_NE]]


@functools.cache
def kernel():
    """The engine, compiled on first call (or loaded from numba's disk cache, keyed by
    the sources of this module and of the ones it compiles):

    ``run(T0, H, CF, offsets, params, options, until_rest, items, out, log)`` runs the
    batch items ``items`` (int64) into ``out`` (n_exc, m, 13) (``OUTCOME_FIELDS``): item
    k is excitation i = k % n_exc (pieces ``offsets[i, 0]:offsets[i, 1]``, until rest if
    ``until_rest[i]``) under parameter set k // n_exc (rows of ``params``, (m, 8)), and
    returns the knot and event logs of the last item if ``log``. It releases the GIL:
    threads run parts of one batch in parallel. One entry point, no parallel loop of
    numba's: each would be a second compilation of the whole engine.
    """
    _register()
    fingerprint = hashlib.sha256(b"".join(pathlib.Path(m.__file__).read_bytes() for m in _SHARED)).hexdigest()

    def run(T0, H, CF, offsets, params, options, until_rest, items, out, log):
        fingerprint  # noqa: B018 -- numba keys its disk cache by the closure's contents
        n_exc = offsets.shape[0]
        o = options.copy()
        knots, events = np.empty((0, KNOT_WIDTH)), np.empty((0, EVENT_WIDTH))
        for item in items:
            i, j = item % n_exc, item // n_exc
            a, b = offsets[i, 0], offsets[i, 1]
            o[4] = until_rest[i]
            outcome, knots, events = _run(T0[a:b], H[a:b], CF[a:b], params[j], o, log)
            _put(out[i, j], outcome)
        return knots, events

    return numba.njit(cache=True, nogil=True, **_OPTIONS)(run)


def run_one(T0, H, CF, p, options):
    """One run with its logs: (outcome (13,), knots (k, 23), events (e, 10)) (see
    :func:`_run`)."""
    out = np.empty((1, 1, len(OUTCOME_FIELDS)))
    offsets = np.array([[0, T0.shape[0]]], dtype=np.int64)
    knots, events = kernel()(T0, H, CF, offsets, p[None, :], options, options[4:5].copy(),
                             np.zeros(1, dtype=np.int64), out, True)
    return out[0, 0], knots, events


_OPTIONS = dict(error_model="numpy")
#: modules whose functions the engine compiles besides its own
_SHARED = (_pieces, _dop853, _rodas4, xp, events, rules, sys.modules[__name__])


def _register():
    """Let numba compile this module's plain functions and the excitation's closed forms
    where the entry points call them (``register_jitable``; they stay plain Python)."""
    for module in (_pieces, rules, sys.modules[__name__]):
        for _, fn in inspect.getmembers(module, inspect.isfunction):
            if fn.__module__ == module.__name__ and fn.__name__ not in ("kernel", "run_one", "_register"):
                register_jitable(**_OPTIONS)(fn)
