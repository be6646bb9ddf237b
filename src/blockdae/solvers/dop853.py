"""Dormand and Prince's 8(5,3) Runge-Kutta pair with its 7th-order continuous extension
(DOP853, Hairer, Nørsett & Wanner, Solving ODEs I, II.10), for numba.

The coefficients are SciPy's (``scipy.integrate._ivp.dop853_coefficients``), read once,
not copied; the step, the error norm, the step-size controller and the dense output
follow ``scipy.integrate.DOP853`` line by line, as plain functions that numba compiles
where a compiled engine calls them (``register_jitable``). The right-hand side is a
compiled function ``fun(t, y, args, out)`` writing dy/dt (:func:`for_flow` closes the steps over
it, which keeps numba's disk cache usable), so nothing here knows a model;
:func:`to_first_root` runs the adaptive steps to the first root that an engine's own
compiled root finder locates on an accepted step.
"""

import math

import numpy as np
from numba.extending import register_jitable
from scipy.integrate._ivp import dop853_coefficients as _c

from ..core import events

N_STAGES = _c.N_STAGES  # 12
A = np.ascontiguousarray(_c.A[:N_STAGES, :N_STAGES])
B = np.ascontiguousarray(_c.B)
C = np.ascontiguousarray(_c.C[:N_STAGES])
E3 = np.ascontiguousarray(_c.E3)
E5 = np.ascontiguousarray(_c.E5)
D = np.ascontiguousarray(_c.D)
A_EXTRA = np.ascontiguousarray(_c.A[N_STAGES + 1:])
C_EXTRA = np.ascontiguousarray(_c.C[N_STAGES + 1:])
#: the error estimate is of order 7: the step grows as error ** (-1 / 8)
ERROR_EXPONENT = -1.0 / 8.0
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
#: stages of a step with its dense output: 12, the end point, 3 extra
N_STAGES_EXTENDED = 16


@register_jitable
def error_norm(K, h, scale):
    """SciPy's DOP853 error norm of the step just taken (< 1: accept), each component
    over its ``scale`` (n,) (SciPy's: atol + rtol max(|y|, |y_new|))."""
    n = scale.shape[0]
    e5, e3 = 0.0, 0.0
    for i in range(n):
        a5, a3 = 0.0, 0.0
        for j in range(N_STAGES + 1):
            a5 += E5[j] * K[j, i]
            a3 += E3[j] * K[j, i]
        e5 += (a5 / scale[i]) ** 2
        e3 += (a3 / scale[i]) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@register_jitable
def error_scale(y, y_new, rtol, atol, out):
    """SciPy's error scale atol + rtol max(|y|, |y_new|) of each component into ``out``
    (n,), returned."""
    for i in range(y.shape[0]):
        out[i] = atol + rtol * max(abs(y[i]), abs(y_new[i]))
    return out


@register_jitable
def factor(norm, accepted):
    """The next step over this one [-] from the error norm."""
    if norm == 0.0:
        return MAX_FACTOR
    value = SAFETY * norm ** ERROR_EXPONENT
    return min(MAX_FACTOR, max(MIN_FACTOR, value)) if accepted else max(MIN_FACTOR, value)


@register_jitable
def dense_value(F, y, x, i):
    """Component ``i`` of the continuous extension at x = (t - t_step) / h in [0, 1]."""
    value = 0.0
    for k in range(7):
        value += F[6 - k, i]
        value *= x if k % 2 == 0 else 1.0 - x
    return value + y[i]


@register_jitable
def dense_state(F, y, x, out):
    """The whole state at x into ``out`` (see :func:`dense_value`)."""
    for i in range(y.shape[0]):
        out[i] = dense_value(F, y, x, i)


