"""The compiled matrix-exponential engine of a flexible sliding mass's slides: the
mathematics and the event rules of :mod:`._table_engine` run by the generic driver
(:mod:`blockdae.core._driver`), in one numba call per slide, final numbers and events only.

The physics comes from :class:`._table_engine._System` (built once in Python, packed by
:func:`._table_engine.system_arrays` into one array, :data:`SYSTEM_ROWS` rows of 7 per
(mode, piece of ky)): the balanced matrix M~ of z' = M z, z = (u, u', s, w, a, a', 1),
its scale and norm, each guard's rows c M^k (k < 4) and what bounds c M^4 z. This module
steps and searches:

* z(tau) = expm(M tau) z(0), expm by Taylor's series (degree 16 at norm 1/2, fewer terms
  below, dropping less than degree 16 does there) on M~ tau scaled to a norm <= 1/2,
  squared back. A whole step's transition (the record's dt up to a few ulps of the
  time: :data:`SLOTS` lengths) and its halvings (the search's intervals, to
  :data:`_DEPTHS`) are kept per (mode, piece of ky); any other length is applied to the
  vector (2^squarings Taylor passes) or, past :data:`_VECTOR_SQUARINGS`, built.
* The first root of a guard on a step by the interval search of ``_Search`` (Taylor at an
  interval's start, its fourth derivative bounded by the matrix norm; an interval shown
  positive, monotone, convex or concave is decided, else halved, the earlier half
  first), crossings bisected to adjacent floats of the time; the breakpoint guard (next
  breakpoint minus s) falls monotonically in SLIP and is bracketed by its values. A
  later half or a bisection's trial is advanced from the nearest state before it.
* The driver's rules: a block at rest re-takes its mode at a piece's start (SLIP where
  d1 a > ky g), a guard at or below zero and falling as a mode starts is left at once, a
  root at the end of a piece is left to the next, a piece's rest shorter than 8 ulps is
  skipped, chatter (more than 5 events within 1e-12 s) and a slide moving upslope stop
  the run with a status.
* The no-sliding response (:func:`_response`, for a total damping too close to 1 for
  the closed forms): max |HEA| at the samples, and the suprema of |HEA| and |u| over
  time by an interval search on their bounds.

Arrays are indexed, not sliced, in the hot paths (a view costs a reference count).
"""

import functools
import math

import numba
import numpy as np
from numba.extending import register_jitable

from ..solvers import CHATTER, FINISHED, UNSETTLED
from ..core import falls, too_short

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
#: the first dropped term of Taylor's series of degree 16 at norm 1/2 (its truncation)
_TRUNCATION = 0.5**17 / math.factorial(17)
#: whole-step lengths whose transitions are kept per system, and halvings of each
SLOTS, _DEPTHS = 16, 12
#: up to this many squarings a transition is applied to the vector (2^n Taylor passes)
_VECTOR_SQUARINGS = 3
#: pending intervals of one root search (its depth: a step halved to rounding is ~60)
_STACK = 256
#: rows of a system (each of 7): M~ (7), scale, each guard's weights of its fourth
#: derivative's bound, each guard's c M^k (k < 4), then (norm [1/s], number of guards,
#: and of guard g at 2 + 2 g and 3 + 2 g: |c M^4 scale|_1 and the inner norm [1/s])
MATRIX, SCALE, WEIGHTS, POWERS, NUMBERS = 0, 7, 8, 10, 18
SYSTEM_ROWS = 19
#: a slide's outcome: its state at the end, counts, status
OUTCOME_FIELDS = ("t", "u", "u_rate", "s", "w", "mode", "passed", "n_events", "n_onsets", "status",
                  "max_events_at_one_instant", "t_last_event")
