"""The compiled matrix-exponential engine of a flexible sliding mass's slides: the
mathematics and the event rules of :mod:`._table_engine` run by the generic driver
(:mod:`blockdae.core._driver`), in one numba call per slide, final numbers and events only.

The physics comes from :class:`._table_engine._System` (built once in Python, handed in
as arrays by :func:`._table_engine.system_arrays`): per (mode, piece of ky), the balanced
matrix M~ of z' = M z, z = (u, u', s, w, a, a', 1), its scale, its norm, and the rows c M^k
(k < 4) of each guard with the bound row of c M^4. This module steps and searches:

* z(tau) = expm(M tau) z(0), expm by Taylor's series (degree 16) on M~ tau scaled to a
  norm <= 1/2, squared back; a whole step's transition (its length recurs: the record's
  dt up to a few ulps of the time) is kept per (mode, piece of ky) in a few slots, any
  other length is applied to the vector (2^squarings Taylor passes) or, past
  :data:`_VECTOR_SQUARINGS`, built as a matrix;
* the first root of a guard on a step by the interval search of ``_Search`` (Taylor at an
  interval's start, its fourth derivative bounded by the matrix norm; an interval shown
  positive, monotone, convex or concave is decided, else halved, the earlier half first),
  crossings bisected to adjacent floats of the time; the breakpoint guard (next
  breakpoint minus s) falls monotonically in SLIP and is bracketed by its values;
* the driver's rules: a block at rest re-takes its mode at a piece's start (SLIP where
  d1 a > ky g), a guard at or below zero and falling as a mode starts is left at once, a
  root at the end of a piece is left to the next, a piece's rest shorter than 8 ulps is
  skipped, chatter (more than 5 events within 1e-12 s) and a slide moving upslope stop
  the run with a status.
"""

import functools
import math

import numba
import numpy as np
from numba.extending import register_jitable

from ..core._driver import _ULPS
from ..engines._linear import CHATTER, FINISHED, UNSETTLED, _falls
from ._column import SLIP_MASS_FRACTION

_EPS = float(np.finfo(float).eps)
#: status of a slide whose state contradicts its mode (w < 0 in SLIP beyond rounding)
INCONSISTENT = 4
STICK, SLIP = 0, 1
#: most intervals one root search may examine before it is reported as unsettled
MAX_INTERVALS = 20_000
#: events closer than this are one instant [s]; most events at one instant (chatter)
EVENT_RESOLUTION, MAX_EVENTS_AT_ONE_INSTANT = 1e-12, 5
#: degree of the Taylor series of the matrix exponential (on |M~ tau| <= 1/2)
TAYLOR_DEGREE = 16
#: whole-step lengths whose transitions are kept per (mode, piece of ky), and halvings of each
SLOTS, _DEPTHS = 16, 24
#: the first dropped term of Taylor's series of degree 16 at norm 1/2 (its truncation)
_TRUNCATION = 0.5**17 / math.factorial(17)
#: up to this many squarings a transition is applied to the vector (2^n Taylor passes)
_VECTOR_SQUARINGS = 3
#: pending intervals of one root search (its depth: a step halved to rounding is ~60)
_STACK = 256
#: a slide's outcome: its state at the end, counts, status
OUTCOME_FIELDS = ("t", "u", "u_rate", "s", "w", "mode", "passed", "n_events", "n_onsets", "status",
                  "max_events_at_one_instant", "t_last_event")
#: columns of the event log: time [s], modes before and after, the state before entry
EVENT_FIELDS = ("t", "mode_before", "mode_after", "u", "u_rate", "s", "w")
_T, _U, _V, _S, _W, _PASSED, _MODE, _LAST = range(8)  # the run's state (floats), the last event's time
_N_EVENTS, _N_ONSETS, _RUN, _MAX_RUN, _STATUS = range(5)  # its counters
_NO_ROOT, _HALVE = -1.0, -2.0


# ---- the matrix exponential ----------------------------------------------------------
@register_jitable
def _squarings(norm, tau):
    """Squarings that bring |M~ tau| [-] (``norm`` [1/s] times ``tau`` [s]) to <= 1/2."""
    return max(0, math.ceil(math.log2(max(norm * tau, 1e-300) / 0.5)))


