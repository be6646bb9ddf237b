"""The compiled exact engine for hybrid models whose every mode is linear.

A model opts in by declaring its modes as tables (:class:`LinearModes`): in mode m the
state (u, u') obeys u'' + c_m u' + k_m u = b_m - a(t), guard j of mode m is
alpha u + beta u' + gamma (left as it falls through zero), reaching it resets the state
to R y + r and enters ``next_mode[m, j]``. The engine knows no model by name.

On a piece of a record, a(tau) = p0 + p1 tau, and the motion from (u, u') is in closed
form (the underdamped oscillator or, with k = c = 0, a cubic), as in
:mod:`._closed_form_linear`, whose Python steps on the generic driver stay the
reference. Each guard's first downward crossing is found the same way: an interval is
kept only where bounds of the guard's first three derivatives fail to show that it stays
of one sign, is monotone or is convex/concave, bisected otherwise, and a crossing in a
monotone part is refined by bisection to adjacent floats (the interval test, the
bisections and the graze rule are :mod:`blockdae.core.events`). The driver's rules are
those of :mod:`blockdae.core._driver`: a guard at zero and falling as a mode starts is left
at once (unless it turns back within the event resolution), a guard reaching zero at the
end of a piece is left to the next piece, and more than ``max_events`` events within the
event resolution are chatter, an error. Compiled with numba, cached on disk.
"""

import functools
import math

import numba
import numpy as np
from numba.extending import register_jitable

from ..core import falls, first_nonpositive, one_sign, sign_change

_EPS = float(np.finfo(float).eps)
#: most intervals one root search may examine; more is reported (outcome ``failed``)
MAX_INTERVALS = 10_000
#: intervals the depth-first root search may hold at once: it halves an interval down to
#: a few ulps of the time, about 60 levels deep, holding one pending interval per level
STACK_DEPTH = 256
#: events closer than this are one instant [s] (as the Python closed-form path)
EVENT_RESOLUTION = 1e-12
#: most events at one instant before the run stops as chatter
MAX_EVENTS_AT_ONE_INSTANT = 5
#: entries of a run's outcome
OUTCOME_FIELDS = ("u", "u_rate", "mode", "n_events", "max_u_at_events", "t_first_event", "u_rate_first_event",
                  "status", "max_events_at_one_instant")
#: outcome ``status``: finished, chatter, a root search that did not settle, log full
FINISHED, CHATTER, UNSETTLED, LOG_FULL = 0, 1, 2, 3
#: columns of the knot log: time [s], u [m], u' [m/s], mode after, mode before, is an event
KNOT_FIELDS = ("t", "u", "u_rate", "mode", "mode_before", "is_event")


# ---- closed forms: u(tau) = q0 + q1 tau + q2 tau² + q3 tau³ + e^{-s tau} (C cos w tau + D sin w tau)
@register_jitable
def piece_form(k, c, b, w, p0, p1, u, v):
    """The form of u'' + c u' + k u = b - (p0 + p1 tau) from (u, u') at tau = 0; ``w``:
    the damped frequency sqrt(k - c²/4) [rad/s]."""
    if k > 0:
        sigma = 0.5 * c
        a1 = -p1 / k
        a0 = (b - p0 - c * a1) / k
        C = u - a0
        D = (v - a1 + sigma * C) / w
        return (a0, a1, 0.0, 0.0, C, D, sigma, w)
    return (u, v, 0.5 * (b - p0), -p1 / 6.0, 0.0, 0.0, 0.0, 0.0)


@register_jitable
def form_derivative(f):
    q0, q1, q2, q3, C, D, s, w = f
    return (q1, 2.0 * q2, 3.0 * q3, 0.0, -s * C + w * D, -s * D - w * C, s, w)


@register_jitable
def combine_forms(alpha, f, beta, g, gamma):
    """alpha f + beta g + gamma (f, g with the same exponent and frequency)."""
    return (alpha * f[0] + beta * g[0] + gamma, alpha * f[1] + beta * g[1], alpha * f[2] + beta * g[2],
            alpha * f[3] + beta * g[3], alpha * f[4] + beta * g[4], alpha * f[5] + beta * g[5], f[6], f[7])


