"""The compiled exact engine of the flexible sliding mass (section 8 of the formulation
note), on the linear engine's closed forms (:mod:`blockdae.solvers._linear`).

On a piece of a record, a(tau) = a + rate tau, every mode is linear: u is the
oscillator's closed form (a "form": cubic + e^{-sigma tau}(C cos w tau + D sin w tau)),
STICK: u'' + 2 xi omega u' + omega² u = -(4/pi) a(tau), coupled SLIP:
d1 u'' + 2 xi omega u' + omega² u = -(4/pi) ky g. In SLIP, w' = a - ky g + (2/pi) u''
integrates to w = w0 + (a - ky g) tau + rate tau²/2 + (2/pi)(u' - u'0) and s' = w to
s = s0 + (w0 - (2/pi) u'0) tau + (a - ky g) tau²/2 + rate tau³/6 + (2/pi)(u - u0): forms
of the same exponent and frequency as u, whose polynomial part (degree <= 1 in u, as
omega > 0) stays within the cubic. The onset guard ky g - HEA = ky g - d1 a(tau) +
(2/pi)(2 xi omega u' + omega² u) and the stop guard w are forms too: their first
downward crossings are located to adjacent floats by the linear engine's search rules
(:mod:`._roots`). The driver's rules hold: a guard at zero and falling as a mode starts
is left at once, one reaching zero at the end of a piece is left to the next, a guard
below zero at rest (t = 0, a(0) > ky g / d1) is an onset at once. On whole steps of a
record each mode runs by its step map (from the closed forms) while bounds show that no
guard can cross; else in closed form. :mod:`._fused` runs the analyses of
``bd.flexible`` (final numbers only) on these pieces.
"""

import functools
import math

import numba
import numpy as np
from numba.extending import register_jitable

from ..solvers import (CHATTER, EVENT_RESOLUTION, FINISHED, LOG_FULL, MAX_EVENTS_AT_ONE_INSTANT, STACK_DEPTH,
                       UNSETTLED, combine_forms, evaluate_form, evaluate_form_at, form_bound, form_derivative,
                       piece_form)
from ..solvers import MAX_INTERVALS  # noqa: F401 -- read through this module (._exact's messages)
from ..core import falls, one_sign
from ._column import MASS_PARTICIPATION, MODE_PARTICIPATION, SLIP_MASS_FRACTION
from ._roots import STACK_COLUMNS, first_fall

_EPS = float(np.finfo(float).eps)
STICK, SLIP = 0, 1
#: entries of a run's outcome: the state at the end, counts, the no-sliding peaks
#: (|HEA| at the samples [m/s²], its supremum over time [m/s²], sup |u| [m]), status
OUTCOME_FIELDS = ("u", "u_rate", "s", "w", "mode", "n_events", "n_episodes", "hea_samples", "hea_sup", "u_sup",
                  "u_samples", "status", "max_events_at_one_instant", "t_last_event")
#: a bound of a rate, widened by a few ulps of its rounding
_WIDEN = 1.0 + 8.0 * _EPS
#: columns of the knot log: time [s], u [m], u' [m/s], s [m], w [m/s], mode after, mode before, is an event
KNOT_FIELDS = ("t", "u", "u_rate", "s", "w", "mode", "mode_before", "is_event")


@register_jitable
def _plus(f, c0, c1, c2, c3):
    """The form f plus the cubic c0 + c1 tau + c2 tau² + c3 tau³."""
    return (f[0] + c0, f[1] + c1, f[2] + c2, f[3] + c3, f[4], f[5], f[6], f[7])


@register_jitable
def _damped(omega, xi, coupled):
    """Damped frequencies [rad/s] of STICK and SLIP (coupled: omega / sqrt(d1), xi / sqrt(d1))."""
    stick = omega * math.sqrt(1.0 - xi * xi)
    if not coupled:
        return stick, stick
    return stick, omega / math.sqrt(SLIP_MASS_FRACTION) * math.sqrt(1.0 - xi * xi / SLIP_MASS_FRACTION)


