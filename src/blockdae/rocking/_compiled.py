"""The rocking block's compiled engine: the hybrid driver's loop for a free-standing block
that rocks (:class:`RockingBlock`, mu >= b/h; the exact equation or the linearised one),
compiled with numba, on records and on sine pieces, horizontal and vertical.

Per mode:

* REST: the state is constant; the guards (onset at |a_x| = limit g_e, g_e > 0) depend on
  time alone and are located by bisection to adjacent floats
  (:func:`blockdae.core.events.static_root`), as the driver does; a linear piece with
  every guard positive at both ends has none (:func:`_quiet_rest`);
* rocking (OUT, IN, BEYOND) and the Zeno tail (SETTLE): DOP853
  (:mod:`blockdae.solvers.dop853`) at the backend's tolerances, a new rocking mode's
  first step the last one tried. A root of a guard of the state (the mode's own) is
  bracketed by a step (> 0 -> <= 0, or a dip below zero between a falling and a rising
  end, found at the minimum of the step's dense output) and located by bisection on the
  dense output to adjacent floats; one of time alone (SETTLE's onsets, g_e) by bisection
  in time; the state there is a step of the same method from the step's start;
* OVERTURNED: terminal; one knot at the end.

The model's rules (the flow, the guards and their rates, the mode after a guard: onset,
apex, impact with r, the Zeno tail, alpha, pi/2) are :mod:`._rules`, which
:class:`RockingBlock` calls too; the driver's event rules (the graze rule, bisections,
turning points, a static mode's first root) are :mod:`blockdae.core.events`. The loop is
the driver's (:mod:`blockdae.core._driver`) on floats: a root at a piece's end is left to
the next piece, a mode whose guard starts at zero and falls leaves at once, the step
stops where theta'' at the frozen state turns, knots at least 1 / (32 w) and 1 / (32 p)
apart (the driver's cubic Hermite dense output).

State (2,): (theta [rad], theta' [rad/s]).
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

from ..core import events
from ..excitation import accel, accel_rate, monotone_rate, pieces as _pieces
from ..sliding import rest_mode
from ..solvers import dop853 as _dop853, xp_scalar as xp
from . import _rules as rules
from ._rules import BEYOND, IN, OUT, OVERTURNED, REST, SETTLE

RELEASE = 7
#: entries of ``params``: alpha [rad], p² [1/s²], g [m/s²], r [-], zeno_arc [s], theta0
#: [rad], linearised (0/1), the limit of rest min(mu, threshold) [-], the rocking
#: threshold [-], the knots' spacing 1 / (32 p) [s], the rate floor of a contradiction [rad/s]
PARAM_FIELDS = ("alpha", "p2", "g", "r", "zeno_arc", "theta0", "linearised", "limit", "threshold", "output_step",
                "rate_floor")
_ALPHA, _P2, _G, _R, _ZENO, _THETA0, _LIN, _LIMIT, _THRESHOLD, _STEP, _FLOOR = range(11)
#: entries of ``options``: rtol [-], atol [rad, rad/s], event resolution [s], most events at
#: one instant [-], until rest (0/1), the bound on the time to rest after the excitation [s]
OPTION_FIELDS = ("rtol", "atol", "event_resolution", "max_events_at_one_instant", "until_rest", "rest_bound")
#: entries of a run's outcome
OUTCOME_FIELDS = ("t_final", "mode", "status", "max_events_at_one_instant", "steps", "rejected_steps", "rhs_calls")
#: outcome ``status``: finished; chatter; the state contradicts its mode; a step below
#: rounding; no rest within the bound; never rests (r = 1); the base falls faster than g
FINISHED, CHATTER, INCONSISTENT, STEP_TOO_SMALL, NO_REST, NEVER_RESTS, FLIGHT = range(7)
#: the flight guard's index (g_e falling through zero) in every mode that has one
_FLIGHT_GUARD = 3
#: counters (int64): knots, events, events at the current instant, most at one instant,
#: status, steps, rejected steps, right-hand-side calls (in this order: the DOP853 flow's
#: counts), mode, restarted
C_NK, C_NE, C_RUN, C_MAX_RUN, C_STATUS, C_STEPS, C_REJECTED, C_RHS, C_MODE, C_RESTARTED = range(10)
#: floats: time [s], largest |theta'| [rad/s], last event [s], step to try [s]
F_T, F_VMAX, F_LAST, F_H = range(4)
#: knot rows: t, theta, theta', mode after, dy/dt after (2), dy/dt before the next knot (2)
KNOT_WIDTH = 8
#: event rows: t, mode before, mode after, (theta, theta') before the entry
EVENT_WIDTH = 5
_INF = math.inf


# ---- the base's motion on a piece: pe = (t0 [s], h [s], (p0, p1, s, w, phi) of a_x, the
# same of a_z, the directions of a_x and a_z) as 14 floats (no array: the hot loop then
# counts no references)
def _component(pe, i, t):
    """a_x (i = 0) or a_z (1) at ``t`` [m/s²]."""
    k, tau = 2 + 5 * i, min(t - pe[0], pe[1])
    if pe[k + 2] == 0:
        return accel(pe[k], pe[k + 1], None, None, None, tau, xp)
    return accel(pe[k], pe[k + 1], pe[k + 2], pe[k + 3], pe[k + 4], tau, xp)


def _component_rate(pe, i, t):
    """Its rate [m/s³], rounding against the piece's direction projected out (as the
    driver's decisions see it)."""
    k, tau = 2 + 5 * i, min(t - pe[0], pe[1])
    if pe[k + 2] == 0:
        raw = accel_rate(pe[k], pe[k + 1], None, None, None, tau, xp)
    else:
        raw = accel_rate(pe[k], pe[k + 1], pe[k + 2], pe[k + 3], pe[k + 4], tau, xp)
    return monotone_rate(raw, pe[12 + i], xp)


