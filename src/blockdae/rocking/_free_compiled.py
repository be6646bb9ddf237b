"""The complete free-standing block's compiled flow: its modes integrated between events,
compiled with numba, on records and on sine pieces, horizontal and vertical.

The kernel runs the hybrid driver's loop (:mod:`blockdae.core._driver`) over the pieces of
the base's motion. It takes the commonest events itself, as the driver would with the
model's rules (:func:`_take_event`: the apex of a rocking arc, and a sticking impact after
which the block rocks on about the corner struck), and hands back to Python
(:mod:`._free_engine`) where any other decision is needed, which the driver's own event
code then takes, unchanged: any other guard root located (the mode after it, the state on
its guard and on entry: the landings, the slips, the Zeno tails), a block at rest whose
piece starts a motion, and a mode entered with a guard at or below zero (whether it is
left at once).

Per mode:

* REST: the state is constant; the guards depend on time alone and are located by
  bisection to adjacent floats (:func:`blockdae.core.events.static_root`), as the driver
  does; a linear piece with every guard positive at both ends has none;
* OVERTURNED: terminal, no guard;
* SLIDE, ROCK (out, in, beyond alpha), SLIDE_ROCK, FLIGHT and the Zeno tail (SETTLE):
  DOP853 (:mod:`blockdae.solvers.dop853`) at the backend's tolerances. A guard that goes
  from > 0 to <= 0 over a step is located by bisection to adjacent floats on the step's
  dense output (the state there, a(t) at the time); the state at the root is a step of
  the same method from the step's start. The step stops where x'' (sliding) or theta''
  (rocking) at the frozen state turns, and knots are at most 1 / (32 w) and 1 / (32 p)
  apart, as the driver's.

The flows and the guards are the model's (:mod:`._free_rules`, on the laws of
:mod:`._slide_rock_laws`), compiled here; every decision at an event is the model's.

State (8,): (x, z, theta, x', z', theta', base work, friction work) in the model's layout
(a slide-rock's x, x' its pivot's, a flight's its reference corner's).
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
from ..core.contract import RATE_STEP as _RATE_STEP
from ..solvers import dop853 as _dop853, xp_scalar as xp
from . import _compiled as rocking
from . import _free_rules as free_rules
from . import _rules as rules
from . import _slide_rock_laws as laws
from ._compiled import _component, _piece, _piece_at, _push

N = 8
THETA, X_RATE, Z_RATE, THETA_RATE = 2, 3, 4, 5
#: kinds (|mode|, :class:`FreeMode`): rest, slide, rock out, in, beyond alpha, overturned,
#: slide-rock slipping toward its pivot's side and back
REST, SLIDE, OUT, IN, BEYOND, OVERTURNED, SLIDE_ROCK_OWN, SLIDE_ROCK_BACK = 0, 1, 2, 3, 4, 6, 7, 8
#: entries of ``params``: b, h [m], mu, mu_k [-], g [m/s²], R [m], alpha [rad], b/h [-],
#: the knots' spacing 1 / (32 p) [s], the contradiction floors RATE_FLOOR p alpha [rad/s]
#: and RATE_FLOOR p R [m/s], the Zeno arc [s]
PARAM_FIELDS = ("b", "h", "mu", "mu_k", "g", "R", "alpha", "lam", "output_step", "theta_floor", "speed_floor",
                "zeno_arc")
_B, _H, _MU, _MUK, _G, _R, _ALPHA, _LAM, _STEP, _THETA_FLOOR, _SPEED_FLOOR, _ZENO_ARC = range(12)
#: entries of ``options``: rtol [-], atol [the states' units]
OPTION_FIELDS = ("rtol", "atol")
#: counters (int64): the piece, the mode, restarted (0/1), the piece entered (0/1), knots,
#: steps, rejected steps, right-hand-side calls (in this order: the DOP853 flow's counts),
#: running after the excitation (0/1), the events taken in the kernel (rows of its event
#: buffer), the driver's run of events at one instant, its longest run, its cap
#: (max_events_at_one_instant)
C_PIECE, C_MODE, C_RESTARTED, C_ENTERED, C_NK, C_STEPS, C_REJECTED, C_RHS, C_TAIL, C_NE, C_RUN, C_MAX_RUN, C_CAP = \
    range(13)
N_COUNTERS = 13
#: floats: time [s], largest speed [m/s], the step to try [s], the tail's end [s], the last
#: event's time [s] (nan: none yet), the event resolution [s]
F_T, F_VMAX, F_H, F_END, F_LAST_EVENT, F_RESOLUTION = range(6)
#: what a call of the kernel stopped at: the last piece done (or the tail at rest); guard
#: ``index`` reached zero at F_T; a block at rest whose piece may start a motion; a mode
#: (re)started with a guard at or below zero; the state contradicts its mode; the tail's
#: bound is needed; a step below rounding
DONE, GUARD, ENTRY, RESTART, INCONSISTENT, BOUND, STEP_TOO_SMALL = range(7)
#: knot rows: t, y (8), mode after, dy/dt after (8), dy/dt before the next knot (8)
KNOT_WIDTH = 2 + 3 * N
_Y, _MODE_COL, _RIGHT, _LEFT = 1, 1 + N, 2 + N, 2 + 2 * N
#: event rows (the events the kernel takes itself): t, mode before, mode after, y (8) as
#: the driver's ``log_event`` gets them, the state entered (8) (both the centroid's: the
#: kernel takes events of rocking and impact modes only)
EVENT_WIDTH = 3 + 2 * N
#: FreeMode's instant mode of a sticking impact on corner +b (its sign the corner)
IMPACT_STICK = 10
#: guards per mode, +inf where a mode has fewer
N_GUARDS = 5
_INF = math.inf
_NO_GUARDS = (_INF, _INF, _INF, _INF, _INF)


def _side(mode):
    return 1 if mode > 0 else -1


def _rocks(kind):
    return kind == OUT or kind == IN or kind == BEYOND


def _slip_direction(mode):
    """sigma of a slide-rock (kind 7: its pivot's side, 8: the other)."""
    kind, s = abs(mode), _side(mode)
    return s if kind == SLIDE_ROCK_OWN else -s


def _is_static(mode):
    return mode == REST or abs(mode) == OVERTURNED


# ---- the model's flow and guards on floats ----------------------------------------------
def _base(t, pe, p):
    """(a_x, g_e) [m/s²] at ``t``."""
    return _component(pe, 0, t), p[_G] + _component(pe, 1, t)


def _flow(mode, t, y, pe, p, out):
    """dy/dt in ``mode`` into ``out`` (8,) (:func:`._free_rules.flow_values`)."""
    ax, ge = _base(t, pe, p)
    values = free_rules.flow_values(mode, y, ax, ge, p[_G], p[_B], p[_H], p[_R], p[_ALPHA], p[_MUK], xp)
    for i in range(N):
        out[i] = values[i]


def _rhs(t, y, args, out):
    """:func:`_flow` as the steps' right-hand side (args: (mode, pe, p))."""
    mode, pe, p = args
    _flow(mode, t, y, pe, p, out)


def _guards(mode, t, y, pe, p):
    """The guards of ``mode`` at (t, y), +inf past its own (:func:`._free_rules.guard_values`)."""
    ax, ge = _base(t, pe, p)
    return free_rules.guard_values(mode, t, y, ax, ge, p[_B], p[_H], p[_R], p[_ALPHA], p[_MU], p[_MUK], xp)


def _turn_value(args, t):
    """(x'' sliding, theta'' rocking at the frozen state, whether the mode has it) (the
    model's ``turn_rate``); dy/dt at ``t_known`` is ``known`` already."""
    mode, y, pe, p, work, t_known, known = args
    kind = abs(mode)
    if kind == SLIDE or _rocks(kind):
        rate = known if t == t_known else work
        if t != t_known:
            _flow(mode, t, y, pe, p, work)
        return (rate[X_RATE] if kind == SLIDE else rate[THETA_RATE]), True
    return 0.0, False


def _next_turn(mode, t, y, end, pe, p, work, rate_known, rate):
    """Where the turn rate changes sign in (t, end), else nan (the driver's ``turning_point``);
    ``rate_known``: dy/dt at (t, y) is ``rate`` already."""
    return events.turning_point(_turn_value, (mode, y, pe, p, work, t if rate_known else math.nan, rate), t, end)


_static_guards, _static_guard = events.of_time(_guards)


def _dense_guard(args, t_mid):
    """Guard ``index`` of ``mode`` on the step's dense output at ``t_mid`` [s] (args: (F, y,
    t, hh, mode, index, pe, p, work))."""
    F, y, t, hh, mode, index, pe, p, work = args
    _dop853.dense_state(F, y, (t_mid - t) / hh, work)
    return _guards(mode, t_mid, work, pe, p)[index]


def _speed(y, p):
    """max(|x'|, |z'|, R |theta'|) [m/s] (the model's ``speed``)."""
    return max(abs(y[X_RATE]), abs(y[Z_RATE]), p[_R] * abs(y[THETA_RATE]))


def _contradicts(mode, y, p, opt, v_max):
    """Whether a slide, a slip or a rotation points against its mode beyond the velocity
    error (the model's ``contradiction``, which then names it)."""
    kind, s = abs(mode), _side(mode)
    tolerance = events.velocity_error(opt[0], opt[1], v_max) + events.ROUNDING * v_max
    speed_error, rate_error = max(tolerance, p[_SPEED_FLOOR]), max(tolerance, p[_THETA_FLOOR])
    if kind == SLIDE:
        return s * y[X_RATE] < -speed_error
    if kind == SLIDE_ROCK_OWN or kind == SLIDE_ROCK_BACK:
        return _slip_direction(mode) * y[X_RATE] < -speed_error
    if kind == OUT or kind == BEYOND:
        return s * y[THETA_RATE] < -rate_error
    return kind == IN and s * y[THETA_RATE] > rate_error


# ---- a mode's flow to its first guard root -----------------------------------------------
_step, _initial_step, _dense_coefficients = _dop853.for_flow(_rhs)


#: golden-section steps for the highest point of a guard on a step: below 1e-16 of it
_MAXIMUM_STEPS = 80
_GOLDEN = 0.5 * (math.sqrt(5.0) - 1.0)


def _dense_maximum(args, lo, hi):
    """Where a guard on the step's dense output (one arc: rising, then falling) is highest
    in [lo, hi] [s], by golden-section search."""
    a, b = hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo)
    fa, fb = _dense_guard(args, a), _dense_guard(args, b)
    for _ in range(_MAXIMUM_STEPS):
        if fa < fb:
            lo, a, fa = a, b, fb
            b = lo + _GOLDEN * (hi - lo)
            fb = _dense_guard(args, b)
        else:
            hi, b, fb = b, a, fa
            a = hi - _GOLDEN * (hi - lo)
            fa = _dense_guard(args, a)
        if not lo < a < b < hi:
            break
    return a if fa >= fb else b


