"""The exact engine compiled with numba: the JAX kernel's algorithm as a plain loop.

Stick: bounds of a(t) per block of ``window`` pieces and per piece (from
:func:`._exact.prepare`) skip the blocks and pieces where the demand stays within
[-mu g, mu g]; the other pieces are checked exactly and the onset is located in closed
form (a linear equation; sine pieces: bisection). Slip: u and v are carried piece by piece in closed
form; the first piece where v returns to zero holds the stop (a quadratic; sine pieces:
a bracketed bisection) and :func:`~blockdae.sliding._model.stop_mode` decides what follows.

The closed forms and every rule come from :mod:`._closed_form`, :mod:`blockdae.sliding`
and :mod:`blockdae.excitation.pieces`, compiled here with ``xp`` = :mod:`._xp_scalar`,
exactly as the JAX kernel traces them; only the loop and :func:`_bisect` are this
engine's own. The entry points compile on first use and are cached on disk by numba
(``__pycache__`` beside this file); the cache key includes a hash of the sources of those
modules, which numba would not otherwise check.

Arguments shared by the entry points:
    exc: (t0, h, p0, p1, s, w, phi, a_hi, a_lo, a_max, a_min): the pieces, each (n,)
        [s, s, m/s², m/s³, m/s², rad/s, rad], with s, w, phi None for linear pieces only;
        the range of the unscaled a(t) on each piece, each (n,) [m/s²], and per block of
        ``window`` pieces, each (ceil(n / window),) [m/s²].
    params: (mu, f, bias, g, scale): static and kinetic friction [-], R/Q [-], g [m/s²]
        and a factor on a(t) [-].
    flags: (slip- allowed, slip+ allowed, until rest after the excitation).
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

from ..excitation import accel, accel_int1, accel_int2, pieces as _pieces, rebase
from . import _closed_form, _model as _block
from ._model import demand, rest_mode, slip_constant
from ..solvers import xp_scalar as xp
from ._closed_form import (BISECTIONS, BLOCK_SLACK, crosses_zero, departure_rate, leaves_stick, mode_after_stop,
                           onset_delta_linear, onset_gap, onset_side, onset_target, onset_within, rate_turns,
                           sine_stop_bracket, slip_motion, slip_rate, slip_velocity, stop_delta_linear,
                           tail_to_rest)

#: columns of the knot log: time [s], u [m], v [m/s], mode after, mode before
KNOT_FIELDS = ("t", "u", "v", "mode", "mode_before")
#: entries of a run's outcome
OUTCOME_FIELDS = ("u", "v", "mode", "max_abs_u", "n_events", "t_final", "rests", "finished",
                  "max_events_at_one_instant")
_OPTIONS = dict(error_model="numpy")  # IEEE division and no exceptions, like the JAX kernel


def _bisect(fun, cf, lo, hi, *args):
    """Bracketed root of ``fun(cf, d, *args)``, monotone on [lo, hi]; the upper end.
    Twin of ``_exact_kernel._bisect`` (same halvings): keep them alike."""
    sign_lo = xp.sign(fun(cf, lo, *args))
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        if xp.sign(fun(cf, mid, *args)) == sign_lo:
            lo = mid
        else:
            hi = mid
    return hi


def _onset_delta(cf, rem, target):
    """Time [s] until a(d) reaches ``target`` [m/s²] on [0, rem] (a monotone).
    Twin of ``_exact_kernel.onset_delta``."""
    if _is_sine(*cf):
        return _bisect(onset_gap, cf, 0.0, rem, target, xp)
    return onset_delta_linear(cf, target, xp)


def _stop_delta(cf, rem, v, c, mode):
    """First d in (0, rem] where v(d) returns to 0 in slip ``mode``: (d [s], found).
    Twin of ``_exact_kernel.stop_delta``."""
    if not _is_sine(*cf):
        if _far_from_rest(cf, rem, v, c, mode):
            return rem, False
        return stop_delta_linear(cf, rem, v, c, mode, xp)
    r0 = departure_rate(cf, v, c, mode, xp)
    turns = rate_turns(r0, slip_rate(cf, rem, c, xp), xp)
    d_turn = _bisect(slip_rate, cf, 0.0, rem, c, xp) if turns else rem
    lo, hi = sine_stop_bracket(r0, turns, d_turn, rem, mode, xp)
    if crosses_zero(slip_velocity(cf, lo, v, c, xp), slip_velocity(cf, hi, v, c, xp), mode):
        return _bisect(slip_velocity, cf, lo, hi, v, c, xp), True
    return rem, False


def _far_from_rest(cf, rem, v, c, mode):
    """Whether v = v0 + r d + q d² (r = c - p0, q = -p1/2) cannot return to 0 on a linear
    piece of length ``rem``: a screen that saves the square root and division of
    :func:`stop_delta_linear` on most sliding pieces, never changing its answer. Either
    v moves away from rest all along (mode v0 >= 0, mode r > 0, mode q >= 0): then the
    discriminant r² - 4 q v0 <= r² rounds to at most r² (sqrt of a rounded square is the
    number itself while r² is normal), so mode (r - mode sqrt) >= 0 and the root
    -2 v0 / (r - mode sqrt) is not positive (at rest, -r / q is not either); or |v0| >
    2 (|r| rem + |q| rem²): the root -2 v0 / (r -+ sqrt(r² - 4 q v0)) lies beyond ``rem``
    whenever |v0| > rem (|r| + sqrt(|q v0|)), which the factor 2 ensures with room for
    rounding (as x² - a x >= (x² - a²) / 2 with x² = |v0|, a² = |q| rem²)."""
    r, q = c - cf[0], -0.5 * cf[1]
    if (mode * v >= 0) & (mode * r > 0) & (mode * q >= 0) & (abs(r) > _NORMAL_SQUARE_ROOT):
        return True
    return mode * v > 2.0 * (abs(r) * rem + abs(q) * rem * rem)


#: rates [m/s²] above this square to a normal float
_NORMAL_SQUARE_ROOT = 1e-150


def _is_sine(p0, p1, s, w, phi):
    """Whether a piece has a sine term (decided at compile time for linear pieces)."""
    if s is None:
        return False
    return s != 0


def _piece(exc, scale, j, tau):
    """Piece j from ``tau`` [s] into it: (start time [s], remaining length [s], coefficients
    of the scaled a(t)), as ``_exact_kernel._piece``."""
    t0, h, p0, p1, s, w, phi = exc[:7]
    cf = rebase(p0[j] * scale, p1[j] * scale, _item(s, j, scale), _item(w, j, 1.0), _item(phi, j, 1.0), tau)
    return t0[j] + tau, h[j] - tau, cf


def _item(x, j, factor):
    if x is None:
        return None
    return x[j] * factor


def _leaves(exc, params, flags, j, tau):
    """Whether the demand leaves stick on piece j from ``tau`` [s]: (up, down)."""
    mu, _, bias, g, scale = params
    _, rem, cf = _piece(exc, scale, j, tau)
    start = demand(accel(*cf, 0.0, xp), bias, g)
    end = demand(accel(*cf, rem, xp), bias, g)
    return leaves_stick(start, end, mu * g, flags[0], flags[1])


def _next_leaving_piece(exc, window, params, flags, thresholds, k, tau):
    """The first piece, from ``tau`` [s] into piece k on, where the demand leaves stick:
    (piece, time into it [s], whether it leaves upwards); (n, 0, False) if none. Blocks
    and pieces whose bounds keep a(t) within ``thresholds`` (see :func:`_thresholds`)
    are skipped unchecked."""
    up, down = _leaves(exc, params, flags, k, tau)
    if up | down:
        return k, tau, up
    n = exc[0].shape[0]
    a_hi, a_lo, a_max, a_min = exc[7:]
    above, below = thresholds
    j = k + 1
    block = j // window
    while j < n:
        end = min((block + 1) * window, n)
        if (a_max[block] > above) | (a_min[block] < below):
            while j < end:
                if (a_hi[j] > above) | (a_lo[j] < below):
                    up, down = _leaves(exc, params, flags, j, 0.0)
                    if up | down:
                        return j, 0.0, up
                j += 1
        j, block = end, block + 1
    return n, 0.0, False


def _thresholds(exc, params, flags):
    """(above, below) [m/s²]: the demand may leave stick only where the unscaled a(t)
    rises above ``above`` or falls below ``below``. Conservative as the JAX kernel's
    :func:`block_may_leave_stick` (its slack taken at the largest |a| of the excitation,
    doubled), but found once per run: only the speed depends on it."""
    a_max, a_min = exc[9], exc[10]
    mu, _, bias, g, scale = params
    limit = mu * g
    if scale == 0:
        return math.inf, -math.inf
    a_abs = max(np.max(a_max), -np.min(a_min))
    slack = 2 * BLOCK_SLACK * (abs(scale) * a_abs + abs(bias * g) + limit)
    up = (bias * g + limit - slack) / scale if flags[0] else math.inf * scale  # a > up slides -
    down = (bias * g - limit + slack) / scale if flags[1] else -math.inf * scale  # a < down slides +
    return (up, down) if scale > 0 else (down, up)


def _logged(knots, n_knots, t, before, after, u):
    """``knots`` with the event (t [s], mode before -> after, u [m]) in row ``n_knots``,
    grown when full."""
    if n_knots == knots.shape[1]:
        grown = np.empty((knots.shape[0], 2 * n_knots))
        for row in range(knots.shape[0]):  # loops: a slice assignment costs seconds of compiling
            for column in range(n_knots):
                grown[row, column] = knots[row, column]
        knots = grown
    knots[0, n_knots] = t
    knots[1, n_knots] = u
    knots[2, n_knots] = 0.0
    knots[3, n_knots] = after
    knots[4, n_knots] = before
    return knots


def _run(exc, window, params, flags, capacity):
    """One parameter set: (outcome, knots).

    ``outcome``: float64 (9,), see :data:`OUTCOME_FIELDS` (rests, finished as 0/1).
    ``knots``: (5, n_events + 2), see :data:`KNOT_FIELDS`: the start, every event and the
    end; with ``capacity`` 0 no event is recorded and ``knots`` is empty.
    """
    mu, f, bias, g, scale = params
    allow_neg, allow_pos, until_rest = flags
    t0, h = exc[0], exc[1]
    n = t0.shape[0]
    knots = np.zeros((5, capacity))
    k, tau, u, v, mode = 0, 0.0, 0.0, 0.0, 0
    max_abs_u, n_events, n_found = 0.0, 0, 0
    last_t, run, max_run = -math.inf, 0, 0
    max_found = 4 * n + 2  # more events than this: chatter
    thresholds = _thresholds(exc, params, flags)
    while k < n and n_found < max_found:
        before = mode
        if mode == 0:
            k, tau, up = _next_leaving_piece(exc, window, params, flags, thresholds, k, tau)
            if k == n:
                break
            t_k, rem, cf = _piece(exc, scale, k, tau)
            going_up, at_once = onset_side(demand(accel(*cf, 0.0, xp), bias, g), up, mu * g, allow_neg, allow_pos)
            d = onset_within(_onset_delta(cf, rem, onset_target(going_up, bias, g, mu * g, xp)), rem, at_once, xp)
            t_event, tau = t_k + d, tau + d
            mode = -1 if going_up else 1
        else:
            c = slip_constant(mode, bias, f, g)
            while True:
                t_k, rem, cf = _piece(exc, scale, k, tau)
                d, stop = _stop_delta(cf, rem, v, c, mode)
                if stop:
                    break
                u += v * rem + 0.5 * c * rem**2 - accel_int2(*cf, rem, xp)
                v += c * rem - accel_int1(*cf, rem, xp)
                k, tau = k + 1, 0.0
                if k == n:
                    break
            if k == n:
                break
            t_event, tau = t_k + d, tau + d
            u = slip_motion(cf, d, u, v, c, xp)[0]
            v = 0.0
            mode = mode_after_stop(cf, d, c, before, t_event, mu, f, g, allow_neg, allow_pos, xp)
        n_found += 1
        max_abs_u = max(max_abs_u, abs(u))
        if mode != before:  # a stop that grazes on is no event
            n_events += 1
            if capacity > 0:
                knots = _logged(knots, n_events, t_event, before, mode, u)
            run = run + 1 if t_event == last_t else 1
            max_run, last_t = max(max_run, run), t_event
    max_abs_u = max(max_abs_u, abs(u))
    finished = k >= n
    t_final = t0[n - 1] + h[n - 1]
    rests = True
    if until_rest:
        d, u_rest, rests = tail_to_rest(u, v, mode, bias, f, g, xp)
        after = rest_mode(-bias * g, 0.0, mu, g, allow_neg, allow_pos, xp)
        t_final += d
        if rests:
            if after != mode:
                n_events += 1
                if capacity > 0:
                    knots = _logged(knots, n_events, t_final, mode, after, u_rest)
                run = run + 1 if t_final == last_t else 1
                max_run = max(max_run, run)
            u, v, mode = u_rest, 0.0, after
            max_abs_u = max(max_abs_u, abs(u))
    outcome = _outcome(u, v, mode, max_abs_u, n_events, t_final, rests, finished, max_run)
    if capacity == 0:
        return outcome, knots
    knots = _logged(knots, n_events + 1, t_final, mode, mode, u)
    knots[2, n_events + 1] = v
    return outcome, knots[:, : n_events + 2]


def _outcome(u, v, mode, max_abs_u, n_events, t_final, rests, finished, max_run):
    out = np.empty(len(OUTCOME_FIELDS))
    out[0], out[1], out[2], out[3], out[4] = u, v, mode, max_abs_u, n_events
    out[5], out[6], out[7], out[8] = t_final, rests, finished, max_run
    return out


def _slice(x, a, b):
    if x is None:
        return None
    return x[a:b]


def _excitation(exc, offsets, i):
    """Excitation i of a batch's concatenated ``exc`` (see :func:`kernels`)."""
    a, b, c, d = offsets[i]
    return (exc[0][a:b], exc[1][a:b], exc[2][a:b], exc[3][a:b], _slice(exc[4], a, b), _slice(exc[5], a, b),
            _slice(exc[6], a, b), exc[7][a:b], exc[8][a:b], exc[9][c:d], exc[10][c:d])