def _angular_acceleration(s, theta, t, pe, p):
    """theta'' [rad/s²] about side ``s`` (:func:`._rules.angular_acceleration`)."""
    return rules.angular_acceleration(s, theta, _component(pe, 0, t), p[_G] + _component(pe, 1, t), p[_ALPHA],
                                      p[_P2], p[_G], p[_LIN] != 0, xp)


def _deceleration(s, t, pe, p):
    """-s theta'' at theta = 0 on side ``s`` [rad/s²] (the model's ``deceleration``)."""
    return -s * _angular_acceleration(s, 0.0, t, pe, p)


def _settle_rate(s, t, pe, p):
    """The Zeno envelope's d theta'/dt [rad/s²] (:func:`._rules.settle_rate`)."""
    return rules.settle_rate(s, _deceleration(s, t, pe, p), _deceleration(-s, t, pe, p), p[_R])


def _side(mode):
    return 1 if mode > 0 else -1


def _rocks(kind):
    return kind == OUT or kind == IN or kind == BEYOND


def _flow(mode, t, theta, rate, pe, p):
    """dy/dt in ``mode``: (theta', theta'') rocking, (0, the envelope's rate) settling,
    zero otherwise."""
    kind, s = abs(mode), _side(mode)
    if _rocks(kind):
        return rate, _angular_acceleration(s, theta, t, pe, p)
    if kind == SETTLE:
        return 0.0, _settle_rate(s, t, pe, p)
    return 0.0, 0.0


def _rhs(t, y, args, out):
    """:func:`_flow` as the steps' right-hand side (args: (mode, pe, p))."""
    mode, pe, p = args
    out[0], out[1] = _flow(mode, t, y[0], y[1], pe, p)


