"""The flexible engine's root and peak searches on the closed forms of
:mod:`blockdae.solvers._linear`, by the same rules as its ``_down_crossing_search``: an
interval is kept only where bounds of the form's first three derivatives fail to show
that it keeps one sign, is monotone or is convex/concave, and is halved otherwise.

Two things make them cheaper: each point's exp, cos and sin serve the form and its
derivatives at once (the stack holds both ends' values), and a sign change on a
monotone part is found by Newton's method within its bracket (halving it where a step
would leave it), started where the inverse cubic Hermite interpolant of the bracket's
ends (values and slopes, already known) is zero, the bracket then closed by a probe a
few ulps across and bisection to one ulp of the time (``_first_nonpositive`` bisects to
adjacent floats of tau, which near tau = 0 are far finer than the time's: up to a
hundred halvings).
"""

import math

import numpy as np
from numba.extending import register_jitable

from ..solvers import MAX_INTERVALS, evaluate_form, evaluate_form_at, form_rounding
from ..core import one_sign

_EPS = float(np.finfo(float).eps)
#: Newton steps before the bracket is closed by bisection alone
_NEWTON_STEPS = 12
#: columns of a search's stack: lo, f, f', f'', e^{-sigma lo}; hi, f, f', f'', e^{-sigma hi}
STACK_COLUMNS = 10


@register_jitable
def _trig(f, tau):
    """(e^{-sigma tau}, cos w tau, sin w tau) of the form f."""
    return math.exp(-f[6] * tau), math.cos(f[7] * tau), math.sin(f[7] * tau)


@register_jitable
def _amplitude(f):
    """sqrt(C² + D²) of the form f: its oscillation's amplitude at tau = 0."""
    return math.sqrt(f[4] * f[4] + f[5] * f[5])


@register_jitable
def form_bound(f, amplitude, hi, decay_lo):
    """An upper bound of |f| on [lo, hi], 0 <= lo <= hi, term by term (as the linear
    engine's ``form_bound``), from sqrt(C² + D²) and e^{-sigma lo} given."""
    poly = abs(f[0]) + abs(f[1]) * hi + abs(f[2]) * hi * hi + abs(f[3]) * hi * hi * hi
    return (poly + amplitude * decay_lo) * (1 + 8 * _EPS)


@register_jitable
def _put(stack, top, lo, f_lo, d_lo, c_lo, e_lo, hi, f_hi, d_hi, c_hi, e_hi):
    stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3], stack[top, 4] = lo, f_lo, d_lo, c_lo, e_lo
    stack[top, 5], stack[top, 6], stack[top, 7], stack[top, 8], stack[top, 9] = hi, f_hi, d_hi, c_hi, e_hi


@register_jitable
def _hermite_start(lo, f_lo, d_lo, hi, f_hi, d_hi):
    """Where the inverse cubic Hermite interpolant of a monotone f (values ``f_lo``,
    ``f_hi`` of opposite signs and slopes ``d_lo``, ``d_hi`` at lo and hi) is zero: a
    start for Newton's method within O((hi - lo)^4) of the root for a smooth f; nan
    where it does not lie inside (lo, hi) (a slope of zero or of the wrong sign)."""
    rise = f_hi - f_lo
    if not (d_lo * rise > 0 and d_hi * rise > 0):
        return math.nan
    s = -f_lo / rise
    s2 = s * s
    s3 = s2 * s
    x = ((2 * s3 - 3 * s2 + 1) * lo + (-2 * s3 + 3 * s2) * hi +
         ((s3 - 2 * s2 + s) * rise / d_lo + (s3 - s2) * rise / d_hi))
    return x if lo < x < hi else math.nan


@register_jitable
def _narrowed(f, f1, x, lo, hi, positive):
    """(f(x), f'(x), the bracket [lo, hi] narrowed by x): x replaces the end on its side
    (f > 0 or not, ``positive``: f(lo)'s)."""
    decay, cos, sin = _trig(f, x)
    fx, dx = evaluate_form_at(f, x, decay, cos, sin), evaluate_form_at(f1, x, decay, cos, sin)
    if (fx > 0) == positive:
        return fx, dx, x, hi
    return fx, dx, lo, x


