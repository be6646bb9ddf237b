"""One ``bd.flexible`` analysis in one compiled pass, final numbers only: the no-sliding
response (max |HEA| at the samples, its supremum over time, sup |u|) and the sliding
runs of both polarities.

Each step of the record advances the response by its step map (as in
:func:`._engine._piece`). A decoupled run slides on that response (its column is the
no-sliding one; the inverse polarity's u is minus the normal one's), so its step costs
a test of its guard; a coupled run steps its own column, in STICK only its difference
from the response (a free oscillation, decaying) where a bound shows that the guard stays
positive. A run's step needs no closed
form where bounds show that its guard cannot cross; otherwise :func:`._engine._piece`
takes it and locates every event. The sups search only the steps whose bound exceeds
the largest sample so far, after the pass.
"""

import functools
import math

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic, register_jitable

from ..solvers import FINISHED, STACK_DEPTH, UNSETTLED, combine_forms, form_derivative, evaluate_form
from ._column import MASS_PARTICIPATION, SLIP_MASS_FRACTION
from ._engine import (OUTCOME_FIELDS, SLIP, STICK, _WIDEN, _cubic, _damped, _forms, _hea_curvature, _hea_rate, _piece,
                      _quick_step, _slip_clear, _slip_polynomials, _step_tables, _stick_clear)
from ._roots import STACK_COLUMNS, peak

#: rows of an analysis's outcome (each OUTCOME_FIELDS): the no-sliding response (state
#: at the end, peaks, status), the run of the record as given, the run of it times -1
RESPONSE, NORMAL, INVERSE = 0, 1, 2
#: columns of an analysis's task (a float64 row): its excitation's index, omega [rad/s],
#: xi [-], ky g [m/s²], then flags (1 or 0): coupled, run the normal polarity, run the
#: inverse, find sup |u|, find the response's peaks (else its row is nan: another analysis
#: has them)
TASK_FIELDS = ("record", "omega", "xi", "kyg", "coupled", "normal", "inverse", "u_sup", "response")


@register_jitable
def _put(row, values):
    """Write the tuple of floats ``values`` into the array ``row``."""
    for k in range(len(values)):
        row[k] = values[k]


@register_jitable
def _response(t0, h, p0, p1, omega, xi, damped, maps, table, step, u, v, hea, amplitude, reach):
    """The no-sliding response from rest: each whole step's forcing (a loop that
    vectorises), (u, u') at the knots by the step map (closed form on a partial step),
    then, in loops without dependences that the compiler vectorises, HEA at the knots, the
    free oscillation's amplitude on each step and a bound of |HEA| on it (inf on a partial
    step). Fills ``u``, ``v``, ``hea`` (n + 1,) [m, m/s, m/s²], ``amplitude`` (n,) [m] and
    ``reach`` (n,) (the bounds' bit patterns, :func:`_bits`, int64; [m/s²])."""
    m, row = maps[STICK], table[STICK]
    k, c, b, forced, inverse_k, inverse_damped, _ = row
    # the map of two whole steps, M², so that the chain from knot to knot is two steps long
    q0, q1 = m[0] * m[0] + m[1] * m[2], m[0] * m[1] + m[1] * m[3]
    q2, q3 = m[2] * m[0] + m[3] * m[2], m[2] * m[1] + m[3] * m[3]
    n = t0.shape[0]
    for i in range(n):  # each whole step's forcing, parked where its end state goes (a loop that vectorises)
        u[i + 1] = m[4] * p0[i] + m[5] * p1[i] + m[8]
        v[i + 1] = m[6] * p0[i] + m[7] * p1[i] + m[9]
    u[0], v[0] = 0.0, 0.0
    u_end, v_end = 0.0, 0.0  # carried in registers, not read back from the arrays
    i = 0
    while i < n:  # as _whole_step, term by term
        if h[i] == step and i + 1 < n and h[i + 1] == step:  # two whole steps: x2 = M² x0 + M F0 + F1
            fu, fv = u[i + 1], v[i + 1]
            gu = u[i + 2] + m[0] * fu + m[1] * fv
            gv = v[i + 2] + m[2] * fu + m[3] * fv
            u[i + 1], v[i + 1] = fu + m[0] * u_end + m[1] * v_end, fv + m[2] * u_end + m[3] * v_end
            u_start = u_end
            u_end = gu + q0 * u_start + q1 * v_end
            v_end = gv + q2 * u_start + q3 * v_end
            u[i + 2], v[i + 2] = u_end, v_end
            i += 2
            continue
        if h[i] == step:
            u_start = u_end
            u_end = u[i + 1] + m[0] * u_start + m[1] * v_end
            v_end = v[i + 1] + m[2] * u_start + m[3] * v_end
        else:
            f, _, _, _ = _forms(STICK, False, omega, xi, damped, 0.0, p0[i], p1[i], u_end, v_end, 0.0, 0.0)
            u_end, v_end = evaluate_form(f, h[i]), evaluate_form(form_derivative(f), h[i])
        u[i + 1], v[i + 1] = u_end, v_end
        i += 1
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
        reach[i] = _bits(max(abs(hea[i]), abs(hea[i + 1])) + min(0.5 * _hea_rate(p1[i], row, a, xi) * step,
                                                                 0.125 * _hea_curvature(row, a, xi) * step * step))