def _guards(mode, t, y, pe, p):
    """The four guards of ``mode`` (+inf where a mode has fewer) at the state ``y`` = (theta,
    theta') (here and below two floats where a function only reads the state), each left
    as it falls through zero; the fourth, g_e [m/s²], a flight of the whole block (an error). REST:
    (limit g_e - a_x, limit g_e + a_x); rocking: :func:`._rules.rocking_guards`; SETTLE:
    (s theta', the two onsets); RELEASE: -1 - t (at once, at a time that no parameter moves)."""
    kind, s = abs(mode), _side(mode)
    if mode == RELEASE:
        return -1.0 - t, _INF, _INF, _INF
    if kind == OVERTURNED:
        return _INF, _INF, _INF, _INF
    ax, ge = _component(pe, 0, t), p[_G] + _component(pe, 1, t)
    if mode == REST:
        return p[_LIMIT] * ge - ax, p[_LIMIT] * ge + ax, _INF, ge
    if kind == SETTLE:
        return s * y[1], p[_THRESHOLD] * ge - ax, p[_THRESHOLD] * ge + ax, ge
    own, back = rules.rocking_guards(kind, s, y[0], y[1], p[_ALPHA])
    return own, back, _INF, ge


def _guard_rates(mode, index, t, y, pe, p):
    """(rate, curvature) in time of guard ``index`` of ``mode`` (the model's ``guard_rates``)."""
    kind, s = abs(mode), _side(mode)
    if mode == RELEASE:
        return -1.0, 0.0
    if kind == OVERTURNED:
        return 0.0, 0.0
    ax_rate, az_rate = _component_rate(pe, 0, t), _component_rate(pe, 1, t)
    if index == _FLIGHT_GUARD:
        return az_rate, 0.0
    if mode == REST or (kind == SETTLE and index > 0):  # limit g_e - a_x (REST 0, SETTLE 1), limit g_e + a_x
        coefficient = p[_THRESHOLD] if kind == SETTLE else p[_LIMIT]
        sign = -1.0 if index == (1 if kind == SETTLE else 0) else 1.0
        return coefficient * az_rate + sign * ax_rate, 0.0
    if kind == SETTLE:
        return s * _settle_rate(s, t, pe, p), 0.0
    ax, ge = _component(pe, 0, t), p[_G] + _component(pe, 1, t)
    accel = rules.angular_acceleration(s, y[0], ax, ge, p[_ALPHA], p[_P2], p[_G], p[_LIN] != 0, xp)
    jerk = rules.angular_jerk(s, y[0], y[1], ax, ge, ax_rate, az_rate, p[_ALPHA], p[_P2], p[_G], p[_LIN] != 0)
    return rules.rocking_guard_rates(kind, s, index, y[1], accel, jerk)


def _mode_at_rest(t, pe, p):
    """REST, or the rocking the demand starts (the model's ``mode_at_rest``: its rate
    decides at the threshold)."""
    direction = rest_mode(_component(pe, 0, t), _component_rate(pe, 0, t), p[_LIMIT],
                          p[_G] + _component(pe, 1, t), True, True, xp)
    return OUT * direction


def _mode_after_guard(mode, index, t, y, pe, p):
    """The mode after guard ``index`` (the model's ``mode_after_guard``); -1 for a flight."""
    kind, s = abs(mode), _side(mode)
    if index == _FLIGHT_GUARD:
        return -1
    if mode == REST:
        return -OUT if index == 0 else OUT
    if mode == RELEASE:
        s = 1 if p[_THETA0] > 0 else -1
        return rules.mode_after_apex(s, p[_THETA0], _angular_acceleration(s, p[_THETA0], t, pe, p), p[_ALPHA])
    ahead, behind = 0.0, 0.0
    if kind == IN and index == 0:
        ahead, behind = _deceleration(-s, t, pe, p), _deceleration(s, t, pe, p)
    after = rules.mode_after_rocking_guard(kind, s, index, y[0], p[_R] * y[1], ahead, behind, p[_ALPHA], p[_ZENO])
    return _mode_at_rest(t, pe, p) if after == rules.DEMAND_DECIDES else after


def _state_at_guard(mode, index, y, p):
    """The state exactly on the guard (the model's ``state_at_guard``), into ``y``."""
    kind, s = abs(mode), _side(mode)
    if mode == RELEASE:
        y[0], y[1] = p[_THETA0], 0.0
    elif kind == OUT or kind == BEYOND:
        if index == 0:
            y[1] = 0.0
        elif index == 1:
            y[0] = s * (0.5 * math.pi if kind == BEYOND else p[_ALPHA])
    elif kind == IN:
        if index == 0:
            y[0] = 0.0
        elif index == 1:
            y[1] = 0.0
    elif kind == SETTLE and index < 3:
        y[0], y[1] = 0.0, 0.0