def _first_root(root_args, start, t, y, t_new, y_new, hh, K):
    """The first guard root in (t, t_new] of the step just taken from (t, y) (its stages in
    ``K``, the guards at its start ``start``; root_args: (mode, pe, p, F, work, cnt)):
    (time, index, the guards at its end), index -1 and time nan where there is none; a
    guard that goes from > 0 to <= 0 over the step, located on its dense output. A guard
    that starts at zero (the mode entered on it: the arc of a slide-rock from its impact)
    and ends below is located from its highest point on the step where that is above zero,
    as CVODE looks past a root function that starts at zero."""
    mode, pe, p, F, work, cnt = root_args
    end = _guards(mode, t_new, y_new, pe, p)
    dense = False
    best, index = _INF, -1
    for j in range(N_GUARDS):
        if not (start[j] >= 0 and start[j] < _INF and end[j] <= 0):
            continue
        if not dense:
            _dense_coefficients((mode, pe, p), t, y, y_new, hh, K, F, work)
            cnt[C_RHS] += 3
            dense = True
        args = (F, y, t, hh, mode, j, pe, p, work)
        lo, hi = t, t_new
        if start[j] == 0:  # entered on it (a slide-rock's impact): from its highest point, if above zero
            lo = _dense_maximum(args, t, t_new)
            if not _dense_guard(args, lo) > 0:
                continue
        root = events.first_nonpositive(_dense_guard, args, lo, hi)
        if root < best:
            best, index = root, j
    return (best, index, end) if index >= 0 else (math.nan, -1, end)