@intrinsic
def _bits(typingctx, x):
    """The bit pattern of the float64 ``x`` as an int64: for x >= 0 (inf included) the
    order of the patterns is that of the values, and an integer maximum vectorises where
    a float one (NaN rules) does not."""
    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))
    return types.int64(types.float64), codegen


@intrinsic
def _float(typingctx, bits):
    """The float64 whose bit pattern is the int64 ``bits`` (:func:`_bits` undone)."""
    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.DoubleType())
    return types.float64(types.int64), codegen


#: the sign bit cleared: a float64's pattern masked by it is that of its |x|
_MAGNITUDE = np.int64(0x7FFFFFFFFFFFFFFF)
#: steps a scan passes at once (a vectorised maximum over their bit patterns)
_CHUNK = 64


@register_jitable
def _largest(x):
    """max |x[1:]|, by the bit patterns of |x| (:func:`_bits`)."""
    bits = x[1:].view(np.int64)
    best = np.int64(0)
    for i in range(bits.shape[0]):
        best = max(best, bits[i] & _MAGNITUDE)
    return _float(best)


@register_jitable
def _first_reaching(reach, start, level):
    """The first step j >= ``start`` whose bound of |HEA| (``reach``: their bit patterns,
    :func:`_bits`) is not below ``level`` >= 0 [m/s²] (len(reach) if none): the next few
    steps one by one (the next is often near), then _CHUNK at a time by their largest
    pattern."""
    threshold = _bits(level)
    n = reach.shape[0]
    j = start
    near = min(start + 8, n)
    while j < near and reach[j] < threshold:
        j += 1
    if j < near:
        return j
    while j + _CHUNK <= n:
        chunk = reach[j:j + _CHUNK]
        top = np.int64(0)
        for k in range(chunk.shape[0]):  # a count unknown to the compiler: vectorised, not unrolled
            top = max(top, chunk[k])
        if top >= threshold:
            break
        j += _CHUNK
    while j < n and reach[j] < threshold:
        j += 1
    return j


@register_jitable
def _sups(t0, h, p0, p1, omega, xi, damped, row, step, u, v, amplitude, reach, hea_sup, want_u, stack):
    """(sup |HEA| [m/s²], max |u| at the samples, sup |u| [m]) of the response
    (:func:`_response`; ``hea_sup``: max |HEA| at the samples): every step whose bound
    exceeds the best so far is searched; -inf where a search did not settle."""
    u_samples = _largest(u) if want_u else math.nan
    u_sup = u_samples
    n = t0.shape[0]
    i = -1
    while i + 1 < n:
        i += 1
        if not want_u:  # pass the steps whose bound does not exceed the best so far
            i = _first_reaching(reach, i, np.nextafter(hea_sup, math.inf))
            if i == n:
                break
        u_reach = math.inf
        if want_u:
            a = amplitude[i]
            u_reach = max(abs(u[i]), abs(u[i + 1])) + min(0.5 * (abs(row[3] * p1[i] * row[4]) + row[6] * a),
                                                          0.125 * row[0] * a * step) * _WIDEN * step
        bound = _float(reach[i])
        if bound > hea_sup or (want_u and u_reach > u_sup):
            f, _, _, guard = _forms(STICK, False, omega, xi, damped, 0.0, p0[i], p1[i], u[i], v[i], 0.0, 0.0)
            if bound > hea_sup:  # the guard is ky g - HEA with ky g = 0
                g = combine_forms(-1.0, guard, 0.0, guard, 0.0)
                g1 = form_derivative(g)
                g2 = form_derivative(g1)
                hea_sup = peak(g, g1, g2, form_derivative(g2), h[i], hea_sup, t0[i], stack)
            if want_u and u_reach > u_sup:
                f1 = form_derivative(f)
                f2 = form_derivative(f1)
                u_sup = peak(f, f1, f2, form_derivative(f2), h[i], u_sup, t0[i], stack)
            if hea_sup == -math.inf or u_sup == -math.inf:
                break
    return hea_sup, u_samples, u_sup