def _state_on_entry(before, after, y, p):
    """An impact multiplies theta' by r; an overturned block lies still at s pi/2 (the
    model's ``state_on_entry``), into ``y``."""
    if abs(before) == IN and after != REST and _side(after) == -_side(before):
        y[1] = p[_R] * y[1]
    if abs(after) == OVERTURNED:
        y[0], y[1] = _side(after) * 0.5 * math.pi, 0.0


def _contradicts(mode, y, p, opt, v_max):
    """Whether theta' points against its rocking mode beyond the velocity error (the
    model's ``contradiction``)."""
    kind, s = abs(mode), _side(mode)
    error = max(events.velocity_error(opt[0], opt[1], v_max) + events.ROUNDING * v_max, p[_FLOOR])
    return ((kind == OUT or kind == BEYOND) and s * y[1] < -error) or (kind == IN and s * y[1] > error)


# ---- roots ------------------------------------------------------------------------------
_guard_values, _guard_value = events.of_time(_guards)


def _turn_value(args, t):
    """(theta'' at the frozen state, whether the mode has it) (the model's ``turn_rate``)."""
    mode, y, pe, p = args
    if _rocks(abs(mode)):
        return _angular_acceleration(_side(mode), y[0], t, pe, p), True
    return 0.0, False


def _next_turn(mode, t, y, end, pe, p):
    """Where the turn rate changes sign in (t, end), else nan (the driver's ``turning_point``)."""
    return events.turning_point(_turn_value, (mode, (y[0], y[1]), pe, p), t, end)


def _rates_at(args, index):
    mode, t, y, pe, p = args
    return _guard_rates(mode, index, t, y, pe, p)


def _dense_guard(args, t_mid):
    """Own guard ``index`` of rocking or settling mode ``kind`` (a function of the state
    alone) on the step's dense output at ``t_mid`` [s] (args: (F, y, t, hh, kind, s,
    index, alpha))."""
    F, y, t, hh, kind, s, index, alpha = args
    x = (t_mid - t) / hh
    rate = _dop853.dense_value(F, y, x, 1)
    if kind == SETTLE:
        return s * rate
    return rules.rocking_guards(kind, s, _dop853.dense_value(F, y, x, 0), rate, alpha)[index]


def _dense_minimum(F, y, t, hh, mode, index, pe, p, work):
    """x in [0, 1] where guard ``index`` on the dense output is least (its rate at the
    dense state goes from < 0 to > 0), by bisection."""
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            break
        _dop853.dense_state(F, y, mid, work)
        if _guard_rates(mode, index, t + mid * hh, (work[0], work[1]), pe, p)[0] < 0:
            lo = mid
        else:
            hi = mid
    return hi


_step, _initial_step, _dense_coefficients = _dop853.for_flow(_rhs)