_integrate = _dop853.to_first_root(_step, _initial_step, _first_root)


def _flow_to(t, y, stop, mode, pe, p, opt, B, cnt, fl, rate_known, guards_known, start):
    """Integrate ``mode`` from (t, y) to ``stop`` [s] or to its first guard root before it:
    (time, state, guard index or -1, -2 where a step fell below rounding). The step to try
    is kept in ``fl[F_H]``. ``rate_known``: dy/dt at (t, y) is in ``B``'s rate row already;
    ``guards_known``: the guards there are ``start``."""
    K, F, V = B
    work, y_cur, y_new, z, scale = V[0], V[1], V[2], V[3], V[4]
    args = (mode, pe, p)
    for i in range(N):
        y_cur[i] = y[i]
    if rate_known:
        for i in range(N):
            K[0, i] = V[5, i]
    else:
        _rhs(t, y_cur, args, K[0])
        cnt[C_RHS] += 1
    if not guards_known:
        start = _guards(mode, t, y_cur, pe, p)
    t, z, index, h = _integrate(args, (mode, pe, p, F, work, cnt), start, t, y_cur, stop, fl[F_H], opt[0], opt[1], K,
                                y_new, z, work, scale, cnt[C_STEPS:C_RHS + 1])
    fl[F_H] = h
    return t, z, index