@register_jitable
def _degree(x):
    """The least degree (<= 16) of Taylor's series of expm on a matrix of norm ``x`` <= 1/2
    whose first dropped term, x^(d+1) / (d+1)!, is at most degree 16's at 1/2 (2e-20)."""
    dropped = x * x / 2.0
    for degree in range(1, TAYLOR_DEGREE):
        if dropped <= _TRUNCATION:
            return degree
        dropped *= x / (degree + 2)
    return TAYLOR_DEGREE


@register_jitable
def _exponential(scaled, scale, norm, tau, out, term, total):
    """``out`` = expm(M tau) (7, 7) for ``tau`` [s] from the balanced M~ (7, 7) [1/s] and
    its ``scale`` (7,): Taylor on M~ tau / 2^n, squared n times, unscaled (as
    ``_System.exponential``); ``term``, ``total``: (7, 7) scratch."""
    squarings = _squarings(norm, tau)
    x = tau / 2.0**squarings
    for i in range(7):
        for j in range(7):
            term[i, j] = total[i, j] = 1.0 if i == j else 0.0
    for k in range(1, _degree(norm * x) + 1):
        factor = x / k
        for i in range(7):  # term @ (M~ x / k), into out as scratch
            for j in range(7):
                acc = 0.0
                for m in range(7):
                    acc += term[i, m] * scaled[m, j]
                out[i, j] = acc * factor
        for i in range(7):
            for j in range(7):
                term[i, j] = out[i, j]
                total[i, j] += out[i, j]
    for _ in range(squarings):
        for i in range(7):
            for j in range(7):
                acc = 0.0
                for m in range(7):
                    acc += total[i, m] * total[m, j]
                out[i, j] = acc
        for i in range(7):
            for j in range(7):
                total[i, j] = out[i, j]
    for i in range(7):
        for j in range(7):
            out[i, j] = total[i, j] * scale[i] / scale[j]


@register_jitable
def _matvec(matrix, z, out):
    """``out`` = ``matrix`` (7, 7) @ ``z`` (7,)."""
    for i in range(7):
        acc = 0.0
        for j in range(7):
            acc += matrix[i, j] * z[j]
        out[i] = acc


@register_jitable
def _dot(row, z):
    """``row`` (7,) . ``z`` (7,)."""
    acc = 0.0
    for j in range(7):
        acc += row[j] * z[j]
    return acc


@register_jitable
def _copy(source, target):
    """``target`` (7,) = ``source`` (7,)."""
    for i in range(7):
        target[i] = source[i]


@register_jitable
def _apply(scaled, scale, norm, tau, z, out, vectors):
    """``out`` = expm(M tau) z from the balanced M~: Taylor's series on M~ tau / 2^n
    applied to z~ = z / scale 2^n times; ``vectors``: (3, 7) scratch."""
    squarings = _squarings(norm, tau)
    x = tau / 2.0**squarings
    degree = _degree(norm * x)
    acc, term, nxt = vectors[0], vectors[1], vectors[2]
    for i in range(7):
        acc[i] = z[i] / scale[i]
    for _ in range(2**squarings):
        _copy(acc, term)
        for k in range(1, degree + 1):
            factor = x / k
            for i in range(7):
                total = 0.0
                for j in range(7):
                    total += scaled[i, j] * term[j]
                nxt[i] = total * factor
            for i in range(7):
                term[i] = nxt[i]
                acc[i] += nxt[i]
    for i in range(7):
        out[i] = acc[i] * scale[i]


@register_jitable
def _advance(system, tau, z, out):
    """``out`` = expm(M tau) z (7,) for ``tau`` [s] in ``system`` (see :func:`_system`):
    on a whole step of length L (its slot >= 0), tau = L / 2^d (d < _DEPTHS) by its kept
    transition (built on first use); else applied to the vector, or past
    :data:`_VECTOR_SQUARINGS` squarings built as a matrix."""
    scaled, scale, norm, taus, maps, slot, whole, matrices, vectors = system
    if slot >= 0:
        mantissa, exponent = math.frexp(whole / tau)
        depth = exponent - 1
        if mantissa == 0.5 and 0 <= depth < _DEPTHS:
            if taus[slot, depth] == tau:
                _matvec(maps[slot, depth], z, out)
                return
            if taus[slot, depth] == 0.0 and tau * 2.0**depth == whole:
                _exponential(scaled, scale, norm, tau, maps[slot, depth], matrices[0], matrices[1])
                taus[slot, depth] = tau
                _matvec(maps[slot, depth], z, out)
                return
    if _squarings(norm, tau) > _VECTOR_SQUARINGS:
        _exponential(scaled, scale, norm, tau, matrices[2], matrices[0], matrices[1])
        _matvec(matrices[2], z, out)
    else:
        _apply(scaled, scale, norm, tau, z, out, vectors)