def _first_root(root_args, carry, t, y, t_new, y_new, hh, K):
    """The first guard root in (t, t_new] of the step just taken from (t, y) (its stages
    in ``K``, the flow at its ends in rows 0 and 12; root_args: (mode, pe, p, F, work,
    cnt); ``carry`` handed on as it is): (time, index, carry), or (nan, -1, carry). The own
    guards of a rocking or settling mode are functions of the state, located on the dense
    output; the others (SETTLE's onsets, g_e) of time alone, monotone on a piece."""
    mode, pe, p, F, work, cnt = root_args
    kind, s = abs(mode), _side(mode)
    start, end = _guards(mode, t, (y[0], y[1]), pe, p), _guards(mode, t_new, (y_new[0], y_new[1]), pe, p)
    dense = False
    best, index = _INF, -1
    for j in range(4):
        if not start[j] > 0 or start[j] == _INF:
            continue
        of_state = (_rocks(kind) and j < 2) or (kind == SETTLE and j == 0)
        upper = math.nan
        if end[j] <= 0:
            upper = t_new
        elif of_state and _rocks(kind):  # a dip below zero within the step: the rates at its ends
            rate_start = rules.rocking_guard_rates(kind, s, j, K[0, 0], K[0, 1], 0.0)[0]
            rate_end = rules.rocking_guard_rates(kind, s, j, K[_dop853.N_STAGES, 0], K[_dop853.N_STAGES, 1], 0.0)[0]
            if rate_start < 0 and rate_end > 0:
                if not dense:
                    _dense_coefficients((mode, pe, p), t, y, y_new, hh, K, F, work)
                    cnt[C_RHS] += 3
                    dense = True
                x = _dense_minimum(F, y, t, hh, mode, j, pe, p, work)
                if _dense_guard((F, y, t, hh, kind, s, j, p[_ALPHA]), t + x * hh) <= 0:
                    upper = t + x * hh
        if math.isnan(upper):
            continue
        if of_state:
            if not dense:
                _dense_coefficients((mode, pe, p), t, y, y_new, hh, K, F, work)
                cnt[C_RHS] += 3
                dense = True
            root = events.first_nonpositive(_dense_guard, (F, y, t, hh, kind, s, j, p[_ALPHA]), t, upper)
        else:
            root = events.first_nonpositive(_guard_value, ((mode, (y[0], y[1]), pe, p), j), t, upper)
        if root < best:
            best, index = root, j
    return (best, index, carry) if index >= 0 else (math.nan, -1, carry)


_integrate = _dop853.to_first_root(_step, _initial_step, _first_root)


def _flow_to(t, y, stop, mode, pe, p, opt, B, cnt, fl):
    """Integrate ``mode`` from (t, y) to ``stop`` [s] or to the first guard root before
    it: (time, state, guard index or -1). The step to try is kept in ``fl[F_H]``."""
    K, F, V = B
    work, y_cur, y_new, z, scale = V[0], V[1], V[2], V[3], V[4]
    args = (mode, pe, p)
    y_cur[0], y_cur[1] = y[0], y[1]
    _rhs(t, y_cur, args, K[0])
    cnt[C_RHS] += 1
    t, z, index, h = _integrate(args, (mode, pe, p, F, work, cnt), 0.0, t, y_cur, stop, fl[F_H], opt[0], opt[1], K,
                                y_new, z, work, scale, cnt[C_STEPS:C_RHS + 1])
    fl[F_H] = h
    if index == -2:
        cnt[C_STATUS] = STEP_TOO_SMALL
        index = -1
    return t, z, index


# ---- the loop: the driver's, on floats ---------------------------------------------------
def _push(buf, n, width):
    """``buf`` with room for row ``n`` (doubled when full)."""
    if n < buf.shape[0]:
        return buf
    grown = np.empty((2 * buf.shape[0], width))
    for i in range(buf.shape[0]):
        for j in range(width):
            grown[i, j] = buf[i, j]
    return grown


def _add_knot(kb, cnt, t, y, mode, left, right):
    """A knot (t, y, mode) with dy/dt ``right`` (2 floats) after it and ``left`` at the
    end of the interval before it."""
    n = cnt[C_NK]
    kb = _push(kb, n, KNOT_WIDTH)
    kb[n, 0], kb[n, 1], kb[n, 2], kb[n, 3] = t, y[0], y[1], mode
    kb[n, 4], kb[n, 5], kb[n, 6], kb[n, 7] = right[0], right[1], 0.0, 0.0
    if n > 0:
        kb[n - 1, 6], kb[n - 1, 7] = left[0], left[1]
    cnt[C_NK] = n + 1
    return kb


def _rate(mode, t, y, pe, p):
    """dy/dt (2 floats) in ``mode`` at (t, y)."""
    return _flow(mode, t, y[0], y[1], pe, p)