@register_jitable
def evaluate_form(f, tau):
    value = ((f[3] * tau + f[2]) * tau + f[1]) * tau + f[0]
    if f[4] != 0.0 or f[5] != 0.0:
        value += math.exp(-f[6] * tau) * (f[4] * math.cos(f[7] * tau) + f[5] * math.sin(f[7] * tau))
    return value


@register_jitable
def evaluate_form_at(f, tau, decay, cos, sin):
    """f(tau) with exp(-sigma tau), cos and sin(w tau) given."""
    return ((f[3] * tau + f[2]) * tau + f[1]) * tau + f[0] + decay * (f[4] * cos + f[5] * sin)


@register_jitable
def form_bound(f, a, b):
    """An upper bound of |f| on [a, b], 0 <= a <= b, term by term."""
    poly = abs(f[0]) + abs(f[1]) * b + abs(f[2]) * b * b + abs(f[3]) * b * b * b
    decay = 1.0 if a == 0 else math.exp(-f[6] * a)
    return (poly + math.sqrt(f[4] * f[4] + f[5] * f[5]) * decay) * (1 + 8 * _EPS)


@register_jitable
def form_rounding(f, tau):
    """The rounding error of f(tau): a few ulps of the sum of its terms' sizes."""
    poly = abs(f[0]) + abs(f[1] * tau) + abs(f[2] * tau * tau) + abs(f[3] * tau * tau * tau)
    return 8 * _EPS * (poly + math.exp(-f[6] * tau) * (abs(f[4]) + abs(f[5])))


@register_jitable
def _monotone_part(f, lo, f_lo, hi, f_hi, decreasing):
    """The crossing on [lo, hi] where f is monotone (nan: none). f must fall below zero by
    more than its rounding: a dip within rounding (a touch at a minimum, computed an ulp
    low) is no crossing; one that goes on falls past hi, where the next window or piece
    finds it at once."""
    if not decreasing or not (f_lo > 0 > f_hi) or f_hi >= -form_rounding(f, hi):
        return math.nan
    return first_nonpositive(evaluate_form, f, lo, hi)


@register_jitable
def _first_down_crossing(f, f1, f2, f3, a, b, origin, stack):
    """The first tau in [a, b] [s] where f falls to <= 0 (nan: none; -inf: the search did
    not settle). ``stack``: scratch (STACK_DEPTH, 4)."""
    resolution = 4 * _EPS * max(abs(origin) + abs(b), 1.0)
    if evaluate_form(f, a) <= 0 and falls(evaluate_form(f1, a), evaluate_form(f2, a), resolution):
        return a
    return _down_crossing_search(f, f1, f2, f3, a, b, origin, stack)


@register_jitable
def _down_crossing_search(f, f1, f2, f3, a, b, origin, stack):
    """:func:`_first_down_crossing` without its test at ``a``: for a caller that has
    decided with its own resolution whether a guard at zero there is left at once."""
    resolution = 4 * _EPS * max(abs(origin) + abs(b), 1.0)
    top = 0
    stack[0, 0], stack[0, 1], stack[0, 2], stack[0, 3] = a, evaluate_form(f, a), b, evaluate_form(f, b)
    budget = MAX_INTERVALS
    while top >= 0:
        lo, f_lo, hi, f_hi = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3]
        top -= 1
        budget -= 1
        if budget < 0:
            return -math.inf
        length = hi - lo
        if one_sign(f_lo, f_hi, form_bound(f1, lo, hi), length) != 0:
            continue
        d_lo, d_hi = evaluate_form(f1, lo), evaluate_form(f1, hi)
        slope_sign = one_sign(d_lo, d_hi, form_bound(f2, lo, hi), length)
        if slope_sign != 0:
            root = _monotone_part(f, lo, f_lo, hi, f_hi, slope_sign < 0)
            if not math.isnan(root):
                return root
            continue
        if one_sign(evaluate_form(f2, lo), evaluate_form(f2, hi), form_bound(f3, lo, hi), length) != 0:
            if d_lo * d_hi >= 0:
                root = _monotone_part(f, lo, f_lo, hi, f_hi, d_lo + d_hi < 0)
                if not math.isnan(root):
                    return root
                continue
            turn = sign_change(evaluate_form, f1, lo, hi)
            f_turn = evaluate_form(f, turn)
            root = _monotone_part(f, lo, f_lo, turn, f_turn, d_lo < 0)
            if math.isnan(root):
                root = _monotone_part(f, turn, f_turn, hi, f_hi, d_hi < 0)
            if not math.isnan(root):
                return root
            continue
        if length <= resolution:
            if f_lo > 0 > f_hi and f_hi < -form_rounding(f, hi):
                return hi
            continue
        mid = lo + 0.5 * length
        f_mid = evaluate_form(f, mid)
        if top + 2 >= stack.shape[0]:
            return -math.inf
        top += 1
        stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3] = mid, f_mid, hi, f_hi
        top += 1
        stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3] = lo, f_lo, mid, f_mid
    return math.nan


