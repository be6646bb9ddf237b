"""The hybrid driver's event rules, one implementation each, for the Python driver
(:mod:`blockdae.core._driver`) and the compiled engines: plain functions that numba
compiles where an engine calls them (``register_jitable``) and Python calls as they are.

* :func:`falls`: whether a guard at zero leaves its mode at once (a graze that turns back
  within the event resolution does not).
* :func:`first_nonpositive`: bisection to adjacent floats (of ``origin`` + t) for the
  first float where a monotone function is <= 0; :func:`sign_change`: the same for a
  sign change either way.
* :func:`one_sign`: the interval test of the derivative-bounded root searches.

A function of time is passed with its arguments: ``fun(args, t)``.

Not shared, and why: the exact 1-D engines halve a fixed ``BISECTIONS`` times so that
numba's loop and the JAX kernel's ``fori_loop`` (a fixed count, and the implicit-function
derivative at the end) give the same floats; the flexible kernel's bisection advances a
matrix-exponential state from the last end it kept (no function of time alone); the
planar engine's stop confirmed on the flow and its turning points carry a state or an
"undefined" answer; the derivative-bounded searches themselves read different closed
forms (a polynomial-exponential row, Python objects with Brent's method, a
matrix-exponential state with a fourth-derivative bound, Newton on shared exp/cos/sin),
so only their interval test is one.
"""

from numba.extending import register_jitable


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
