"""One ``bd.flexible`` analysis in one compiled pass, final numbers only: the no-sliding
response (max |HEA| at the samples, its supremum over time, sup |u|) and the sliding
runs of both polarities.

Each step of the record advances the response by its step map (as in
:func:`._engine._piece`). A decoupled run slides on that response (its column is the
no-sliding one; the inverse polarity's u is minus the normal one's), so its step costs
a test of its guard; a coupled run steps its own column. A run's step needs no closed
form where bounds show that its guard cannot cross; otherwise :func:`._engine._piece`
takes it and locates every event. The sups search only the steps whose bound exceeds
the largest sample so far, after the pass.
"""

import functools
import math

import numba
import numpy as np
from numba.extending import register_jitable

from ..engines._linear import FINISHED, STACK_DEPTH, UNSETTLED, _combine, _derivative, _eval
from ._column import MASS_PARTICIPATION, SLIP_MASS_FRACTION
from ._engine import (OUTCOME_FIELDS, SLIP, STICK, _WIDEN, _cubic, _damped, _forms, _hea_curvature, _hea_rate, _piece,
                      _quick_step, _slip_clear, _slip_polynomials, _step_tables, _stick_clear)
from ._roots import STACK_COLUMNS, peak

#: rows of an analysis's outcome (each OUTCOME_FIELDS): the no-sliding response (state
#: at the end, peaks, status), the run of the record as given, the run of it times -1
RESPONSE, NORMAL, INVERSE = 0, 1, 2
#: columns of ``flags``: coupled, run the normal polarity, run the inverse, find sup |u|,
#: find the response's peaks (else its row is nan: another analysis has them)
FLAG_FIELDS = ("coupled", "normal", "inverse", "u_sup", "response")
#: columns of ``parameters``: omega [rad/s], xi [-], ky g [m/s²]
PARAMETER_FIELDS = ("omega", "xi", "kyg")


@register_jitable
def _put(row, values):
    """Write the tuple of floats ``values`` into the array ``row``."""
    for k in range(len(values)):
        row[k] = values[k]


@register_jitable
def _response(t0, h, p0, p1, omega, xi, damped, maps, table, step, u, v, hea, amplitude, reach):
    """The no-sliding response from rest, in two passes: (u, u') at the knots by the step
    map (closed form on a partial step), then, in a loop without dependences that the
    compiler vectorises, HEA at the knots, the free oscillation's amplitude on each step
    and a bound of |HEA| on it (inf on a partial step). Fills ``u``, ``v``, ``hea`` (n + 1,)
    [m, m/s, m/s²], ``amplitude`` (n,) [m] and ``reach`` (n,) [m/s²]."""
    m, row = maps[STICK], table[STICK]
    k, c, b, forced, inverse_k, inverse_damped, _ = row
    n = t0.shape[0]
    u[0], v[0] = 0.0, 0.0
    for i in range(n):  # as _whole_step, term by term
        a0, rate = p0[i], p1[i]
        if h[i] == step:
            u[i + 1] = m[0] * u[i] + m[1] * v[i] + m[4] * a0 + m[5] * rate + m[8]
            v[i + 1] = m[2] * u[i] + m[3] * v[i] + m[6] * a0 + m[7] * rate + m[9]
        else:
            f, _, _, _ = _forms(STICK, False, omega, xi, damped, 0.0, a0, rate, u[i], v[i], 0.0, 0.0)
            u[i + 1], v[i + 1] = _eval(f, h[i]), _eval(_derivative(f), h[i])
    hea[0] = SLIP_MASS_FRACTION * p0[0] - MASS_PARTICIPATION * (c * v[0] + k * u[0])
    for i in range(n):
        rate = p1[i]
        particular = -forced * rate * inverse_k
        free = u[i] - (b - forced * p0[i] - c * particular) * inverse_k
        rotated = (v[i] - particular + 0.5 * c * free) * inverse_damped
        a = math.sqrt(free * free + rotated * rotated) if h[i] == step else math.inf
        amplitude[i] = a
        hea[i + 1] = SLIP_MASS_FRACTION * (p0[i] + rate * h[i]) - MASS_PARTICIPATION * (c * v[i + 1] + k * u[i + 1])
    for i in range(n):  # apart: hea[i] written by the loop above would tie its iterations
        a = amplitude[i]
        reach[i] = max(abs(hea[i]), abs(hea[i + 1])) + min(0.5 * _hea_rate(p1[i], row, a, xi) * step,
                                                           0.125 * _hea_curvature(row, a, xi) * step * step)


@register_jitable
def _largest(x):
    """max |x[1:]| (four running maxima, so that their latencies overlap)."""
    best = np.zeros(4)
    n = x.shape[0] - 1
    for i in range(1, n - 2, 4):
        best[0], best[1] = max(best[0], abs(x[i])), max(best[1], abs(x[i + 1]))
        best[2], best[3] = max(best[2], abs(x[i + 2])), max(best[3], abs(x[i + 3]))
    for i in range(max(1, n - (n % 4) + 1), n + 1):
        best[0] = max(best[0], abs(x[i]))
    return max(max(best[0], best[1]), max(best[2], best[3]))


