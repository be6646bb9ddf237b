"""The complete free-standing block: rest, slide, rock, slide-rock (the pivot slips),
flight and overturning, with frictional plastic impacts and landings.

A uniform rectangular block 2b wide and 2h high [m] on a rigid base that accelerates by
a_x(t) and a_z(t) [m/s²]; g_e = g + a_z. Newton-Euler for a rigid body with two unilateral
Coulomb contacts (its base corners), per unit mass, in the base's frame. The state is the
centroid's position relative to the base, x and z [m] (z = h standing flat, x = 0 at
rest at the start), the rotation theta [rad] (theta > 0: leaning toward +x on the corner
at +b), their rates, and two work integrals [J/kg]: of the base's inertial force,
∫ (-a_x x' - a_z z') dt, and of friction, ∫ F u' dt (the energy balance's terms).

Modes (:class:`FreeMode`): REST; SLIDE sigma (flat, x'' = -a_x - sigma mu_k g_e); ROCK s
(the pivot s sticks; out, in and beyond alpha as Housner's block, whose rules they share);
SLIDE_ROCK (s, sigma) (the pivot slips toward sigma, F = -sigma mu_k N); FLIGHT c (no
contact: x'' = -a_x, z'' = -g_e, theta'' = 0; while it flies the state's position and
rates are those of its corner c, the one that lifted, converted back to the centroid's in
events and the solution); OVERTURNED (|theta| = pi/2). Impacts and
landings are instant modes whose entry is the velocity jump (perfectly plastic, sticking
if static friction can hold the corner, else slipping through with mu_k), after which the
state decides the mode. The laws are :mod:`._slide_rock_laws`'.
"""

import copy
import dataclasses
import math
import warnings

import numpy as np

from ..core import HermiteDense, LazyEngine
from ..core.contract import KNOTS_PER_RADIAN, SCALAR
from ..sliding import stop_mode
from ..units import STANDARD_GRAVITY
from . import _free_rules as free_rules
from . import _rules as rules
from . import _slide_rock_laws as laws
from ._block import HOUSNER_OPTIONS, RATE_FLOOR, BlockBase, model_of
from ._derivatives import FreeStandingDerivatives
from ._free_modes import (BEYOND, IN, INSTANT, OUT, OVERTURNED, SETTLE, SLIDE_ROCK_KINDS, FreeMode, kind_of,
                          rock_mode, side, slide_rock_mode, slip_direction)
from ._free_solution import FreeEvent, FreeStandingSolution

X, Z, THETA, X_RATE, Z_RATE, THETA_RATE, BASE_WORK, FRICTION_WORK = range(8)
_ROCK = (OUT, IN, BEYOND)
#: a force guard below -JUMP_FLOOR g [-] is past zero (a jump of a(t)), not at a located root
JUMP_FLOOR = 1e-9
#: a corner of a flying block that reaches the base at a speed below GRAZE_SPEED times the
#: block's speed scale [-] while accelerating away grazes it (rounding of its height)
GRAZE_SPEED = 1e-12
#: Painlevé's paradox is possible from this kinetic friction on [-]
PAINLEVE_FRICTION = 4.0 / 3.0


class PainleveWarning(UserWarning):
    """Kinetic friction of 4/3 or more: slide-rocking may meet Painlevé's paradox (no
    consistent contact force), which stops a run with an error naming the time."""