def _slow_step(t_start, length, a0, rate, step, maps, table, omega, xi, damped, kyg, coupled, cached, stack, no_log,
               counts, mode, u, v, s, w):
    """:func:`._engine._piece`, its quick step tried already, for a run from (``mode``,
    u, u', s, w), its counters ``counts`` (COUNT_FIELDS) updated: its (mode, u, u', s, w)
    at the end of the piece. ``no_log``: an empty (0, 8) knot log."""
    (mode, u, v, s, w, n_events, n_episodes, at_once, most, last, status, _) = _piece(
        t_start, length, a0, rate, step, maps, table, omega, xi, damped, kyg, coupled, cached, stack, no_log, 0, mode,
        u, v, s, w, int(counts[0]), int(counts[1]), int(counts[2]), int(counts[3]), counts[4], False)
    counts[0], counts[1], counts[2], counts[3], counts[4], counts[5] = (n_events, n_episodes, at_once, most, last,
                                                                        status)
    return mode, u, v, s, w


#: a run's counters: events, episodes, events at the last instant, most at one instant,
#: the last event's time [s], status
COUNT_FIELDS = ("n_events", "n_episodes", "at_once", "max_events_at_one_instant", "t_last_event", "status")
#: the kernels' compiler options: ``contract`` lets a multiply and an add fuse (FMA, one
#: rounding instead of two; no other fast-math licence), a fifth off the response's
#: recurrence (measured)
OPTIONS = dict(cache=True, error_model="numpy", fastmath={"contract"})
#: the closed-form step, compiled on its own: inlined, its size slows the loop over the
#: quick steps (by about a third, measured)
_slow_step_compiled = numba.njit(**OPTIONS)(_slow_step)


@register_jitable
def _difference_bound(du, dv, row):
    """A bound [m/s²] of |(2/pi)(c du' + k du)|, the part of HEA of a free STICK
    oscillation from (``du`` [m], ``dv`` [m/s]) (|X| <= amplitude, |X'| <= natural
    frequency x amplitude), for all later times while it stays free."""
    k, c, inverse_damped, natural = row[0], row[1], row[5], row[6]
    rotated = (dv + 0.5 * c * du) * inverse_damped
    return MASS_PARTICIPATION * (c * natural + k) * math.sqrt(du * du + rotated * rotated) * _WIDEN


@register_jitable
def _free_powers(m, row, step, n, scratch):
    """The free STICK oscillation over 2^p whole steps [s], p = 0 .. bits of ``n`` - 1
    (at most 64), in ``scratch`` (at least 5 per row): row p holds M^(2^p) (m0, m1, m2, m3; M the step map ``m``'s (u, u') part) and its
    amplitude's decay over those steps, rounded up (e^(-c step / 2) widened, then
    squared: each factor keeps its widening above a product's rounding)."""
    count = 1
    while (1 << count) <= n:
        count += 1
    powers = scratch[:5 * count].reshape((count, 5))
    powers[0, 0], powers[0, 1], powers[0, 2], powers[0, 3] = m[0], m[1], m[2], m[3]
    powers[0, 4] = math.exp(-0.5 * row[1] * step) * _WIDEN
    for p in range(1, count):
        a, b, c, d = powers[p - 1, 0], powers[p - 1, 1], powers[p - 1, 2], powers[p - 1, 3]
        powers[p, 0], powers[p, 1] = a * a + b * c, a * b + b * d
        powers[p, 2], powers[p, 3] = c * a + d * c, c * b + d * d
        powers[p, 4] = powers[p - 1, 4] * powers[p - 1, 4] * _WIDEN
    return powers


@register_jitable
def _free_steps(powers, count, du, dv, bound):
    """(du [m], du' [m/s], the bound of its |HEA| [m/s²]) of a free STICK oscillation
    ``count`` >= 1 whole steps on, by the powers of its step map (:func:`_free_powers`)."""
    p = 0
    while count:
        if count & 1:
            du, dv = powers[p, 0] * du + powers[p, 1] * dv, powers[p, 2] * du + powers[p, 3] * dv
            bound *= powers[p, 4]
        count >>= 1
        p += 1
    return du, dv, bound