#: columns of the event log: time [s], modes before and after, the state before entry
EVENT_FIELDS = ("t", "mode_before", "mode_after", "u", "u_rate", "s", "w")
_T, _U, _V, _S, _W, _PASSED, _MODE, _LAST = range(8)  # the run's state (floats), the last event's time
_N_EVENTS, _N_ONSETS, _RUN, _MAX_RUN, _STATUS = range(5)  # its counters
#: rows of the vectors' scratch (each z of 7): a step's start, end and result; a search
#: interval's ends; a bisection's kept and trial states; the turn; a parent; Taylor's
_Z0, _ZEND, _Z, _ZLO, _ZHI, _ZA, _ZM, _ZTURN, _ZPARENT, _ACC, _TERM, _NEXT = range(12)
_NO_ROOT, _HALVE = -1.0, -2.0
#: a peak search ends where no interval's bound exceeds the largest value by more than this [-]
_PEAK_TOLERANCE = 1e-14


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
def _exponential(systems, i, tau, scratch):
    """scratch[2] = expm(M tau) (7, 7) of system ``i`` for ``tau`` [s]: Taylor on M~ tau /
    2^n, squared n times, unscaled (as ``_System.exponential``); scratch[0], [1]: work."""
    squarings = _squarings(systems[i, NUMBERS, 0], tau)
    x = tau / 2.0**squarings
    for r in range(7):
        for c in range(7):
            scratch[0, r, c] = scratch[1, r, c] = 1.0 if r == c else 0.0
    for k in range(1, _degree(systems[i, NUMBERS, 0] * x) + 1):
        factor = x / k
        for r in range(7):  # term @ (M~ x / k)
            for c in range(7):
                acc = 0.0
                for m in range(7):
                    acc += scratch[0, r, m] * systems[i, MATRIX + m, c]
                scratch[2, r, c] = acc * factor
        for r in range(7):
            for c in range(7):
                scratch[0, r, c] = scratch[2, r, c]
                scratch[1, r, c] += scratch[2, r, c]
    for _ in range(squarings):
        for r in range(7):
            for c in range(7):
                acc = 0.0
                for m in range(7):
                    acc += scratch[1, r, m] * scratch[1, m, c]
                scratch[2, r, c] = acc
        for r in range(7):
            for c in range(7):
                scratch[1, r, c] = scratch[2, r, c]
    for r in range(7):
        for c in range(7):
            scratch[2, r, c] = scratch[1, r, c] * systems[i, SCALE, r] / systems[i, SCALE, c]


@register_jitable
def _apply(systems, i, tau, vectors, a, b):
    """vectors[b] = expm(M tau) vectors[a] in system ``i``: Taylor's series on M~ tau / 2^n
    applied to z~ = z / scale 2^n times."""
    squarings = _squarings(systems[i, NUMBERS, 0], tau)
    x = tau / 2.0**squarings
    degree = _degree(systems[i, NUMBERS, 0] * x)
    for r in range(7):
        vectors[_ACC, r] = vectors[a, r] / systems[i, SCALE, r]
    for _ in range(2**squarings):
        for r in range(7):
            vectors[_TERM, r] = vectors[_ACC, r]
        for k in range(1, degree + 1):
            factor = x / k
            for r in range(7):
                acc = 0.0
                for c in range(7):
                    acc += systems[i, MATRIX + r, c] * vectors[_TERM, c]
                vectors[_NEXT, r] = acc * factor
            for r in range(7):
                vectors[_TERM, r] = vectors[_NEXT, r]
                vectors[_ACC, r] += vectors[_NEXT, r]
    for r in range(7):
        vectors[b, r] = vectors[_ACC, r] * systems[i, SCALE, r]


@register_jitable
def _advance(systems, kept, scratch, vectors, step, tau, a, b):
    """vectors[b] = expm(M tau) vectors[a] for ``tau`` [s] (a != b) in the step's system;
    ``step`` = (system, slot of the step's whole length or -1, that length [s]). A length
    L / 2^d (d < _DEPTHS) of a whole step uses its kept transition (built on first use);
    any other is applied to the vector, or built past :data:`_VECTOR_SQUARINGS`."""
    i, slot, whole = step
    if slot >= 0:
        mantissa, exponent = math.frexp(whole / tau)
        d = exponent - 1
        if mantissa == 0.5 and 0 <= d < _DEPTHS and (kept[i, slot, d, 7, 0] == tau or (
                kept[i, slot, d, 7, 0] == 0.0 and tau * 2.0**d == whole)):
            if kept[i, slot, d, 7, 0] == 0.0:
                _exponential(systems, i, tau, scratch)
                kept[i, slot, d, :7, :] = scratch[2]
                kept[i, slot, d, 7, 0] = tau
            for r in range(7):
                acc = 0.0
                for c in range(7):
                    acc += kept[i, slot, d, r, c] * vectors[a, c]
                vectors[b, r] = acc
            return
    if _squarings(systems[i, NUMBERS, 0], tau) > _VECTOR_SQUARINGS:
        _exponential(systems, i, tau, scratch)
        for r in range(7):
            acc = 0.0
            for c in range(7):
                acc += scratch[2, r, c] * vectors[a, c]
            vectors[b, r] = acc
    else:
        _apply(systems, i, tau, vectors, a, b)


