"""The planar block's rules on plain numbers, written once: :class:`~blockdae.PlanarBlock`'s
methods and the compiled planar engine (:mod:`._compiled`) both call them.

Each rule takes the forces per unit mass at one instant as numbers: the normal force n
[m/s²] and its rate [m/s³], the demand sigma = (s_x, s_y) = a_h - b g [m/s²] and its rate
(r_x, r_y) [m/s³] (the model from its excitation and support, the engine from its
piece's coefficients), and the state y (the model's 7 entries; the engine's 8th, the path
length, is not read). Rules that JAX traces too (the flows, guards and entry states) use
only arithmetic, comparisons and ``xp.sqrt/where`` of an array namespace ``xp`` (NumPy,
``jax.numpy``, the model's ``SCALAR`` or, inside numba, :mod:`blockdae.solvers.xp_scalar`)
and branch on the mode alone; the mode rules are scalar (``math``, Python ``if``).
Modes are the :class:`~blockdae.planar.PlanarMode` values as ints.
"""

import math

from ._modes import _CX, _CY, _S, _UX, _UY, _W, _WD

STICK, SLIP, FLIGHT = 0, 1, 2
#: below this speed [m/s] the direction relaxes towards the demand at the rate
#: |sigma| / SLOW_SPEED instead of |sigma| / s. Just after an onset with f = mu,
#: s ~ tau², and the exact rate |sigma| / s makes the slide so stiff that no solver
#: steps through it (explicit ones need ~1 / tau steps). The lag of the direction
#: behind the demand, omega s / |sigma| (omega: its turning rate), is then
#: omega SLOW_SPEED / |sigma| < 1e-6 rad while s < SLOW_SPEED, which moves u by less
#: than omega SLOW_SPEED² tau / |sigma| ~ 1e-15 m (Elms's pulse: stops 2e-12 s,
#: u 1e-11 off a reference with the exact rate, tests/test_planar_jax.py).
SLOW_SPEED = 1e-6


# ---- forces -------------------------------------------------------------------------
def rigid_normal(g, a_z):
    """n = g + a_z [m/s²] on a rigid support."""
    return g + a_z


def demand(a_x, a_y, bias_x, bias_y, g):
    """sigma = a_h - b g [m/s²], as (x, y)."""
    return a_x - bias_x * g, a_y - bias_y * g


def circle_margin(mu, n, n_rate, sx, sy, rx, ry):
    """mu n - |sigma| [m/s²] (> 0 inside the friction circle) and its rate [m/s³] (where
    sigma = 0, the rate of -|sigma| is -|sigma'|)."""
    size = math.hypot(sx, sy)
    return mu * n - size, mu * n_rate - ((sx * rx + sy * ry) / size if size > 0 else math.hypot(rx, ry))


# ---- flows ------------------------------------------------------------------------------
def slip_rates(y, rx, ry, kinetic, xp):
    """The slide's e = c / |c| [-] (0 where c = 0), s' [m/s²] and c' [1/s] as (e_x, e_y, s', c_x', c_y'),
    with relative acceleration (rx, ry) = F - sigma [m/s²] besides the kinetic friction
    ``kinetic`` = f n [m/s²] along -e (0 where F is the friction already)."""
    square = y[_CX] ** 2 + y[_CY] ** 2
    moving = square > 0  # c = 0 (a state at rest, as the driver's shape check gives): e = 0, no 0/0
    size = xp.where(moving, xp.sqrt(xp.where(moving, square, 1.0)), 0.0)  # no infinite slope of sqrt at 0
    ex, ey = y[_CX] / xp.where(moving, size, 1.0), y[_CY] / xp.where(moving, size, 1.0)
    along = ex * rx + ey * ry - kinetic  # e . (F - sigma) - f n
    across = ex * ry - ey * rx  # e_perp . (F - sigma), e_perp = (-e_y, e_x)
    s = y[_S]
    turn = across / xp.where(s > SLOW_SPEED, s, SLOW_SPEED)  # de/dt along e_perp [1/s]
    return ex, ey, along, -ey * turn * size, ex * turn * size