def _run_set(one, window, params, flags, i, j, out):
    """Excitation i (``one``) under parameter set j into ``out[i, j]``."""
    p = params[j]
    outcome, _ = _run(one, window, (p[0], p[1], p[2], p[3], p[4]), (flags[0], flags[1], flags[2][i]), 0)
    for k in range(outcome.shape[0]):  # as in _logged, a loop where a slice assignment would do
        out[i, j, k] = outcome[k]


def run_one_uncompiled(exc, window, params, flags, capacity):
    """``run_one`` of :func:`kernels` run by the Python interpreter: the same source and
    float64 arithmetic (numpy's scalars, with IEEE division as compiled), no compile wait
    (numba's takes seconds on a first run) but some hundred times slower per piece: for a
    motion of a few pieces (the worked examples)."""
    with np.errstate(all="ignore"):
        return _run(exc, window, tuple(np.float64(p) for p in params), flags, capacity)


@functools.cache
def kernels():
    """(run_one, run_items), compiled on their first call (or loaded from numba's cache).

    ``run_one(exc, window, params, flags, capacity)``: :func:`_run`, one parameter set
    with its knot log (``capacity``: rows to start with, > 0).

    ``run_items(exc, offsets, window, params, flags, items, out)``: final numbers only,
    into ``out`` (n_exc, m, 9) (``OUTCOME_FIELDS``), of the batch's items ``items``
    (int64): item k is excitation i = k % n_exc (pieces ``offsets[i, 0]:offsets[i, 1]``,
    blocks ``offsets[i, 2]:offsets[i, 3]`` of ``exc``) under parameter set j = k // n_exc
    (rows of ``params``, (m, 5)). ``flags``: (slip- allowed, slip+ allowed, until rest
    per excitation (n_exc,) bool). It releases the GIL: threads run parts of one batch
    (:func:`blockdae.core.run_items`).
    """
    _register()
    fingerprint = hashlib.sha256(b"".join(pathlib.Path(m.__file__).read_bytes() for m in _SHARED)).hexdigest()

    def run_one(exc, window, params, flags, capacity):
        fingerprint  # noqa: B018 -- numba keys its disk cache by the closure's contents
        return _run(exc, window, params, flags, capacity)

    def run_items(exc, offsets, window, params, flags, items, out):
        fingerprint  # noqa: B018
        n_exc, current = offsets.shape[0], 0
        one = _excitation(exc, offsets, 0)
        for item in items:
            i, j = item % n_exc, item // n_exc
            if i != current:  # items of one excitation in a row slice it once
                one, current = _excitation(exc, offsets, i), i
            _run_set(one, window, params, flags, i, j, out)

    return (numba.njit(cache=True, **_OPTIONS)(run_one),
            numba.njit(cache=True, nogil=True, **_OPTIONS)(run_items))


#: modules whose functions the engine compiles besides its own
_SHARED = (_block, _pieces, _closed_form, xp)


def _register():
    """Let numba compile the plain functions of the shared modules and of this one
    where the entry points call them (``register_jitable``; they stay plain Python)."""
    for module in (*_SHARED[:-1], sys.modules[__name__]):
        for _, fn in inspect.getmembers(module, inspect.isfunction):
            if fn.__module__ == module.__name__:
                register_jitable(inline="always" if fn in _INLINED else "never", **_OPTIONS)(fn)


#: functions inlined where they are called (numba IR): a call that takes the excitation's
#: arrays counts a reference to each on entry and releases it on return, two atomic
#: operations per array (~40 per onset search); inlined, the search costs none
_INLINED = (_next_leaving_piece,)