@register_jitable
def sign_change(f, f1, lo, f_lo, d_lo, hi, f_hi, d_hi, origin):
    """The float hi of a pair (lo, hi) within one ulp of the time ``origin`` + tau [s]
    (adjacent floats of tau where tau outgrows it) where f, monotone on [lo, hi] with
    f(lo) = ``f_lo``, f'(lo) = ``d_lo``, f(hi) = ``f_hi`` and f'(hi) = ``d_hi`` on either
    side, changes from f(lo)'s side (f > 0 or not) to the other; f1 is f's derivative
    form. Newton's method starts from :func:`_hermite_start` (else the end nearer zero)."""
    positive = f_lo > 0
    tiny = _EPS * abs(origin)  # finer than this, tau no longer moves origin + tau
    x = _hermite_start(lo, f_lo, d_lo, hi, f_hi, d_hi)
    if math.isnan(x):
        x, fx, dx = (lo, f_lo, d_lo) if abs(f_lo) < abs(f_hi) else (hi, f_hi, d_hi)
    else:
        fx, dx, lo, hi = _narrowed(f, f1, x, lo, hi, positive)
    for _ in range(_NEWTON_STEPS):
        if hi - lo <= tiny:
            return hi
        if abs(fx) <= max(tiny, 4 * _EPS * abs(x)) * abs(dx):  # the next step would be below the resolution:
            break  # the root is within it, which the probe below confirms
        x_new = x - fx / dx if dx != 0.0 else math.nan
        if not lo < x_new < hi:  # a step out of the bracket: halve it instead
            x_new = lo + 0.5 * (hi - lo)
            if x_new <= lo or x_new >= hi:
                return hi
        fx, dx, lo, hi = _narrowed(f, f1, x_new, lo, hi, positive)
        x = x_new
    gap = max(tiny, 8 * _EPS * abs(x))
    if hi - lo > 2 * gap:  # close the other side by a probe a few ulps across
        probe = x - gap if x == hi else x + gap
        if lo < probe < hi:
            if (evaluate_form(f, probe) > 0) == positive:
                lo = probe
            else:
                hi = probe
    while hi - lo > tiny:
        mid = lo + 0.5 * (hi - lo)
        if mid <= lo or mid >= hi:
            break
        if (evaluate_form(f, mid) > 0) == positive:
            lo = mid
        else:
            hi = mid
    return hi


@register_jitable
def _falling_part(f, f1, lo, f_lo, d_lo, hi, f_hi, d_hi, decreasing, origin):
    """The crossing on [lo, hi] where f is monotone (nan: none), as the linear engine's
    ``_monotone_part``: f must fall below zero by more than its rounding."""
    if not decreasing or not (f_lo > 0 > f_hi) or f_hi >= -form_rounding(f, hi):
        return math.nan
    return sign_change(f, f1, lo, f_lo, d_lo, hi, f_hi, d_hi, origin)


@register_jitable
def first_fall(f, f1, f2, f3, span, origin, stack, decay, cos, sin):
    """The first tau in [0, span] [s] where f falls to <= 0 (nan: none; -inf: the search
    did not settle), as the linear engine's ``_down_crossing_search`` from 0: for a caller
    that has decided whether a guard at zero at 0 is left at once. ``origin``: the time
    of tau = 0 [s] (the resolution is a few ulps of it); ``stack``: scratch
    (STACK_DEPTH, STACK_COLUMNS); ``decay``, ``cos``, ``sin``: e^{-sigma span}, cos and
    sin(w span) of f (the caller has them)."""
    resolution = 4 * _EPS * max(abs(origin) + abs(span), 1.0)
    amplitudes = (_amplitude(f1), _amplitude(f2), _amplitude(f3))
    _put(stack, 0, 0.0, f[0] + f[4], f1[0] + f1[4], f2[0] + f2[4], 1.0, span, evaluate_form_at(f, span, decay, cos, sin),
         evaluate_form_at(f1, span, decay, cos, sin), evaluate_form_at(f2, span, decay, cos, sin), decay)
    top = 0
    budget = MAX_INTERVALS
    while top >= 0:
        lo, f_lo, d_lo, c_lo, e_lo = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3], stack[top, 4]
        hi, f_hi, d_hi, c_hi, e_hi = stack[top, 5], stack[top, 6], stack[top, 7], stack[top, 8], stack[top, 9]
        top -= 1
        budget -= 1
        if budget < 0:
            return -math.inf
        length = hi - lo
        if one_sign(f_lo, f_hi, form_bound(f1, amplitudes[0], hi, e_lo), length) != 0:
            continue
        slope_sign = one_sign(d_lo, d_hi, form_bound(f2, amplitudes[1], hi, e_lo), length)
        if slope_sign != 0:
            root = _falling_part(f, f1, lo, f_lo, d_lo, hi, f_hi, d_hi, slope_sign < 0, origin)
            if not math.isnan(root):
                return root
            continue
        if one_sign(c_lo, c_hi, form_bound(f3, amplitudes[2], hi, e_lo), length) != 0:
            if d_lo * d_hi >= 0:
                root = _falling_part(f, f1, lo, f_lo, d_lo, hi, f_hi, d_hi, d_lo + d_hi < 0, origin)
                if not math.isnan(root):
                    return root
                continue
            turn = sign_change(f1, f2, lo, d_lo, c_lo, hi, d_hi, c_hi, origin)
            decay, cos, sin = _trig(f, turn)
            f_turn, d_turn = evaluate_form_at(f, turn, decay, cos, sin), evaluate_form_at(f1, turn, decay, cos, sin)
            root = _falling_part(f, f1, lo, f_lo, d_lo, turn, f_turn, d_turn, d_lo < 0, origin)
            if math.isnan(root):
                root = _falling_part(f, f1, turn, f_turn, d_turn, hi, f_hi, d_hi, d_hi < 0, origin)
            if not math.isnan(root):
                return root
            continue
        if length <= resolution:
            if f_lo > 0 > f_hi and f_hi < -form_rounding(f, hi):
                return hi
            continue
        if top + 2 >= stack.shape[0]:
            return -math.inf
        mid = lo + 0.5 * length
        decay, cos, sin = _trig(f, mid)
        f_mid, d_mid, c_mid = (evaluate_form_at(f, mid, decay, cos, sin), evaluate_form_at(f1, mid, decay, cos, sin),
                               evaluate_form_at(f2, mid, decay, cos, sin))
        top += 1
        _put(stack, top, mid, f_mid, d_mid, c_mid, decay, hi, f_hi, d_hi, c_hi, e_hi)
        top += 1
        _put(stack, top, lo, f_lo, d_lo, c_lo, e_lo, mid, f_mid, d_mid, c_mid, decay)
    return math.nan