@register_jitable
def _slip_polynomials(a, rate, kyg, u, v, s, w):
    """The cubics of w and s in SLIP besides (2/pi) u' and (2/pi) u: from w' = a - ky g +
    (2/pi) u'' and s' = w, w = w0 + (a - ky g) tau + rate tau²/2 + (2/pi)(u' - u'0) and
    s = s0 + (w0 - (2/pi) u'0) tau + (a - ky g) tau²/2 + rate tau³/6 + (2/pi)(u - u0)."""
    return ((w - MASS_PARTICIPATION * v, a - kyg, 0.5 * rate, 0.0),
            (s - MASS_PARTICIPATION * u, w - MASS_PARTICIPATION * v, 0.5 * (a - kyg), rate / 6.0))


@register_jitable
def _oscillator(mode, coupled, omega, xi, kyg):
    """(k [1/s²], c [1/s], b [m/s²], forced [-]) of u'' + c u' + k u = b - forced a(t) in
    ``mode``: STICK and decoupled SLIP feel the ground, coupled SLIP the friction."""
    k, c = omega * omega, 2.0 * xi * omega
    if mode == SLIP and coupled:
        return k / SLIP_MASS_FRACTION, c / SLIP_MASS_FRACTION, -MODE_PARTICIPATION * kyg / SLIP_MASS_FRACTION, 0.0
    return k, c, 0.0, MODE_PARTICIPATION


@register_jitable
def _forms(mode, coupled, omega, xi, damped, kyg, a, rate, u, v, s, w):
    """(u, s, w, guard) as forms over tau from the state (u, v, s, w) in ``mode`` under
    a(tau) = a + rate tau [m/s²]; ``damped``: the mode's damped frequency [rad/s]."""
    k, c, b, forced = _oscillator(mode, coupled, omega, xi, kyg)
    f = piece_form(k, c, b, damped, forced * a, forced * rate, u, v)
    f1 = form_derivative(f)
    if mode == STICK:
        guard = _plus(combine_forms(MASS_PARTICIPATION * k, f, MASS_PARTICIPATION * c, f1, kyg - SLIP_MASS_FRACTION * a),
                      0.0, -SLIP_MASS_FRACTION * rate, 0.0, 0.0)
        constant = (s, 0.0, 0.0, 0.0, 0.0, 0.0, f[6], f[7])
        return f, constant, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, f[6], f[7]), guard
    pw, ps = _slip_polynomials(a, rate, kyg, u, v, s, w)
    wf = _plus(combine_forms(MASS_PARTICIPATION, f1, 0.0, f1, 0.0), pw[0], pw[1], pw[2], pw[3])
    sf = _plus(combine_forms(MASS_PARTICIPATION, f, 0.0, f, 0.0), ps[0], ps[1], ps[2], ps[3])
    return f, sf, wf, wf


@register_jitable
def _moves(f):
    """Whether the form f is not identically zero (a guard that is cannot cross it:
    HEA = ky g all along a step, e.g. ky = 0 under no motion)."""
    return f[0] != 0.0 or f[1] != 0.0 or f[2] != 0.0 or f[3] != 0.0 or f[4] != 0.0 or f[5] != 0.0


@register_jitable
def _cubic(p, tau):
    """p0 + p1 tau + p2 tau² + p3 tau³."""
    return ((p[3] * tau + p[2]) * tau + p[1]) * tau + p[0]


