"""The free-standing rectangular block on a shaking base: rest, slide, rock with impacts,
the Zeno rest, overturning (Housner 1963; the sliding modes are the 1-D sliding block's).

A uniform block of width 2b and height 2h [m] stands on a rigid base; R = sqrt(b² + h²)
[m], the slenderness alpha = atan(b/h) [rad] and the frequency parameter
p = sqrt(3 g / (4 R)) [rad/s]. The base accelerates by a_x(t) (horizontal) and a_z(t)
(vertical, upward) [m/s²]; g_e = g + a_z is the effective gravity. Rocking about the
corner on side s (+1: x = +b, theta > 0), with phi = s alpha - theta:

    theta'' = -p² [ (g_e/g) sin phi + (a_x/g) cos phi ]            [rad/s²],

exact (the linearised block: sin phi -> phi, cos phi -> 1). From rest it rocks about +b
when a_x < -g_e tan(alpha) (about -b when a_x > g_e tan(alpha)) and slides when |a_x| >
mu g_e: for mu < tan(alpha) the block only slides (the 1-D sliding block's rules with g_e
for g), otherwise it only rocks (the linearised block: alpha for tan(alpha)). When theta returns to 0 the other corner strikes the
base: theta' -> r theta' (Housner's r = 1 - 3/2 sin² alpha unless given) and the pivot
switches. The impacts accumulate before rest: when the next arc would be shorter than
``zeno_arc`` [s], the rest of the geometric series is summed (mode SETTLE, in which
theta' is the envelope of the impact velocities, linear in time to zero at the
accumulation point, where the block rests). |theta| = pi/2 is OVERTURNED.

State y = (u [m], u' [m/s]) for a block that slides, (theta [rad], theta' [rad/s]) for
one that rocks (which of the two is fixed by mu against b/h).
"""

import copy
import dataclasses
import math

import numpy as np

from ..core import LazyEngine
from ..core.contract import KNOTS_PER_RADIAN, SCALAR, DifferentiableModel, scale_factor_units
from ..sliding import relative_acceleration, rest_mode, slip_constant, stop_mode
from ..units import STANDARD_GRAVITY
from . import _rules as rules
from ._block import BlockBase
from ._modes import BEYOND, IN, OUT, OVERTURNED, SETTLE, RockingMode, event_kind, rock_mode, side
from ._solution import ContactLimit, RockingEvent, RockingSolution

_Q, _RATE = range(2)


def housner_restitution(alpha: float) -> float:
    """Housner's (1963) restitution of a rectangular block of slenderness ``alpha``
    [rad]: the ratio of angular velocities through an impact, 1 - 3/2 sin² alpha [-]."""
    return 1.0 - 1.5 * math.sin(alpha) ** 2