@register_jitable
def _run(t0, h, p0, p1, sign, omega, xi, kyg, coupled, damped, maps, table, step, u, v, hea, amplitude, reach,
         powers, cached, stack, counts):
    """One sliding run of a(t) times ``sign`` from rest, its state in registers: each
    whole step quick where bounds allow (a coupled run steps its own column; a
    decoupled one's is the response's ``u``, ``v``, ``hea`` (n + 1,), ``amplitude``
    and bound of |HEA| ``reach`` (n,; bit patterns) times ``sign``), else in closed form.
    In STICK a coupled run differs from the response times ``sign`` by a free
    oscillation d, stepped alone, whose share of HEA has a bound that decays with it: a
    step where the response's bound plus it stays below ky g needs no more, and a stretch
    of such steps, found by the scan of the bounds, advances d at once by ``powers``
    (:func:`_free_powers`). Returns
    (mode, u, u', s, w) at the end; ``counts`` (COUNT_FIELDS) holds its counters and
    status."""
    stick_map, stick = maps[STICK], table[STICK]
    slip_map, slip = maps[SLIP], table[SLIP]
    mode, run_u, run_v, s, w = STICK, 0.0, 0.0, 0.0, 0.0
    # the free oscillation d = run - sign x response in STICK (from rest: 0), its bound of
    # |HEA| and that bound's factor over a step (rounded up)
    tracking, du, dv, bound = coupled, 0.0, 0.0, 0.0
    decay = powers[0, 4]
    no_log = stack[:0, :8]  # an empty knot log (a view: no allocation)
    n = t0.shape[0]
    i = -1
    while i + 1 < n:
        i += 1
        if not coupled and mode == STICK:  # decoupled: pass the steps whose bound of |HEA| stays below ky g
            i = _first_reaching(reach, i, kyg)
            if i == n:
                break
        level = kyg - bound
        if tracking and level > 0:  # pass at once the steps where the response's bound stays below it (a
            j = _first_reaching(reach, i, level)  # bound that is nan passes none)
            if j > i:
                du, dv, bound = _free_steps(powers, j - i, du, dv, bound)
                i = j
                if i == n:
                    break
        a0, rate = sign * p0[i], sign * p1[i]
        if h[i] == step:
            if coupled:  # each mode's map picked statically (a tuple indexed at run time is copied)
                if tracking:
                    if _float(reach[i]) + bound < kyg:
                        du, dv = stick_map[0] * du + stick_map[1] * dv, stick_map[2] * du + stick_map[3] * dv
                        bound *= decay
                        continue
                    run_u, run_v, tracking = sign * u[i] + du, sign * v[i] + dv, False
                if mode == STICK:
                    quick, u_end, v_end, s_end, w_end = _quick_step(STICK, stick_map, stick, step, xi, kyg, a0, rate,
                                                                    run_u, run_v, s, w)
                else:
                    quick, u_end, v_end, s_end, w_end = _quick_step(SLIP, slip_map, slip, step, xi, kyg, a0, rate,
                                                                    run_u, run_v, s, w)
                if quick:
                    run_u, run_v, s, w = u_end, v_end, s_end, w_end
                    if mode == STICK:
                        du, dv = run_u - sign * u[i + 1], run_v - sign * v[i + 1]
                        bound, tracking = _difference_bound(du, dv, stick), True
                    continue
            elif mode == STICK:  # decoupled: the response's step decides (its bound of |HEA| reaches ky g)
                if _stick_clear(kyg - sign * hea[i], kyg - sign * hea[i + 1], rate, stick, amplitude[i], xi, step):
                    continue
            else:
                pw, ps = _slip_polynomials(a0, rate, kyg, sign * u[i], sign * v[i], s, w)
                w_end = _cubic(pw, step) + MASS_PARTICIPATION * sign * v[i + 1]
                if _slip_clear(w, w_end, a0, rate, kyg, stick, amplitude[i], step):
                    s, w = _cubic(ps, step) + MASS_PARTICIPATION * sign * u[i + 1], w_end
                    continue
        if not coupled:
            run_u, run_v = sign * u[i], sign * v[i]
        elif tracking:
            run_u, run_v, tracking = sign * u[i] + du, sign * v[i] + dv, False
        mode, run_u, run_v, s, w = _slow_step_compiled(t0[i], h[i], a0, rate, step, maps, table, omega, xi, damped,
                                                       kyg, coupled, cached, stack, no_log, counts, mode, run_u, run_v,
                                                       s, w)
        if counts[5] != FINISHED:
            break
        if coupled and mode == STICK:
            du, dv = run_u - sign * u[i + 1], run_v - sign * v[i + 1]
            bound, tracking = _difference_bound(du, dv, stick), True
    if not coupled:  # the column's state is the response's
        run_u, run_v = sign * u[n], sign * v[n]
    elif tracking:
        run_u, run_v = sign * u[n] + du, sign * v[n] + dv
    return mode, run_u, run_v, s, w


