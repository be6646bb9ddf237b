"""Closed-form relative motion on one monotone piece of a(t), its guard roots and the
exact engines' transition rules, as scalar functions of an array namespace ``xp``.

Written once for both exact engines: the JAX kernel traces them with ``xp = jax.numpy``
(elementwise, so they also map over arrays) and the numba engine compiles them with
``xp`` = :mod:`._xp_scalar`. Only arithmetic, comparisons, ``& | ~`` on booleans and
``xp.where/maximum/minimum/abs/sign/sqrt`` appear. Dense output uses them with NumPy.

Coefficients ``cf = (p0, p1, s, w, phi)`` are those of :mod:`blockdae.excitation.pieces`,
rebased so that local time ``d`` [s] starts at the current point (``s = w = phi = None``
for linear pieces). In slip the relative velocity is

    v(d) = v + c d - A1(d),    u(d) = u + v d + c d²/2 - A2(d),

with c = slip_constant(mode) [m/s²] and A1, A2 the first and double integrals of a.
"""

from ..excitation import accel, accel_int1, accel_int2, accel_rate
from ._model import comes_to_rest, demand, slip_constant, stop_mode

#: halvings of a bracket: ~1 s down to below one ulp; both engines bisect alike
BISECTIONS = 64
#: relative slack of the per-block bounds of a(t), so that rounding never hides an onset
BLOCK_SLACK = 1e-9


def slip_motion(cf, d, u, v, c, xp):
    """(u [m], v [m/s]) after ``d`` [s] of sliding with slip constant ``c`` [m/s²]."""
    return u + v * d + 0.5 * c * d**2 - accel_int2(*cf, d, xp), slip_velocity(cf, d, v, c, xp)


def slip_velocity(cf, d, v, c, xp):
    """v [m/s] after ``d`` [s] of sliding from ``v`` with slip constant ``c`` [m/s²]."""
    return v + c * d - accel_int1(*cf, d, xp)


def slip_rate(cf, d, c, xp):
    """dv/dd = c - a(d) in slip [m/s²]."""
    return c - accel(*cf, d, xp)


def onset_gap(cf, d, target, xp):
    """a(d) - ``target`` [m/s²]; its root on a piece is an onset."""
    return accel(*cf, d, xp) - target


def leaves_stick(sigma_start, sigma_end, limit, allow_neg, allow_pos):
    """Whether a demand monotone between ``sigma_start`` and ``sigma_end`` [m/s²] exceeds
    +``limit`` (-> slip-) / -``limit`` (-> slip+) = mu g [m/s²]: (up, down)."""
    up = allow_neg & ((sigma_end > limit) | (sigma_start > limit))
    down = allow_pos & ((sigma_end < -limit) | (sigma_start < -limit))
    return up, down


def block_may_leave_stick(a_max, a_min, scale, bias, g, limit, allow_neg, allow_pos, xp):
    """Whether the demand may leave [-limit, limit] on a block of pieces where the
    unscaled a(t) lies in [a_min, a_max] [m/s²]. Conservative by :data:`BLOCK_SLACK`
    (the pieces are checked one by one after), never missing an onset. A filter, not a
    rule: the numba engine applies a coarser one (``_exact_numba._thresholds``)."""
    highest = xp.maximum(scale * a_max, scale * a_min)
    lowest = xp.minimum(scale * a_max, scale * a_min)
    slack = BLOCK_SLACK * (xp.maximum(highest, -lowest) + xp.abs(bias * g) + limit)
    up = allow_neg & (demand(highest, bias, g) > limit - slack)
    down = allow_pos & (demand(lowest, bias, g) < -limit + slack)
    return up | down


def onset_side(sigma_start, up, limit, allow_neg, allow_pos):
    """For a piece that leaves stick: (whether it slides -, whether it does so at once
    because the demand ``sigma_start`` [m/s²] is already beyond a threshold). Beyond a
    threshold at the start wins; else a (monotone) crosses the one ``up`` names."""
    starts_up = allow_neg & (sigma_start > limit)
    starts_down = allow_pos & (sigma_start < -limit)
    return starts_up | (~starts_down & up), starts_up | starts_down