# ---- the driver's commonest events, taken in the kernel -------------------------------------
def _difference_rates(mode, index, t, y, pe, p, V):
    """(rate, curvature) of guard ``index`` of ``mode`` at (t, y) by the backward differences
    of :func:`blockdae.core.contract.difference_rates` (step RATE_STEP), on the same flow
    and guards."""
    rate, rate_back, back, accel = V[0], V[1], V[2], V[3]
    h = _RATE_STEP
    _flow(mode, t, y, pe, p, rate)
    for i in range(N):
        back[i] = y[i] - h * rate[i]
    _flow(mode, t - h, back, pe, p, rate_back)
    for i in range(N):
        accel[i] = (rate[i] - rate_back[i]) / h
    g0 = _guards(mode, t, y, pe, p)[index]
    for i in range(N):
        back[i] = y[i] - h * rate[i] + 0.5 * h**2 * accel[i]
    g1 = _guards(mode, t - h, back, pe, p)[index]
    for i in range(N):
        back[i] = y[i] - 2 * h * rate[i] + 2 * h**2 * accel[i]
    g2 = _guards(mode, t - 2 * h, back, pe, p)[index]
    return (3 * g0 - 4 * g1 + g2) / (2 * h), (g0 - 2 * g1 + g2) / h**2


def _log_event(t, before, after, y, entered, cnt, fl, eb):
    """The driver's ``log_event``'s count of events at one instant and its record (the
    state ``y`` before the entry, ``entered`` after it); the event buffer, grown where full."""
    last = fl[F_LAST_EVENT]
    same_instant = not math.isnan(last) and abs(t - last) <= fl[F_RESOLUTION]
    cnt[C_RUN] = cnt[C_RUN] + 1 if same_instant else 1
    cnt[C_MAX_RUN] = max(cnt[C_MAX_RUN], cnt[C_RUN])
    fl[F_LAST_EVENT] = t
    n = cnt[C_NE]
    eb = _push(eb, n, EVENT_WIDTH)
    eb[n, 0], eb[n, 1], eb[n, 2] = t, before, after
    for i in range(N):
        eb[n, 3 + i], eb[n, 3 + N + i] = y[i], entered[i]
    cnt[C_NE] = n + 1
    return eb


def _runs_within(t, n_events, cnt, fl):
    """Whether ``n_events`` more events at ``t`` stay within the driver's cap on events at
    one instant (else the driver's own code takes them, and raises)."""
    last = fl[F_LAST_EVENT]
    run = cnt[C_RUN] if not math.isnan(last) and abs(t - last) <= fl[F_RESOLUTION] else 0
    return run + n_events <= cnt[C_CAP]


def _pivot(s, y, theta, rate, p, out):
    values = free_rules.pivot_state(s, y, theta, rate, p[_R], p[_ALPHA], xp)
    for i in range(N):
        out[i] = values[i]