def slip_flow(y, rx, ry, kinetic, xp):
    """(u_x', u_y', s', c_x', c_y') of a slide (see :func:`slip_rates`)."""
    ex, ey, along, turn_x, turn_y = slip_rates(y, rx, ry, kinetic, xp)
    s = y[_S]
    return s * ex, s * ey, along, turn_x, turn_y


def flow(mode, y, rx, ry, kinetic, fall, xp):
    """dy/dt (7 values) in ``mode`` with relative acceleration (rx, ry) = F - sigma
    [m/s²], kinetic friction ``kinetic`` = f n [m/s²] (slip) and w'' = ``fall`` =
    -(g + a_z) [m/s²] (flight); in contact the vertical rates are zero (a rigid support)."""
    zero = 0.0 * y[_UX]
    if mode == STICK:
        return zero, zero, zero, zero, zero, zero, zero
    if mode == FLIGHT:
        return y[_CX], y[_CY], zero, rx, ry, y[_WD], fall
    u_x, u_y, s, c_x, c_y = slip_flow(y, rx, ry, kinetic, xp)
    return u_x, u_y, s, c_x, c_y, zero, zero


def speed(y):
    """|v| [m/s] on a rigid support: |c| at s = 0 (c is v in flight), else (s, w')."""
    if y[_S] == 0:
        return math.hypot(y[_CX], y[_CY])
    return math.hypot(y[_S], y[_WD])


# ---- guards -----------------------------------------------------------------------------
def guards(mode, y, n, sx, sy, mu, scale, xp):
    """Stick: (n, mu n - |sigma|); slip: (n, s); flight: (w, inf) (one guard). The force
    guards times ``scale`` [-, or s² on a spring]."""
    if mode == FLIGHT:
        return y[_W], math.inf
    n = n * scale
    if mode == STICK:
        return n, mu * n - xp.sqrt(sx**2 + sy**2) * scale
    return n, y[_S]


def guard_rates(mode, index, y, mu, f, n, n_rate, sx, sy, rx, ry, scale, xp):
    """Guard ``index``'s (rate, curvature) in ``mode`` (a flight on a rigid support)."""
    if mode == SLIP and index == 1:
        along = slip_rates(y, -sx, -sy, f * n, xp)[2]
        return along, math.hypot(rx, ry) + f * abs(n_rate)
    if mode == FLIGHT:  # w'' = -n
        return y[_WD], -n
    if mode == STICK and index == 1:
        return circle_margin(mu, n, n_rate, sx, sy, rx, ry)[1] * scale, 0.0
    return n_rate * scale, 0.0


def turn_rate(mode, y, mu, f, n, n_rate, sx, sy, rx, ry, xp):
    """(value, defined): stick: the rate of (mu n)² - |sigma|² (linear in t on a linear
    piece); flight: w'; slip along a line: s'; a turning slide: none (defined False)."""
    if mode == STICK:
        return 2 * (mu**2 * n * n_rate - (sx * rx + sy * ry)), True
    if mode == FLIGHT:
        return y[_WD], True
    _, _, along, turn_x, turn_y = slip_rates(y, -sx, -sy, f * n, xp)
    return along, turn_x == 0 and turn_y == 0


# ---- transitions ------------------------------------------------------------------------
def lifts_off(n, n_rate):
    """Whether n is negative, or zero and falling."""
    return n < 0 or (n == 0 and n_rate < 0)


def mode_at_rest(mu, n, n_rate, sx, sy, rx, ry):
    """Flight if n < 0 (or n = 0 falling), else slip if the demand is outside the friction
    circle (or on it moving outwards), else stick."""
    if lifts_off(n, n_rate):
        return FLIGHT
    margin, margin_rate = circle_margin(mu, n, n_rate, sx, sy, rx, ry)
    if margin < 0 or (margin == 0 and margin_rate < 0):
        return SLIP
    return STICK