@dataclasses.dataclass(frozen=True, eq=False)
class RockingBlock(DifferentiableModel, BlockBase):
    """Housner's free-standing rectangular block, whose rocking pivot holds: it rests,
    slides, rocks or overturns (``FreeStandingBlock(..., contact="housner")``).

    Args:
        b: half-width [m], > 0.
        h: half-height [m], > 0.
        mu: static friction coefficient at the base [-], >= 0.
        mu_kinetic: kinetic friction coefficient while sliding [-], in [0, mu];
            defaults to ``mu``.
        restitution: r, theta' after / before an impact [-], in [0, 1]; None: Housner's
            value 1 - 3/2 sin² alpha.
        p: frequency parameter [rad/s]; None: a uniform block's sqrt(3 g / (4 R)).
        theta0: initial tilt [rad], |theta0| < pi/2, released at rest (0: at rest on
            the base).
        linearised: the linearised block (sin phi -> phi, cos phi -> 1: slender,
            small rotations).
        zeno_arc: the arc duration [s] below which the remaining impacts are summed.
        strict: stop with an error where the contact force leaves its limits (N <= 0: the
            pivot would lift, |F| > mu N: it would slip), located as a guard; otherwise
            Housner's model goes on through them and ``solution.contact_events`` lists
            each, located (:class:`ContactLimit`: where the complete block would lift or
            slip).
        g: gravitational acceleration [m/s²].

    The motion is an excitation (a_x alone) or a :class:`~blockdae.BaseMotion` with x
    and z components [m/s²].

    Backends: "cvode", "ida" and "jax" run every block; a block that rocks (mu >= b/h)
    also runs on "compiled" (the exact or the linearised equation, a compiled DOP853 with
    located events, any motion; its default) and, linearised, on "exact" (its closed form,
    compiled, for horizontal piecewise-linear records). A block that slides runs on
    "cvode" by default.

    ``b``, ``h``, ``mu``, ``mu_kinetic``, ``restitution``, ``p`` and ``theta0`` may be 1-D
    arrays of one size (the others numbers): a batch of parameter sets, which
    :func:`blockdae.simulate` runs set by set on the backend of one set
    (``item(i)``: set i as a block of its own). Its sets all rock or all slide (one
    batch's displacements share one unit): a batch that mixes them is refused.
    """

    b: float
    h: float
    mu: float
    mu_kinetic: float | None = None
    restitution: float | None = None
    p: float | None = None
    theta0: float = 0.0
    linearised: bool = False
    zeno_arc: float = 1e-5
    strict: bool = False
    g: float = STANDARD_GRAVITY

    #: the parameters a batch may give as 1-D arrays, one value per parameter set
    batch_fields = ("b", "h", "mu", "mu_kinetic", "restitution", "p", "theta0")
    optional_fields = ("mu_kinetic", "restitution", "p")
    #: Housner's contact: the pivot holds (:class:`FreeStandingBlock`'s ``contact`` option)
    contact = "housner"

    modes = RockingMode
    instant_modes = (RockingMode.RELEASE,)  # the release from theta0, left at once
    component_names = ("x", "z")
    #: the compiled engines: the integrated one of either equation (``backend="compiled"``),
    #: the linearised block's closed form (``backend="exact"``)
    _compiled = {"compiled": LazyEngine("blockdae.rocking._engine", "CompiledEngine")}
    _exact = {**_compiled, "exact": LazyEngine("blockdae.rocking._engine", "LinearisedEngine")}

    def __post_init__(self):
        if not self._check_fields():
            return
        if self.restitution is not None and not 0 <= self.restitution <= 1:
            raise ValueError(f"restitution={self.restitution!r} must be in [0, 1]")
        if self.p is not None and self.p <= 0:
            raise ValueError(f"p={self.p!r} must be > 0 [rad/s]")
        if self.theta0 != 0 and self.slides:
            raise ValueError(f"theta0={self.theta0!r}: a block with mu={self.mu} below its rocking threshold "
                             f"{self.rocking_threshold:.6g} slides and never rocks")

    # ---- what the block is ----------------------------------------------------------
    @property
    def frequency(self):
        """p [rad/s]: the one given, else sqrt(3 g / (4 R)) (a uniform block)."""
        return self.p if self.p is not None else math.sqrt(0.75 * self.g / self.R)

    @property
    def r(self):
        """Restitution [-]: the one given, else Housner's 1 - 3/2 sin² alpha."""
        return self.restitution if self.restitution is not None else housner_restitution(self.alpha)

    @property
    def rocking_threshold(self):
        """|a_x| / g_e [-] that lifts a corner from rest: b/h = tan(alpha), or alpha for the
        linearised block."""
        return self.alpha if self.linearised else self.b / self.h

    def _threshold(self, xp):
        """:attr:`rocking_threshold` from the (possibly traced) parameters."""
        return xp.arctan2(self.b, self.h) if self.linearised else self.b / self.h

    @property
    def slides(self) -> bool:
        """Whether the block slides (mu below the rocking threshold, b/h) rather than rocks:
        it never does both (nor do the sets of a batch)."""
        if self.batch_shape:
            return self._slides
        return self.mu < self.rocking_threshold

    @property
    def engines(self):
        """backend name -> engine, for a block that rocks: "compiled" (the integrated
        engine, either equation) and, for the linearised block, "exact" (its closed form);
        the generic driver otherwise."""
        if self.slides:
            return {}
        return self._exact if self.linearised else self._compiled

    @property
    def state_names(self):
        return ("u", "u_rate") if self.slides else ("theta", "theta_rate")

    @property
    def default_backend(self):
        """"compiled" for a block that rocks (the compiled engine), "cvode" for one that slides."""
        return "cvode" if self.slides else "compiled"

    def final_quantities(self, displacement, max_abs_displacement) -> dict:
        """overturned (|theta| at the end is pi/2, where an overturned block lies) and
        max_theta_over_alpha (max |theta| / alpha [-]) of n runs (a batch's: the set runs
        fastest, each over its own alpha); False and 0 for a block that slides."""
        largest = np.asarray(max_abs_displacement, dtype=float)
        if self.slides:
            return {"overturned": np.zeros(largest.shape, dtype=bool), "max_theta_over_alpha": np.zeros(largest.shape)}
        alpha = self.alpha if not self.batch_shape else \
            np.resize([self.item(j).alpha for j in range(self.batch_shape[0])], largest.shape)  # the set runs fastest
        return {"overturned": np.abs(np.asarray(displacement, dtype=float)[:, 0]) == 0.5 * math.pi,
                "max_theta_over_alpha": largest / alpha}

    @property
    def state_units(self):
        """[m, m/s] for a block that slides (u), [rad, rad/s] for one that rocks (theta)."""
        return ("m", "m/s") if self.slides else ("rad", "rad/s")

    @property
    def initial_mode(self):
        """REST, or RELEASE from a tilt theta0: an instant mode at the state at rest that
        ``state_at_guard`` takes to (theta0, 0) rather than an ``initial_state``, since the
        mode after the release depends on a(0) and theta0 is a parameter whose derivative
        flows through that map (the initial state is taken as independent of the parameters)."""
        return RockingMode.RELEASE if self.theta0 != 0 else RockingMode.REST

    # ---- a batch of parameter sets ----------------------------------------------------
    def _check_batch(self) -> None:
        """A batch (:meth:`BlockBase._check_batch`) whose sets all rock or all slide: one
        that mixes them is refused (ValueError naming mu and the sets of each)."""
        super()._check_batch()
        slides = [self.item(j).slides for j in range(self.batch_shape[0])]
        if any(slides) and not all(slides):
            sliding, rocking = ([j for j, s in enumerate(slides) if s == value] for value in (True, False))
            threshold = "alpha = atan(b/h)" if self.linearised else "b/h"
            raise ValueError(f"mu: parameter sets {sliding} have mu below their rocking threshold {threshold} (they "
                             f"slide: u [m]) and sets {rocking} at or above it (they rock: theta [rad]); a batch's "
                             "displacements share one unit: run the sliding and the rocking sets as two batches")
        object.__setattr__(self, "_slides", slides[0])

    # ---- the physics (xp: numpy, jax.numpy or SCALAR) ---------------------------------
    def _geometry(self, xp):
        """(alpha [rad], R [m], p² [1/s²], r [-]) from the (possibly traced) parameters."""
        alpha = xp.arctan2(self.b, self.h)
        radius = xp.hypot(self.b, self.h)
        p2 = self.p * self.p if self.p is not None else 0.75 * self.g / radius
        r = self.restitution if self.restitution is not None else 1.0 - 1.5 * xp.sin(alpha) ** 2
        return alpha, radius, p2, r

    def angular_acceleration(self, s, theta, t, excitation, xp=np):
        """theta'' [rad/s²] rocking about the corner on side ``s`` at ``theta`` [rad]."""
        alpha, _, p2, _ = self._geometry(xp)
        ax, ge, _, _ = self._base(t, excitation)
        return rules.angular_acceleration(s, theta, ax, ge, alpha, p2, self.g, self.linearised, xp)

    def angular_jerk(self, s, theta, rate, t, excitation):
        """theta''' [rad/s³] rocking about side ``s`` at (theta, theta') (for the guards' curvature)."""
        alpha, _, p2, _ = self._geometry(SCALAR)
        ax, ge, ax_rate, az_rate = self._base(t, excitation)
        return rules.angular_jerk(s, theta, rate, ax, ge, ax_rate, az_rate, alpha, p2, self.g, self.linearised)

    def contact_force(self, s, theta, rate, t, excitation, xp=np):
        """(F, N) [m/s²]: horizontal and vertical force per unit mass at the pivot on side
        ``s``, from the centre of mass's absolute acceleration at (theta, theta')."""
        alpha, radius, _, _ = self._geometry(xp)
        ax, ge, _, _ = self._base(t, excitation)
        phi = s * alpha - theta
        accel = self.angular_acceleration(s, theta, t, excitation, xp)
        return (ax + radius * xp.cos(phi) * accel + radius * xp.sin(phi) * rate ** 2,
                ge + radius * xp.sin(phi) * accel - radius * xp.cos(phi) * rate ** 2)

    def contact_margins(self, s, theta, rate, t, excitation, xp=np):
        """(N, mu N - |F|) [m/s²] about side ``s``: where either falls through zero the
        pivot would lift or slip (see :meth:`contact_force`)."""
        force, normal = self.contact_force(s, theta, rate, t, excitation, xp)
        return normal, self.mu * normal - xp.abs(force)

    def deceleration(self, s, t, excitation, xp=SCALAR):
        """-s theta'' at theta = 0 on side ``s`` [rad/s²]: how fast an arc from the base
        about that corner turns back (<= 0: the demand holds it out)."""
        return -s * self.angular_acceleration(s, 0.0, t, excitation, xp)

    def _limit(self, ge, xp):
        """g_e times the smaller of mu and the rocking threshold [m/s²]: where rest ends."""
        return xp.minimum(self.mu, self._threshold(xp)) * ge

    def _settle_rate(self, s, t, excitation, xp=SCALAR):
        """d theta'/dt [rad/s²] of the Zeno envelope on side ``s`` (:func:`._rules.settle_rate`)."""
        _, _, _, r = self._geometry(xp)
        ahead, behind = self.deceleration(s, t, excitation, xp), self.deceleration(-s, t, excitation, xp)
        return rules.settle_rate(s, ahead, behind, r)

    # ---- the automaton ----------------------------------------------------------------
    def flow(self, mode, t, y, excitation, xp=np):
        """(q', q'') in ``mode``: (u', u'') sliding, (theta', theta'') rocking, zero at rest."""
        kind, s = abs(int(mode)), side(mode)
        zero = 0.0 * y[_Q]
        if kind == 1:
            ax, ge, _, _ = self._base(t, excitation)
            return xp.stack([y[_RATE], relative_acceleration(mode, ax, 0.0, self.friction_kinetic, ge, xp)])
        if kind in (OUT, IN, BEYOND):
            return xp.stack([y[_RATE], self.angular_acceleration(s, y[_Q], t, excitation, xp)])
        if kind == SETTLE:
            return xp.stack([zero, zero + self._settle_rate(s, t, excitation, xp)])
        return xp.stack([zero, zero])

    def guards(self, mode, t, y, excitation, xp=np):
        """Guards of ``mode``, each left as it falls through zero; the last one at rest,
        sliding and rocking, g_e [m/s²], is a flight of the whole block (an error). REST:
        (limit - a_x, limit + a_x) with limit = min(mu, b/h) g_e; SLIDE: (s u'); OUT: (s theta' ->
        apex, alpha - s theta); IN: (s theta -> impact, -s theta' -> outward again);
        BEYOND: (s theta', pi/2 - s theta -> overturned); SETTLE: (s theta' -> rest, the
        two onsets)."""
        kind, s = abs(int(mode)), side(mode)
        ax, ge, _, _ = self._base(t, excitation)
        one = 0.0 * y[_Q] + 1.0
        if mode == RockingMode.REST:
            limit = self._limit(ge, xp)
            return xp.stack([limit - ax, limit + ax, ge])
        if kind == 1:
            return xp.stack([mode * y[_RATE], ge])
        if kind in (OUT, IN, BEYOND):
            own = list(rules.rocking_guards(kind, s, y[_Q], y[_RATE], xp.arctan2(self.b, self.h)))
            contact = list(self.contact_margins(s, y[_Q], y[_RATE], t, excitation, xp)) if self.strict else []
            return xp.stack([*own, *contact, ge])
        if kind == SETTLE:
            limit = self._threshold(xp) * ge
            return xp.stack([s * y[_RATE], limit - ax, limit + ax, ge])
        if mode == RockingMode.RELEASE:
            return xp.stack([-one - t])  # left at once; its rate -1 (a fixed time: dt/dp = 0)
        return xp.stack([one])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        """REST, or the slide or rock the demand starts (its rate decides at a threshold)."""
        ax, ge, ax_rate, _ = self._base(t, excitation)
        direction = int(rest_mode(ax, ax_rate, min(self.mu, self.rocking_threshold), ge, True, True, SCALAR))
        return self._start(direction)

    def _start(self, direction):
        """The mode a block at rest takes toward ``direction`` (+1, -1; 0: rest)."""
        if direction == 0:
            return RockingMode.REST
        return RockingMode(direction) if self.slides else rock_mode(OUT, direction)

    def _is_flight_guard(self, mode, guard_index, t, y, excitation):
        """Whether guard ``guard_index`` of ``mode`` is g_e (the last one, at rest, sliding
        and rocking)."""
        kind = abs(int(mode))
        return (kind != OVERTURNED and mode != RockingMode.RELEASE
                and guard_index == len(self.guards(mode, t, y, excitation, SCALAR)) - 1)

    def _is_contact_guard(self, mode, guard_index):
        """Whether guard ``guard_index`` of ``mode`` is a contact limit (rocking, strict)."""
        return self.strict and abs(int(mode)) in (OUT, IN, BEYOND) and guard_index in (2, 3)

    def _contact_error(self, s, t, y, excitation, lifts):
        force, normal = self.contact_force(s, y[_Q], y[_RATE], t, excitation, SCALAR)
        limit = ContactLimit(t, "lift_limit" if lifts else "slip_limit", y[_Q], y[_RATE], force, normal)
        return ValueError(f"at t = {t:.9f} s {limit.describe(self.mu)}; strict=True stops here")

    def _flight(self, t, excitation):
        ax, ge, _, _ = self._base(t, excitation)
        return ValueError(f"at t = {t:.12g} s the base falls faster than g (g + a_z = {ge:.6g} m/s²): a flight "
                          "of the whole block is outside this model")

    def _after_apex(self, s, theta, t, excitation):
        """The rocking mode at rest in rotation (theta' = 0) at ``theta`` on side ``s``."""
        return RockingMode(rules.mode_after_apex(s, theta, self.angular_acceleration(s, theta, t, excitation, SCALAR),
                                                 self.alpha))

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        """The mode after guard ``guard_index`` of ``mode``: see :meth:`guards`; an impact
        enters the other side's OUT, or SETTLE where the next arc is shorter than
        ``zeno_arc`` [s] and both corners restore."""
        kind, s = abs(int(mode)), side(mode)
        if self._is_flight_guard(mode, guard_index, t, y, excitation):
            raise self._flight(t, excitation)
        if mode == RockingMode.REST:
            return self._start(-1 if guard_index == 0 else 1)
        if self._is_contact_guard(mode, guard_index):
            raise self._contact_error(s, t, y, excitation, guard_index == 2)
        if kind == 1:
            ax, ge, ax_rate, _ = self._base(t, excitation)
            slip_rate = self.flow(mode, t, y, excitation, SCALAR)[_RATE]
            return RockingMode(int(stop_mode(int(mode), slip_rate, ax_rate, t, self.mu, self.friction_kinetic, ge,
                                             True, True, SCALAR, time_tol)))
        if mode == RockingMode.RELEASE:
            return self._after_apex(1 if self.theta0 > 0 else -1, self.theta0, t, excitation)
        if kind in (OUT, IN, BEYOND, SETTLE):
            impact = kind == IN and guard_index == 0
            ahead, behind = (self.deceleration(-s, t, excitation), self.deceleration(s, t, excitation)) if impact \
                else (0.0, 0.0)
            after = rules.mode_after_rocking_guard(kind, s, guard_index, y[_Q], self.r * y[_RATE], ahead, behind,
                                                   self.alpha, self.zeno_arc)
            return self.mode_at_rest(t, excitation) if after == rules.DEMAND_DECIDES else RockingMode(after)
        return mode

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """The state exactly on the guard: theta' = 0 at an apex or a stop, theta = 0 at
        an impact, alpha or pi/2 at those guards; (theta0, 0) on release."""
        kind, s = abs(int(mode)), side(mode)
        q, rate = y[_Q], y[_RATE]
        if mode == RockingMode.REST or mode == RockingMode.RELEASE and guard_index != 0:
            return y
        if mode == RockingMode.RELEASE:
            return xp.stack([0.0 * q + self.theta0, 0.0 * rate])
        if kind == 1:
            return xp.stack([q, 0.0 * rate]) if guard_index == 0 else y
        if kind in (OUT, BEYOND):
            if guard_index == 0:
                return xp.stack([q, 0.0 * rate])
            if guard_index == 1:
                edge = math.pi / 2 if kind == BEYOND else xp.arctan2(self.b, self.h)
                return xp.stack([0.0 * q + s * edge, rate])
            return y
        if kind == IN:
            if guard_index == 0:
                return xp.stack([0.0 * q, rate])
            return xp.stack([q, 0.0 * rate]) if guard_index == 1 else y
        if kind == SETTLE and guard_index < 3:
            return xp.stack([0.0 * q, 0.0 * rate])
        return y

    def state_on_entry(self, before, after, t, y, excitation, xp=np):
        """An impact multiplies theta' by r; an overturned block lies still at theta = s pi/2."""
        if abs(int(before)) == IN and side(after) == -side(before):
            return xp.stack([y[_Q], self._geometry(xp)[3] * y[_RATE]])
        if abs(int(after)) == OVERTURNED:
            return xp.stack([0.0 * y[_Q] + side(after) * 0.5 * math.pi, 0.0 * y[_RATE]])
        return y

    # ---- what the hybrid driver asks ------------------------------------------------
    def is_static(self, mode):
        return mode == RockingMode.REST or abs(int(mode)) == OVERTURNED

    def at_rest(self, mode, y):
        return mode == RockingMode.REST or (abs(int(mode)) == 1 and y[_RATE] == 0)

    def rest_state(self, y):
        return np.array([y[_Q], 0.0])

    def output_step(self):
        """Largest gap between dense-output knots [s]: 1 / (32 p) rocking (inf sliding:
        the excitation sets it, as for the sliding block)."""
        return math.inf if self.slides else 1.0 / (KNOTS_PER_RADIAN * self.frequency)

    def turn_rate(self, mode, t, y, excitation, xp=np):
        """In a slide, u'' (as the sliding block); rocking, theta'' at the state ``y``
        (monotone in t on a piece: a_x and a_z are), so that the integrator stops where
        theta' may turn and no step hides an apex and its return."""
        kind = abs(int(mode))
        if kind == 1 or kind in (OUT, IN, BEYOND):
            return self.flow(mode, t, y, excitation, xp)[_RATE]
        return None

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(rate, curvature) of guard ``guard_index`` of ``mode`` in time [its unit /s, /s²]."""
        kind, s = abs(int(mode)), side(mode)
        ax, ge, ax_rate, az_rate = self._base(t, excitation)
        if mode == RockingMode.RELEASE:
            return -1.0, 0.0
        if kind == OVERTURNED:
            return 0.0, 0.0
        if self._is_flight_guard(mode, guard_index, t, y, excitation):
            return az_rate, 0.0
        if self._is_contact_guard(mode, guard_index):
            return self._contact_rate(s, guard_index - 2, t, y, excitation), 0.0
        if mode == RockingMode.REST or (kind == SETTLE and guard_index > 0):
            coefficient = self.rocking_threshold if kind == SETTLE else min(self.mu, self.rocking_threshold)
            sign = -1.0 if guard_index in (0, 1) and (mode == RockingMode.REST) == (guard_index == 0) else 1.0
            return coefficient * az_rate + sign * ax_rate, 0.0
        if kind == 1:
            return mode * self.flow(mode, t, y, excitation, SCALAR)[_RATE], -mode * ax_rate
        if kind == SETTLE:
            return s * self._settle_rate(s, t, excitation), 0.0
        accel = self.angular_acceleration(s, y[_Q], t, excitation, SCALAR)
        jerk = self.angular_jerk(s, y[_Q], y[_RATE], t, excitation)
        return rules.rocking_guard_rates(kind, s, guard_index, y[_RATE], accel, jerk)

    def _contact_rate(self, s, index, t, y, excitation):
        """d/dt of contact margin ``index`` [m/s³] along the flow, by central differences
        over 1e-7 s."""
        step = 1e-7
        rate = np.array(self.flow(rock_mode(OUT, s), t, y, excitation, SCALAR))
        ahead, behind = np.asarray(y) + step * rate, np.asarray(y) - step * rate
        value = lambda when, state: self.contact_margins(s, state[_Q], state[_RATE], when, excitation, SCALAR)[index]
        return (value(t + step, ahead) - value(t - step, behind)) / (2 * step)

    def contradiction(self, mode, y, velocity_error):
        """A slide or a rotation whose rate points against its mode: beyond the velocity
        error, and for a rotation beyond 1e-10 p alpha [rad/s] (an apex that grazes zero
        where a(t) turns at a sample dips below it by the integrator's error)."""
        kind, s = abs(int(mode)), side(mode)
        if kind == 1 and mode * y[_RATE] < -velocity_error:
            return f"u' = {y[_RATE]:+.6g} m/s points against the slide"
        return self.rotation_contradiction(kind, s, y[_RATE], velocity_error)

    def speed(self, y):
        return abs(float(y[_RATE]))

    def time_to_rest(self, mode, y):
        """A bound [s] on the time to rest after the excitation: a slide's stop, or
        (rocking) the free decay of the impacts, which needs r < 1."""
        if self.slides:
            rate = slip_constant(int(mode), 0.0, self.friction_kinetic, self.g)
            if rate == 0 and y[_RATE] != 0:
                raise ValueError("a block without kinetic friction slides on forever: give t_end [s]")
            return 2.0 * abs(y[_RATE] / rate) if rate != 0 else 0.0
        if self.r >= 1:
            raise ValueError("a block with restitution 1 rocks on forever: give t_end [s]")
        return 200.0 * math.pi / (self.frequency * (1.0 - self.r)) + 10.0 / self.frequency

    def event(self, t, mode_before, mode_after, y):
        kind = event_kind(mode_before, mode_after)
        rate_after = self.r * float(y[_RATE]) if kind in ("impact", "zeno") else float(y[_RATE])
        return RockingEvent(float(t), mode_before, mode_after, kind, float(y[_Q]), float(y[_RATE]), rate_after)

    def solution(self, *, t, y, mode, events, backend, dense, stats):
        return RockingSolution(t=t, state=y, mode=mode, events=events, backend=backend, dense=dense, stats=stats)

    def check_solution(self, solution):
        """Locate where the contact force left its limits while the block rocked
        (``solution.contact_events``, kept on the solution; for a batch, on each set's
        run); with ``strict``, a ValueError naming the first (:meth:`RockingSolution.check_contact`)."""
        runs = [solution.solve_one(j) for j in range(self.batch_shape[0])] if self.batch_shape else [solution]
        for run in runs:  # a BatchSolution keeps each set's run (its solve_one)
            run.check_contact()

    # ---- parameters, for the JAX twin and derivatives --------------------------------
    def parameters(self):
        """b [m], h [m], mu [-]; mu_kinetic [-], restitution [-] and p [rad/s] where given;
        theta0 [rad], g [m/s²] (and the flags "linearised" and "strict" [-] where set)."""
        values = {"b": self.b, "h": self.h, "mu": self.mu}
        if self.mu_kinetic is not None:
            values["mu_kinetic"] = self.mu_kinetic
        if self.restitution is not None:
            values["restitution"] = self.restitution
        if self.p is not None:
            values["p"] = self.p
        for flag in ("linearised", "strict"):
            if getattr(self, flag):
                values[flag] = 1.0  # a name of its own: the JAX twin compiles its rules apart
        return {**values, "theta0": self.theta0, "g": self.g}

    def with_parameters(self, values):
        model = copy.copy(self)
        for name, value in {**self.parameters(), **values}.items():
            if name not in ("linearised", "strict"):
                object.__setattr__(model, name, value)
        return model

    def parameter_units(self) -> dict:
        return {"b": "m", "h": "m", "mu": "-", "mu_kinetic": "-", "restitution": "-", "p": "rad/s",
                "theta0": "rad", "g": "m/s²", **scale_factor_units(self)}

    def default_wrt(self) -> tuple[str, ...]:
        return ("b", "h")

    def scalar_quantities(self) -> dict:
        """"max_theta_over_alpha": max |theta| / alpha [-] (``bd.sensitivities(..., of=...)``)."""
        return {"max_theta_over_alpha": "-"}

    def scalar_quantity_jacobian(self, name, solution, final, events):
        """d(max |theta| / alpha)/dp (:func:`._derivatives.max_theta_jacobian`)."""
        from ._derivatives import max_theta_jacobian

        return max_theta_jacobian(self, solution, final, events)