def _log_event(kb, eb, cnt, fl, y, t, after, pe, p, opt, B):
    before = cnt[C_MODE]
    same = cnt[C_NE] > 0 and abs(t - fl[F_LAST]) <= opt[2]
    cnt[C_RUN] = cnt[C_RUN] + 1 if same else 1
    cnt[C_MAX_RUN] = max(cnt[C_MAX_RUN], cnt[C_RUN])
    n = cnt[C_NE]
    eb = _push(eb, n, EVENT_WIDTH)
    eb[n, 0], eb[n, 1], eb[n, 2], eb[n, 3], eb[n, 4] = t, before, after, y[0], y[1]
    cnt[C_NE] = n + 1
    fl[F_LAST] = t
    _state_on_entry(before, after, y, p)
    if cnt[C_RUN] > int(opt[3]):
        cnt[C_STATUS] = CHATTER
        return kb, eb
    cnt[C_MODE], cnt[C_RESTARTED] = after, 1
    fl[F_H] = 0.0 if after == REST or abs(after) == OVERTURNED else fl[F_H]  # the last step tried, else fresh
    kb = _add_knot(kb, cnt, t, y, after, (0.0, 0.0), _rate(after, t, y, pe, p))
    return kb, eb


def _on_guard(kb, eb, cnt, fl, y, index, pe, p, opt, B):
    mode, t = cnt[C_MODE], fl[F_T]
    _state_at_guard(mode, index, y, p)
    after = _mode_after_guard(mode, index, t, (y[0], y[1]), pe, p)
    if after == -1:
        cnt[C_STATUS] = FLIGHT
        return kb, eb
    rate = _rate(mode, t, y, pe, p)
    kb = _add_knot(kb, cnt, t, y, mode, rate, rate)
    if after != mode:
        kb, eb = _log_event(kb, eb, cnt, fl, y, t, after, pe, p, opt, B)
    return kb, eb


def _output_step(pe, p):
    """The driver's ``output_step`` [s]: 1 / (32 w) on a sine piece, at most 1 / (32 p)."""
    w = max(pe[5] if pe[4] != 0 else 0.0, pe[10] if pe[9] != 0 else 0.0)
    return min(1.0 / (32.0 * w) if w > 0 else _INF, p[_STEP])


def _advance(kb, eb, cnt, fl, y, end, until_rest, pe, p, opt, B):
    """The driver's ``advance_to``: from ``fl[F_T]`` to ``end`` [s]."""
    turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
    while fl[F_T] < end:
        mode, t = cnt[C_MODE], fl[F_T]
        static = mode == REST or abs(mode) == OVERTURNED
        if cnt[C_STATUS] != FINISHED or (until_rest and static):
            return kb, eb
        if static:
            root, index = events.static_root(_guard_values, _guard_value, (mode, (y[0], y[1]), pe, p), t, math.nan,
                                             end)
            if index < 0:
                fl[F_T], cnt[C_RESTARTED] = end, 1
                return _add_knot(kb, cnt, end, y, mode, (0.0, 0.0), (0.0, 0.0)), eb
            fl[F_T] = root
            kb, eb = _on_guard(kb, eb, cnt, fl, y, index, pe, p, opt, B)
            turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
            continue
        if cnt[C_RESTARTED]:
            q = (y[0], y[1])
            index = events.left_at_once(_guards(mode, t, q, pe, p), _rates_at, (mode, t, q, pe, p), opt[2])
            if index >= 0:
                kb, eb = _on_guard(kb, eb, cnt, fl, y, index, pe, p, opt, B)
                turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
                if cnt[C_MODE] != mode:
                    continue
            cnt[C_RESTARTED] = 0
        target = end if math.isnan(turn) or turn <= t else turn
        if events.too_short(t, target):
            fl[F_T], cnt[C_RESTARTED] = target, 1
            continue
        t_out = min(target, t + _output_step(pe, p))
        t_new, z, root = _flow_to(t, y, t_out, mode, pe, p, opt, B, cnt, fl)
        if cnt[C_STATUS] != FINISHED:
            return kb, eb
        if root >= 0 and t_new >= end:  # left to the next piece's right-hand limits
            root, t_new = -1, t_out
        fl[F_T] = t_new
        y[0], y[1] = z[0], z[1]
        fl[F_VMAX] = max(fl[F_VMAX], abs(y[1]))
        if _contradicts(mode, (y[0], y[1]), p, opt, fl[F_VMAX]):
            cnt[C_STATUS] = INCONSISTENT
            return kb, eb
        if root < 0:
            rate = _rate(mode, t_new, y, pe, p)
            kb = _add_knot(kb, cnt, t_new, y, mode, rate, rate)
        else:
            kb, eb = _on_guard(kb, eb, cnt, fl, y, root, pe, p, opt, B)
            turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p)
    return kb, eb


