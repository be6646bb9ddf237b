"""The hybrid driver's event rules, one implementation each, for the Python driver
(:mod:`blockdae.core._driver`) and the compiled engines: plain functions that numba
compiles where an engine calls them (``register_jitable``) and Python calls as they are.

* :func:`falls`: whether a guard at zero leaves its mode at once (a graze that turns back
  within the event resolution does not).
* :func:`first_nonpositive`: bisection to adjacent floats (of ``origin`` + t) for the
  first float where a monotone function is <= 0; :func:`sign_change`: the same for a
  sign change either way.
* :func:`turning_point`: where a monotone rate leaves its sign (the driver splits a piece
  there so that the guards are monotone on both parts).
* :func:`static_root`: the first guard root of a static mode (guards of time alone);
  :func:`left_at_once`: the guard a flow leaves as it starts; :func:`of_time`: a compiled
  engine's guards as the functions of time these take.
* :func:`velocity_error`, :func:`stop_uncertainty`: how far a located stop may lie from
  the true one, which decides whether a stop slides on; :func:`too_short`: an interval
  not worth a step.
* :func:`one_sign`: the interval test of the derivative-bounded root searches.

A function of time is passed with its arguments: ``fun(args, t)``.

Copies that stay, and why:

* the exact 1-D engines (the numba one and its JAX twin) halve a fixed
  ``BISECTIONS`` times, so that numba's loop and JAX's ``fori_loop`` (a fixed count, and
  the implicit-function derivative at the end) give the same floats;
* the flexible ky-table kernel's bisection advances a matrix-exponential state from the
  last end it kept (it is no function of time alone), and the fused flexible engine's
  sign change starts with Newton's method and stops at one ulp of the time;
* the planar engine's stop confirmed on the flow and its dense minimum write a state as
  they go;
* the derivative-bounded root searches read different closed forms (polynomial-
  exponential rows in numba, Python objects with sine terms and Brent's method, a
  matrix exponential with a fourth-derivative bound, Newton on shared exp/cos/sin), and
  the Python ones are the references their compiled twins are tested against: only
  their interval test (:func:`one_sign`) and graze rule are one.
"""

import math

import numpy as np
from numba.extending import register_jitable

_EPS = float(np.finfo(float).eps)
#: intervals shorter than this many ulps of their end are not integrated (a solver
#: refuses them; nothing can happen there)
ULPS = 8
#: global error of v in local tolerances: |v'| |t_stop - t_exact| / (rtol max|v| + atol)
#: at every stop on the 18 sample records (two-way mu 0.15, f 0.12, bias 0.03 and
#: one-way mu 0.1) at rtol 1e-10 reaches 1.1 for CVODE and 9.2 for IDA
V_ERROR_FACTOR = 10.0
#: a state contradicts its mode only beyond the velocity error and this much of the
#: largest speed [-]: closed forms (the exact upthrow backend, tolerance 0) round
ROUNDING = 1e-12


@register_jitable
def falls(rate, curvature, resolution):
    """Whether a guard at zero with ``rate`` and ``curvature`` leaves its mode at once: it
    falls (by its rate, or at a zero rate by its curvature) for longer than
    ``resolution`` [s]. A rate that turns back within it (-rate / curvature, a rate of
    rounding size at a located onset) is a graze: the mode holds."""
    if rate == 0:
        return curvature < 0
    return rate < 0 and (curvature <= 0 or -rate / curvature > resolution)


@register_jitable
def too_short(t, target):
    """Whether [t, target] [s] is shorter than ``ULPS`` ulps of ``target``."""
    return target - t <= ULPS * _EPS * max(1.0, abs(target))


@register_jitable
def velocity_error(rtol, atol, v_max):
    """The error [m/s] of integrated velocities: ``V_ERROR_FACTOR`` local tolerances at
    the largest speed ``v_max`` [m/s] so far."""
    return V_ERROR_FACTOR * (rtol * v_max + atol)


@register_jitable
def stop_uncertainty(slope, curvature, error, resolution):
    """How far [s] a located root of a guard with rate ``slope`` and ``curvature`` may lie
    from the true one, at least ``resolution`` [s]: with the guard's error ``error``,
    the d that solves |g'| d + |g''| d²/2 = e (e / |g'| at a crossing, sqrt(2 e / |g''|)
    at a graze); a guard that does not move has its root where it was found."""
    slope, curvature = abs(slope), abs(curvature)
    if slope == 0 and curvature == 0:
        return resolution
    return max(resolution, 2 * error / (slope + math.sqrt(slope**2 + 2 * curvature * error)))