@register_jitable
def _left_at_once(mode, u, v, a, a_rate, k, c, b, guards):
    """The first guard of ``mode`` at or below zero and falling at (u, v) under a(t) =
    ``a`` with rate ``a_rate``; -1: none."""
    for j in range(guards.shape[1]):
        alpha, beta, gamma = guards[mode, j, 0], guards[mode, j, 1], guards[mode, j, 2]
        if (alpha == 0 and beta == 0) or alpha * u + beta * v + gamma > 0:
            continue
        accel = b[mode] - k[mode] * u - c[mode] * v - a
        jerk = -k[mode] * v - c[mode] * accel - a_rate
        if falls(alpha * v + beta * accel, alpha * accel + beta * jerk, EVENT_RESOLUTION):
            return j
    return -1


@register_jitable
def _run(t0, h, p0, p1, scale, k, c, b, guards, next_mode, resets, initial_mode, log):
    """One run over the pieces (t0, h, p0, p1) [s, s, m/s², m/s³], a(t) times ``scale``;
    ``log``: (capacity, 6) knot rows (KNOT_FIELDS), or (0, 6) for the outcome only.
    Returns (outcome (OUTCOME_FIELDS), rows logged)."""
    stack = np.empty((STACK_DEPTH, 4))
    damped = np.sqrt(np.maximum(k - 0.25 * c * c, 0.0))  # damped frequency of each mode [rad/s]
    cached = np.full(6, math.nan)  # sigma [1/s], w [rad/s], span [s]; exp(-sigma span), cos, sin(w span)
    mode, u, v = initial_mode, 0.0, 0.0
    n_events, n_rows, run, max_run = 0, 0, 0, 0
    last_event, max_u, t_first, v_first = -math.inf, -math.inf, math.nan, math.nan
    status = FINISHED
    logging = log.shape[0] > 0
    for i in range(t0.shape[0]):
        length, q0, q1 = h[i], scale * p0[i], scale * p1[i]
        tau = 0.0
        if logging:
            if n_rows >= log.shape[0]:
                status = LOG_FULL
                break
            log[n_rows, 0], log[n_rows, 1], log[n_rows, 2] = t0[i], u, v
            log[n_rows, 3], log[n_rows, 4], log[n_rows, 5] = mode, mode, 0.0
            n_rows += 1
        while True:
            a, event_tau, index = q0 + q1 * tau, math.nan, _left_at_once(mode, u, v, q0 + q1 * tau, q1, k, c, b,
                                                                         guards)
            if index >= 0:
                event_tau = tau
                u_new, v_new = u, v
            else:
                f = piece_form(k[mode], c[mode], b[mode], damped[mode], a, q1, u, v)
                f1 = form_derivative(f)
                span = length - tau
                if f[6] != cached[0] or f[7] != cached[1] or span != cached[2]:  # a record: one step
                    cached[0], cached[1], cached[2] = f[6], f[7], span
                    cached[3], cached[4], cached[5] = math.exp(-f[6] * span), math.cos(f[7] * span), math.sin(
                        f[7] * span)
                u_end = evaluate_form_at(f, span, cached[3], cached[4], cached[5])
                v_end = evaluate_form_at(f1, span, cached[3], cached[4], cached[5])
                for j in range(guards.shape[1]):
                    alpha, beta, gamma = guards[mode, j, 0], guards[mode, j, 1], guards[mode, j, 2]
                    if alpha == 0 and beta == 0:
                        continue
                    g = combine_forms(alpha, f, beta, f1, gamma)
                    if one_sign(g[0] + g[4], evaluate_form_at(g, span, cached[3], cached[4], cached[5]),
                               form_bound(form_derivative(g), 0.0, span), span) > 0:
                        continue  # positive all along the piece: no crossing (the search's first test)
                    g1 = form_derivative(g)
                    g2 = form_derivative(g1)
                    root = _first_down_crossing(g, g1, g2, form_derivative(g2), 0.0,
                                                length - tau if math.isnan(event_tau) else event_tau - tau,
                                                t0[i] + tau, stack)
                    if root == -math.inf:
                        status = UNSETTLED
                        break
                    if not math.isnan(root) and (math.isnan(event_tau) or tau + root < event_tau):
                        event_tau, index = tau + root, j
                if status != FINISHED:
                    break
                if math.isnan(event_tau) or event_tau >= length:  # the end of the piece: the next decides
                    u, v = u_end, v_end
                    break
                u_new, v_new = evaluate_form(f, event_tau - tau), evaluate_form(f1, event_tau - tau)
            t_event = t0[i] + event_tau
            before = mode
            u = resets[before, index, 0, 0] * u_new + resets[before, index, 0, 1] * v_new + resets[before, index, 0, 2]
            v = resets[before, index, 1, 0] * u_new + resets[before, index, 1, 1] * v_new + resets[before, index, 1, 2]
            mode = next_mode[before, index]
            run = run + 1 if t_event - last_event <= EVENT_RESOLUTION else 1
            max_run = max(max_run, run)
            last_event = t_event
            if n_events == 0:
                t_first, v_first = t_event, v
            n_events += 1
            max_u = max(max_u, u)
            if logging:
                if n_rows >= log.shape[0]:
                    status = LOG_FULL
                    break
                log[n_rows, 0], log[n_rows, 1], log[n_rows, 2] = t_event, u, v
                log[n_rows, 3], log[n_rows, 4], log[n_rows, 5] = mode, before, 1.0
                n_rows += 1
            if run > MAX_EVENTS_AT_ONE_INSTANT:
                status = CHATTER
                break
            tau = event_tau
        if status != FINISHED:
            break
    if logging and status == FINISHED:
        if n_rows >= log.shape[0]:
            status = LOG_FULL
        else:
            end = t0[t0.shape[0] - 1] + h[h.shape[0] - 1]
            log[n_rows, 0], log[n_rows, 1], log[n_rows, 2] = end, u, v
            log[n_rows, 3], log[n_rows, 4], log[n_rows, 5] = mode, mode, 0.0
            n_rows += 1
    outcome = np.array([u, v, mode, n_events, max_u, t_first, v_first, status, max_run], dtype=np.float64)
    return outcome, n_rows