# ---- the root search on one step ------------------------------------------------------
@register_jitable
def _lower(c, length):
    """A lower bound of sum c_k x^k over x in [0, ``length``] (nested)."""
    bound = c[len(c) - 1]
    for k in range(len(c) - 2, -1, -1):
        bound = c[k] + length * min(0.0, bound)
    return bound


@register_jitable
def _upper(c, length):
    """An upper bound of sum c_k x^k over x in [0, ``length``]."""
    bound = c[len(c) - 1]
    for k in range(len(c) - 2, -1, -1):
        bound = c[k] + length * max(0.0, bound)
    return bound


@register_jitable
def _bisect(system, row, t0, lo, hi, z_lo, work):
    """The first tau in (lo, hi] [s] where ``row`` . z is <= 0, to adjacent floats of
    ``t0`` + tau, for > 0 at lo (state ``z_lo``), <= 0 at hi, one crossing between; each
    trial advanced from the last lo kept. ``work``: (5, 7), rows 3 and 4 used."""
    z_a, z_m = work[3], work[4]
    _copy(z_lo, z_a)
    while True:
        mid = lo + 0.5 * (hi - lo)
        if not (t0 + lo < t0 + mid < t0 + hi):
            return hi
        _advance(system, mid - lo, z_a, z_m)
        if _dot(row, z_m) > 0:
            lo = mid
            _copy(z_m, z_a)
        else:
            hi = mid


@register_jitable
def _bisect_rate(system, row, t0, lo, hi, z_lo, z_hi, work):
    """Where g' = ``row`` . z (rising on [lo, hi] [s], states ``z_lo``, ``z_hi``) crosses
    zero; lo or hi if it does not."""
    if _dot(row, z_lo) >= 0:
        return lo
    if _dot(row, z_hi) <= 0:
        return hi
    z_a, z_m = work[3], work[4]
    _copy(z_lo, z_a)
    while True:
        mid = lo + 0.5 * (hi - lo)
        if not (t0 + lo < t0 + mid < t0 + hi):
            return hi
        _advance(system, mid - lo, z_a, z_m)
        if _dot(row, z_m) < 0:
            lo = mid
            _copy(z_m, z_a)
        else:
            hi = mid


@register_jitable
def _fourth_bound(bound, z, length):
    """A bound of the guard's fourth derivative on [0, ``length``] [s] from z at its
    start (``_System.fourth_bound``): ``bound`` = (|c M^4 scale|_1, weights (7,): 1 / scale
    on the subsystem J that c M^4 z reads, 0 elsewhere, |M~_JJ| [1/s]); |c M^4 scale|_1
    exp(|M~_JJ| length) |z~_J|_inf, inf past a growth of e^50."""
    row4, weights, inner = bound
    growth = inner * length
    if growth > 50.0:
        return math.inf
    largest = 0.0
    for i in range(7):
        largest = max(largest, abs(z[i] * weights[i]))
    return row4 * math.exp(growth) * largest * (1.0 + 1e-9)