@register_jitable
def _sups(t0, h, p0, p1, omega, xi, damped, row, step, u, v, amplitude, reach, hea_sup, want_u, stack):
    """(sup |HEA| [m/s²], max |u| at the samples, sup |u| [m]) of the response
    (:func:`_response`; ``hea_sup``: max |HEA| at the samples): every step whose bound
    exceeds the best so far is searched; -inf where a search did not settle."""
    u_samples = _largest(u) if want_u else math.nan
    u_sup = u_samples
    for i in range(t0.shape[0]):
        u_reach = math.inf
        if want_u:
            a = amplitude[i]
            u_reach = max(abs(u[i]), abs(u[i + 1])) + min(0.5 * (abs(row[3] * p1[i] * row[4]) + row[6] * a),
                                                          0.125 * row[0] * a * step) * _WIDEN * step
        if reach[i] > hea_sup or (want_u and u_reach > u_sup):
            f, _, _, guard = _forms(STICK, False, omega, xi, damped, 0.0, p0[i], p1[i], u[i], v[i], 0.0, 0.0)
            if reach[i] > hea_sup:  # the guard is ky g - HEA with ky g = 0
                g = _combine(-1.0, guard, 0.0, guard, 0.0)
                g1 = _derivative(g)
                g2 = _derivative(g1)
                hea_sup = peak(g, g1, g2, _derivative(g2), h[i], hea_sup, t0[i], stack)
            if want_u and u_reach > u_sup:
                f1 = _derivative(f)
                f2 = _derivative(f1)
                u_sup = peak(f, f1, f2, _derivative(f2), h[i], u_sup, t0[i], stack)
            if hea_sup == -math.inf or u_sup == -math.inf:
                break
    return hea_sup, u_samples, u_sup


def _slow_runs(slow_normal, slow_inverse, t_start, length, a0, rate, step, maps, table, omega, xi, damped, kyg,
               coupled, cached, stack, state, counts, status, u, v):
    """The runs flagged over a piece in closed form (:func:`._engine._piece`), from and to
    ``state`` (mode, u, u', s, w of each), their counters ``counts`` and ``status``; a
    decoupled run's column is the response's (``u``, ``v`` at the start) times its sign."""
    no_log = np.empty((0, 8))
    for r in range(2):
        if not (slow_normal if r == 0 else slow_inverse):
            continue
        sign = 1.0 - 2.0 * r
        run_u, run_v = (state[r, 1], state[r, 2]) if coupled else (sign * u, sign * v)
        (mode, run_u, run_v, s, w, n_events, n_episodes, at_once, most, last, run_status,
         _) = _piece(t_start, length, sign * a0, sign * rate, step, maps, table, omega, xi, damped, kyg, coupled,
                     cached, stack, no_log, 0, int(state[r, 0]), run_u, run_v, state[r, 3], state[r, 4],
                     int(counts[r, 0]), int(counts[r, 1]), int(counts[r, 2]), int(counts[r, 3]), counts[r, 4])
        _put(state[r], (float(mode), run_u, run_v, s, w))
        _put(counts[r], (float(n_events), float(n_episodes), float(at_once), float(most), last))
        status[1 + r] = run_status


#: the closed-form steps, compiled on their own: inlined, their size slows the loop over
#: the quick steps (by about a third, measured)
_slow_runs_compiled = numba.njit(cache=True, error_model="numpy")(_slow_runs)