@dataclasses.dataclass(frozen=True, eq=False)
class FreeStandingBlock(FreeStandingDerivatives, BlockBase):
    """A free-standing rectangular block that rests, slides, rocks, slide-rocks, flies
    and overturns, with frictional plastic impacts and landings.

    Args:
        b: half-width [m], > 0.
        h: half-height [m], > 0.
        mu: static friction coefficient at the base [-], >= 0.
        mu_kinetic: kinetic friction coefficient [-], in [0, mu]; defaults to ``mu``.
        theta0: initial tilt [rad], |theta0| < pi/2, released at rest on its corner.
        zeno_arc: the arc [s] below which the rest of a Zeno sequence of sticking impacts
            is summed (and a slide-rock's chatter ends in a slide). An arc a rises only
            p² sin(alpha) a²/8, so the impacts of shorter arcs are located no better than
            the integrator's atol on theta allows (b/h = 1/2 on CVODE: the rest is 8e-9 s
            from the impacts' accumulation time at 1e-5 s, 9e-10 s at 1e-4 s, 7e-8 s at
            1e-6 s; below about 3e-8 s the impacts are lost in atol = 1e-14 rad).
        g: gravitational acceleration [m/s²].
        contact: "complete" (this block: its corners may slip and lift) or "housner":
            Housner's block, whose rocking pivot holds (the literature's overturning
            spectra): ``FreeStandingBlock(..., contact="housner")`` is a
            :class:`RockingBlock` of the same arguments, which also takes
            ``restitution``, ``p``, ``linearised`` and ``strict``.

    The motion is an excitation (a_x alone) or a :class:`~blockdae.BaseMotion` with x and
    z components [m/s²]. Backends: "compiled" (default: a compiled DOP853 with located
    events), "cvode", "ida" and "jax" (the diffrax twin).

    ``b``, ``h``, ``mu``, ``mu_kinetic`` and ``theta0`` may be 1-D arrays of one size (the
    others numbers): a batch of parameter sets, which :func:`blockdae.simulate` runs set
    by set on the backend of one set (``item(i)``: set i as a block of its own), each row
    of its ensemble that set's own run.
    """

    b: float
    h: float
    mu: float
    mu_kinetic: float | None = None
    theta0: float = 0.0
    zeno_arc: float = 1e-5
    g: float = STANDARD_GRAVITY
    contact: str = "complete"

    state_names = ("x", "z", "theta", "x_rate", "z_rate", "theta_rate", "base_work", "friction_work")
    state_units = ("m", "m", "rad", "m/s", "m/s", "rad/s", "J/kg", "J/kg")
    modes = FreeMode
    instant_modes = INSTANT
    component_names = ("x", "z")
    displacement_states = (X,)
    default_backend = "compiled"
    engines = {"compiled": LazyEngine("blockdae.rocking._free_engine", "FreeCompiledEngine")}

    def __new__(cls, *args, contact: str = "complete", **kwargs):
        """The complete block, or with ``contact="housner"`` Housner's (a
        :class:`RockingBlock` of the same arguments)."""
        if contact != "complete":
            names = [field.name for field in dataclasses.fields(cls)]
            return model_of(contact)(**dict(zip(names, args)), **kwargs)
        housner_only = sorted(set(kwargs) & HOUSNER_OPTIONS)
        if housner_only:
            raise ValueError(f"{', '.join(housner_only)}: an option of Housner's block only "
                             "(FreeStandingBlock(..., contact='housner'))")
        return super().__new__(cls)

    def __post_init__(self):
        if not self._check_fields():
            return
        if self.friction_kinetic >= PAINLEVE_FRICTION:
            warnings.warn(f"mu_kinetic={self.friction_kinetic} >= 4/3: slide-rocking may meet Painlevé's paradox "
                          "(no consistent contact force, D <= 0), where a run stops with an error naming the time",
                          PainleveWarning, stacklevel=3)

    # ---- what the block is ----------------------------------------------------------
    @property
    def frequency(self):
        """p = sqrt(3 g / (4 R)) [rad/s]."""
        return math.sqrt(0.75 * self.g / self.R)

    @property
    def r(self):
        """Housner's restitution 1 - 3/2 sin² alpha [-]: a sticking impact's theta'+/theta'-."""
        return 1.0 - 1.5 * math.sin(self.alpha) ** 2

    @property
    def initial_mode(self):
        """REST, or RELEASE from the tilt theta0 (an instant mode whose guard takes the
        state to the tilt: the mode after it depends on a(0))."""
        return FreeMode.RELEASE if self.theta0 != 0 else FreeMode.REST

    def initial_state(self):
        """At rest flat on the base: x = 0, z = h, no rotation, no work done."""
        y = np.zeros(len(self.state_names))
        y[Z] = self.h
        return y

    # ---- the laws in this state layout ------------------------------------------------
    def _geometry(self, xp):
        """(alpha [rad], R [m]) from the (possibly traced: the JAX twin's) parameters."""
        return xp.arctan2(self.b, self.h), xp.hypot(self.b, self.h)

    def rock_forces(self, s, y, ax, ge, xp=SCALAR):
        """(theta'' [rad/s²], F, N [m/s²]) rocking on the sticking pivot ``s`` in state ``y``."""
        alpha, radius = self._geometry(xp)
        accel = laws.rock_acceleration(s, y[THETA], ax, ge, radius, alpha, xp)
        force, normal = laws.rock_contact_force(s, y[THETA], y[THETA_RATE], accel, ax, ge, radius, alpha, xp)
        return accel, force, normal

    def slide_rock(self, s, sigma, y, ax, ge, xp=SCALAR):
        """(D [-], N [m/s²], theta'' [rad/s²], u'' [m/s²]) on pivot ``s`` slipping toward ``sigma``."""
        alpha, radius = self._geometry(xp)
        return laws.slide_rock_acceleration(s, sigma, y[THETA], y[THETA_RATE], ax, ge, radius, alpha,
                                            self.friction_kinetic, xp)

    def pivot_slip_rate(self, s, y, xp=SCALAR):
        """u' [m/s]: the velocity of corner ``s`` along the base (x' - R cos phi theta')."""
        alpha, radius = self._geometry(xp)
        return y[X_RATE] - radius * xp.cos(s * alpha - y[THETA]) * y[THETA_RATE]

    def to_corner(self, c, y, xp=SCALAR):
        """``y`` (the centroid's position and rates) as a flight's state: corner ``c``'s
        position (x_c, z_c) and velocity, the rest as it is. A corner that just lifted has
        z_c = 0 exactly and rises as t³: as a state its height keeps every digit, as the
        difference of the centroid's height and h cos theta it would be rounding."""
        r_cx, r_cz = laws.corner_offset(c, y[THETA], self.b, self.h, xp)
        rate = y[THETA_RATE]
        return xp.stack([y[X] + r_cx, y[Z] + r_cz, y[THETA], y[X_RATE] + r_cz * rate, y[Z_RATE] - r_cx * rate,
                         rate, y[BASE_WORK], y[FRICTION_WORK]])

    def to_centroid(self, c, y, xp=SCALAR):
        """A flight's state with reference corner ``c`` as the centroid's (:meth:`to_corner`'s inverse)."""
        r_cx, r_cz = laws.corner_offset(c, y[THETA], self.b, self.h, xp)
        rate = y[THETA_RATE]
        return xp.stack([y[X] - r_cx, y[Z] - r_cz, y[THETA], y[X_RATE] - r_cz * rate, y[Z_RATE] + r_cx * rate,
                         rate, y[BASE_WORK], y[FRICTION_WORK]])

    def centroid_state(self, mode, y):
        """``y`` in ``mode`` as the centroid's state (a flight's and a slide-rock's converted:
        :meth:`to_centroid`, :meth:`from_pivot`)."""
        y = np.asarray(y, dtype=float)
        if kind_of(mode) in SLIDE_ROCK_KINDS:
            return np.array(self.from_pivot(side(mode), y))
        return np.array(self.to_centroid(side(mode), y)) if kind_of(mode) == 9 else y

    def centroid_rate(self, mode, y, rate):
        """d/dt of :meth:`centroid_state` from a state ``y`` in ``mode`` and its rate."""
        if kind_of(mode) in SLIDE_ROCK_KINDS:
            phi = side(mode) * self.alpha - y[THETA]
            out = np.array(rate, dtype=float)
            out[X] = rate[X] + self.R * math.cos(phi) * rate[THETA]
            out[X_RATE] = (rate[X_RATE] + self.R * math.sin(phi) * y[THETA_RATE] * rate[THETA]
                           + self.R * math.cos(phi) * rate[THETA_RATE])
            return out
        if kind_of(mode) != 9:
            return rate
        r_cx, r_cz = laws.corner_offset(side(mode), y[THETA], self.b, self.h, math)
        w, dw = y[THETA_RATE], rate[THETA_RATE]
        out = np.array(rate, dtype=float)
        out[X], out[Z] = rate[X] - r_cz * rate[THETA], rate[Z] + r_cx * rate[THETA]
        out[X_RATE] = rate[X_RATE] + r_cx * w * rate[THETA] - r_cz * dw
        out[Z_RATE] = rate[Z_RATE] + r_cz * w * rate[THETA] + r_cx * dw
        return out

    def _flight(self, c=1):
        """FLIGHT with reference corner ``c`` (the one that lifted; +b for a flat block)."""
        return FreeMode(9 * c)

    # ---- the automaton ----------------------------------------------------------------
    def flow(self, mode, t, y, excitation, xp=np):
        """dy/dt in ``mode`` (zero at rest, overturned and in the instant modes):
        :func:`._free_rules.flow_values`."""
        ax, ge, _, _ = self._base(t, excitation)
        alpha, radius = self._geometry(xp)
        return xp.stack(free_rules.flow_values(int(mode), y, ax, ge, self.g, self.b, self.h, radius, alpha,
                                               self.friction_kinetic, xp))

    def guards(self, mode, t, y, excitation, xp=np):
        """Guards of ``mode``, each left as it falls through zero (:func:`._free_rules.guard_values`).

        REST: (limit - a_x, limit + a_x, g_e), limit = min(mu, b/h) g_e; SLIDE sigma:
        (sigma x', g_e); ROCK s: its two own (out: s theta' -> apex, alpha - s theta; in:
        s theta -> impact, -s theta' -> out again; beyond: s theta', pi/2 - s theta), N
        (-> flight), mu N - |F| (-> slip); SLIDE_ROCK (s, sigma): (s theta -> impact,
        pi/2 - s theta, N, sigma u' -> the slip stops, D -> Painlevé's paradox); FLIGHT:
        (``z_+``, ``z_-``, pi/2 - |theta|) (the corners' heights); SETTLE s: (s theta' -> rest, the two onsets, g_e)."""
        ax, ge, _, _ = self._base(t, excitation)
        alpha, radius = self._geometry(xp)
        values = free_rules.guard_values(int(mode), t, y, ax, ge, self.b, self.h, radius, alpha, self.mu,
                                         self.friction_kinetic, xp)
        return xp.stack(values[:free_rules.GUARD_COUNTS[kind_of(mode)]])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        """The mode a block at rest takes at ``t``: section 6's map (Shenton 1996 with g_e),
        a threshold touched decided by the demand's rate."""
        ax, ge, ax_rate, az_rate = self._base(t, excitation)
        kind, d = laws.rest_mode(ax, ge, self.slenderness_ratio, self.mu, self.friction_kinetic, ax_rate, az_rate)
        return self._mode_of(kind, d)

    def _mode_of(self, kind, d):
        """The mode of a law's (kind, direction) from rest: d the side driven to (a slide's
        sigma, a pivot, a slide-rock's pivot and slip)."""
        if kind == laws.REST:
            return FreeMode.REST
        if kind == laws.SLIDE:
            return FreeMode(d)
        if kind == laws.ROCK:
            return rock_mode(OUT, d)
        if kind == laws.SLIDE_ROCK:
            return slide_rock_mode(d, d)
        return self._flight()

    def _on_corner(self, s, y, ax, ge):
        """The mode of a block on corner ``s`` whose pivot has stopped (a slip that stops, the
        release): ROCK s, SLIDE_ROCK (s, -sgn F) or FLIGHT (:func:`._slide_rock_laws.pivot_mode`)."""
        kind, sigma = laws.pivot_mode(s, y[THETA], y[THETA_RATE], ax, ge, self.R, self.alpha, self.mu,
                                      self.friction_kinetic)
        return self._contact_mode(kind, s, sigma, y, ax, ge)

    def _contact_mode(self, kind, s, sigma, y, ax, ge):
        """The mode of a law's (kind, pivot ``s``, slip ``sigma``) in state ``y``: a rocking mode
        out, in or beyond alpha by theta' (at theta' = 0 by theta'')."""
        if kind == laws.SLIDE_ROCK:
            return slide_rock_mode(s, sigma)
        if kind != laws.ROCK:
            return self._flight(s)
        if s * y[THETA_RATE] > 0:
            return rock_mode(OUT if s * y[THETA] < self.alpha else BEYOND, s)
        if s * y[THETA_RATE] < 0:
            return rock_mode(IN, s)
        accel = laws.rock_acceleration(s, y[THETA], ax, ge, self.R, self.alpha, math)
        return FreeMode(rules.mode_after_apex(s, y[THETA], accel, self.alpha))

    def _grazes(self, c, y, ge):
        """Whether corner ``c`` of a block in flight that reached height 0 in state ``y`` only
        grazes the base: it does not approach it (v_cz >= 0 within rounding of the speed) and
        accelerates away (z_c'' = -g_e - r_cz theta'² > 0). Just after a lift-off, where N
        fell to 0, the corner rises as the cube of the time and its height is rounding."""
        *_, v_cz = laws.corner_state(c, y[Z], y[THETA], y[X_RATE], y[Z_RATE], y[THETA_RATE], self.b, self.h, math)
        r_cz = laws.corner_offset(c, y[THETA], self.b, self.h, math)[1]
        return v_cz >= -GRAZE_SPEED * max(self.speed(y), self.R * self.frequency) and \
            -ge - r_cz * y[THETA_RATE] ** 2 > 0

    def _impact_mode(self, y):
        """The instant mode of the impact or landing from the located state ``y`` (theta = 0
        from a rocking mode, a corner at 0 height from flight)."""
        c, *_, sticks, _, _ = laws.landing(y[THETA], y[X_RATE], y[Z_RATE], y[THETA_RATE], self.b, self.h, self.mu,
                                           self.friction_kinetic)
        if c == 0:
            return FreeMode.LANDING_FLAT
        return FreeMode((10 if sticks else 11) * c)

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        """The mode after guard ``guard_index`` of ``mode`` (see :meth:`guards`): impacts and
        landings enter their instant mode, after which the jumped state decides. A
        slide-rock entered, or left by its guard D, where D <= 0 is Painlevé's paradox: a
        ValueError naming the time."""
        after = self._next_mode(mode, guard_index, t, y, excitation, time_tol)
        if kind_of(after) in SLIDE_ROCK_KINDS:
            ax, ge, _, _ = self._base(t, excitation)
            denominator = self.slide_rock(side(after), slip_direction(after), y, ax, ge)[0]
            if denominator <= 0:
                raise self._painleve(after, t, y, denominator)
        return after

    def _painleve(self, mode, t, y, denominator):
        """The error of Painlevé's paradox at ``t`` [s] in ``mode``, state ``y``: D = ``denominator`` [-]
        where a slide-rock is entered, or the located root where it falls to 0 inside one."""
        where = "<= 0" if denominator <= 0 else "falling to 0"
        return ValueError(f"at t = {t:.12g} s Painlevé's paradox: slide-rocking on the corner {side(mode):+d} b "
                          f"slipping toward {slip_direction(mode):+d} x with mu_kinetic = {self.friction_kinetic} "
                          f"has no consistent contact force (D = {denominator:.6g} {where} at theta = "
                          f"{y[THETA]:+.6g} rad, theta' = {y[THETA_RATE]:+.6g} rad/s); outside this model")

    def _next_mode(self, mode, guard_index, t, y, excitation, time_tol):
        kind, s = kind_of(mode), side(mode)
        ax, ge, ax_rate, az_rate = self._base(t, excitation)
        if mode == FreeMode.REST or kind == SETTLE:
            if ge <= 0 or guard_index == (2 if mode == FreeMode.REST else 3):
                return self._flight()  # g_e at 0, or a jump below it that took the demand's limits along
        if mode == FreeMode.REST:
            d = -1 if guard_index == 0 else 1
            # at the threshold |a_x| = min(mu, b/h) g_e: a slide, or (mu > b/h) a rock, whose
            # pivot holds there with the margin 4 g_e (1 + lambda²)(mu - lambda) of (S)
            return FreeMode(d) if self.mu <= self.slenderness_ratio else rock_mode(OUT, d)
        if kind == 1:
            if guard_index == 1:
                return self._flight()
            return self._after_slide_stop(int(mode), t, y, excitation, time_tol)
        if kind in _ROCK:
            if guard_index == 2:
                return self._flight(s)
            if guard_index == 3:
                _, force, _ = self.rock_forces(s, y, ax, ge)
                return slide_rock_mode(s, -1 if force > 0 else 1)
            if kind == IN and guard_index == 0:
                return self._impact_mode(y)
            after = rules.mode_after_rocking_guard(kind, s, guard_index, y[THETA], 0.0, 0.0, 0.0, self.alpha,
                                                   self.zeno_arc)
            return self.mode_at_rest(t, excitation) if after == rules.DEMAND_DECIDES else FreeMode(after)
        if kind in SLIDE_ROCK_KINDS:
            if guard_index == 0:
                return self._impact_mode(self.centroid_state(mode, y))
            if guard_index == 1:
                return rock_mode(OVERTURNED, s)
            if guard_index == 2:
                return self._flight(s)
            if guard_index == 3:
                return self._on_corner(s, y, ax, ge)
            raise self._painleve(mode, t, y, self.slide_rock(s, slip_direction(mode), y, ax, ge)[0])
        if kind == 9:
            if guard_index == 2:
                return rock_mode(OVERTURNED, 1 if y[THETA] > 0 else -1)
            centroid = self.centroid_state(mode, y)
            if self._grazes(1 if guard_index == 0 else -1, centroid, ge):
                return mode
            return self._impact_mode(centroid)
        if kind == SETTLE:
            return FreeMode.REST if guard_index == 0 else rock_mode(OUT, -1 if guard_index == 1 else 1)
        if mode == FreeMode.RELEASE:
            return self._on_corner(1 if self.theta0 > 0 else -1, y, ax, ge)
        if mode in INSTANT:
            return self._after_impact(mode, t, y, excitation)
        return mode

    def _after_slide_stop(self, mode, t, y, excitation, time_tol):
        """The mode after a slide stops: REST, the slide on or reversed (the sliding block's
        rule, with min(mu, b/h) for mu), or what the rest map starts toward that side."""
        ax, ge, ax_rate, az_rate = self._base(t, excitation)
        slip_rate = self.flow(mode, t, y, excitation, SCALAR)[X_RATE]
        d = int(stop_mode(mode, slip_rate, ax_rate, t, min(self.mu, self.slenderness_ratio), self.friction_kinetic,
                          ge, True, True, SCALAR, time_tol))
        if d == 0 or self.mu <= self.slenderness_ratio:
            return FreeMode(d)
        kind, _ = laws.rest_mode(-d * max(abs(ax), self.slenderness_ratio * ge), ge, self.slenderness_ratio,
                                 self.mu, self.friction_kinetic)
        return self._mode_of(kind if kind != laws.REST else laws.ROCK, d)

    def _after_impact(self, mode, t, y, excitation):
        """The mode after the jump of an impact or landing (``mode``, instant) in the state
        ``y`` after it."""
        ax, ge, _, _ = self._base(t, excitation)
        if mode == FreeMode.LANDING_FLAT:
            if y[X_RATE] == 0:
                return self.mode_at_rest(t, excitation)
            sigma = 1 if y[X_RATE] > 0 else -1
            return self._mode_of(laws.sliding_kind(self.slenderness_ratio, self.friction_kinetic), sigma)
        c = side(mode)
        kind, _, sigma = laws.mode_after_impact(c, y[THETA], y[X_RATE], y[Z_RATE], y[THETA_RATE], kind_of(mode) == 10,
                                                ax, ge, self.b, self.h, self.mu, self.friction_kinetic)
        after = self._contact_mode(kind, c, sigma, y, ax, ge)
        if kind_of(after) == OUT and self._settles(c, t, y, excitation):
            return rock_mode(SETTLE, c)
        if kind_of(after) in SLIDE_ROCK_KINDS and self._chatters(c, slip_direction(after), y, ax, ge):
            sigma = slip_direction(after)
            if sigma * self.chatter_rate(sigma, y) > 0:
                return FreeMode(sigma)
            if self.mode_at_rest(t, excitation) == FreeMode.REST:  # the tail's friction stops the face
                return FreeMode.REST
        return after

    def chatter_rate(self, sigma, y, xp=SCALAR):
        """x' [m/s] with which the face slides on toward ``sigma`` from the impact (state
        ``y`` after it) whose slide-rock's arcs, and all after them, are summed: x' + sigma mu_k z'.

        Over the tail (duration T) the base's normal impulse is ∫ g_e dt - z' (z' of the
        centroid after the impact, 0 at the tail's end) and friction's -sigma mu_k times it,
        so x' ends at x' - ∫ a_x dt - sigma mu_k (∫ g_e dt - z'): where a slide from the
        impact's time arrives after T, whatever the excitation, while the slip keeps its
        sign (the position differs by O(T R theta'))."""
        return y[X_RATE] + sigma * self.friction_kinetic * y[Z_RATE]

    def deceleration(self, s, t, excitation, xp=SCALAR):
        """-s theta'' [rad/s²] rocking on corner ``s`` at theta = 0: how fast an arc from the
        base about that corner turns back (<= 0: the demand holds it out)."""
        ax, ge, _, _ = self._base(t, excitation)
        alpha, radius = self._geometry(xp)
        return free_rules.restoring_decelerations(s, ax, ge, radius, alpha, xp)[0]

    def _settles(self, c, t, y, excitation):
        """Whether the arc on corner ``c`` that a sticking impact starts with theta' in ``y`` is
        shorter than ``zeno_arc`` and both corners restore: the Zeno tail is summed."""
        ax, ge, _, _ = self._base(t, excitation)
        alpha, radius = self._geometry(SCALAR)
        return free_rules.settles(c, y[THETA_RATE], ax, ge, radius, alpha, self.zeno_arc, SCALAR)

    def _chatters(self, c, sigma, y, ax, ge):
        """Whether a slide-rock arc on corner ``c`` slipping toward ``sigma`` that an impact
        starts is restoring and shorter than ``zeno_arc`` with mu_k <= b/h: the chatter ends
        in a slide."""
        if self.friction_kinetic > self.slenderness_ratio:
            return False
        rest = np.array(y, dtype=float)
        rest[THETA], rest[THETA_RATE] = 0.0, 0.0
        accel = self.slide_rock(c, sigma, rest, ax, ge)[2]
        return c * accel < 0 and 2 * abs(y[THETA_RATE]) / abs(accel) < self.zeno_arc

    # ---- states on guards and on entry ------------------------------------------------
    def _pivot_state(self, s, y, theta, rate, xp=SCALAR):
        """``y`` on the sticking pivot ``s`` (kept where it is) at (theta, theta'): the centroid's
        x, z and rates from the rotation alone."""
        alpha, radius = self._geometry(xp)
        return xp.stack(free_rules.pivot_state(s, y, theta, rate, radius, alpha, xp))

    def _slide_rock_state(self, s, u, theta, rate, slip, y, xp=SCALAR):
        """A slide-rock's state on pivot ``s`` at u [m] slipping at u' = ``slip`` [m/s], at
        (theta, theta'): (u, z, theta, u', z', theta') with the centroid's z, z' from the
        rotation (and ``y``'s work integrals). Its slip as a state starts at 0 exactly at a
        slip onset and grows as t², below the rounding of x' - R cos phi theta'."""
        alpha, radius = self._geometry(xp)
        phi = s * alpha - theta
        return xp.stack([u, radius * xp.cos(phi), theta, slip, radius * xp.sin(phi) * rate, rate,
                         y[BASE_WORK], y[FRICTION_WORK]])

    def to_pivot(self, s, y, slip, xp=SCALAR):
        """The centroid's state ``y`` as a slide-rock's on pivot ``s`` slipping at u' = ``slip``."""
        alpha, radius = self._geometry(xp)
        u = y[X] + radius * xp.sin(s * alpha - y[THETA])
        return self._slide_rock_state(s, u, y[THETA], y[THETA_RATE], slip, y, xp)

    def from_pivot(self, s, y, xp=SCALAR):
        """A slide-rock's state on pivot ``s`` as the centroid's (:meth:`to_pivot`'s inverse)."""
        alpha, radius = self._geometry(xp)
        phi = s * alpha - y[THETA]
        return xp.stack([y[X] - radius * xp.sin(phi), y[Z], y[THETA], y[X_RATE] + radius * xp.cos(phi) * y[THETA_RATE],
                         y[Z_RATE], y[THETA_RATE], y[BASE_WORK], y[FRICTION_WORK]])

    def _flat_state(self, y, x_rate, xp=SCALAR):
        """``y`` standing flat (theta = 0, z = h) with x' = ``x_rate`` [m/s]."""
        zero = 0.0 * y[X]
        return xp.stack([y[X], zero + self.h, zero, zero + x_rate, zero, zero, y[BASE_WORK], y[FRICTION_WORK]])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """The state exactly on the guard: theta' = 0 at an apex, theta = 0 at an impact,
        alpha or pi/2 at those guards, u' = 0 where a slip stops, the corner at height 0
        at a landing, x' = 0 where a slide stops, flat and still where a Zeno tail ends; the
        tilt on release."""
        kind, s = kind_of(mode), side(mode)
        if kind == 1 and guard_index == 0:
            return self._flat_state(y, 0.0, xp)
        if kind in _ROCK:
            theta, rate = y[THETA], y[THETA_RATE]
            if guard_index >= 2:  # lift-off, slip onset: on the pivot exactly (no drift of x', z')
                pass
            elif (kind == IN) == (guard_index == 0):
                edge = self._geometry(xp)[0] if kind == OUT else 0.5 * math.pi
                theta = 0.0 * theta + (0.0 if kind == IN else s * edge)
            else:
                rate = 0.0 * rate
            return self._pivot_state(s, y, theta, rate, xp)
        if kind in SLIDE_ROCK_KINDS and guard_index < 4:
            theta = y[THETA] if guard_index > 1 else 0.0 * y[THETA] + (0.0 if guard_index == 0 else s * 0.5 * math.pi)
            slip = 0.0 * y[X_RATE] if guard_index == 3 else y[X_RATE]
            return self._slide_rock_state(s, y[X], theta, y[THETA_RATE], slip, y, xp)
        if kind == 9 and guard_index < 2:  # the corner struck at height 0 exactly (see guards)
            level = -(s - (1 if guard_index == 0 else -1)) * self.b * xp.sin(y[THETA])
            return xp.stack([y[X], level, *(y[i] for i in range(THETA, len(self.state_names)))])
        if kind == SETTLE:  # its theta' is the envelope of the summed impacts, not a rotation
            return self._flat_state(y, 0.0, xp)
        if mode == FreeMode.RELEASE:
            s = 1 if self.theta0 > 0 else -1
            return self._pivot_state(s, self._flat_state(y, 0.0, xp), self.theta0, 0.0, xp)
        return y

    def state_on_entry(self, before, after, t, y, excitation, xp=np):
        """The jump on entering ``after`` from ``before`` at ``t`` (:meth:`entry_state`)."""
        return self.entry_state(before, after, y, xp)

    def entry_state(self, before, after, y, xp=np):
        """The state on entering ``after`` from ``before`` [the units of :attr:`state_names`]:
        an impact's or landing's velocity jump on the branch its instant mode names (the
        corner struck, sticking or slipping: :func:`._slide_rock_laws.impact_jump`; the face
        landing flat: :func:`._slide_rock_laws.flat_landing`); the rocking state made exact on
        its pivot; flat in a slide or at rest after an impact; still on its side overturned.
        Needs no excitation (the event records use it); xp-generic (the JAX twin
        differentiates it)."""
        kind = kind_of(after)
        if kind_of(before) in (9, *SLIDE_ROCK_KINDS):
            if kind == kind_of(before) or (kind in SLIDE_ROCK_KINDS and kind_of(before) in SLIDE_ROCK_KINDS):
                return y  # a restart, a slip reversed on the same pivot
            y = (self.to_centroid if kind_of(before) == 9 else self.from_pivot)(side(before), y, xp)
        if kind == 9:
            return self.to_corner(side(after), y, xp)
        if after == FreeMode.LANDING_FLAT:
            p_n = -y[Z_RATE]
            sliding = y[X_RATE] - xp.sign(y[X_RATE]) * self.friction_kinetic * p_n
            x_rate = xp.where(xp.abs(y[X_RATE]) <= self.mu * p_n, 0.0 * p_n, sliding)
            return self._rates(y, x_rate, 0.0 * p_n, 0.0 * p_n, xp)
        if kind in (10, 11):
            x_rate, z_rate, theta_rate, _, _ = laws.impact_jump(side(after), kind == 10, y[THETA], y[X_RATE],
                                                                y[Z_RATE], y[THETA_RATE], self.b, self.h,
                                                                self.friction_kinetic, xp)
            return self._rates(y, x_rate, z_rate, theta_rate, xp)
        s = side(after)
        if kind in _ROCK:
            return self._pivot_state(s, y, y[THETA], y[THETA_RATE], xp)
        if kind == SETTLE:
            settled = self._flat_state(y, 0.0, xp)
            return xp.stack([*(settled[i] for i in range(THETA_RATE)), y[THETA_RATE], settled[BASE_WORK],
                             settled[FRICTION_WORK]])
        if kind in SLIDE_ROCK_KINDS:  # slipping on through an impact or a face landing, or from rest
            slip = self.pivot_slip_rate(s, y, xp) if kind_of(before) in (11, 12) else 0.0 * y[X]
            return self.to_pivot(s, y, slip, xp)
        if kind == OVERTURNED:
            return self._pivot_state(s, y, 0.0 * y[THETA] + s * 0.5 * math.pi, 0.0 * y[THETA], xp)
        if kind_of(before) in (10, 11) and kind in (0, 1):  # a chatter's end: the tail summed
            return self._flat_state(y, self.chatter_rate(side(after), y, xp) if kind == 1 else 0.0 * y[X], xp)
        if after == FreeMode.REST or (kind == 1 and kind_of(before) not in (0, 1)):
            return self._flat_state(y, 0.0 if after == FreeMode.REST else y[X_RATE], xp)
        return y

    @staticmethod
    def _rates(y, x_rate, z_rate, theta_rate, xp):
        """``y`` with the rates (x', z', theta') replaced."""
        return xp.stack([y[X], y[Z], y[THETA], x_rate, z_rate, theta_rate, y[BASE_WORK], y[FRICTION_WORK]])

    # ---- parameters, for the JAX twin ------------------------------------------------
    def parameters(self):
        """b [m], h [m], mu [-], mu_kinetic [-] (where given) and g [m/s²]: what ``flow`` and
        ``guards`` read."""
        values = {"b": self.b, "h": self.h, "mu": self.mu}
        if self.mu_kinetic is not None:
            values["mu_kinetic"] = self.mu_kinetic
        return {**values, "g": self.g}

    def with_parameters(self, values):
        model = copy.copy(self)
        for name, value in values.items():
            object.__setattr__(model, name, value)
        return model

    # ---- what the hybrid driver asks ------------------------------------------------
    def is_static(self, mode):
        return mode == FreeMode.REST or kind_of(mode) == OVERTURNED

    def at_rest(self, mode, y):
        return mode == FreeMode.REST or (kind_of(mode) == 1 and y[X_RATE] == 0)

    def rest_state(self, y):
        y = np.array(y, dtype=float)
        y[X_RATE:BASE_WORK] = 0.0
        return y

    def output_step(self):
        """Largest gap between dense-output knots [s]: 1 / (32 p)."""
        return 1.0 / (KNOTS_PER_RADIAN * self.frequency)

    def turn_rate(self, mode, t, y, excitation, xp=np):
        """x'' sliding, theta'' rocking at the state ``y``: the integrator stops where the
        slide's or the rotation's rate may turn."""
        kind = kind_of(mode)
        if kind == 1:
            return self.flow(mode, t, y, excitation, xp)[X_RATE]
        if kind in _ROCK:
            return self.flow(mode, t, y, excitation, xp)[THETA_RATE]
        return None

    def guard_restarts(self, mode, guard_index):
        """A corner of a flying block that grazes the base (:meth:`_grazes`) restarts the
        flight, and a slipping pivot whose slip touches zero and goes on the same way
        restarts its slide-rock (an event within one mode, which the solution leaves out):
        an integrator cannot go on from a root it found."""
        return (kind_of(mode) == 9 and guard_index < 2) or (kind_of(mode) in SLIDE_ROCK_KINDS and guard_index == 3)

    def _is_force_guard(self, mode, guard_index):
        """Whether guard ``guard_index`` of ``mode`` is a force [m/s²] (g_e, a rest limit, N,
        a friction margin): the only guards a jump of a(t) moves."""
        kind = kind_of(mode)
        return (mode == FreeMode.REST or (kind == 1 and guard_index == 1) or (kind in _ROCK and guard_index >= 2)
                or (kind in SLIDE_ROCK_KINDS and guard_index == 2) or (kind == SETTLE and guard_index >= 1))

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(rate, curvature) of the guard in time [its unit /s, /s²], by differences along the
        flow; a force guard that a jump of a(t) at a knot carried below zero (by more than
        JUMP_FLOOR g) falls at once: the event is at the knot."""
        if mode in INSTANT:
            return -1.0, 0.0
        if kind_of(mode) == OVERTURNED:
            return 0.0, 0.0
        if self._is_force_guard(mode, guard_index) and \
                self.guards(mode, t, y, excitation, SCALAR)[guard_index] < -JUMP_FLOOR * self.g:
            return -1.0, 0.0
        return super().guard_rates(mode, guard_index, t, y, excitation)

    def contradiction(self, mode, y, velocity_error):
        """A slide, a slip or a rotation whose rate points against its mode beyond the
        velocity error, and beyond 1e-10 p R [m/s] (1e-10 p alpha [rad/s]): a stop located
        within the root's time tolerance (2e-13 s at t = 10 s) may lie past zero by its
        acceleration times that, more than the velocity error of a block that barely moves."""
        kind, s = kind_of(mode), side(mode)
        speed_error = max(velocity_error, RATE_FLOOR * self.frequency * self.R)
        if kind == 1 and s * y[X_RATE] < -speed_error:
            return f"x' = {y[X_RATE]:+.6g} m/s points against the slide"
        if kind in SLIDE_ROCK_KINDS and slip_direction(mode) * y[X_RATE] < -speed_error:
            return f"the pivot's slip u' = {y[X_RATE]:+.6g} m/s points against its mode"
        return self.rotation_contradiction(kind, s, y[THETA_RATE], velocity_error)

    def speed(self, y):
        """max(|x'|, |z'|, R |theta'|) [m/s]."""
        return max(abs(float(y[X_RATE])), abs(float(y[Z_RATE])), self.R * abs(float(y[THETA_RATE])))

    def time_to_rest(self, mode, y):
        """A bound [s] on the time to rest after the excitation: the free decay of the
        impacts and a slide's stop."""
        f = self.friction_kinetic
        if f == 0 and self.speed(y) != 0:
            raise ValueError("a block without kinetic friction slides on forever: give t_end [s]")
        slide = 2.0 * self.speed(y) / (f * self.g) if f > 0 else 0.0
        return 200.0 * math.pi / (self.frequency * (1.0 - self.r)) + 10.0 / self.frequency + slide

    def event(self, t, mode_before, mode_after, y):
        """The event record: the centroid's state before and after the mode change."""
        after = self.centroid_state(mode_after, self.entry_state(mode_before, mode_after, y))
        return FreeEvent.make(float(t), mode_before, mode_after, self.centroid_state(mode_before, y)[:BASE_WORK],
                              after[:BASE_WORK])

    def solution(self, *, t, y, mode, events, backend, dense, stats):
        """The solution in the centroid's coordinates (the knots and rates of a flight and of
        a slide-rock converted; the others are the centroid's already)."""
        given, knots = np.asarray(y, dtype=float), np.asarray(dense.y, dtype=float)
        y, rates = given.copy(), [np.array(r, dtype=float) for r in (dense.rate_start, dense.rate_end)]
        for i in np.flatnonzero(np.isin(np.abs(np.asarray(mode, dtype=int)), (*SLIDE_ROCK_KINDS, 9))):
            m = FreeMode(int(mode[i]))
            y[i] = self.centroid_state(m, given[i])
            for rate, raw in zip(rates, (dense.rate_start, dense.rate_end)):
                rate[i] = self.centroid_rate(m, knots[i], raw[i])
        return FreeStandingSolution(t=t, state=y, mode=mode, events=FreeEvent.merge(events), backend=backend,
                                    dense=HermiteDense(t, y, *rates), stats=stats)

    def energy(self, mode, y):
        """E = ½ (x'² + z'²) + (R²/6) theta'² + g z [J/kg] of the centroid's state ``y`` in
        ``mode`` (a settling block's rotation rate is the envelope of its summed impacts: no
        kinetic energy)."""
        if kind_of(mode) == SETTLE:
            return self.g * y[Z]
        return laws.energy(y[X_RATE], y[Z_RATE], y[THETA_RATE], y[Z], self.R, self.g)