@register_jitable
def _decide(system, powers, bound, t0, lo, hi, z_lo, z_hi, work):
    """One interval (lo, hi] [s] of the search, z_lo and z_hi (7,) at its ends: the first
    crossing in it (> 0), none (:data:`_NO_ROOT`) or :data:`_HALVE`."""
    length = hi - lo
    d0, d1, d2, d3 = _dot(powers[0], z_lo), _dot(powers[1], z_lo), _dot(powers[2], z_lo), _dot(powers[3], z_lo)
    g_lo, g_hi = d0, _dot(powers[0], z_hi)
    if t0 + lo + length <= t0 + lo or length <= 4 * _EPS * max(abs(t0) + abs(hi), 1.0):
        return hi if g_lo > 0 >= g_hi else _NO_ROOT
    if g_lo == 0 and g_hi == 0 and d1 == 0 and d2 == 0 and d3 == 0:
        return _NO_ROOT  # a guard that stays at zero (HEA = ky g = 0 at rest): no fall through it
    b4 = _fourth_bound(bound, z_lo, length)
    if _lower((d0, d1, d2 / 2, d3 / 6, -b4 / 24), length) > 0:
        return _NO_ROOT  # positive all along
    if _lower((d1, d2, d3 / 2, -b4 / 6), length) >= 0:
        return _NO_ROOT  # rising all along
    if _upper((d1, d2, d3 / 2, b4 / 6), length) <= 0:  # falling all along
        return _bisect(system, powers[0], t0, lo, hi, z_lo, work) if g_lo > 0 >= g_hi else _NO_ROOT
    if _lower((d2, d3, -b4 / 2), length) > 0 and g_lo > 0:  # convex: falls, then rises
        turn = _bisect_rate(system, powers[1], t0, lo, hi, z_lo, z_hi, work)
        z_turn = work[0]
        if turn == lo:
            _copy(z_lo, z_turn)
        else:
            _advance(system, turn - lo, z_lo, z_turn)
        if _dot(powers[0], z_turn) <= 0:
            return _bisect(system, powers[0], t0, lo, turn, z_lo, work)
        return _NO_ROOT
    if _upper((d2, d3, b4 / 2), length) < 0 and g_lo > 0:  # concave: one crossing at most
        return _bisect(system, powers[0], t0, lo, hi, z_lo, work) if g_hi <= 0 else _NO_ROOT
    return _HALVE


@register_jitable
def _first_root(system, powers, bound, z0, z_end, t0, h, work, stack):
    """The first tau in (0, ``h``] [s] where the guard c z (``powers``: c M^k, (4, 7);
    ``bound``: of its fourth derivative, see :func:`_fourth_bound`) falls to <= 0 from > 0 on a step from z0 (7,) at ``t0`` [s], ``z_end`` = z(h):
    (tau or :data:`_NO_ROOT`, settled). A later half waits on ``stack`` (n, 10) with its
    parent's start and state, from which it is advanced. ``work``: (5, 7) scratch."""
    lo, hi, top = 0.0, h, 0
    z_lo, z_hi = work[1], work[2]
    _copy(z0, z_lo)
    _copy(z_end, z_hi)
    for budget in range(MAX_INTERVALS):
        if budget > 0:
            _advance(system, hi - lo, z_lo, z_hi)
        found = _decide(system, powers, bound, t0, lo, hi, z_lo, z_hi, work)
        if found > 0:
            return found, True
        if found == _HALVE:  # the earlier half first, the later one kept
            if top == stack.shape[0]:
                return _NO_ROOT, False
            mid = lo + 0.5 * (hi - lo)
            stack[top, 0], stack[top, 1], stack[top, 2] = mid, hi, lo
            stack[top, 3:] = z_lo
            top += 1
            hi = mid
            continue
        if top == 0:
            return _NO_ROOT, True
        top -= 1
        lo, hi = stack[top, 0], stack[top, 1]
        _advance(system, lo - stack[top, 2], stack[top, 3:], z_lo)
    return _NO_ROOT, False


# ---- the driver's rules -----------------------------------------------------------
@register_jitable
def _state_vector(state, a, rate, z):
    """z = (u, u', s, w, a, a', 1) from the run's ``state`` and a(t), a'(t)."""
    z[0], z[1], z[2], z[3] = state[_U], state[_V], state[_S], state[_W]
    z[4], z[5], z[6] = a, rate, 1.0


@register_jitable
def _left_at_once(powers, n_guards, z):
    """The first guard at or below zero and falling as a mode starts (the driver's
    ``guard_left_at_once``), or -1."""
    for g in range(n_guards):
        if _dot(powers[g, 0], z) <= 0:
            if _falls(_dot(powers[g, 1], z), _dot(powers[g, 2], z), EVENT_RESOLUTION):
                return g
    return -1