@register_jitable
def _step_maps(mode, coupled, omega, xi, damped, kyg, step):
    """``mode``'s oscillator over a whole step [s] as a linear map, from the closed forms:
    (u, u') at its end = [m0 m1; m2 m3] (u, u') + [m4 m5; m6 m7] (a, rate) at its start
    + (m8, m9)."""
    k, c, b, forced = _oscillator(mode, coupled, omega, xi, kyg)
    maps = np.empty(10)
    decay, cos, sin = 1.0, 1.0, 0.0
    for j in range(5):  # unit u, u', a, rate; then b alone
        f = piece_form(k, c, b * (j == 4), damped, forced * (j == 2), forced * (j == 3), 1.0 * (j == 0), 1.0 * (j == 1))
        if j == 0:  # the five forms share exp(-sigma step), cos and sin(w step)
            decay, cos, sin = math.exp(-f[6] * step), math.cos(f[7] * step), math.sin(f[7] * step)
        row = (0, 1, 4, 5, 8)[j]
        maps[row], maps[row + 2 if j < 4 else row + 1] = (evaluate_form_at(f, step, decay, cos, sin),
                                                          evaluate_form_at(form_derivative(f), step, decay, cos, sin))
    return maps


@register_jitable
def _log(log, n_rows, t, u, v, s, w, mode, before, is_event):
    """Append a knot row; False if the log is full."""
    if n_rows >= log.shape[0]:
        return False
    log[n_rows, 0], log[n_rows, 1], log[n_rows, 2], log[n_rows, 3] = t, u, v, s
    log[n_rows, 4], log[n_rows, 5], log[n_rows, 6], log[n_rows, 7] = w, mode, before, is_event
    return True


@register_jitable
def _step_tables(omega, xi, coupled, kyg, damped, step):
    """For whole steps [s] of a record: each mode's step map (:func:`_step_maps`, a
    tuple of 10) and its constants (k, c, b, forced, 1/k, 1/damped frequency, natural
    frequency), tuples indexed by mode (scalars to the compiler, not arrays)."""
    maps = (_step_maps(STICK, coupled, omega, xi, damped[STICK], kyg, step),
            _step_maps(SLIP, coupled, omega, xi, damped[SLIP], kyg, step))
    stick = _oscillator(STICK, coupled, omega, xi, kyg)
    slip = _oscillator(SLIP, coupled, omega, xi, kyg)
    return ((maps[0][0], maps[0][1], maps[0][2], maps[0][3], maps[0][4], maps[0][5], maps[0][6], maps[0][7],
             maps[0][8], maps[0][9]),
            (maps[1][0], maps[1][1], maps[1][2], maps[1][3], maps[1][4], maps[1][5], maps[1][6], maps[1][7],
             maps[1][8], maps[1][9])), \
        (stick + (1.0 / stick[0], 1.0 / damped[STICK], math.sqrt(stick[0])),
         slip + (1.0 / slip[0], 1.0 / damped[SLIP], math.sqrt(slip[0])))


@register_jitable
def _whole_step(m, row, u, v, a0, rate):
    """(u [m], u' [m/s]) at the end of a whole step from its map ``m`` and the mode's
    constants ``row``; the free oscillation's amplitude [m] (|u' - forced| <= natural
    frequency x amplitude, |u''| <= its square x amplitude) and the forced part's u' [m/s]."""
    k, c, b, forced, inverse_k, inverse_damped, _ = row
    u_end = m[4] * a0 + m[5] * rate + m[8] + m[0] * u + m[1] * v  # the state's terms last: a shorter chain
    v_end = m[6] * a0 + m[7] * rate + m[9] + m[2] * u + m[3] * v  # from one step to the next
    particular = -forced * rate * inverse_k  # piece_form's a1
    free = u - (b - forced * a0 - c * particular) * inverse_k
    rotated = (v - particular + 0.5 * c * free) * inverse_damped
    return u_end, v_end, math.sqrt(free * free + rotated * rotated), particular


@register_jitable
def _hea_rate(rate, row, amplitude, xi):
    """A bound of |HEA'| [m/s³] on a STICK step: HEA' = a' - (2/pi)(c X'' + k X') for the
    free part X, |X^(n)| <= omega^n amplitude."""
    return (abs(rate) + MASS_PARTICIPATION * row[6] * row[0] * amplitude * (1.0 + 2.0 * xi)) * _WIDEN