@register_jitable
def peak(f, f1, f2, f3, span, best, origin, stack):
    """max(best, sup of |f| on [0, span]) [f's unit]: extrema located to adjacent floats
    where f' changes sign (bounds of f', f'', f''' prune and split the interval as in
    :func:`first_fall`); -inf if the search did not settle."""
    resolution = 4 * _EPS * max(abs(origin) + abs(span), 1.0)
    amplitudes = (_amplitude(f1), _amplitude(f2), _amplitude(f3))
    decay, cos, sin = _trig(f, span)
    _put(stack, 0, 0.0, f[0] + f[4], f1[0] + f1[4], f2[0] + f2[4], 1.0, span, evaluate_form_at(f, span, decay, cos, sin),
         evaluate_form_at(f1, span, decay, cos, sin), evaluate_form_at(f2, span, decay, cos, sin), decay)
    top = 0
    budget = MAX_INTERVALS
    while top >= 0:
        lo, f_lo, d_lo, c_lo, e_lo = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3], stack[top, 4]
        hi, f_hi, d_hi, c_hi, e_hi = stack[top, 5], stack[top, 6], stack[top, 7], stack[top, 8], stack[top, 9]
        top -= 1
        budget -= 1
        if budget < 0:
            return -math.inf
        best = max(best, abs(f_lo), abs(f_hi))
        length = hi - lo
        if max(abs(f_lo), abs(f_hi)) + 0.5 * form_bound(f1, amplitudes[0], hi, e_lo) * length <= best or \
                length <= resolution:
            continue  # cannot exceed the best
        if one_sign(d_lo, d_hi, form_bound(f2, amplitudes[1], hi, e_lo), length) != 0:
            continue  # monotone: its ends
        if one_sign(c_lo, c_hi, form_bound(f3, amplitudes[2], hi, e_lo), length) != 0:
            if d_lo * d_hi < 0:  # one extremum inside
                best = max(best, abs(evaluate_form(f, sign_change(f1, f2, lo, d_lo, c_lo, hi, d_hi, c_hi, origin))))
            continue
        if top + 2 >= stack.shape[0]:
            return -math.inf
        mid = lo + 0.5 * length
        decay, cos, sin = _trig(f, mid)
        f_mid, d_mid, c_mid = (evaluate_form_at(f, mid, decay, cos, sin), evaluate_form_at(f1, mid, decay, cos, sin),
                               evaluate_form_at(f2, mid, decay, cos, sin))
        top += 1
        _put(stack, top, mid, f_mid, d_mid, c_mid, decay, hi, f_hi, d_hi, c_hi, e_hi)
        top += 1
        _put(stack, top, lo, f_lo, d_lo, c_lo, e_lo, mid, f_mid, d_mid, c_mid, decay)
    return best