@register_jitable
def _log_event(state, counts, t, after, log):
    """An event at ``t`` [s] into ``after`` (the driver's ``log_event``): logged while the
    log has room, counted, chatter checked; past a breakpoint one more passed."""
    same_instant = counts[_N_EVENTS] > 0 and abs(t - state[_LAST]) <= EVENT_RESOLUTION
    counts[_RUN] = counts[_RUN] + 1 if same_instant else 1
    counts[_MAX_RUN] = max(counts[_MAX_RUN], counts[_RUN])
    before = int(state[_MODE])
    n = counts[_N_EVENTS]
    if n < log.shape[0]:
        log[n, 0], log[n, 1], log[n, 2] = t, before, after
        log[n, 3], log[n, 4], log[n, 5], log[n, 6] = state[_U], state[_V], state[_S], state[_W]
    counts[_N_EVENTS] = n + 1
    if before == STICK and after == SLIP:
        counts[_N_ONSETS] += 1
    if before == SLIP and after == SLIP:
        state[_PASSED] += 1.0
    if counts[_RUN] > MAX_EVENTS_AT_ONE_INSTANT:
        counts[_STATUS] = CHATTER
    state[_MODE], state[_LAST] = after, t


@register_jitable
def _on_guard(state, counts, index, t, log):
    """Guard ``index`` of the current mode reached zero at ``t`` [s]: w = 0 at an onset or
    a stop; STICK -> SLIP, SLIP -> STICK, a breakpoint (SLIP guard 1) stays in SLIP."""
    mode = int(state[_MODE])
    breakpoint = mode == SLIP and index == 1
    if not breakpoint:
        state[_W] = 0.0
    _log_event(state, counts, t, SLIP if mode == STICK or breakpoint else STICK, log)


@register_jitable
def _at_rest(state):
    """Nothing has moved yet: STICK and every state zero."""
    return (state[_MODE] == STICK and state[_U] == 0.0 and state[_V] == 0.0 and state[_S] == 0.0
            and state[_W] == 0.0 and state[_PASSED] == 0.0)


@register_jitable
def _step(state, counts, system, powers, bound, n_guards, end, a, rate, z0, z_end, z, work, stack):
    """One step of the current mode from the state at ``state[_T]`` to ``end`` [s] or its
    first guard root (the driver's step with :class:`TableIntegrator`): the state
    advanced, its root's index returned (-1: none)."""
    t = state[_T]
    h = end - t
    _state_vector(state, a, rate, z0)
    _advance(system, h, z0, z_end)
    best, index = _NO_ROOT, -1
    root, settled = _first_root(system, powers[0], bound, z0, z_end, t, h, work, stack)
    if not settled:
        counts[_STATUS] = UNSETTLED
        return -1
    if root > 0:
        best, index = root, 0
    if n_guards == 2 and _dot(powers[1, 0], z0) > 0 >= _dot(powers[1, 0], z_end):
        root = _bisect(system, powers[1, 0], t, 0.0, h, z0, work)
        if best < 0 or root < best:
            best, index = root, 1
    if best < 0:
        _copy(z_end, z)
        state[_T] = end
    else:
        _advance(system, best, z0, z)
        state[_T] = t + best
        if state[_T] >= end:  # a root at the end of the piece is left to the next piece
            state[_T], index = end, -1
    state[_U], state[_V], state[_S], state[_W] = z[0], z[1], z[2], z[3]
    return index