def _take_event(mode, index, t, y, pe, p, cnt, fl, kb, eb, V):
    """Guard ``index`` of ``mode`` reached zero at (t, y): where it is an apex (OUT or BEYOND
    to IN) or a sticking impact of a rocking block that rocks on about the corner struck
    (IN to the impact's instant mode to OUT), take it as the driver's ``on_guard``,
    ``log_event`` and ``guard_left_at_once`` would, with the model's rules: the same states,
    knots, events and modes. (knots, events, whether it was taken); nothing is changed
    where it was not (the driver's own code takes it then)."""
    kind, s = abs(mode), _side(mode)
    on, jumped, entered, work, rate = V[6], V[7], V[8], V[9], V[5]
    if index != 0 or not _rocks(kind):
        return kb, eb, False
    if kind == IN:  # the impact: the state on the guard (theta = 0), the corner struck
        _pivot(s, y, 0.0 * y[THETA] + 0.0, y[THETA_RATE], p, on)
        c, _, _, _, sticks, _, _ = laws.landing(on[THETA], on[X_RATE], on[Z_RATE], on[THETA_RATE], p[_B], p[_H],
                                                p[_MU], p[_MUK])
        if c == 0 or not sticks or not _runs_within(t, 2, cnt, fl):
            return kb, eb, False
        x_rate, z_rate, theta_rate, _, _ = laws.impact_jump(c, True, on[THETA], on[X_RATE], on[Z_RATE],
                                                            on[THETA_RATE], p[_B], p[_H], p[_MUK], xp)
        for i in range(N):
            jumped[i] = on[i]
        jumped[X_RATE], jumped[Z_RATE], jumped[THETA_RATE] = x_rate, z_rate, theta_rate
        ax, ge = _base(t, pe, p)
        after_kind, _, _ = laws.mode_after_impact(c, jumped[THETA], jumped[X_RATE], jumped[Z_RATE],
                                                   jumped[THETA_RATE], True, ax, ge, p[_B], p[_H], p[_MU], p[_MUK])
        if after_kind != laws.ROCK or not c * jumped[THETA_RATE] > 0 or not c * jumped[THETA] < p[_ALPHA]:
            return kb, eb, False
        if free_rules.settles(c, jumped[THETA_RATE], ax, ge, p[_R], p[_ALPHA], p[_ZENO_ARC], xp):
            return kb, eb, False
        after = OUT * c
        _pivot(c, jumped, jumped[THETA], jumped[THETA_RATE], p, entered)
        values = _guards(after, t, entered, pe, p)
        for j in range(N_GUARDS):
            if not values[j] > 0:
                return kb, eb, False
        instant = IMPACT_STICK * c
        _flow(mode, t, on, pe, p, rate)
        kb = add_knot(kb, cnt, t, on, mode, rate, rate)
        eb = _log_event(t, mode, instant, on, jumped, cnt, fl, eb)
        for i in range(N):
            rate[i] = 0.0
        kb = add_knot(kb, cnt, t, jumped, instant, rate, rate)
        kb = add_knot(kb, cnt, t, jumped, instant, rate, rate)
        eb = _log_event(t, instant, after, jumped, entered, cnt, fl, eb)
    else:  # the apex: theta' = 0 on the guard, falling back
        _pivot(s, y, y[THETA], 0.0 * y[THETA_RATE], p, on)
        after = rules.mode_after_rocking_guard(kind, s, index, on[THETA], 0.0, 0.0, 0.0, p[_ALPHA], p[_ZENO_ARC])
        if after == rules.DEMAND_DECIDES or abs(after) != IN or not _runs_within(t, 1, cnt, fl):
            return kb, eb, False
        _pivot(s, on, on[THETA], on[THETA_RATE], p, entered)
        values = _guards(after, t, entered, pe, p)
        for j in range(N_GUARDS):
            if values[j] < 0 or (values[j] == 0 and j >= 2):
                return kb, eb, False
            if values[j] == 0:
                slope, curvature = _difference_rates(after, j, t, entered, pe, p, V[10:])
                if events.falls(slope, curvature, fl[F_RESOLUTION]):
                    return kb, eb, False
        _flow(mode, t, on, pe, p, rate)
        kb = add_knot(kb, cnt, t, on, mode, rate, rate)
        eb = _log_event(t, mode, after, on, entered, cnt, fl, eb)
    for i in range(N):
        work[i] = 0.0
        y[i] = entered[i]
    _flow(after, t, y, pe, p, rate)
    kb = add_knot(kb, cnt, t, y, after, work, rate)
    cnt[C_MODE], cnt[C_RESTARTED] = after, 0
    return kb, eb, True