def _quiet_rest(pe, p, t, end):
    """Whether REST certainly lasts from ``t`` to ``end`` [s]: a(t) is linear on the piece,
    so are its guards, and each is positive at both ends (no root between)."""
    if pe[4] != 0 or pe[9] != 0:
        return False
    g0, g1, _, g3 = _guards(REST, t, (0.0, 0.0), pe, p)
    e0, e1, _, e3 = _guards(REST, end, (0.0, 0.0), pe, p)
    return g0 > 0 and g1 > 0 and g3 > 0 and e0 > 0 and e1 > 0 and e3 > 0


def _piece(t0, h, c, directions):
    """The piece's floats from t0, h [s], its coefficients ``c`` (2, 5) and the directions."""
    return (t0, h, c[0, 0], c[0, 1], c[0, 2], c[0, 3], c[0, 4], c[1, 0], c[1, 1], c[1, 2], c[1, 3], c[1, 4],
            directions[0], directions[1])


def _piece_at(T0, H, CF, k):
    """Piece k of the motion, with the directions in which a_x and a_z move on it."""
    flat = _piece(T0[k], H[k], CF[k], (0.0, 0.0))
    return _piece(T0[k], H[k], CF[k], (np.sign(_component(flat, 0, T0[k] + H[k]) - _component(flat, 0, T0[k])),
                                       np.sign(_component(flat, 1, T0[k] + H[k]) - _component(flat, 1, T0[k]))))


def _buffers():
    """Work arrays (few, since every array an engine function takes counts references on
    each call): K (16, 2) of the steps' stages, F (7, 2) of a dense output, and rows (2,)
    of V: a stage's state, the step's start, its end, the state at a root, the error scale."""
    return np.empty((_dop853.N_STAGES_EXTENDED, 2)), np.empty((7, 2)), np.empty((5, 2))