@register_jitable
def _analysis(t0, h, p0, p1, omega, xi, kyg, coupled, runs, want_u, respond, out):
    """One analysis over the pieces (t0, h, p0, p1) [s, s, m/s², m/s³] of a(t) from rest:
    column omega [rad/s], xi [-], ky g [m/s²], ``coupled`` or decoupled; ``runs``: (2,)
    whether to run the normal and the inverse polarity; ``want_u``: find sup |u| (else
    nan); ``respond``: find the response's peaks (else nan; a coupled analysis then
    steps no response). Writes ``out`` (3, len(OUTCOME_FIELDS)): rows RESPONSE and the
    runs asked for."""
    n = t0.shape[0]
    stack = np.empty((STACK_DEPTH, STACK_COLUMNS))
    cached = np.full(6, math.nan)
    damped = _damped(omega, xi, coupled)
    step = h[0]
    maps, table = _step_tables(omega, xi, coupled, kyg, damped, step)
    stick_map, stick = maps[STICK], table[STICK]
    slip_map, slip = maps[SLIP], table[SLIP]
    # the response: u, u', HEA at the knots, the free amplitude on each step
    u, v, hea = np.empty(n + 1), np.empty(n + 1), np.empty(n + 1)  # every entry is written before it is read
    amplitude, reach = np.empty(n), np.empty(n)
    u[n], v[n] = 0.0, 0.0  # (the response's row of a coupled analysis without it)
    if respond or not coupled:
        _response(t0, h, p0, p1, omega, xi, damped[STICK], maps, table, step, u, v, hea, amplitude, reach)
    if respond:
        hea_samples = _largest(hea)
        hea_sup, u_samples, u_sup = _sups(t0, h, p0, p1, omega, xi, damped[STICK], stick, step, u, v, amplitude,
                                          reach, hea_samples, want_u, stack)
    else:
        hea_samples, hea_sup, u_samples, u_sup = math.nan, math.nan, math.nan, math.nan
    response_status = UNSETTLED if hea_sup == -math.inf or u_sup == -math.inf else FINISHED
    _put(out[RESPONSE], (u[n], v[n], 0.0, 0.0, float(STICK), 0.0, 0.0, hea_samples, hea_sup,
                         u_sup if want_u else math.nan, u_samples, float(response_status), 0.0, math.nan))
    if not (runs[0] or runs[1]):
        return
    # each run's mode, u, u', s, w (a decoupled run's u, u' are the response's times its sign)
    state = np.zeros((2, 5))
    # each run's events, episodes, events at the last instant, most at one instant, last event time
    counts = np.zeros((2, 5))
    counts[:, 4] = -math.inf
    status = np.full(3, FINISHED)
    for i in range(n):
        a0, rate, length = p0[i], p1[i], h[i]
        whole = length == step
        slow_normal, slow_inverse = False, False
        for r in range(2):  # each run's step: quick where bounds allow, else in closed form
            if not runs[r] or status[1 + r] != FINISHED:
                continue
            sign = 1.0 - 2.0 * r
            mode, s, w = int(state[r, 0]), state[r, 3], state[r, 4]
            if coupled and whole:  # each mode's map picked statically (a tuple indexed at run time is copied)
                if mode == STICK:
                    quick, run_u, run_v, s, w = _quick_step(STICK, stick_map, stick, step, xi, kyg, sign * a0,
                                                            sign * rate, state[r, 1], state[r, 2], s, w)
                else:
                    quick, run_u, run_v, s, w = _quick_step(SLIP, slip_map, slip, step, xi, kyg, sign * a0,
                                                            sign * rate, state[r, 1], state[r, 2], s, w)
                if quick:
                    state[r, 1], state[r, 2], state[r, 3], state[r, 4] = run_u, run_v, s, w
                    continue
            elif whole:  # decoupled: the response's step decides, for either sign
                if mode == STICK:
                    if _stick_clear(kyg - sign * hea[i], kyg - sign * hea[i + 1], rate, stick, amplitude[i], xi,
                                    step):
                        continue
                else:
                    pw, ps = _slip_polynomials(sign * a0, sign * rate, kyg, sign * u[i], sign * v[i], s, w)
                    w_end = _cubic(pw, step) + MASS_PARTICIPATION * sign * v[i + 1]
                    if _slip_clear(w, w_end, sign * a0, sign * rate, kyg, stick, amplitude[i], step):
                        state[r, 3], state[r, 4] = _cubic(ps, step) + MASS_PARTICIPATION * sign * u[i + 1], w_end
                        continue
            if r == 0:
                slow_normal = True
            else:
                slow_inverse = True
        if slow_normal or slow_inverse:
            _slow_runs_compiled(slow_normal, slow_inverse, t0[i], length, a0, rate, step, maps, table, omega, xi,
                                damped, kyg, coupled, cached, stack, state, counts, status, u[i], v[i])
    for r in range(2):
        if runs[r]:
            if not coupled:  # the column's state is the response's
                state[r, 1], state[r, 2] = (1.0 - 2.0 * r) * u[n], (1.0 - 2.0 * r) * v[n]
            _put(out[1 + r], (state[r, 1], state[r, 2], state[r, 3], state[r, 4], state[r, 0], counts[r, 0],
                              counts[r, 1], 0.0, 0.0, 0.0, 0.0, float(status[1 + r]), counts[r, 3], counts[r, 4]))


def _analyses(t0, h, p0, p1, offsets, record, parameters, flags, out):
    """Analyses in parallel: analysis j runs excitation ``record[j]`` (pieces
    ``offsets[record[j]]:offsets[record[j] + 1]`` of the concatenated arrays) with
    ``parameters[j]`` (PARAMETER_FIELDS) and ``flags[j]`` (FLAG_FIELDS); writes
    ``out[j]`` (3, len(OUTCOME_FIELDS))."""
    for j in numba.prange(record.shape[0]):
        lo, hi = offsets[record[j]], offsets[record[j] + 1]
        _analysis(t0[lo:hi], h[lo:hi], p0[lo:hi], p1[lo:hi], parameters[j, 0], parameters[j, 1], parameters[j, 2],
                  flags[j, 0] != 0, flags[j, 1:3] != 0, flags[j, 3] != 0, flags[j, 4] != 0, out[j])


@functools.cache
def kernels():
    """(analyses parallel over cores, analyses serial) compiled with numba (on first use,
    then from the disk cache)."""
    options = dict(cache=True, error_model="numpy")
    return numba.njit(parallel=True, **options)(_analyses), numba.njit(**options)(_analyses)


#: width of an analysis's outcome rows
WIDTH = len(OUTCOME_FIELDS)