@register_jitable
def _hea_curvature(row, amplitude, xi):
    """A bound of |HEA''| [m/s⁴] on a STICK step: a'' = 0 on a piece, so HEA'' =
    -(2/pi)(c X''' + k X'') for the free part X."""
    return MASS_PARTICIPATION * row[0] * row[0] * amplitude * (1.0 + 2.0 * xi) * _WIDEN


@register_jitable
def _clear(value_a, value_b, curvature, length):
    """Whether a function with these end values and |f''| <= ``curvature`` stays > 0 on
    an interval of ``length``: it lies above its chord less curvature tau (length - tau) / 2."""
    return min(value_a, value_b) > 0.125 * curvature * length * length


@register_jitable
def _stick_hea(a, u, v, row):
    """HEA = d1 a - (2/pi)(c u' + k u) [m/s²] in STICK."""
    return SLIP_MASS_FRACTION * a - MASS_PARTICIPATION * (row[1] * v + row[0] * u)


@register_jitable
def _quick_step(mode, m, row, step, xi, kyg, a0, rate, u, v, s, w):
    """A whole step [s] of ``mode`` by its map ``m`` and constants ``row`` (from
    :func:`_step_tables`) under a(tau) = a0 + rate tau [m/s², m/s³], where its guard's
    values at the ends and a bound of its rate show that it stays positive: (True, u, u',
    s, w at the end); (False, ...) where they do not (the closed form decides)."""
    u_end, v_end, amplitude, _ = _whole_step(m, row, u, v, a0, rate)
    if mode == SLIP:  # w' = a - ky g + (2/pi) u''
        pw, ps = _slip_polynomials(a0, rate, kyg, u, v, s, w)
        w_end = _cubic(pw, step) + MASS_PARTICIPATION * v_end
        if _slip_clear(w, w_end, a0, rate, kyg, row, amplitude, step):
            return True, u_end, v_end, _cubic(ps, step) + MASS_PARTICIPATION * u_end, w_end
        return False, u, v, s, w
    hea_start, hea_end = _stick_hea(a0, u, v, row), _stick_hea(a0 + rate * step, u_end, v_end, row)
    return _stick_clear(kyg - hea_start, kyg - hea_end, rate, row, amplitude, xi, step), u_end, v_end, s, w


@register_jitable
def _stick_clear(guard_start, guard_end, rate, row, amplitude, xi, step):
    """Whether the onset guard ky g - HEA [m/s²] stays > 0 on a whole STICK step [s],
    from its end values and bounds of its rate or its curvature."""
    return one_sign(guard_start, guard_end, _hea_rate(rate, row, amplitude, xi), step) > 0 or _clear(
        guard_start, guard_end, _hea_curvature(row, amplitude, xi), step)


@register_jitable
def _slip_clear(w, w_end, a0, rate, kyg, row, amplitude, step):
    """Whether w [m/s] stays > 0 on a whole SLIP step [s] from its end values and bounds
    of w' = a - ky g + (2/pi) u'' or w'' = a' + (2/pi) u''' (the free part's)."""
    w_rate = (max(abs(a0 - kyg), abs(a0 + rate * step - kyg)) + MASS_PARTICIPATION * row[0] * amplitude) * _WIDEN
    w_curvature = (abs(rate) + MASS_PARTICIPATION * row[0] * row[6] * amplitude) * _WIDEN
    return one_sign(w, w_end, w_rate, step) > 0 or _clear(w, w_end, w_curvature, step)