# ---- the driver's loop on floats -----------------------------------------------------------
def add_knot(kb, cnt, t, y, mode, left, right):
    """A knot (t, y, mode) with dy/dt ``right`` (8,) after it and ``left`` (8,) at the end
    of the interval before it; ``kb`` grown where full."""
    n = cnt[C_NK]
    kb = _push(kb, n, KNOT_WIDTH)
    kb[n, 0], kb[n, _MODE_COL] = t, mode
    for i in range(N):
        kb[n, _Y + i], kb[n, _RIGHT + i], kb[n, _LEFT + i] = y[i], right[i], 0.0
        if n > 0:
            kb[n - 1, _LEFT + i] = left[i]
    cnt[C_NK] = n + 1
    return kb


def _output_step(pe, p):
    """The driver's ``output_step`` [s]: 1 / (32 w) on a sine piece, at most 1 / (32 p)."""
    w = max(pe[5] if pe[4] != 0 else 0.0, pe[10] if pe[9] != 0 else 0.0)
    return min(1.0 / (32.0 * w) if w > 0 else _INF, p[_STEP])


def _quiet_rest(y, pe, p, t, end):
    """Whether REST certainly lasts from ``t`` to ``end`` [s]: a(t) is linear on the piece,
    so are its guards, and each is positive at both ends."""
    if pe[4] != 0 or pe[9] != 0:
        return False
    g0, g1, g2, _, _ = _guards(REST, t, y, pe, p)
    e0, e1, e2, _, _ = _guards(REST, end, y, pe, p)
    return g0 > 0 and g1 > 0 and g2 > 0 and e0 > 0 and e1 > 0 and e2 > 0


def _advance(T0, H, CF, p, opt, cnt, fl, y, kb, eb, B):
    """The driver's pieces and ``advance_to`` from ``fl[F_T]`` in piece ``cnt[C_PIECE]``
    until the model is needed or the last piece ends, taking the commonest events itself
    (:func:`_take_event`): (knots, events, what it stopped at, guard index)."""
    K, F, V = B
    rate = V[5]
    n = T0.shape[0]
    tail = cnt[C_TAIL] != 0
    while cnt[C_PIECE] < n:
        k = cnt[C_PIECE]
        pe = _piece_at(T0, H, CF, k) if not tail else _piece(T0[k], _INF, CF[k], (0.0, 0.0))
        end = T0[k + 1] if k + 1 < n else (fl[F_END] if tail else T0[k] + H[k])
        rate_known = False  # dy/dt at (t, y) in rate
        if cnt[C_ENTERED] == 0:  # enter_piece
            cnt[C_ENTERED], cnt[C_RESTARTED], rate_known = 1, 1, True
            _flow(cnt[C_MODE], fl[F_T], y, pe, p, rate)
            for i in range(N):
                kb[cnt[C_NK] - 1, _RIGHT + i] = rate[i]
            mode = cnt[C_MODE]
            if mode == REST or (abs(mode) == SLIDE and y[X_RATE] == 0):
                ax, ge = _base(pe[0], pe, p)
                kind, _ = laws.rest_mode(ax, ge, p[_LAM], p[_MU], p[_MUK], rocking._component_rate(pe, 0, pe[0]),
                                         rocking._component_rate(pe, 1, pe[0]))
                if mode != REST or kind != laws.REST:
                    return kb, eb, ENTRY, -1
        if tail:  # the driver's tail_to_rest
            if _is_static(cnt[C_MODE]):
                return kb, eb, DONE, -1
            if math.isnan(fl[F_END]):
                return kb, eb, BOUND, -1
            end = fl[F_END]
        turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p, V[14], rate_known, rate)
        while fl[F_T] < end:
            mode, t = cnt[C_MODE], fl[F_T]
            if tail and _is_static(mode):
                return kb, eb, DONE, -1
            if _is_static(mode):
                if mode == REST and _quiet_rest(y, pe, p, t, end):
                    root, index = math.nan, -1
                else:
                    root, index = events.static_root(_static_guards, _static_guard, (mode, y, pe, p), t, math.nan,
                                                     end)
                if index < 0:
                    fl[F_T], cnt[C_RESTARTED] = end, 1
                    for i in range(N):
                        rate[i] = 0.0
                    kb = add_knot(kb, cnt, end, y, mode, rate, rate)
                    break
                fl[F_T] = root
                return kb, eb, GUARD, index
            guards_known, values = False, _NO_GUARDS
            if cnt[C_RESTARTED]:
                values = _guards(mode, t, y, pe, p)
                for j in range(N_GUARDS):
                    if values[j] <= 0:
                        return kb, eb, RESTART, -1
                cnt[C_RESTARTED], guards_known = 0, True
            target = end if math.isnan(turn) or turn <= t else turn
            if events.too_short(t, target):
                fl[F_T], cnt[C_RESTARTED], rate_known = target, 1, False
                continue
            t_out = min(target, t + _output_step(pe, p))
            t_new, z, root = _flow_to(t, y, t_out, mode, pe, p, opt, B, cnt, fl, rate_known, guards_known, values)
            if root == -2:
                return kb, eb, STEP_TOO_SMALL, -1
            if root >= 0 and t_new >= end:  # left to the next piece's right-hand limits
                root, t_new = -1, t_out
            fl[F_T] = t_new
            for i in range(N):
                y[i] = z[i]
            fl[F_VMAX] = max(fl[F_VMAX], _speed(y, p))
            if _contradicts(mode, y, p, opt, fl[F_VMAX]):
                return kb, eb, INCONSISTENT, -1
            if root >= 0:
                kb, eb, taken = _take_event(mode, root, t_new, y, pe, p, cnt, fl, kb, eb, V)
                if not taken:
                    return kb, eb, GUARD, root
                rate_known = True  # the mode entered's dy/dt (_take_event)
                turn = _next_turn(cnt[C_MODE], fl[F_T], y, end, pe, p, V[14], rate_known, rate)
                continue
            _flow(mode, t_new, y, pe, p, rate)
            kb = add_knot(kb, cnt, t_new, y, mode, rate, rate)
            rate_known = True
        cnt[C_PIECE] = k + 1
        cnt[C_ENTERED] = 0
    return kb, eb, DONE, -1