def _run_batch(t0, h, p0, p1, offsets, scales, tables):
    """Final numbers of every (excitation, table set, scale): excitations concatenated
    (``offsets`` (e + 1,) into the pieces), ``tables`` a tuple of stacked LinearModes
    arrays (n_sets leading), ``scales`` (s,). Returns (e, n_sets * s, len(OUTCOME_FIELDS))."""
    k, c, b, guards, next_mode, resets, initial = tables
    n_exc, n_sets, n_scales = offsets.shape[0] - 1, k.shape[0], scales.shape[0]
    out = np.empty((n_exc, n_sets * n_scales, len(OUTCOME_FIELDS)))
    empty = np.empty((0, 6))
    for item in numba.prange(n_exc * n_sets * n_scales):
        # excitations interleaved, so that each thread's share mixes long and short ones
        e, rest = item % n_exc, item // n_exc
        j, s = rest // n_scales, rest % n_scales
        lo, hi = offsets[e], offsets[e + 1]
        outcome, _ = _run(t0[lo:hi], h[lo:hi], p0[lo:hi], p1[lo:hi], scales[s], k[j], c[j], b[j], guards[j],
                          next_mode[j], resets[j], initial[j], empty)
        out[e, rest] = outcome
    return out


@functools.cache
def kernels():
    """(run, run_batch) compiled with numba (on first use, then from the disk cache)."""
    options = dict(cache=True, error_model="numpy")
    return numba.njit(**options)(_run), numba.njit(parallel=True, **options)(_run_batch)
