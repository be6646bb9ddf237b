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
#: whole-step transitions kept per (mode, piece of ky): distinct step lengths [-]
_SLOTS = 16
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
_NO_ROOT = -1.0


# ---- the matrix exponential ----------------------------------------------------------
@register_jitable
def _squarings(norm, tau):
    """Squarings that bring |M~ tau| [-] (``norm`` [1/s] times ``tau`` [s]) to <= 1/2."""
    return max(0, math.ceil(math.log2(max(norm * tau, 1e-300) / 0.5)))


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
    for k in range(1, TAYLOR_DEGREE + 1):
        factor = x / k
        for i in range(7):  # term @ (M~ x / k), row by row into out's rows as scratch
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
def _apply(scaled, scale, norm, tau, z, out, vectors):
    """``out`` = expm(M tau) z from the balanced M~: Taylor's series of degree 16 on
    M~ tau / 2^n applied to z~ = z / scale 2^n times; ``vectors``: (3, 7) scratch."""
    squarings = _squarings(norm, tau)
    x = tau / 2.0**squarings
    acc, term, nxt = vectors[0], vectors[1], vectors[2]
    for i in range(7):
        acc[i] = z[i] / scale[i]
    for _ in range(2**squarings):
        for i in range(7):
            term[i] = acc[i]
        for k in range(1, TAYLOR_DEGREE + 1):
            factor = x / k
            for i in range(7):
                s = 0.0
                for j in range(7):
                    s += scaled[i, j] * term[j]
                nxt[i] = s * factor
            for i in range(7):
                term[i] = nxt[i]
                acc[i] += nxt[i]
    for i in range(7):
        out[i] = acc[i] * scale[i]


@register_jitable
def _advance(system, tau, z, out, keep):
    """``out`` = expm(M tau) z (7,) for ``tau`` [s] in ``system`` (see :func:`_system`):
    from a kept transition of that length, else (``keep``: a whole step's, kept while a
    slot is free) built, else applied to the vector."""
    scaled, scale, norm, taus, maps, count, matrices, vectors = system
    for slot in range(count[0]):
        if taus[slot] == tau:
            _matvec(maps[slot], z, out)
            return
    if keep and count[0] < taus.shape[0]:
        slot = count[0]
        _exponential(scaled, scale, norm, tau, maps[slot], matrices[0], matrices[1])
        taus[slot] = tau
        count[0] = slot + 1
        _matvec(maps[slot], z, out)
    elif _squarings(norm, tau) > _VECTOR_SQUARINGS:
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
def _value(system, powers, order, tau, z0, work):
    """The guard's derivative of ``order`` (c M^order z) at ``tau`` [s] from z0 at 0."""
    _advance(system, tau, z0, work, False)
    return _dot(powers[order], work)


@register_jitable
def _bisect(system, powers, order, z0, t0, lo, hi, work):
    """The first tau in (lo, hi] [s] where the guard's derivative of ``order`` is <= 0,
    to adjacent floats of ``t0`` + tau, for > 0 at lo, <= 0 at hi, one crossing between."""
    while True:
        mid = lo + 0.5 * (hi - lo)
        if not (t0 + lo < t0 + mid < t0 + hi):
            return hi
        if _value(system, powers, order, mid, z0, work) > 0:
            lo = mid
        else:
            hi = mid


@register_jitable
def _bisect_rate(system, powers, z0, t0, lo, hi, work):
    """Where g' (rising on [lo, hi] [s]) crosses zero; lo or hi if it does not."""
    if _value(system, powers, 1, lo, z0, work) >= 0:
        return lo
    if _value(system, powers, 1, hi, z0, work) <= 0:
        return hi
    while True:
        mid = lo + 0.5 * (hi - lo)
        if not (t0 + lo < t0 + mid < t0 + hi):
            return hi
        if _value(system, powers, 1, mid, z0, work) < 0:
            lo = mid
        else:
            hi = mid


@register_jitable
def _fourth_bound(system, row4, z, length):
    """A bound of |g''''| on [0, ``length``] [s] from z at its start: |c M^4 scale|_1
    exp(|M~| length) |z / scale|_inf (inf where the growth exceeds e^50)."""
    scale, norm = system[1], system[2]
    growth = norm * length
    if growth > 50.0:
        return math.inf
    largest = 0.0
    for i in range(7):
        largest = max(largest, abs(z[i] / scale[i]))
    return row4 * math.exp(growth) * largest * (1.0 + 1e-9)


@register_jitable
def _decide(system, powers, row4, z0, t0, lo, hi, z_lo, z_hi, work):
    """One interval (lo, hi] [s] of the search, z_lo and z_hi (7,) at its ends: the first
    crossing in it (> 0), none (:data:`_NO_ROOT`), or -2 (halve it)."""
    length = hi - lo
    d0, d1, d2, d3 = _dot(powers[0], z_lo), _dot(powers[1], z_lo), _dot(powers[2], z_lo), _dot(powers[3], z_lo)
    g_lo, g_hi = d0, _dot(powers[0], z_hi)
    if t0 + lo + length <= t0 + lo or length <= 4 * _EPS * max(abs(t0) + abs(hi), 1.0):
        return hi if g_lo > 0 >= g_hi else _NO_ROOT
    if g_lo == 0 and g_hi == 0 and d1 == 0 and d2 == 0 and d3 == 0:
        return _NO_ROOT  # a guard that stays at zero (HEA = ky g = 0 at rest): no fall through it
    b4 = _fourth_bound(system, row4, z_lo, length)
    if _lower((d0, d1, d2 / 2, d3 / 6, -b4 / 24), length) > 0:
        return _NO_ROOT  # positive all along
    if _lower((d1, d2, d3 / 2, -b4 / 6), length) >= 0:
        return _NO_ROOT  # rising all along
    if _upper((d1, d2, d3 / 2, b4 / 6), length) <= 0:  # falling all along
        return _bisect(system, powers, 0, z0, t0, lo, hi, work) if g_lo > 0 >= g_hi else _NO_ROOT
    if _lower((d2, d3, -b4 / 2), length) > 0 and g_lo > 0:  # convex: falls, then rises
        turn = _bisect_rate(system, powers, z0, t0, lo, hi, work)
        if _value(system, powers, 0, turn, z0, work) <= 0:
            return _bisect(system, powers, 0, z0, t0, lo, turn, work)
        return _NO_ROOT
    if _upper((d2, d3, b4 / 2), length) < 0 and g_lo > 0:  # concave: one crossing at most
        return _bisect(system, powers, 0, z0, t0, lo, hi, work) if g_hi <= 0 else _NO_ROOT
    return -2.0