def mode_after_guard(mode, index, t, y, mu, n, n_rate, sx, sy, rx, ry, restitution, bounce_threshold, rigid,
                     time_tol):
    """Stick or slip: n reaching zero and falling -> flight (a touch of zero keeps the
    mode); stick: the circle reached -> slip (flight where the demand is zero: the
    circle shrinks to its centre only as n reaches zero); a stop -> stick, unless the
    demand leaves the circle within ``time_tol`` [s] (it slides on along the demand).
    Landing -> a rebound (flight) while -restitution w' exceeds ``bounce_threshold``
    [m/s] (on a ``rigid`` support), else slip if still moving, else the mode at rest."""
    if mode != FLIGHT and index == 0:
        return FLIGHT if lifts_off(n, n_rate) else mode
    if mode == STICK:
        return FLIGHT if sx == 0 and sy == 0 else SLIP
    if mode == FLIGHT:
        if rigid and -restitution * y[_WD] > bounce_threshold:
            return FLIGHT
        if y[_CX] != 0 or y[_CY] != 0:
            return FLIGHT if lifts_off(n, n_rate) else SLIP
    rest = mode_at_rest(mu, n, n_rate, sx, sy, rx, ry)
    margin, margin_rate = circle_margin(mu, n, n_rate, sx, sy, rx, ry)
    if rest == STICK and margin_rate < 0 and (t + margin / -margin_rate) - t <= time_tol:
        return SLIP
    return rest


def state_on_entry(before, after, y, sx, sy, rx, ry, restitution, rigid, xp):
    """The state (7 values) entering ``after`` from ``before``: a liftoff starts with v in
    Cartesian form and, on a ``rigid`` support, w = w' = 0; a landing keeps the
    horizontal velocity and, on a rigid support, takes -restitution times the vertical
    one (a rebound) or zero (contact); on a spring the vertical motion goes on. Sliding
    from rest starts along -sigma (or, where sigma = 0, along -sigma')."""
    u_x, u_y, s, c_x, c_y, w, w_rate = y[_UX], y[_UY], y[_S], y[_CX], y[_CY], y[_W], y[_WD]
    if after == FLIGHT:
        if before == FLIGHT:
            return u_x, u_y, s, c_x, c_y, 0.0, -restitution * w_rate
        size = xp.sqrt(c_x**2 + c_y**2)
        moving = size > 0
        size = xp.where(moving, size, 1.0)
        e_x, e_y = xp.where(moving, c_x / size, 0.0), xp.where(moving, c_y / size, 0.0)
        if rigid:
            w, w_rate = 0.0, 0.0
        return u_x, u_y, 0.0, s * e_x, s * e_y, w, w_rate
    if before == FLIGHT:  # back to the polar form
        s = xp.sqrt(c_x**2 + c_y**2)
        if rigid:
            w, w_rate = 0.0, 0.0
    if after == STICK:
        return u_x, u_y, 0.0, c_x, c_y, w, w_rate
    size, rate_size = xp.sqrt(sx**2 + sy**2), xp.sqrt(rx**2 + ry**2)
    on_demand = size > 0
    x, y_, m = xp.where(on_demand, sx, rx), xp.where(on_demand, sy, ry), xp.where(on_demand, size, rate_size)
    turns = (s == 0) & (m > 0)
    m = xp.where(turns, m, 1.0)
    return u_x, u_y, s, xp.where(turns, -x / m, c_x), xp.where(turns, -y_ / m, c_y), w, w_rate


def time_to_rest(mode, y, bias_x, bias_y, f, g):
    """With a = 0 (n = g, relative acceleration b g) on a rigid support: the flight ends
    within (w' + sqrt(w'² + 2 g w)) / g, the slide within twice s / ((f - |b|) g) after
    it [s]; -1 where f <= |b| (it never rests)."""
    b = math.hypot(bias_x, bias_y)
    if f <= b:
        return -1.0
    flight = (y[_WD] + math.sqrt(y[_WD] ** 2 + 2 * g * y[_W])) / g if mode == FLIGHT else 0.0
    speed_ = math.hypot(y[_CX], y[_CY]) if mode == FLIGHT else abs(y[_S])
    return flight + 2.0 * (speed_ + b * g * flight) / ((f - b) * g) + 1e-12