@register_jitable
def _dot(systems, i, row, vectors, a):
    """systems[i, row] . vectors[a]."""
    acc = 0.0
    for c in range(7):
        acc += systems[i, row, c] * vectors[a, c]
    return acc


@register_jitable
def _copy(vectors, a, b):
    """vectors[b] = vectors[a]."""
    for c in range(7):
        vectors[b, c] = vectors[a, c]


# ---- the root search on one step ------------------------------------------------------
#: sides of :func:`_bound`
LOWER, UPPER = 1.0, -1.0


@register_jitable
def _bound(c, length, side):
    """A bound of sum c_k x^k over x in [0, ``length``] (nested): a lower one for ``side``
    LOWER, an upper one for UPPER (the lower bound of the negated sum, negated: the same
    floats, as negation is exact and rounding symmetric)."""
    bound = side * c[len(c) - 1]
    for k in range(len(c) - 2, -1, -1):
        bound = side * c[k] + length * min(0.0, bound)
    return side * bound


#: directions of a crossing for :func:`_bisect`: a form falling to <= 0, or rising to >= 0
FALLING, RISING = 1.0, -1.0


@register_jitable
def _bisect(systems, kept, scratch, vectors, step, row, t0, lo, hi, a, direction=FALLING):
    """The first tau in (lo, hi] [s] where ``direction`` x systems[i, ``row``] . z is <= 0,
    to adjacent floats of ``t0`` + tau, for > 0 at lo (state vectors[a]), <= 0 at hi, one
    crossing between; each trial advanced from the last lo kept."""
    _copy(vectors, a, _ZA)
    while True:
        mid = lo + 0.5 * (hi - lo)
        if not (t0 + lo < t0 + mid < t0 + hi):
            return hi
        _advance(systems, kept, scratch, vectors, step, mid - lo, _ZA, _ZM)
        if direction * _dot(systems, step[0], row, vectors, _ZM) > 0:
            lo = mid
            _copy(vectors, _ZM, _ZA)
        else:
            hi = mid


@register_jitable
def _bisect_rate(systems, kept, scratch, vectors, step, row, t0, lo, hi):
    """Where g' = systems[i, ``row``] . z (rising on [lo, hi] [s], states at _ZLO, _ZHI)
    crosses zero; lo or hi if it does not."""
    i = step[0]
    if _dot(systems, i, row, vectors, _ZLO) >= 0:
        return lo
    if _dot(systems, i, row, vectors, _ZHI) <= 0:
        return hi
    return _bisect(systems, kept, scratch, vectors, step, row, t0, lo, hi, _ZLO, RISING)


@register_jitable
def _fourth_bound(systems, i, g, vectors, length):
    """A bound of guard ``g``'s fourth derivative on [0, ``length``] [s] from z =
    vectors[_ZLO] at its start (``_System.fourth_bound``): |c M^4 scale|_1 exp(|M~_JJ|
    length) |z~_J|_inf, J the subsystem c M^4 z reads; inf past a growth of e^50."""
    growth = systems[i, NUMBERS, 3 + 2 * g] * length
    if growth > 50.0:
        return math.inf
    largest = 0.0
    for c in range(7):
        largest = max(largest, abs(vectors[_ZLO, c] * systems[i, WEIGHTS + g, c]))
    return systems[i, NUMBERS, 2 + 2 * g] * math.exp(growth) * largest * (1.0 + 1e-9)


