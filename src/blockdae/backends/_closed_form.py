"""Closed-form relative motion on one monotone piece of a(t), and its guard roots.

Shared by the exact kernel (``jax.numpy``) and by dense output (``numpy``). Coefficients
``cf = (p0, p1, s, w, phi)`` are those of :mod:`blockdae.excitation._pieces`, rebased so
that local time ``d`` [s] starts at the current point. In slip the relative velocity is

    v(d) = v + c d - A1(d),    u(d) = u + v d + c d²/2 - A2(d),

with c = slip_constant(mode) [m/s²] and A1, A2 the first and double integrals of a.
"""

import jax
import jax.numpy as jnp

from ..excitation._pieces import accel, accel_int1, accel_int2

_BISECTIONS = 64  # halves a bracket of ~1 s below one ulp


def slip_motion(cf, d, u, v, c, xp=jnp):
    """(u, v) after ``d`` [s] of sliding with slip constant ``c`` [m/s²]."""
    return (u + v * d + 0.5 * c * d**2 - accel_int2(*cf, d, xp),
            v + c * d - accel_int1(*cf, d, xp))


def _bisect(fun, lo, hi):
    """Bracketed root of ``fun``, monotone on [lo, hi]; returns the upper end.

    The value is the bisection's; its derivative with respect to parameters that
    ``fun`` closes over is the implicit function theorem's, -dF/dp / dF/dt.
    """
    flo_sign = jnp.sign(fun(lo))

    def halve(_, bracket):
        lo, hi = bracket
        mid = 0.5 * (lo + hi)
        keep_lo = jnp.sign(fun(mid)) == flo_sign
        return jnp.where(keep_lo, mid, lo), jnp.where(keep_lo, hi, mid)

    _, root = jax.lax.fori_loop(0, _BISECTIONS, halve, jax.lax.stop_gradient((lo, hi)))
    root = jax.lax.stop_gradient(root)
    value, slope = jax.jvp(fun, (root,), (jnp.ones_like(root),))
    step = jnp.where(slope != 0, value / jnp.where(slope != 0, slope, 1.0), 0.0)
    return root - (step - jax.lax.stop_gradient(step))


def onset_delta(cf, rem, target, is_sine):
    """Time [s] until a(d) reaches ``target`` [m/s²] on [0, rem] (a monotone)."""
    linear = (target - cf[0]) / jnp.where(cf[1] != 0, cf[1], 1.0)
    if not is_sine:
        return linear
    sine = _bisect(lambda d: accel(*cf, d, jnp) - target, jnp.zeros_like(rem), rem)
    return jnp.where(cf[2] != 0, sine, linear)


def stop_delta(cf, rem, v, c, mode, is_sine):
    """First time d in (0, rem] where v(d) returns to 0 in slip ``mode`` (= sign of v).

    Returns (d [s], found). A start at rest (v = 0) leaves first; a velocity that only
    touches zero with the wrong slope (rounding at a graze) is not a return.
    """
    r0 = c - cf[0]  # dv/dd at d = 0
    at_rest = v == 0
    r0 = jnp.where(at_rest & (mode * r0 < 0), 0.0, r0)  # leave rest, never re-enter at once
    d_lin, found_lin = _stop_delta_linear(r0, -0.5 * cf[1], v, mode, rem, at_rest)
    if not is_sine:
        return d_lin, found_lin
    d_sin, found_sin = _stop_delta_sine(cf, rem, v, c, mode, r0)
    sine = cf[2] != 0
    return jnp.where(sine, d_sin, d_lin), jnp.where(sine, found_sin, found_lin)


def _stop_delta_linear(r, q, v, mode, rem, at_rest):
    """Root of v + r d + q d² = 0 that ends the current slip (stable formulas)."""
    departure = -r / jnp.where(q != 0, q, 1.0)
    found_departure = (q != 0) & (departure > 0)
    disc = r * r - 4.0 * q * v
    den = r - mode * jnp.sqrt(jnp.maximum(disc, 0.0))
    moving = -2.0 * v / jnp.where(den != 0, den, 1.0)
    found_moving = (disc >= 0) & (den != 0) & (moving > 0)
    d = jnp.where(at_rest, departure, moving)
    found = jnp.where(at_rest, found_departure, found_moving) & (d <= rem)
    return jnp.where(found, d, rem), found


def _stop_delta_sine(cf, rem, v, c, mode, r0):
    def rate(d):
        return c - accel(*cf, d, jnp)

    def vel(d):
        return v + c * d - accel_int1(*cf, d, jnp)

    zero = jnp.zeros_like(rem)
    r_end = rate(rem)
    turns = jnp.sign(r0) != jnp.sign(r_end)  # dv/dd is monotone: one sign change at most
    d_turn = jnp.where(turns, _bisect(rate, zero, rem), rem)
    toward = mode * r0 < 0
    lo = jnp.where(toward, zero, jnp.where(turns, d_turn, rem))
    hi = jnp.where(toward & turns, d_turn, rem)
    found = (mode * vel(lo) > 0) & (mode * vel(hi) <= 0)
    d = _bisect(vel, lo, hi)
    return jnp.where(found, d, rem), found