def onset_target(going_up, bias, g, limit, xp):
    """a(t) [m/s²] at the threshold the demand crosses: bias g +- mu g."""
    return bias * g + xp.where(going_up, limit, -limit)


def onset_delta_linear(cf, target, xp):
    """Time [s] until a linear a(d) reaches ``target`` [m/s²]."""
    return (target - cf[0]) / xp.where(cf[1] != 0, cf[1], 1.0)


def onset_within(d, rem, at_once, xp):
    """The onset time ``d`` [s] kept in [0, rem]; 0 ``at_once``. (A clip would halve
    the derivative of a root that lies on a bound.)"""
    return xp.where(at_once | (d < 0), 0.0, xp.where(d > rem, rem, d))


def departure_rate(cf, v, c, mode, xp):
    """dv/dd [m/s²] at the start of a piece in slip ``mode``; for a block at rest (v = 0)
    a rate pointing back into rest counts as zero: it leaves rest, never re-enters at once."""
    r0 = slip_rate(cf, 0.0, c, xp)
    return xp.where((v == 0) & (mode * r0 < 0), 0.0, r0)


def stop_delta_linear(cf, rem, v, c, mode, xp):
    """First d in (0, rem] where v(d) = v + r0 d - (p1/2) d² returns to 0 in slip ``mode``
    (= sign of v) on a linear piece, by stable formulas. Returns (d [s], found); a start
    at rest (v = 0) leaves first; a velocity that only touches zero with the wrong
    slope (rounding at a graze) is not a return."""
    r = departure_rate(cf, v, c, mode, xp)
    q = -0.5 * cf[1]
    at_rest = v == 0
    disc = r * r - 4.0 * q * v
    den = r - mode * xp.sqrt(xp.maximum(disc, 0.0))
    # at rest the departure -r / q, else the return -2 v / den: one division
    d = xp.where(at_rest, -r, -2.0 * v) / xp.where(at_rest, xp.where(q != 0, q, 1.0), xp.where(den != 0, den, 1.0))
    found = xp.where(at_rest, q != 0, (disc >= 0) & (den != 0)) & (d > 0) & (d <= rem)
    return xp.where(found, d, rem), found


def mode_after_stop(cf, d, c, mode, t_stop, mu, f, g, allow_neg, allow_pos, xp):
    """Mode after v returns to zero ``d`` [s] into a piece in slip ``mode`` at time
    ``t_stop`` [s] (the model's :func:`~blockdae.sliding._model.stop_mode`)."""
    return stop_mode(mode, slip_rate(cf, d, c, xp), accel_rate(*cf, d, xp), t_stop, mu, f, g,
                     allow_neg, allow_pos, xp)


def rate_turns(r0, r_end, xp):
    """Whether dv/dd, monotone on a piece, changes sign between its ends."""
    return xp.sign(r0) != xp.sign(r_end)


def sine_stop_bracket(r0, turns, d_turn, rem, mode, xp):
    """[lo, hi] [s] on a sine piece where v, moving with initial rate ``r0`` [m/s²] and
    turning at ``d_turn`` [s] if it ``turns``, may return to zero in slip ``mode``."""
    toward = mode * r0 < 0
    lo = xp.where(toward, 0.0, xp.where(turns, d_turn, rem))
    hi = xp.where(toward & turns, d_turn, rem)
    return lo, hi


def crosses_zero(v_lo, v_hi, mode):
    """Whether v goes from ``v_lo`` (moving in ``mode``) to rest or beyond at ``v_hi``."""
    return (mode * v_lo > 0) & (mode * v_hi <= 0)


def tail_to_rest(u, v, mode, bias, f, g, xp):
    """After the excitation (a = 0) a block sliding at ``v`` [m/s] in ``mode`` changes
    speed at the slip constant: (time d [s] until v = 0, u [m] then, whether it rests)."""
    c = slip_constant(mode, bias, f, g)
    rests = comes_to_rest(v, mode, bias, f, g)
    d = xp.where((v != 0) & rests, -v / xp.where(c != 0, c, 1.0), 0.0)
    return d, u + 0.5 * v * d, rests