@register_jitable
def _piece(t_start, length, a0, rate, step, maps, table, omega, xi, damped, kyg, coupled, cached, stack, log, n_rows,
           mode, u, v, s, w, n_events, n_episodes, run, max_run, last_event, quick_first):
    """One piece of a(t) = a0 + rate tau [m/s², m/s³], ``length`` [s] from ``t_start``
    [s], from the state (``mode``, u, v, s, w) and the event counters: whole steps by
    their map (``maps``, ``table`` from :func:`_step_tables` for ``step`` [s]) where
    bounds show that no guard crosses (``quick_first``: try that first; a caller that has
    tried it says False), else in closed form with every event located.
    ``cached``: (6,) scratch of exp, cos, sin of the last span; ``stack``: the root
    search's scratch; ``log``: knot rows from ``n_rows`` on ((0, 8): none). Returns
    (mode, u, v, s, w, n_events, n_episodes, run, max_run, last_event, status, n_rows)."""
    status = FINISHED
    logging = log.shape[0] > 0
    tau = 0.0
    while True:
        if quick_first and tau == 0.0 and length == step:
            quick, u_end, v_end, s_end, w_end = _quick_step(mode, maps[mode], table[mode], step, xi, kyg, a0, rate, u,
                                                            v, s, w)
            if quick:
                u, v, s, w = u_end, v_end, s_end, w_end
                break
        a = a0 + rate * tau
        span = length - tau
        f, sf, wf, guard = _forms(mode, coupled, omega, xi, damped[mode], kyg, a, rate, u, v, s, w)
        if f[6] != cached[0] or f[7] != cached[1] or span != cached[2]:  # a record: once per mode and step
            cached[0], cached[1], cached[2] = f[6], f[7], span
            cached[3], cached[4], cached[5] = math.exp(-f[6] * span), math.cos(f[7] * span), math.sin(
                f[7] * span)
        event_tau = math.nan
        g1 = form_derivative(guard)
        g2 = form_derivative(g1)
        at_start = guard[0] + guard[4]
        if at_start <= 0 and (falls(g1[0] + g1[4], g2[0] + g2[4], EVENT_RESOLUTION) or (  # values at 0
                at_start < 0 and mode == STICK and u == 0.0 and v == 0.0)):
            event_tau = 0.0  # left at once (at rest: an excess at t = 0 slides at once)
        elif one_sign(at_start, evaluate_form_at(guard, span, cached[3], cached[4], cached[5]),
                     form_bound(g1, 0.0, span), span) <= 0 and _moves(guard):
            root = first_fall(guard, g1, g2, form_derivative(g2), span, t_start + tau, stack, cached[3], cached[4],
                              cached[5])
            if root == -math.inf:
                status = UNSETTLED
                break
            if root < span:  # a root at the end of the piece: the next piece decides
                event_tau = root
        if math.isnan(event_tau):
            u, v = evaluate_form_at(f, span, cached[3], cached[4], cached[5]), evaluate_form_at(
                form_derivative(f), span, cached[3], cached[4], cached[5])
            s = evaluate_form_at(sf, span, cached[3], cached[4], cached[5])
            w = evaluate_form_at(wf, span, cached[3], cached[4], cached[5])
            break
        decay, cos, sin = math.exp(-f[6] * event_tau), math.cos(f[7] * event_tau), math.sin(f[7] * event_tau)
        u, v = evaluate_form_at(f, event_tau, decay, cos, sin), evaluate_form_at(form_derivative(f), event_tau, decay, cos, sin)
        s = evaluate_form_at(sf, event_tau, decay, cos, sin)  # sf: u's exponent and frequency
        w = 0.0  # exactly, at an onset and at a stop
        before = mode
        mode = SLIP if before == STICK else STICK
        n_episodes += mode == SLIP
        tau += event_tau
        t_event = t_start + tau
        run = run + 1 if t_event - last_event <= EVENT_RESOLUTION else 1
        max_run = max(max_run, run)
        last_event = t_event
        n_events += 1
        if logging and not _log(log, n_rows, t_event, u, v, s, w, mode, before, 1.0):
            status = LOG_FULL
            break
        n_rows += logging
        if run > MAX_EVENTS_AT_ONE_INSTANT:
            status = CHATTER
            break
    return mode, u, v, s, w, n_events, n_episodes, run, max_run, last_event, status, n_rows