@register_jitable
def _decide(systems, kept, scratch, vectors, step, t0, lo, hi):
    """One interval (lo, hi] [s] of the first guard's search, its states at _ZLO and _ZHI:
    the first crossing in it (> 0), none (:data:`_NO_ROOT`) or :data:`_HALVE`."""
    i, length = step[0], hi - lo
    d0, d1 = _dot(systems, i, POWERS, vectors, _ZLO), _dot(systems, i, POWERS + 1, vectors, _ZLO)
    d2, d3 = _dot(systems, i, POWERS + 2, vectors, _ZLO), _dot(systems, i, POWERS + 3, vectors, _ZLO)
    g_lo, g_hi = d0, _dot(systems, i, POWERS, vectors, _ZHI)
    if t0 + lo + length <= t0 + lo or length <= 4 * _EPS * max(abs(t0) + abs(hi), 1.0):
        return hi if g_lo > 0 >= g_hi else _NO_ROOT
    if g_lo == 0 and g_hi == 0 and d1 == 0 and d2 == 0 and d3 == 0:
        return _NO_ROOT  # a guard that stays at zero (HEA = ky g = 0 at rest): no fall through it
    b4 = _fourth_bound(systems, i, 0, vectors, length)
    if _bound((d0, d1, d2 / 2, d3 / 6, -b4 / 24), length, LOWER) > 0:
        return _NO_ROOT  # positive all along
    if _bound((d1, d2, d3 / 2, -b4 / 6), length, LOWER) >= 0:
        return _NO_ROOT  # rising all along
    if _bound((d1, d2, d3 / 2, b4 / 6), length, UPPER) <= 0:  # falling all along
        return _bisect(systems, kept, scratch, vectors, step, POWERS, t0, lo, hi, _ZLO) if g_lo > 0 >= g_hi \
            else _NO_ROOT
    if _bound((d2, d3, -b4 / 2), length, LOWER) > 0 and g_lo > 0:  # convex: falls, then rises
        turn = _bisect_rate(systems, kept, scratch, vectors, step, POWERS + 1, t0, lo, hi)
        if turn == lo:
            _copy(vectors, _ZLO, _ZTURN)
        else:
            _advance(systems, kept, scratch, vectors, step, turn - lo, _ZLO, _ZTURN)
        if _dot(systems, i, POWERS, vectors, _ZTURN) <= 0:
            return _bisect(systems, kept, scratch, vectors, step, POWERS, t0, lo, turn, _ZLO)
        return _NO_ROOT
    if _bound((d2, d3, b4 / 2), length, UPPER) < 0 and g_lo > 0:  # concave: one crossing at most
        return _bisect(systems, kept, scratch, vectors, step, POWERS, t0, lo, hi, _ZLO) if g_hi <= 0 \
            else _NO_ROOT
    return _HALVE


@register_jitable
def _push_later_half(stack, top, vectors, lo, hi):
    """Halve (lo, hi] [s]: its later half waits on ``stack`` at ``top`` with its parent's
    start lo and state vectors[_ZLO]. Returns (the earlier half's end, the new top)."""
    mid = lo + 0.5 * (hi - lo)
    stack[top, 0], stack[top, 1], stack[top, 2] = mid, hi, lo
    for c in range(7):
        stack[top, 3 + c] = vectors[_ZLO, c]
    return mid, top + 1


@register_jitable
def _pop_later_half(systems, kept, scratch, vectors, step, stack, top):
    """The last half waiting on ``stack`` below ``top``, its start state advanced from its
    parent's into vectors[_ZLO]. Returns (lo, hi [s], the new top)."""
    top -= 1
    lo, hi = stack[top, 0], stack[top, 1]
    for c in range(7):
        vectors[_ZPARENT, c] = stack[top, 3 + c]
    _advance(systems, kept, scratch, vectors, step, lo - stack[top, 2], _ZPARENT, _ZLO)
    return lo, hi, top