def _slides(t0, h, p0, p1, slots, scaled, scale, norm, powers, row4, weights, inner, n_guards, n_pieces, kyg, log):
    """One slide from rest over a record's linear pieces (``t0``, ``h`` [s], a = ``p0`` +
    ``p1`` tau [m/s², m/s³], (n,) each; ``slots`` (n,): the slot of each piece's length,
    or -1, from :func:`step_slots`) by the systems (mode * ``n_pieces`` + pieces of ky
    passed; ``scaled`` (k, 7, 7) [1/s], ``scale`` (k, 7), ``norm`` (k,) [1/s], ``powers``
    (k, 2, 4, 7), ``row4`` (k, 2), ``weights`` (k, 2, 7), ``inner`` (k, 2) [1/s] (see
    :func:`_fourth_bound`), ``n_guards`` (k,)); ``kyg``: ky g at s = 0 [m/s²].
    Events go into ``log`` (m, 7) (EVENT_FIELDS) while it has room. Returns the outcome
    (OUTCOME_FIELDS)."""
    n_systems = scaled.shape[0]
    taus, maps = np.zeros((n_systems, SLOTS, _DEPTHS)), np.empty((n_systems, SLOTS, _DEPTHS, 7, 7))
    matrices, vectors = np.empty((3, 7, 7)), np.empty((3, 7))
    z0, z_end, z, work, stack = np.empty(7), np.empty(7), np.empty(7), np.empty((5, 7)), np.empty((_STACK, 10))
    state = np.zeros(8)  # t, u, u', s, w, passed, mode, the last event's time
    counts = np.zeros(5, dtype=np.int64)
    v_max = 0.0
    n = t0.shape[0]
    for k in range(n):
        start = t0[k]
        end = t0[k + 1] if k + 1 < n else t0[k] + h[k]
        if _at_rest(state):  # the driver's mode_at_rest at the piece's start
            excess = SLIP_MASS_FRACTION * p0[k] - kyg
            if excess > 0 or (excess == 0 and p1[k] > 0):
                _log_event(state, counts, start, SLIP, log)
        restarted = True
        while state[_T] < end and counts[_STATUS] == FINISHED:
            i = int(state[_MODE]) * n_pieces + int(state[_PASSED])
            a = p0[k] + p1[k] * min(state[_T] - start, h[k])
            if restarted:
                _state_vector(state, a, p1[k], z0)
                index = _left_at_once(powers[i], n_guards[i], z0)
                if index >= 0:
                    before = state[_MODE]
                    _on_guard(state, counts, index, state[_T], log)
                    if state[_MODE] != before or counts[_STATUS] != FINISHED:
                        continue
                    i = int(state[_MODE]) * n_pieces + int(state[_PASSED])
                restarted = False
            if end - state[_T] <= _ULPS * _EPS * max(1.0, abs(end)):
                state[_T], restarted = end, True  # too short for a step: nothing can happen
                continue
            slot = slots[k] if state[_T] == start else -1
            system = (scaled[i], scale[i], norm[i], taus[i], maps[i], slot, end - start, matrices, vectors)
            bound = (row4[i, 0], weights[i, 0], inner[i, 0])  # of the first guard (the second is monotone)
            index = _step(state, counts, system, powers[i], bound, n_guards[i], end, a, p1[k], z0, z_end, z,
                          work, stack)
            v_max = max(v_max, abs(state[_V]), abs(state[_W]))
            if state[_MODE] == SLIP and state[_W] < -1e-12 * v_max:
                counts[_STATUS] = INCONSISTENT
            elif index >= 0:
                _on_guard(state, counts, index, state[_T], log)
                restarted = True
        if counts[_STATUS] != FINISHED:
            break
    out = np.empty(len(OUTCOME_FIELDS))
    out[0], out[1], out[2], out[3], out[4] = state[_T], state[_U], state[_V], state[_S], state[_W]
    out[5], out[6], out[7], out[8] = state[_MODE], state[_PASSED], counts[_N_EVENTS], counts[_N_ONSETS]
    out[9], out[10] = counts[_STATUS], counts[_MAX_RUN]
    out[11] = state[_LAST] if counts[_N_EVENTS] > 0 else np.nan
    return out


def step_slots(t0, h):
    """The slot of each piece's length (end - start [s], (n,)) among the :data:`SLOTS`
    most frequent ones (their transitions are kept), -1 for the others."""
    lengths = np.append(t0[1:], t0[-1] + h[-1]) - t0
    distinct, inverse, counts = np.unique(lengths, return_inverse=True, return_counts=True)
    slot_of = np.full(distinct.size, -1, dtype=np.int64)
    slot_of[np.argsort(-counts, kind="stable")[:SLOTS]] = np.arange(min(SLOTS, distinct.size))
    return slot_of[inverse]


@functools.cache
def kernel():
    """:func:`_slides` compiled with numba (on first use, then from the disk cache)."""
    return numba.njit(cache=True, error_model="numpy")(_slides)