@register_jitable
def _first_root(system, powers, row4, z0, z_end, t0, h, work, stack):
    """The first tau in (0, ``h``] [s] where the guard c z (``powers``: c M^k, (4, 7))
    falls to <= 0 from > 0 on a step from z0 (7,) at ``t0`` [s], ``z_end`` = z(h):
    (tau or :data:`_NO_ROOT`, settled). ``work``: (4, 7) scratch, ``stack``: (n, 2)."""
    lo, hi, top = 0.0, h, 0
    z_lo, z_hi, z_mid = work[1], work[2], work[3]
    for i in range(7):
        z_lo[i], z_hi[i] = z0[i], z_end[i]
    for budget in range(MAX_INTERVALS):
        if budget > 0:
            _advance(system, hi - lo, z_lo, z_hi, False)
        found = _decide(system, powers, row4, z0, t0, lo, hi, z_lo, z_hi, work[0])
        if found > 0:
            return found, True
        if found == -2.0:  # the earlier half first, the later one kept
            if top == stack.shape[0]:
                return _NO_ROOT, False
            mid = lo + 0.5 * (hi - lo)
            stack[top, 0], stack[top, 1] = mid, hi
            top += 1
            hi = mid
            continue
        if top == 0:
            return _NO_ROOT, True
        top -= 1
        lo, hi = stack[top, 0], stack[top, 1]
        _advance(system, lo, z0, z_mid, False)
        for i in range(7):
            z_lo[i] = z_mid[i]
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
def _system(k, scaled, scale, norm, taus, maps, count, matrices, vectors):
    """The tuple of system ``k`` that :func:`_advance` takes."""
    return (scaled[k], scale[k], norm[k], taus[k], maps[k], count[k:k + 1], matrices, vectors)


@register_jitable
def _step(state, counts, system, powers, row4, n_guards, t_start, end, a, rate, z0, z_end, z, work, stack):
    """One step of the current mode from the state at ``state[_T]`` to ``end`` [s] or its
    first guard root (the driver's step with :class:`TableIntegrator`): the state
    advanced, its root's index returned (-1: none)."""
    t = state[_T]
    h = end - t
    _state_vector(state, a, rate, z0)
    _advance(system, h, z0, z_end, t == t_start)
    best, index = _NO_ROOT, -1
    root, settled = _first_root(system, powers[0], row4[0], z0, z_end, t, h, work, stack)
    if not settled:
        counts[_STATUS] = UNSETTLED
        return -1
    if root > 0:
        best, index = root, 0
    if n_guards == 2 and _dot(powers[1, 0], z0) > 0 >= _dot(powers[1, 0], z_end):
        root = _bisect(system, powers[1], 0, z0, t, 0.0, h, work[0])
        if best < 0 or root < best:
            best, index = root, 1
    if best < 0:
        for i in range(7):
            z[i] = z_end[i]
        state[_T] = end
    else:
        _advance(system, best, z0, z, False)
        state[_T] = t + best
        if state[_T] >= end:  # a root at the end of the piece is left to the next piece
            state[_T], index = end, -1
    state[_U], state[_V], state[_S], state[_W] = z[0], z[1], z[2], z[3]
    return index


def _slides(t0, h, p0, p1, scaled, scale, norm, powers, row4, n_guards, n_pieces, kyg, log):
    """One slide from rest over a record's linear pieces (``t0``, ``h`` [s], a = ``p0`` +
    ``p1`` tau [m/s², m/s³], (n,) each) by the systems (mode * ``n_pieces`` + pieces of ky
    passed; ``scaled`` (k, 7, 7) [1/s], ``scale`` (k, 7), ``norm`` (k,) [1/s], ``powers``
    (k, 2, 4, 7), ``row4`` (k, 2), ``n_guards`` (k,)) of :func:`system_arrays`; ``kyg``: ky
    g at s = 0 [m/s²]. Events go into ``log`` (m, 7) (EVENT_FIELDS) while it has room.
    Returns the outcome (OUTCOME_FIELDS)."""
    n_systems = scaled.shape[0]
    taus, maps = np.empty((n_systems, _SLOTS)), np.empty((n_systems, _SLOTS, 7, 7))
    count = np.zeros(n_systems, dtype=np.int64)
    matrices, vectors = np.empty((3, 7, 7)), np.empty((3, 7))
    z0, z_end, z, work, stack = np.empty(7), np.empty(7), np.empty(7), np.empty((4, 7)), np.empty((_STACK, 2))
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
            system = _system(i, scaled, scale, norm, taus, maps, count, matrices, vectors)
            index = _step(state, counts, system, powers[i], row4[i], n_guards[i], start, end, a, p1[k], z0, z_end,
                          z, work, stack)
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


@functools.cache
def kernel():
    """:func:`_slides` compiled with numba (on first use, then from the disk cache)."""
    return numba.njit(cache=True, error_model="numpy")(_slides)
