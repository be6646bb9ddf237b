"""The rocking block's rules on plain numbers, written once: :class:`RockingBlock`'s methods
and the compiled engine (:mod:`._compiled`) both call them.

Each rule takes the base's motion at one instant as numbers: a_x [m/s²], g_e = g + a_z
[m/s²] and their rates [m/s³]; the geometry as alpha [rad], p² [1/s²], g [m/s²] (the
model from its possibly traced parameters, the engine from its parameter row). The
flow's rule uses only arithmetic and ``xp.sin/cos`` of an array namespace ``xp`` (NumPy,
``jax.numpy``, the model's ``SCALAR`` or, inside numba,
:mod:`blockdae.solvers.xp_scalar`); the mode rules are scalar. Modes are
:class:`~blockdae.rocking.RockingMode` values as ints, a rocking mode ``kind * s``.
"""

import math

REST, OUT, IN, BEYOND, SETTLE, OVERTURNED = 0, 2, 3, 4, 5, 6
#: what :func:`mode_after_rocking_guard` returns where the block comes to rest and the
#: demand at that instant decides (the model's ``mode_at_rest``)
DEMAND_DECIDES = 8


def angular_acceleration(s, theta, ax, ge, alpha, p2, g, linearised, xp):
    """theta'' [rad/s²] rocking about the corner on side ``s`` at ``theta`` [rad]:
    -p² [(g_e/g) sin phi + (a_x/g) cos phi], phi = s alpha - theta (linearised: sin phi
    -> phi, cos phi -> 1)."""
    phi = s * alpha - theta
    if linearised:
        return -p2 * ((ge / g) * phi + ax / g)
    return -p2 * ((ge / g) * xp.sin(phi) + (ax / g) * xp.cos(phi))


def angular_jerk(s, theta, rate, ax, ge, ax_rate, az_rate, alpha, p2, g, linearised):
    """theta''' [rad/s³] rocking about side ``s`` at (theta [rad], theta' [rad/s])."""
    phi = s * alpha - theta
    if linearised:
        return -p2 * ((az_rate / g) * phi - (ge / g) * rate + ax_rate / g)
    return -p2 * ((az_rate / g) * math.sin(phi) - (ge / g) * math.cos(phi) * rate
                  + (ax_rate / g) * math.cos(phi) + (ax / g) * math.sin(phi) * rate)


def settle_rate(s, ahead, behind, r):
    """d theta'/dt [rad/s²] of the Zeno envelope on side ``s``, with the decelerations
    ``ahead`` (-s theta'' at theta = 0 on side s) and ``behind`` (on side -s) [rad/s²]:
    with the excitation frozen the arcs last 2 |w| / ahead and 2 r |w| / behind in turn,
    so the rest comes after |w| K, K = 2 (1/ahead + r/behind) / (1 - r²), and the
    envelope falls by 1/K."""
    return -s / (2.0 * (1.0 / ahead + r / behind) / (1 - r * r))


def rocking_guards(kind, s, theta, rate, alpha):
    """The two own guards of rocking mode ``kind`` on side ``s``, each left as it falls
    through zero: OUT (s theta' -> apex, alpha - s theta -> beyond alpha); IN (s theta
    -> impact, -s theta' -> outward again); BEYOND (s theta' -> apex, pi/2 - s theta ->
    overturned)."""
    if kind == IN:
        return s * theta, -s * rate
    return s * rate, (alpha if kind == OUT else 0.5 * math.pi) - s * theta


def rocking_guard_rates(kind, s, index, rate, accel, jerk):
    """(rate, curvature) in time of own guard ``index`` of rocking mode ``kind`` (see
    :func:`rocking_guards`), from theta' [rad/s], theta'' and theta''' at the instant."""
    if kind == IN:
        return (s * rate, s * accel) if index == 0 else (-s * accel, -s * jerk)
    return (s * accel, s * jerk) if index == 0 else (-s * rate, -s * accel)


def mode_after_apex(s, theta, accel, alpha):
    """The rocking mode at rest in rotation (theta' = 0) at ``theta`` [rad] on side
    ``s`` with theta'' = ``accel`` [rad/s²]: falling back (IN), or on outward (OUT below
    alpha, BEYOND above)."""
    if s * accel <= 0:
        return IN * s
    return (OUT if s * theta < alpha else BEYOND) * s


def mode_after_rocking_guard(kind, s, index, theta, w, ahead, behind, alpha, zeno_arc):
    """The mode after own guard ``index`` of rocking or settling mode ``kind`` on side
    ``s``, at ``theta`` [rad]; at an impact ``w`` = r theta' [rad/s] is the rate after
    it and ``ahead``, ``behind`` [rad/s²] the decelerations about the new and the old
    pivot (see :func:`settle_rate`): the other side's OUT, or its SETTLE where the next
    arc, 2 |w| / ahead, is shorter than ``zeno_arc`` [s] and both corners restore.
    SETTLE's guards: the envelope's end (REST), a_x past +limit (OUT -) or -limit (OUT +).
    :data:`DEMAND_DECIDES` where the block comes to rest on the base."""
    if kind == OUT:
        if index == 1:
            return BEYOND * s
        return DEMAND_DECIDES if theta == 0 else IN * s
    if kind == BEYOND:
        return IN * s if index == 0 else OVERTURNED * s
    if kind == IN:
        if index == 1:
            return (OUT if s * theta < alpha else BEYOND) * s
        if w == 0:
            return DEMAND_DECIDES
        if ahead > 0 and behind > 0 and 2 * abs(w) / ahead < zeno_arc:
            return -SETTLE * s
        return -OUT * s
    if kind == SETTLE:
        return REST if index == 0 else (-OUT if index == 1 else OUT)
    return kind * s