@register_jitable
def _first_root(systems, kept, scratch, vectors, step, t0, h, stack):
    """The first tau in (0, ``h``] [s] where the first guard (c M^k and the bound of c M^4
    z in the system) falls to <= 0 from > 0 on a step from vectors[_Z0] at ``t0`` [s],
    vectors[_ZEND] = z(h): (tau or :data:`_NO_ROOT`, settled). A later half waits on
    ``stack`` (n, 10) with its parent's start and state, from which it is advanced."""
    lo, hi, top = 0.0, h, 0
    _copy(vectors, _Z0, _ZLO)
    _copy(vectors, _ZEND, _ZHI)
    for budget in range(MAX_INTERVALS):
        if budget > 0:
            _advance(systems, kept, scratch, vectors, step, hi - lo, _ZLO, _ZHI)
        found = _decide(systems, kept, scratch, vectors, step, t0, lo, hi)
        if found > 0:
            return found, True
        if found == _HALVE:  # the earlier half first, the later one kept
            if top == stack.shape[0]:
                return _NO_ROOT, False
            hi, top = _push_later_half(stack, top, vectors, lo, hi)
            continue
        if top == 0:
            return _NO_ROOT, True
        lo, hi, top = _pop_later_half(systems, kept, scratch, vectors, step, stack, top)
    return _NO_ROOT, False


# ---- the driver's rules -----------------------------------------------------------
@register_jitable
def _state_vector(state, a, rate, vectors):
    """vectors[_Z0] = (u, u', s, w, a, a', 1) from the run's ``state`` and a(t), a'(t)."""
    vectors[_Z0, 0], vectors[_Z0, 1], vectors[_Z0, 2], vectors[_Z0, 3] = state[_U], state[_V], state[_S], state[_W]
    vectors[_Z0, 4], vectors[_Z0, 5], vectors[_Z0, 6] = a, rate, 1.0


@register_jitable
def _left_at_once(systems, i, vectors):
    """The first guard of system ``i`` at or below zero and falling at vectors[_Z0] as a
    mode starts (the driver's ``guard_left_at_once``), or -1."""
    for g in range(int(systems[i, NUMBERS, 1])):
        row = POWERS + 4 * g
        if _dot(systems, i, row, vectors, _Z0) <= 0:
            if falls(_dot(systems, i, row + 1, vectors, _Z0), _dot(systems, i, row + 2, vectors, _Z0),
                      EVENT_RESOLUTION):
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
def _step(state, counts, systems, kept, scratch, vectors, step, end, stack):
    """One step of the current mode (``step`` = (system, slot, whole length [s])) from
    vectors[_Z0] at ``state[_T]`` to ``end`` [s] or its first guard root (the driver's
    step with :class:`TableIntegrator`): the state advanced, its root's index returned
    (-1: none)."""
    i, t = step[0], state[_T]
    h = end - t
    _advance(systems, kept, scratch, vectors, step, h, _Z0, _ZEND)
    best, index = _NO_ROOT, -1
    root, settled = _first_root(systems, kept, scratch, vectors, step, t, h, stack)
    if not settled:
        counts[_STATUS] = UNSETTLED
        return -1
    if root > 0:
        best, index = root, 0
    breakpoint = POWERS + 4
    if systems[i, NUMBERS, 1] == 2 and _dot(systems, i, breakpoint, vectors, _Z0) > 0 >= \
            _dot(systems, i, breakpoint, vectors, _ZEND):
        root = _bisect(systems, kept, scratch, vectors, step, breakpoint, t, 0.0, h, _Z0)
        if best < 0 or root < best:
            best, index = root, 1
    if best < 0:
        _copy(vectors, _ZEND, _Z)
        state[_T] = end
    else:
        _advance(systems, kept, scratch, vectors, step, best, _Z0, _Z)
        state[_T] = t + best
        if state[_T] >= end:  # a root at the end of the piece is left to the next piece
            state[_T], index = end, -1
    state[_U], state[_V], state[_S], state[_W] = vectors[_Z, 0], vectors[_Z, 1], vectors[_Z, 2], vectors[_Z, 3]
    return index