@register_jitable
def _run(t0, h, p0, p1, scale, omega, xi, kyg, coupled, log):
    """One sliding run over the pieces (t0, h, p0, p1) [s, s, m/s², m/s³] of a(t) times
    ``scale`` from rest: column omega [rad/s], xi [-], ky g [m/s²], coupled or decoupled.
    ``log``: (capacity, 8) knot rows (KNOT_FIELDS), or (0, 8) for the outcome only.
    Returns (outcome (OUTCOME_FIELDS; no peaks), rows logged)."""
    stack = np.empty((STACK_DEPTH, STACK_COLUMNS))
    damped = _damped(omega, xi, coupled)
    step = h[0]  # a whole step of a record, the common case, by its map
    maps, table = _step_tables(omega, xi, coupled, kyg, damped, step)
    cached = np.full(6, math.nan)  # sigma [1/s], w [rad/s], span [s]; exp(-sigma span), cos, sin(w span)
    mode, u, v, s, w = STICK, 0.0, 0.0, 0.0, 0.0
    n_events, n_episodes, n_rows, run, max_run = 0, 0, 0, 0, 0
    last_event = -math.inf
    status = FINISHED
    logging = log.shape[0] > 0
    for i in range(t0.shape[0]):
        if logging and not _log(log, n_rows, t0[i], u, v, s, w, mode, mode, 0.0):
            status = LOG_FULL
            break
        n_rows += logging
        mode, u, v, s, w, n_events, n_episodes, run, max_run, last_event, status, n_rows = _piece(
            t0[i], h[i], scale * p0[i], scale * p1[i], step, maps, table, omega, xi, damped, kyg, coupled, cached,
            stack, log, n_rows, mode, u, v, s, w, n_events, n_episodes, run, max_run, last_event, True)
        if status != FINISHED:
            break
    if logging and status == FINISHED:
        end = t0[t0.shape[0] - 1] + h[h.shape[0] - 1]
        if _log(log, n_rows, end, u, v, s, w, mode, mode, 0.0):
            n_rows += 1
        else:
            status = LOG_FULL
    outcome = np.array([u, v, s, w, mode, n_events, n_episodes, 0.0, 0.0, 0.0, 0.0, status, max_run, last_event],
                       dtype=np.float64)
    return outcome, n_rows


def _dense(knot_t, knots, knot_mode, t0, p0, p1, scale, omega, xi, kyg, coupled, t):
    """(u, u', s, w) at times ``t`` (m,) [s] from the knot before each (times (n,),
    states (n, 4), modes (n,)) under the piece of a(t) that holds it. Returns (m, 4)."""
    damped = _damped(omega, xi, coupled)
    out = np.empty((t.shape[0], 4))
    for q in range(t.shape[0]):
        i = min(max(np.searchsorted(knot_t, t[q], side="right") - 1, 0), knot_t.shape[0] - 1)
        j = min(max(np.searchsorted(t0, knot_t[i], side="right") - 1, 0), t0.shape[0] - 1)
        rate = scale * p1[j]
        a = scale * p0[j] + rate * (knot_t[i] - t0[j])
        mode = int(knot_mode[i])
        f, sf, wf, _ = _forms(mode, coupled, omega, xi, damped[mode], kyg, a, rate, knots[i, 0], knots[i, 1],
                              knots[i, 2], knots[i, 3])
        tau = t[q] - knot_t[i]
        out[q, 0], out[q, 1] = evaluate_form(f, tau), evaluate_form(form_derivative(f), tau)
        out[q, 2], out[q, 3] = evaluate_form(sf, tau), evaluate_form(wf, tau)
    return out


#: the first compile of ``run`` [s] (one core; benchmarks/cold_start.py)
COMPILE_SECONDS = 7


@functools.cache
def kernels():
    """(run, dense) compiled with numba (on first use, then from the disk cache)."""
    options = dict(cache=True, error_model="numpy")
    return numba.njit(**options)(_run), numba.njit(**options)(_dense)