def _buffers():
    """Work arrays: K (16, 8) of the steps' stages, F (7, 8) of a dense output, and rows
    (8,) of V: a stage's state, the step's start, its end, the state at a root, the error
    scale, a rate, eight for the events taken in the kernel (:func:`_take_event`) and the
    turning point's."""
    return np.empty((_dop853.N_STAGES_EXTENDED, N)), np.empty((7, N)), np.empty((15, N))


def _run(T0, H, CF, params, options, cnt, fl, y, kb, eb):
    """Advance from where ``cnt``, ``fl`` and ``y`` stand over the pieces (t0 (n,), h (n,)
    [s], CF (n, 2, 5): (p0, p1, s, w, phi) of a_x and a_z), ``params``
    (:data:`PARAM_FIELDS`), ``options`` (:data:`OPTION_FIELDS`), knots in ``kb`` (k, 26),
    the events taken in the kernel in ``eb`` (k, 19): (knots, events, what it stopped at,
    guard index)."""
    p = (params[0], params[1], params[2], params[3], params[4], params[5], params[6], params[7], params[8],
         params[9], params[10], params[11])
    opt = (options[0], options[1])
    return _advance(T0, H, CF, p, opt, cnt, fl, y, kb, eb, _buffers())


@functools.cache
def kernel():
    """The kernel, compiled on first call (or loaded from numba's disk cache, keyed by the
    sources of this module and of the ones it compiles):
    ``run(T0, H, CF, params, options, cnt, fl, y, kb, eb) -> (knots, events, stop, index)``
    (:func:`_run`)."""
    _register()
    fingerprint = hashlib.sha256(b"".join(pathlib.Path(m.__file__).read_bytes() for m in _SHARED)).hexdigest()

    def run(T0, H, CF, params, options, cnt, fl, y, kb, eb):
        fingerprint  # noqa: B018 -- numba keys its disk cache by the closure's contents
        return _run(T0, H, CF, params, options, cnt, fl, y, kb, eb)

    return numba.njit(cache=True, nogil=True, **_OPTIONS)(run)


_OPTIONS = dict(error_model="numpy")
_INLINE = ("_rhs",)
#: modules whose functions the engine compiles besides its own
_SHARED = (rocking, laws, free_rules, *rocking._SHARED)


def _register():
    """Let numba compile this module's plain functions and the laws' where the kernel calls
    them (``register_jitable``; they stay plain Python), with the rocking engine's."""
    rocking._register()
    for module in (laws, free_rules, sys.modules[__name__]):
        for _, fn in inspect.getmembers(module, inspect.isfunction):
            if fn.__module__ == module.__name__ and fn.__name__ not in ("kernel", "_register"):
                register_jitable(**_OPTIONS, **({"inline": "always"} if fn.__name__ in _INLINE else {}))(fn)