def _run(T0, H, CF, params, options):
    """One run over the pieces (t0 (n,), h (n,) [s], CF (n, 2, 5): (p0, p1, s, w, phi) of
    a_x and a_z), ``params`` (``PARAM_FIELDS``), ``options`` (``OPTION_FIELDS``). Returns
    (outcome (7,), knots (k, 8), events (e, 5))."""
    n = T0.shape[0]
    cnt = np.zeros(10, dtype=np.int64)
    fl = np.zeros(4)
    fl[F_LAST] = math.nan
    y = np.zeros(2)
    kb = np.empty((256, KNOT_WIDTH))
    eb = np.empty((64, EVENT_WIDTH))
    B = _buffers()
    p = (params[0], params[1], params[2], params[3], params[4], params[5], params[6], params[7], params[8],
         params[9], params[10])
    opt = (options[0], options[1], options[2], options[3], options[4], options[5])
    cnt[C_MODE], cnt[C_RESTARTED] = (RELEASE if p[_THETA0] != 0 else REST), 1
    kb = _add_knot(kb, cnt, 0.0, y, cnt[C_MODE], (0.0, 0.0), (0.0, 0.0))
    until_rest = opt[4] != 0
    t_end = T0[n - 1] + H[n - 1]
    for k in range(n + 1 if until_rest else n):
        if abs(cnt[C_MODE]) == OVERTURNED:  # it lies still to the end: one knot there
            if fl[F_T] < t_end:
                fl[F_T] = t_end
                kb = _add_knot(kb, cnt, t_end, y, cnt[C_MODE], (0.0, 0.0), (0.0, 0.0))
            break
        if k < n:
            pe = _piece_at(T0, H, CF, k)
            end = T0[k + 1] if k + 1 < n else t_end
        else:  # after the excitation: a = 0
            pe = _piece(t_end, _INF, np.zeros((2, 5)), (0.0, 0.0))
            end = t_end
        rate = _rate(cnt[C_MODE], fl[F_T], y, pe, p)  # enter_piece: dy/dt after the last knot on this piece
        kb[cnt[C_NK] - 1, 4], kb[cnt[C_NK] - 1, 5] = rate[0], rate[1]
        cnt[C_RESTARTED] = 1
        if cnt[C_MODE] == REST:
            rest = _mode_at_rest(pe[0], pe, p)
            if rest != REST:
                kb, eb = _log_event(kb, eb, cnt, fl, y, pe[0], rest, pe, p, opt, B)
                if cnt[C_STATUS] != FINISHED:
                    break
        if k == n:
            if cnt[C_MODE] == REST or abs(cnt[C_MODE]) == OVERTURNED:
                break
            if opt[5] == _INF:
                cnt[C_STATUS] = NEVER_RESTS
                break
            end = fl[F_T] + opt[5]
        if cnt[C_MODE] == REST and k < n and _quiet_rest(pe, p, fl[F_T], end):  # _advance's, short
            fl[F_T], cnt[C_RESTARTED] = end, 1
            kb = _add_knot(kb, cnt, end, y, REST, (0.0, 0.0), (0.0, 0.0))
            continue
        kb, eb = _advance(kb, eb, cnt, fl, y, end, k == n, pe, p, opt, B)
        if cnt[C_STATUS] != FINISHED:
            break
        if k == n and not (cnt[C_MODE] == REST or abs(cnt[C_MODE]) == OVERTURNED):
            cnt[C_STATUS] = NO_REST
    out = np.empty(len(OUTCOME_FIELDS))
    out[0], out[1], out[2], out[3] = fl[F_T], cnt[C_MODE], cnt[C_STATUS], cnt[C_MAX_RUN]
    out[4], out[5], out[6] = cnt[C_STEPS], cnt[C_REJECTED], cnt[C_RHS]
    return out, kb[: cnt[C_NK]], eb[: cnt[C_NE]]


@functools.cache
def kernel():
    """The engine, compiled on first call (or loaded from numba's disk cache, keyed by
    the sources of this module and of the ones it compiles):
    ``run(T0, H, CF, params, options) -> (outcome, knots, events)`` (see :func:`_run`)."""
    _register()
    fingerprint = hashlib.sha256(b"".join(pathlib.Path(m.__file__).read_bytes() for m in _SHARED)).hexdigest()

    def run(T0, H, CF, params, options):
        fingerprint  # noqa: B018 -- numba keys its disk cache by the closure's contents
        return _run(T0, H, CF, params, options)

    return numba.njit(cache=True, nogil=True, **_OPTIONS)(run)


_OPTIONS = dict(error_model="numpy")
#: inlined where called (numba's IR): the steps' right-hand side, whose array arguments'
#: reference counts then cancel
_INLINE = ("_rhs",)
_RULES = (rules, sys.modules[__name__])
#: modules whose functions the engine compiles besides its own
_SHARED = (_pieces, _dop853, xp, events, sys.modules[rest_mode.__module__], *_RULES)


def _register():
    """Let numba compile this module's plain functions, the rules' and the excitation's
    closed forms where the entry point calls them (``register_jitable``; they stay plain
    Python)."""
    register_jitable(**_OPTIONS)(rest_mode)
    for module in (_pieces, *_RULES):
        for _, fn in inspect.getmembers(module, inspect.isfunction):
            if fn.__module__ == module.__name__ and fn.__name__ not in ("kernel", "_register"):
                register_jitable(**_OPTIONS, **({"inline": "always"} if fn.__name__ in _INLINE else {}))(fn)