def _slides(t0, h, p0, p1, slots, systems, n_pieces, kyg, share, log):
    """One slide from rest over a record's linear pieces (``t0``, ``h`` [s], a = ``p0`` +
    ``p1`` tau [m/s², m/s³], (n,) each; ``slots`` (n,): the slot of each piece's length,
    or -1, from :func:`step_slots`) by ``systems`` (k, SYSTEM_ROWS, 7) of
    :func:`._table_engine.system_arrays` (system mode * ``n_pieces`` + pieces of ky
    passed); ``kyg``: ky g at s = 0 [m/s²]; ``share``: HEA at rest as a share of a [-]
    (1 - 8/pi² for a shear column, 1 for a rigid one). Events go into ``log`` (m, 7)
    (EVENT_FIELDS) while it has room. Returns the outcome (OUTCOME_FIELDS)."""
    kept = np.empty((systems.shape[0], SLOTS, _DEPTHS, 8, 7))  # transitions; row 7: their tau [s] (0: none)
    kept[:, :, :, 7, 0] = 0.0
    scratch, vectors, stack = np.empty((3, 7, 7)), np.empty((12, 7)), np.empty((_STACK, 10))
    state = np.zeros(8)  # t, u, u', s, w, passed, mode, the last event's time
    counts = np.zeros(5, dtype=np.int64)
    v_max = 0.0
    n = t0.shape[0]
    for k in range(n):
        start = t0[k]
        end = t0[k + 1] if k + 1 < n else t0[k] + h[k]
        if _at_rest(state):  # the driver's mode_at_rest at the piece's start
            excess = share * p0[k] - kyg
            if excess > 0 or (excess == 0 and p1[k] > 0):
                _log_event(state, counts, start, SLIP, log)
        restarted = True
        while state[_T] < end and counts[_STATUS] == FINISHED:
            i = int(state[_MODE]) * n_pieces + int(state[_PASSED])
            _state_vector(state, p0[k] + p1[k] * min(state[_T] - start, h[k]), p1[k], vectors)
            if restarted:
                index = _left_at_once(systems, i, vectors)
                if index >= 0:
                    before = state[_MODE]
                    _on_guard(state, counts, index, state[_T], log)
                    if state[_MODE] != before or counts[_STATUS] != FINISHED:
                        continue
                    i = int(state[_MODE]) * n_pieces + int(state[_PASSED])
                restarted = False
            if too_short(state[_T], end):
                state[_T], restarted = end, True  # too short for a step: nothing can happen
                continue
            step = (i, slots[k] if state[_T] == start else -1, end - start)
            index = _step(state, counts, systems, kept, scratch, vectors, step, end, stack)
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


# ---- the no-sliding response (a total damping too close to 1 for the closed forms) ----
@register_jitable
def _form_bound(systems, i, g, vectors, length):
    """A bound of |c z| of form ``g`` of system ``i`` on [0, ``length``] [s] from z =
    vectors[_ZLO] at its start: Taylor's terms in absolute value, the fourth
    derivative bounded (:func:`_fourth_bound`)."""
    row = POWERS + 4 * g
    return _bound((abs(_dot(systems, i, row, vectors, _ZLO)), abs(_dot(systems, i, row + 1, vectors, _ZLO)),
                   abs(_dot(systems, i, row + 2, vectors, _ZLO)) / 2, abs(_dot(systems, i, row + 3, vectors, _ZLO)) / 6,
                   _fourth_bound(systems, i, g, vectors, length) / 24), length, UPPER)