@register_jitable
def _analysis(t0, h, p0, p1, omega, xi, kyg, coupled, runs, want_u, respond, out):
    """One analysis over the pieces (t0, h, p0, p1) [s, s, m/s², m/s³] of a(t) from rest:
    column omega [rad/s], xi [-], ky g [m/s²], ``coupled`` or decoupled; ``runs``: (2,)
    whether to run the normal and the inverse polarity; ``want_u``: find sup |u| (else
    nan); ``respond``: find the response's peaks (else nan; the response is stepped
    all the same, as every run reads it). Writes ``out`` (3, len(OUTCOME_FIELDS)): rows RESPONSE and the
    runs asked for."""
    n = t0.shape[0]
    # one allocation, in views: the response's u, u', HEA at the knots (n + 1 each), the free
    # amplitude on each step and the bit patterns of its bounds of |HEA| (n each; :func:`_bits`);
    # the searches' stack, the exp/cos/sin cache, a run's counters, the free powers
    scratch = np.empty(5 * n + 3 + STACK_DEPTH * STACK_COLUMNS + 6 + len(COUNT_FIELDS) + 64 * 5)
    u, v, hea = scratch[:n + 1], scratch[n + 1:2 * n + 2], scratch[2 * n + 2:3 * n + 3]  # each entry written
    amplitude, reach = scratch[3 * n + 3:4 * n + 3], scratch[4 * n + 3:5 * n + 3].view(np.int64)  # before read
    at = 5 * n + 3
    stack = scratch[at:at + STACK_DEPTH * STACK_COLUMNS].reshape((STACK_DEPTH, STACK_COLUMNS))
    at += STACK_DEPTH * STACK_COLUMNS
    cached, counts = scratch[at:at + 6], scratch[at + 6:at + 6 + len(COUNT_FIELDS)]
    free = scratch[at + 6 + len(COUNT_FIELDS):]
    cached[:] = math.nan
    damped = _damped(omega, xi, coupled)
    step = h[0]
    maps, table = _step_tables(omega, xi, coupled, kyg, damped, step)
    stick = table[STICK]
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
    powers = _free_powers(maps[STICK], stick, step, n, free)
    for r in range(2):
        if runs[r]:
            counts[:] = 0.0
            counts[4] = -math.inf
            mode, run_u, run_v, s, w = _run(t0, h, p0, p1, 1.0 - 2.0 * r, omega, xi, kyg, coupled, damped, maps, table,
                                            step, u, v, hea, amplitude, reach, powers, cached, stack, counts)
            _put(out[1 + r], (run_u, run_v, s, w, float(mode), counts[0], counts[1], 0.0, 0.0, 0.0, 0.0, counts[5],
                              counts[3], counts[4]))


@register_jitable
def _task(t0, h, p0, p1, offsets, tasks, j, out):
    """Analysis j: the task ``tasks[j]`` (TASK_FIELDS) on its excitation r (pieces
    ``offsets[r]:offsets[r + 1]`` of the concatenated arrays); writes ``out[j]`` (3,
    len(OUTCOME_FIELDS))."""
    task = tasks[j]
    r = int(task[0])
    lo, hi = offsets[r], offsets[r + 1]
    _analysis(t0[lo:hi], h[lo:hi], p0[lo:hi], p1[lo:hi], task[1], task[2], task[3], task[4] != 0, task[5:7] != 0,
              task[7] != 0, task[8] != 0, out[j])


def _analyses(t0, h, p0, p1, offsets, tasks, out):
    """Every analysis of ``tasks`` (:func:`_task`), in parallel over cores."""
    for j in numba.prange(tasks.shape[0]):
        _task(t0, h, p0, p1, offsets, tasks, j, out)


def _analyses_serial(t0, h, p0, p1, offsets, tasks, out):
    """Every analysis of ``tasks`` (:func:`_task`), one after another. A function of its
    own: numba's cache key omits ``parallel``, so one function compiled both ways shares
    one cache entry, and the serial kernel could load the parallel one (a parallel region
    per call, and an OpenMP worker left spinning)."""
    for j in range(tasks.shape[0]):
        _task(t0, h, p0, p1, offsets, tasks, j, out)


#: the first compile of either kernel [s] (one core; the serial one, benchmarks/cold_start.py)
COMPILE_SECONDS = 14


@functools.cache
def kernels():
    """(analyses parallel over cores, analyses serial) compiled with numba (on first use,
    then from the disk cache)."""
    return numba.njit(parallel=True, **OPTIONS)(_analyses), numba.njit(**OPTIONS)(_analyses_serial)


#: width of an analysis's outcome rows
WIDTH = len(OUTCOME_FIELDS)