def for_flow(fun):
    """(step, initial_step, dense_coefficients) for the compiled right-hand side
    ``fun(t, y, args, out)`` (writes dy/dt into ``out``), each taking ``args`` first;
    they allocate nothing: ``K`` (16, n) holds the stages, ``work`` (n,) a stage's state."""

    @register_jitable
    def step(args, t, y, h, K, y_new, work):
        """One step of size ``h`` [s] from (t, y) with K[0] = fun(t, y): y_new; the
        stages are left in ``K`` (rows 0-12; row 12 is f at the new state)."""
        n = y.shape[0]
        for s in range(1, N_STAGES):
            for i in range(n):
                acc = 0.0
                for j in range(s):
                    acc += A[s, j] * K[j, i]
                work[i] = y[i] + h * acc
            fun(t + C[s] * h, work, args, K[s])
        for i in range(n):
            acc = 0.0
            for j in range(N_STAGES):
                acc += B[j] * K[j, i]
            y_new[i] = y[i] + h * acc
        fun(t + h, y_new, args, K[N_STAGES])

    @register_jitable
    def initial_step(args, t, y, bound, rtol, atol, K, work):
        """Hairer's first step [s] (SciPy's ``select_initial_step``), at most ``bound``
        [s]; K[0] = fun(t, y) (row 1 is overwritten)."""
        n = y.shape[0]
        d0, d1 = 0.0, 0.0
        for i in range(n):
            scale = atol + abs(y[i]) * rtol
            d0 += (y[i] / scale) ** 2
            d1 += (K[0, i] / scale) ** 2
        d0, d1 = math.sqrt(d0 / n), math.sqrt(d1 / n)
        h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
        h0 = min(h0, bound)
        for i in range(n):
            work[i] = y[i] + h0 * K[0, i]
        fun(t + h0, work, args, K[1])
        d2 = 0.0
        for i in range(n):
            d2 += ((K[1, i] - K[0, i]) / (atol + abs(y[i]) * rtol)) ** 2
        d2 = math.sqrt(d2 / n) / h0
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
        return min(100.0 * h0, h1, bound)

    @register_jitable
    def dense_coefficients(args, t, y, y_new, h, K, F, work):
        """The 7 rows ``F`` (7, n) of the continuous extension of the step (t, y) ->
        (t + h, y_new) whose stages are in ``K`` (fills rows 13-15)."""
        n = y.shape[0]
        for e in range(A_EXTRA.shape[0]):
            s = N_STAGES + 1 + e
            for i in range(n):
                acc = 0.0
                for j in range(s):
                    acc += A_EXTRA[e, j] * K[j, i]
                work[i] = y[i] + h * acc
            fun(t + C_EXTRA[e] * h, work, args, K[s])
        for i in range(n):
            delta = y_new[i] - y[i]
            F[0, i] = delta
            F[1, i] = h * K[0, i] - delta
            F[2, i] = 2.0 * delta - h * (K[N_STAGES, i] + K[0, i])
            for r in range(4):
                acc = 0.0
                for j in range(N_STAGES_EXTENDED):
                    acc += D[r, j] * K[j, i]
                F[3 + r, i] = h * acc

    return step, initial_step, dense_coefficients


#: the entries of a flow's ``counts`` (int64): accepted steps, rejected steps, right-hand-side calls
STEPS, REJECTED, RHS = 0, 1, 2


def to_first_root(step, initial_step, first_root):
    """``flow(args, root_args, carry, t, y, stop, h, rtol, atol, K, y_new, z, work, scale,
    counts)``: SciPy's adaptive DOP853 steps (:func:`for_flow`'s ``step`` and
    ``initial_step``) from (t, y) to ``stop`` [s] or to the first root the compiled
    ``first_root(root_args, carry, t, y, t_new, y_new, h, K) -> (time, index, carry)``
    finds on a step accepted from (t, y) to (t_new, y_new) (index -1: none; ``carry``:
    what it hands on to the next step, e.g. the guards at its end). Returns (time, state,
    index, the step to try next [s]): index -1 at ``stop``, -2 where a step fell below
    rounding (then ``y`` where it stopped); the state at a root is a step of the method to
    it, in ``z``. ``y`` (n,) is advanced in place; K[0] must hold fun(t, y); ``h`` <= 0:
    Hairer's first step; ``counts`` (3,) (:data:`STEPS`, :data:`REJECTED`, :data:`RHS`)
    is added to."""

    @register_jitable
    def flow(args, root_args, carry, t, y, stop, h, rtol, atol, K, y_new, z, work, scale, counts):
        if h <= 0:
            h = initial_step(args, t, y, stop - t, rtol, atol, K, work)
            counts[RHS] += 1
        rejected = False
        while t < stop:
            rest = stop - t
            last = h >= rest
            hh = rest if last else h
            if not last and hh <= events.ULPS * 2.220446049250313e-16 * max(1.0, abs(t)):
                return t, y, -2, h
            step(args, t, y, hh, K, y_new, work)
            counts[RHS] += 12
            err = error_norm(K, hh, error_scale(y, y_new, rtol, atol, scale))
            accepted = err <= 1.0
            h_next = hh * factor(err, accepted)
            if accepted and rejected:
                h_next = min(h_next, hh)
            rejected = not accepted
            if rejected:
                h = h_next
                counts[REJECTED] += 1
                continue
            counts[STEPS] += 1
            t_new = stop if last else t + hh
            root, index, carry = first_root(root_args, carry, t, y, t_new, y_new, hh, K)
            if index >= 0:
                step(args, t, y, root - t, K, z, work)  # the state at the root, on the flow
                counts[RHS] += 12
                return root, z, index, h
            h = max(h, h_next) if last else h_next
            t = t_new
            for i in range(y.shape[0]):
                y[i] = y_new[i]
                K[0, i] = K[N_STAGES, i]
        return t, y, -1, h

    return flow