@register_jitable
def first_nonpositive(fun, args, lo, hi, origin=0.0):
    """The first t in (lo, hi] where ``fun(args, t)`` (> 0 at lo, <= 0 at hi, monotone)
    is <= 0, by bisection to adjacent floats of ``origin`` + t."""
    while True:
        mid = 0.5 * (lo + hi)
        if not (origin + lo < origin + mid < origin + hi):
            return hi
        if fun(args, mid) > 0:
            lo = mid
        else:
            hi = mid


@register_jitable
def sign_change(fun, args, lo, hi):
    """Where ``fun(args, t)``, monotone on [lo, hi], changes sign: the float after the
    last one with the sign it has at lo (hi if none), by bisection to adjacent floats."""
    positive_lo = fun(args, lo) > 0
    while True:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            return hi
        if (fun(args, mid) > 0) == positive_lo:
            lo = mid
        else:
            hi = mid


@register_jitable
def one_sign(value_a, value_b, bound, length):
    """+1 / -1 if a function with these end values and |slope| <= ``bound`` keeps one
    sign strictly inside an interval of ``length``, else 0."""
    if value_a >= 0 and value_b >= 0 and value_a + value_b > bound * length:
        return 1
    if value_a <= 0 and value_b <= 0 and -(value_a + value_b) > bound * length:
        return -1
    return 0


#: halvings of a piece in :func:`turning_point`: below 1e-18 of its length
TURN_BISECTIONS = 60


@register_jitable
def turning_point(fun, args, lo, hi):
    """Where a rate ``fun(args, t)`` -> (value, defined), monotone on [lo, hi], leaves the
    sign it has at lo (a zero of either sign, +0.0 or -0.0, counts as turned, so that
    a(t) -> -a(t) mirrors the turn exactly): the first float after it, by bisection
    (at most ``TURN_BISECTIONS`` halvings); nan where it does not turn before hi or is
    undefined at a time asked."""
    first, defined = fun(args, lo)
    if not defined:
        return math.nan
    sign_lo = math.copysign(1.0, first)
    value, defined = fun(args, hi)
    if not defined or sign_lo * value > 0:
        return math.nan
    end = hi
    for _ in range(TURN_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            break
        value, defined = fun(args, mid)
        if not defined:
            return math.nan
        if sign_lo * value > 0:
            lo = mid
        else:
            hi = mid
    return hi if hi < end else math.nan


@register_jitable
def left_at_once(values, rates, args, resolution):
    """The first guard of ``values`` (at one instant) that is at or below zero and falls at
    once (:func:`falls`, with ``rates(args, index)`` -> (rate, curvature)); -1: none."""
    for index in range(len(values)):
        if values[index] <= 0:
            rate, curvature = rates(args, index)
            if falls(rate, curvature, resolution):
                return index
    return -1


def of_time(guards):
    """A compiled engine's ``guards(mode, t, y, pe, p)`` (a tuple) as functions of time for
    :func:`static_root` and :func:`first_nonpositive`: (``values(args, t)``, all of them,
    ``value((args, i), t)``, guard i), args = (mode, y, pe, p)."""

    @register_jitable
    def values(args, t):
        mode, y, pe, p = args
        return guards(mode, t, y, pe, p)

    @register_jitable
    def value(pair, t):
        args, index = pair
        return values(args, t)[index]

    return values, value


@register_jitable
def static_root(guards, guard, args, t, turn, end):
    """The first root in (t, end] [s] of guards that depend on time alone (a static mode):
    ``guards(args, t)`` -> all of them, ``guard((args, i), t)`` -> guard i, each monotone
    on (t, turn) and (turn, end) (``turn`` nan: on (t, end)). (time, index), or (nan, -1).
    A root is bracketed where a guard goes from > 0 to < 0; zero at the turn is a
    crossing only if the guard goes on below zero (else it touches zero there); zero at
    ``end`` is left to the next piece's right-hand limits."""
    split = not math.isnan(turn)
    for k in range(2 if split else 1):
        a = t if k == 0 else turn
        b = end if k == 1 or not split else turn
        at_a, at_b = guards(args, a), guards(args, b)
        best_t, best_i = math.inf, -1
        for i in range(len(at_a)):
            if at_a[i] > 0 and (at_b[i] < 0 or (at_b[i] == 0 and b < end and guards(args, end)[i] < 0)):
                root = first_nonpositive(guard, (args, i), a, b)
                if root < best_t:
                    best_t, best_i = root, i
        if best_i >= 0:
            return best_t, best_i
    return math.nan, -1