@register_jitable
def _sup(systems, kept, scratch, vectors, step, g, t0, h, best, stack):
    """max(``best``, sup |form g| on [0, ``h``] [s]) from vectors[_Z0] at ``t0`` [s] and
    vectors[_ZEND] = z(h) on a STICK step: an interval whose bound of |c z| (Taylor at
    its start, the fourth derivative bounded) exceeds the largest value found by more
    than :data:`_PEAK_TOLERANCE` of it is halved; -1 where the search does not settle."""
    row, i = POWERS + 4 * g, step[0]
    lo, hi, top = 0.0, h, 0
    _copy(vectors, _Z0, _ZLO)
    _copy(vectors, _ZEND, _ZHI)
    for budget in range(MAX_INTERVALS):
        if budget > 0:
            _advance(systems, kept, scratch, vectors, step, hi - lo, _ZLO, _ZHI)
        length = hi - lo
        best = max(best, abs(_dot(systems, i, row, vectors, _ZLO)), abs(_dot(systems, i, row, vectors, _ZHI)))
        tiny = t0 + lo + length <= t0 + lo or length <= 4 * _EPS * max(abs(t0) + abs(hi), 1.0)
        reach = _form_bound(systems, i, g, vectors, length)
        if not tiny and reach > best * (1.0 + _PEAK_TOLERANCE):
            if top == stack.shape[0]:
                return -1.0
            hi, top = _push_later_half(stack, top, vectors, lo, hi)
            continue
        if top == 0:
            return best
        lo, hi, top = _pop_later_half(systems, kept, scratch, vectors, step, stack, top)
    return -1.0


def _response(t0, h, p0, p1, slots, systems, with_u):
    """The no-sliding response from rest over a record's linear pieces (as
    :func:`_slides`) in ``systems`` (1, SYSTEM_ROWS, 7): STICK with the forms HEA and u
    (:func:`._table_engine.response_arrays`). Returns (max |HEA| at the pieces' ends
    [m/s²], sup |HEA| over time [m/s²], sup |u| [m] (with ``with_u``, else nan), settled):
    a first pass steps the record and bounds each form on each step, a second searches
    the steps whose bound exceeds the largest value so far."""
    n = t0.shape[0]
    kept = np.empty((1, SLOTS, _DEPTHS, 8, 7))
    kept[:, :, :, 7, 0] = 0.0
    scratch, vectors, stack = np.empty((3, 7, 7)), np.empty((12, 7)), np.empty((_STACK, 10))
    starts, reach = np.empty((n, 7)), np.empty((n, 2))
    u, v, samples = 0.0, 0.0, 0.0
    for k in range(n):
        end = t0[k + 1] if k + 1 < n else t0[k] + h[k]
        vectors[_Z0, 0], vectors[_Z0, 1], vectors[_Z0, 2], vectors[_Z0, 3] = u, v, 0.0, 0.0
        vectors[_Z0, 4], vectors[_Z0, 5], vectors[_Z0, 6] = p0[k], p1[k], 1.0
        for c in range(7):
            starts[k, c] = vectors[_Z0, c]
        step = (0, slots[k], end - t0[k])
        _advance(systems, kept, scratch, vectors, step, end - t0[k], _Z0, _ZEND)
        _copy(vectors, _Z0, _ZLO)
        for g in range(2):
            reach[k, g] = _form_bound(systems, 0, g, vectors, end - t0[k])
        samples = max(samples, abs(_dot(systems, 0, POWERS, vectors, _Z0)), abs(_dot(systems, 0, POWERS, vectors,
                                                                                      _ZEND)))
        u, v = vectors[_ZEND, 0], vectors[_ZEND, 1]
    peaks = np.array([samples, 0.0])
    for k in range(n):
        peaks[1] = max(peaks[1], abs(starts[k, 0]))
    peaks[1] = max(peaks[1], abs(u))
    for g in range(2 if with_u else 1):
        for k in range(n):
            if reach[k, g] > peaks[g] * (1.0 + _PEAK_TOLERANCE):
                end = t0[k + 1] if k + 1 < n else t0[k] + h[k]
                for c in range(7):
                    vectors[_Z0, c] = starts[k, c]
                step = (0, slots[k], end - t0[k])
                _advance(systems, kept, scratch, vectors, step, end - t0[k], _Z0, _ZEND)
                found = _sup(systems, kept, scratch, vectors, step, g, t0[k], end - t0[k], peaks[g], stack)
                if found < 0:
                    return samples, peaks[0], np.nan, False
                peaks[g] = found
    return samples, peaks[0], peaks[1] if with_u else np.nan, True


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


@functools.cache
def response_kernel():
    """:func:`_response` compiled with numba (on first use, then from the disk cache)."""
    return numba.njit(cache=True, error_model="numpy")(_response)
