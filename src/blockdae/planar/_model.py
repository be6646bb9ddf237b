"""The rigid block on a plane under two horizontal and one vertical base component
(Elms 2000), with flight when the base falls faster than g.

With the base acceleration (a_x, a_y, a_z)(t) [m/s²] (z upward) and the bias
b = (b_x, b_y) (a constant horizontal force on the block as a fraction of its
weight), the normal force per unit mass is n = g + a_z and the friction force per
unit mass that carries the block with the base is the *demand*

    sigma(t) = a_h(t) - b g            [m/s²],   a_h = (a_x, a_y).

Stick holds while |sigma| <= mu n (the friction circle, seed eq. 7). Sliding, the
relative velocity v = s e (speed s >= 0, direction e) obeys v' = -sigma - f n e, kept
as

    s' = e . (-sigma) - f n,      s e' = (e_perp . (-sigma)) e_perp,

so that a stop is a simple root of s, not a touch of |v| (seed eqs. 19-20 in SI; below
``SLOW_SPEED`` the rate of e takes s = SLOW_SPEED, see :mod:`._rules`). In
flight (n <= 0) there is no friction: v' = -sigma, and the gap w above the base obeys
w'' = -n; the block lands when w returns to zero.

State y = (u_x, u_y, s, c_x, c_y, w, w'): relative displacement [m]; on the base the
speed s [m/s] and the direction as a vector c (e = c / |c|) [-]; in flight s = 0 and
c = v [m/s] (Cartesian: nothing stops there, and the polar form is singular at s = 0);
the gap [m] and its rate [m/s]. On a compliant support (``support``, see
:mod:`blockdae.upthrow._support`) n comes from the support's law at (w, w'), w is the
height from the static position and moves in contact too (w'' = n - g - a_z), and the
flight ends by the support's landing rule. The direction is a vector rather than an angle so that
with a_y = b_y = 0 the motion stays exactly on the x axis.
"""

import dataclasses
import math

import numpy as np

from ..units import STANDARD_GRAVITY, length_units
from ..excitation import AbstractExcitation, BaseMotion, check_horizontal
from ._solution import PlanarEvent, PlanarSolution
from ..core.contract import (KNOTS_PER_RADIAN, SCALAR, BatchedModel, DifferentiableModel, EngineModel, StudyModel,
                             scale_factor_units)
from ..core import LazyEngine, set_real_fields
from ._modes import _CX, _CY, _S, _UX, _UY, _W, _WD, PlanarMode, horizontal_velocity
from . import _rules as rules
from ._rules import SLOW_SPEED
from ..upthrow import RigidSupport, SpringSupport, parse_support

#: relative tolerance of the compiled engine in studies [-]: against IDA at rtol 1e-12
#: on the benchmark's cases (Elms, two record pairs, El Centro in three components)
#: events within 3.2e-12 s and u within 2.8e-11 relative (bars: 1e-9 s, 1e-9), with
#: ~20 % fewer steps than at 1e-12 on the records
STUDY_RTOL = 1e-10


@dataclasses.dataclass(frozen=True, eq=False)
class PlanarBlock(BatchedModel, DifferentiableModel, EngineModel, StudyModel):
    """Rigid block on a horizontal plane shaken in x, y and z (Elms 2000).

    Args:
        mu: static friction coefficient [-], > 0.
        mu_kinetic: kinetic friction coefficient f [-], 0 <= f <= mu; default ``mu``.
        bias: (b_x, b_y), a constant horizontal force on the block as a fraction of
            its weight [-], |bias| < mu (Elms's P acts in -x: ``bias=(-P, 0)``).
        g: gravitational acceleration [m/s²]; standard gravity by default.
        restitution: vertical coefficient of restitution at landing [-], in [0, 1):
            the vertical relative velocity is multiplied by -restitution, the
            horizontal one is kept.
        bounce_threshold: a rebound slower than this [m/s] ends in contact, so that a
            bouncing block settles in finitely many bounces (no Zeno loop).
        support: what the block stands on (:mod:`blockdae.upthrow._support`): a
            :class:`RigidSupport` (default: n = g + a_z, w = 0 in contact) or a
            :class:`SpringSupport` (n from its spring-dashpot law, w its deflection
            from the static position; ``restitution`` then plays no part: the block
            lands on the unloaded spring and stays on it while it pushes).

    ``mu``, ``mu_kinetic``, ``b_x`` and ``b_y`` may be 1-D arrays (broadcast together):
    the block is then a batch of parameter sets.
    """

    mu: float
    mu_kinetic: float | None = None
    bias: tuple[float, float] = (0.0, 0.0)
    g: float = STANDARD_GRAVITY
    restitution: float = 0.0
    bounce_threshold: float = 1e-4
    support: RigidSupport | SpringSupport = RigidSupport()

    state_names = ("u_x", "u_y", "s", "c_x", "c_y", "w", "w_rate")
    modes = PlanarMode
    initial_mode = PlanarMode.STICK
    component_names = ("x", "y", "z")
    displacement_states = (_UX, _UY)
    default_backend = "ida"  # CVODE loses the sliding direction on turning slides
    #: the compiled engine (rigid support), for studies
    engines = {"compiled": LazyEngine("blockdae.planar._engine", "PlanarEngine")}

    def __post_init__(self):
        set_real_fields(self, ("g", "restitution", "bounce_threshold"))
        for name in ("mu", "mu_kinetic"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, _parameter(name, getattr(self, name)))
        try:
            pair = tuple(self.bias)
        except TypeError:
            pair = ()
        if len(pair) != 2:
            raise ValueError(f"bias must be a pair (b_x, b_y) [-] of numbers or of 1-D arrays, got {self.bias!r}")
        object.__setattr__(self, "bias", tuple(_parameter(name, b) for name, b in zip(("bias_x", "bias_y"), pair)))
        try:
            mu, f, bx, by = np.broadcast_arrays(self.mu, self.friction_kinetic, *self.bias)
        except ValueError as err:
            raise ValueError(f"mu, mu_kinetic and bias must broadcast together: {err}") from None
        _check(mu <= 0, "mu", mu, lambda i: "must be > 0")
        _check((f < 0) | (f > mu), "mu_kinetic", f, lambda i: f"must lie in [0, mu={float(mu[i])!r}]")
        _check(np.hypot(bx, by) >= mu, "bias", np.stack([bx, by], axis=-1),
               lambda i: f"must satisfy |bias| < mu (|bias| = {float(np.hypot(bx, by)[i]):.6g}, "
                         f"mu={float(mu[i])!r}; else the block slides with the base at rest)")
        if self.g <= 0:
            raise ValueError(f"g must be a positive acceleration [m/s²], got {self.g!r}")
        if not 0 <= self.restitution < 1:
            raise ValueError(f"restitution={self.restitution!r} must lie in [0, 1)")
        if self.bounce_threshold <= 0:
            raise ValueError(f"bounce_threshold={self.bounce_threshold!r} must be > 0 [m/s]")
        parse_support(self.support)

    @property
    def state_units(self):
        """The units of ``state_names``: u_x, u_y, w in m, s and w' in m/s, the direction
        c in - (in flight c is v [m/s]); g s² and g s for a block with g = 1."""
        length, velocity = length_units(self.g)
        return (length, length, velocity, "-", "-", length, velocity)

    @property
    def friction_kinetic(self) -> float:
        """Kinetic friction coefficient f [-] (``mu_kinetic``, or ``mu`` if None)."""
        return self.mu if self.mu_kinetic is None else self.mu_kinetic

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """() for one parameter set, (n,) for a batch of n."""
        return np.broadcast_shapes(*(np.shape(p) for p in (self.mu, self.friction_kinetic, *self.bias)))

    parameter_labels = {"mu": "static friction coefficient mu [-]", "mu_kinetic": "kinetic friction coefficient [-]",
                        "bias_x": "bias force R_x/Q [-]", "bias_y": "bias force R_y/Q [-]"}

    def batch_parameters(self) -> dict:
        """The grid: mu, mu_kinetic (the coefficient in effect), bias_x, bias_y [-], each
        of shape ``batch_shape``."""
        values = (self.mu, self.friction_kinetic, *self.bias)
        return {name: np.broadcast_to(np.asarray(p, dtype=float), self.batch_shape)
                for name, p in zip(("mu", "mu_kinetic", "bias_x", "bias_y"), values)}

    def item(self, index: int) -> "PlanarBlock":
        """The ``index``-th parameter set of a batch, as one block (whose ``mu_kinetic``
        stays None, following ``mu``, where the batch's does)."""
        p = {name: float(value[index]) for name, value in self.batch_parameters().items()}
        mu_kinetic = None if self.mu_kinetic is None else p["mu_kinetic"]  # None: f follows mu (tied_parameters)
        return dataclasses.replace(self, mu=p["mu"], mu_kinetic=mu_kinetic, bias=(p["bias_x"], p["bias_y"]))

    def engine_parameters(self, scale=(1.0,)) -> np.ndarray:
        """The compiled engine's parameter rows, (m * s, 8): (mu, mu_kinetic, bias_x,
        bias_y [-], g [m/s²], restitution [-], bounce_threshold [m/s], factor on a(t)
        [-]) for each of the m parameter sets (1 for one block) at each of the s
        factors in ``scale``; set j at factor k in row j * s + k."""
        p = {name: np.atleast_1d(value) for name, value in self.batch_parameters().items()}
        rows = np.stack([p["mu"], p["mu_kinetic"], p["bias_x"], p["bias_y"], np.full_like(p["mu"], self.g),
                         np.full_like(p["mu"], self.restitution), np.full_like(p["mu"], self.bounce_threshold)], axis=1)
        factors = np.asarray(scale, dtype=float)
        return np.ascontiguousarray(np.column_stack([np.repeat(rows, len(factors), axis=0),
                                                     np.tile(factors, len(rows))]))

    def replace(self, **changes) -> "PlanarBlock":
        """A copy with some parameters changed (validated again)."""
        return dataclasses.replace(self, **changes)

    #: what :func:`bd.study` sweeps: its keyword, the table's column, the unit
    study_parameter = ("mu", "mu", "-")

    def study_batch(self, mu) -> "PlanarBlock":
        """This block at every friction coefficient ``mu`` [-] (1-D), for :func:`bd.study`
        (checks them against the other parameters)."""
        return self.replace(mu=mu)

    def study_columns(self, motions, t_end, scale, rtol=None) -> dict:
        """What :func:`bd.study` tabulates of this block (a batch of m parameter sets)
        on ``motions`` (BaseMotions) at the factors ``scale`` on a(t) [-]: one row per
        motion x set x factor, from the compiled planar engine at ``rtol`` [-] (None:
        :data:`STUDY_RTOL`). displacement_x_m, displacement_y_m (u at the end [m]),
        displacement_m (|u| at the end [m]), max_abs_displacement_m (max |u| [m]),
        slide_distance_m (path length [m]), n_events, n_flights, t_end_s [s]."""
        from ..core import Horizon, make_backend

        backend = make_backend("compiled", rtol=STUDY_RTOL if rtol is None else rtol)
        out = backend.solve_final(self, list(motions), [Horizon.resolve(m, t_end) for m in motions], scale=tuple(scale))
        u_x, u_y = out[..., 0].ravel(), out[..., 1].ravel()
        return dict(displacement_x_m=u_x, displacement_y_m=u_y, displacement_m=np.hypot(u_x, u_y),
                    max_abs_displacement_m=out[..., 2].ravel(), slide_distance_m=out[..., 3].ravel(),
                    n_events=out[..., 4].ravel().astype(int), n_flights=out[..., 5].ravel().astype(int),
                    t_end_s=out[..., 6].ravel())

    # ---- forces per unit mass -------------------------------------------------
    def normal(self, t, excitation, y=None):
        """n [m/s²] and its rate [m/s³] on the base: g + a_z on a rigid support; on a
        spring the law at the state ``y``, whose rate follows from w'' = n - g - a_z."""
        if not self.support.compliant:
            return rules.rigid_normal(self.g, excitation.component(2, t)), excitation.component_rate(2, t)
        n = self.support.law(self.g, y[_W], y[_WD])
        k, c = self.support.stiffness()
        return n, -k * y[_WD] - c * (n - self.g - excitation.component(2, t))

    def _vertical_flow(self, t, y, excitation, n):
        """(w', w'') in contact under the normal force ``n`` [m/s²]: zero on a rigid
        support, (w', n - g - a_z) on a spring."""
        zero = 0.0 * y[_UX]
        if not self.support.compliant:
            return zero, zero
        return y[_WD], n - self.g - excitation.component(2, t)

    def demand(self, t, excitation):
        """sigma = a_h - b g [m/s²] and its rate [m/s³], as (x, y) pairs."""
        sigma = rules.demand(excitation.component(0, t), excitation.component(1, t), *self.bias, self.g)
        return sigma, (excitation.component_rate(0, t), excitation.component_rate(1, t))

    def friction(self, mode, t, y, excitation, xp=np):
        """(F_x, F_y): the friction force per unit mass the base exerts on the block in
        ``mode`` [m/s²], so that the relative horizontal acceleration is F - sigma: the
        demand sigma in stick, -f n e in slip, zero in flight."""
        if mode == PlanarMode.STICK:
            return self.demand(t, excitation)[0]
        if mode == PlanarMode.FLIGHT:
            return 0.0 * y[_UX], 0.0 * y[_UX]
        n, _ = self.normal(t, excitation, y)
        scale = -self.friction_kinetic * n / xp.sqrt(y[_CX] ** 2 + y[_CY] ** 2)
        return scale * y[_CX], scale * y[_CY]

    # ---- hybrid automaton ----------------------------------------------------
    def flow(self, mode, t, y, excitation, xp=np, friction=None):
        """dy/dt in ``mode`` (zero in stick on a rigid support; :func:`._rules.flow`).
        ``friction``: (F_x, F_y) [m/s²] in place of the mode's own (:meth:`friction`), so
        that the relative horizontal acceleration is F - sigma (a DAE backend's algebraic F)."""
        zero = 0.0 * y[_UX]
        if mode == PlanarMode.STICK and not self.support.compliant:
            return xp.stack(rules.flow(mode, y, zero, zero, zero, zero, xp))
        (sx, sy), _ = self.demand(t, excitation)
        rx, ry = (-sx, -sy) if friction is None else (friction[0] - sx, friction[1] - sy)
        if mode == PlanarMode.FLIGHT:
            return xp.stack(rules.flow(mode, y, rx, ry, zero, -(self.g + excitation.component(2, t)), xp))
        n, _ = self.normal(t, excitation, y)
        kinetic = self.friction_kinetic * n if friction is None else 0.0
        rates = rules.flow(mode, y, rx, ry, kinetic, zero, xp)
        return xp.stack([*rates[:5], *self._vertical_flow(t, y, excitation, n)])

    def guards(self, mode, t, y, excitation, xp=np):
        """Stick: (n -> flight, mu n - |sigma| -> slip). Slip: (n -> flight,
        s -> stop). Flight: (w -> landing; on a spring the support's landing gap).
        The force guards are times :attr:`guard_scale`."""
        if mode == PlanarMode.FLIGHT:
            if self.support.compliant:
                return xp.stack([self.support.landing_gap(self.g, y[_W], y[_WD], xp)])
            return xp.stack(rules.guards(mode, y, None, None, None, self.mu, 1.0, xp)[:1])
        n, _ = self.normal(t, excitation, y)
        sx, sy = self.demand(t, excitation)[0] if mode == PlanarMode.STICK else (None, None)
        return xp.stack(rules.guards(mode, y, n, sx, sy, self.mu, self.guard_scale, xp))

    @property
    def guard_scale(self):
        """Factor of the force guards (n, mu n - |sigma|): 1 [-] on a rigid support,
        1 / omega² [s²] on a spring, where they are then lengths [m] like the
        support's law rows (n / omega²), so that a root finder asking |guard| < atol
        at adjacent floats of t can meet it where n moves as fast as omega² w'."""
        return 1.0 / self.support.stiffness()[0] if self.support.compliant else 1.0

    def circle_margin(self, t, excitation, y=None):
        """mu n - |sigma| [m/s²] (> 0 inside the friction circle) and its rate [m/s³]
        (where sigma = 0, the rate of -|sigma| is -|sigma'|); ``y``: the state (on a spring)."""
        return rules.circle_margin(self.mu, *self._forces(t, excitation, y))

    def _forces(self, t, excitation, y=None):
        """(n, n', sigma_x, sigma_y, sigma_x', sigma_y') [m/s², m/s³] at ``t``, as the
        rules take them."""
        n, n_rate = self.normal(t, excitation, y)
        (sx, sy), (rx, ry) = self.demand(t, excitation)
        return n, n_rate, sx, sy, rx, ry

    def lifts_off(self, t, excitation, y=None):
        """Whether n is negative, or zero and falling, at ``t`` (in state ``y``)."""
        return rules.lifts_off(*self.normal(t, excitation, y))

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        """Flight if n < 0 (or n = 0 falling), else slip if the demand is outside the
        friction circle (or on it moving outwards), else stick (``y``: the state, which
        sets n on a spring)."""
        return PlanarMode(rules.mode_at_rest(self.mu, *self._forces(t, excitation, y)))

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        """:func:`._rules.mode_after_guard`: a liftoff, a slide, a stop (that slides on
        if the demand leaves the circle within ``time_tol`` [s]), a rebound (on a rigid
        support) or a landing."""
        return PlanarMode(rules.mode_after_guard(mode, guard_index, t, y, self.mu, *self._forces(t, excitation, y),
                                                 self.restitution, self.bounce_threshold,
                                                 not self.support.compliant, time_tol))

    # ---- what the hybrid driver asks -----------------------------------------
    def check_motion(self, motion):
        """An excitation (a_x alone) or a :class:`~blockdae.BaseMotion` (x, y, z)."""
        if not isinstance(motion, (AbstractExcitation, BaseMotion)):
            raise TypeError(f"motion must be an excitation (Harmonic, Record, ...) or a BaseMotion, "
                            f"got {type(motion).__name__}")
        for horizontal in (motion,) if isinstance(motion, AbstractExcitation) else (motion.x, motion.y):
            check_horizontal(horizontal)

    def dae_form(self, piece):
        """The states and the friction force (F_x, F_y) as IDA's algebraic variables
        (:class:`PlanarDAEForm`)."""
        return PlanarDAEForm(self, piece)

    def excitation_pieces(self, excitation, t_end):
        """(a_x, a_y, a_z) pieces on one partition; a 1-D excitation is a_x alone."""
        motion = excitation if isinstance(excitation, BaseMotion) else BaseMotion(excitation)
        return motion.aligned_pieces(t_end)

    def is_static(self, mode):
        """Stick on a rigid support (on a spring the block moves with it)."""
        return mode == PlanarMode.STICK and not self.support.compliant

    def at_rest(self, mode, y):
        return mode == PlanarMode.STICK or (mode == PlanarMode.SLIP and y[_S] == 0)

    def rest_state(self, y):
        """s = 0, and w = w' = 0 on a rigid support (a spring keeps its motion)."""
        if self.support.compliant:
            return _with(y, {_S: 0.0})
        return _with(y, {_S: 0.0, _W: 0.0, _WD: 0.0})

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """A stop has s = 0 and a landing on a rigid support w = 0, exactly; a landing on
        a spring keeps the located state (u0 moves with the parameters, which a map of
        y alone could not follow in the derivatives)."""
        if mode == PlanarMode.SLIP and guard_index == 1:
            return _with(y, {_S: 0.0}, xp)
        if mode == PlanarMode.FLIGHT and not self.support.compliant:
            return _with(y, {_W: 0.0}, xp)
        return y

    def guard_restarts(self, mode, guard_index):
        """A landing (a rebound stays in flight) and a stop (the slide may go on in a
        new direction) are events."""
        return mode == PlanarMode.FLIGHT or (mode == PlanarMode.SLIP and guard_index == 1)

    def state_on_entry(self, before, after, t, y, excitation, xp=np):
        """A liftoff starts with v in Cartesian form and, on a rigid support, w = w' = 0;
        a landing keeps the horizontal velocity and, on a rigid support, takes
        -restitution times the vertical one (a rebound) or zero (contact); on a spring
        the vertical motion goes on. Sliding from rest starts along the relative
        acceleration -sigma (or, where sigma = 0, along its rate)."""
        (sx, sy), (rx, ry) = self.demand(t, excitation)
        z = rules.state_on_entry(before, after, y, sx, sy, rx, ry, self.restitution, not self.support.compliant, xp)
        return np.array(z, dtype=float) if xp is np else xp.stack(z)

    # ---- parameters ----------------------------------------------------------
    def parameters(self):
        """mu, mu_kinetic (f), bias_x, bias_y [-], g [m/s²], restitution [-], and the
        support's (a spring's support_frequency [Hz] and support_damping [-])."""
        return {"mu": self.mu, "mu_kinetic": self.friction_kinetic, "bias_x": self.bias[0],
                "bias_y": self.bias[1], "g": self.g, "restitution": self.restitution, **self.support.parameters()}

    def with_parameters(self, values):
        """The block with ``values``; a spring support where they name its parameters."""
        values = {**self.parameters(), **values}
        support = SpringSupport.unchecked(values["support_frequency"], values["support_damping"]) \
            if "support_frequency" in values else RigidSupport()
        model = object.__new__(PlanarBlock)
        fields = {"mu": values["mu"], "mu_kinetic": values["mu_kinetic"], "bias": (values["bias_x"], values["bias_y"]),
                  "g": values["g"], "restitution": values["restitution"], "bounce_threshold": self.bounce_threshold,
                  "support": support}
        for name, value in fields.items():
            object.__setattr__(model, name, value)
        return model

    def replace_parameter(self, name, value):
        """As ``replace``; "bias_x" and "bias_y" set one component of ``bias``,
        "support_frequency" and "support_damping" a field of the spring support."""
        if name in ("support_frequency", "support_damping"):
            return self.replace(support=self.support.replace(**{name.removeprefix("support_"): value}))
        if name in ("bias_x", "bias_y"):
            bias = list(self.bias)
            bias[name == "bias_y"] = value
            return self.replace(bias=tuple(bias))
        return self.replace(**{name: value})

    def default_wrt(self):
        """("mu", "mu_kinetic", "bias_x", "bias_y", "A")."""
        return ("mu", "mu_kinetic", "bias_x", "bias_y", "A")

    def parameter_units(self):
        """Units of :meth:`parameters` (g [m/s²], a spring's support_frequency [Hz], the
        others [-]) and of the motion's scale factors (A [g], A_x, A_y, A_z [-])."""
        units = {"g": "m/s²", "support_frequency": "Hz"}
        return {name: units.get(name, "-") for name in self.parameters()} | scale_factor_units(self)

    def tied_parameters(self):
        """mu moves the kinetic friction too when ``mu_kinetic`` is None."""
        return {"mu": ("mu_kinetic",)} if self.mu_kinetic is None else {}

    def turn_rate(self, mode, t, y, excitation, xp=np):
        """Stick: the rate of (mu n)² - |sigma|² (linear in t on a linear piece), where
        the stick guards may turn. Flight: w' (the gap turns at its top). Slip along a
        line (the direction does not turn): s' (linear in t on a linear piece), so that
        s, which may dip below zero and come back within one sample, is stopped at its
        minimum; a turning slide: none. On a spring: none (the guards follow the
        oscillating state; :meth:`output_step` resolves it)."""
        if self.support.compliant:
            return None
        value, defined = rules.turn_rate(mode, y, self.mu, self.friction_kinetic, *self._forces(t, excitation), SCALAR)
        return value if defined else None

    def output_step(self):
        """1 / (32 omega) [s] on a spring (its oscillation), else inf."""
        if self.support.compliant:
            return 1.0 / (KNOTS_PER_RADIAN * self.support.omega)
        return math.inf

    def guard_rates(self, mode, guard_index, t, y, excitation):
        if self.support.compliant and mode == PlanarMode.FLIGHT:
            fall = -(self.g + excitation.component(2, t))  # w''
            ratio = 2 * self.support.damping / self.support.omega if y[_WD] > 0 else 0.0
            return y[_WD] + ratio * fall, fall
        return rules.guard_rates(mode, guard_index, y, self.mu, self.friction_kinetic, *self._forces(t, excitation, y),
                                 self.guard_scale, SCALAR)

    def contradiction(self, mode, y, velocity_error):
        """A slide with a negative speed s [m/s]."""
        if mode == PlanarMode.SLIP and y[_S] < -velocity_error:
            return f"the slide's speed s = {y[_S]:+.6g} m/s is negative"
        return None

    def speed(self, y):
        if self.support.compliant:  # horizontal and vertical
            return math.hypot(y[_S], y[_CX], y[_CY], y[_WD]) if y[_S] == 0 else math.hypot(y[_S], y[_WD])
        return rules.speed(y)

    def time_to_rest(self, mode, y):
        """With a = 0 (n = g, relative acceleration b g): the flight ends within
        (w' + sqrt(w'² + 2 g w)) / g, the slide within twice s / ((f - |b|) g) after it.
        On a spring the block never rests exactly (ValueError)."""
        if self.support.compliant:
            raise ValueError("a block on a spring support never comes to rest exactly after the excitation: "
                             "give t_end [s]")
        bound = rules.time_to_rest(mode, y, *self.bias, self.friction_kinetic, self.g)
        if bound < 0:
            raise ValueError(f"the block never comes to rest after the excitation: kinetic friction "
                             f"mu_kinetic={self.friction_kinetic} does not exceed |bias|={math.hypot(*self.bias)}; "
                             "give t_end [s]")
        return bound

    def event(self, t, mode_before, mode_after, y):
        vx, vy = horizontal_velocity(mode_before, y)
        return PlanarEvent(t, mode_before, mode_after, float(y[_UX]), float(y[_UY]), float(vx), float(vy),
                           float(y[_WD]))

    def solution(self, *, t, y, mode, events, backend, dense, stats):
        return PlanarSolution(t=t, state=y, mode=mode, events=events, backend=backend, dense=dense,
                              stats=stats)


def _parameter(name, value):
    """A float, or a 1-D array of floats (a batch); finite."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number or a 1-D array of them, got {value!r}") from None
    if array.ndim > 1 or isinstance(value, bool):
        raise ValueError(f"{name} must be a real number or a 1-D array of them, got {value!r}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return float(array) if array.ndim == 0 else array


def _check(bad, name, value, message):
    """Raise naming ``name`` and its value in the first parameter set where ``bad``;
    ``message(index)`` says what is wrong."""
    if np.any(bad):
        index = (int(np.flatnonzero(bad)[0]),) if np.ndim(bad) else ()
        where = f" (parameter set {index[0]})" if index else ""
        shown = np.asarray(value)[index]
        shown = tuple(float(v) for v in shown) if shown.ndim else float(shown)
        raise ValueError(f"{name}={shown!r} {message(index)}{where}")


def _with(y, changes, xp=np):
    """``y`` with the components ``changes`` (index -> value) replaced."""
    if xp is np:
        y = np.array(y, dtype=float)
        for index, value in changes.items():
            y[index] = value
        return y
    return xp.stack([changes.get(index, y[index]) for index in range(len(y))])


class PlanarDAEForm:
    """:class:`PlanarBlock`: (u_x, u_y, s, c_x, c_y, w, w', F_x, F_y)."""

    n_states, n_friction = 7, 2

    def __init__(self, block, piece):
        if block.state_names != ("u_x", "u_y", "s", "c_x", "c_y", "w", "w_rate"):
            raise RuntimeError(f"the planar DAE form expects another state layout than {block.state_names}")
        self.block, self.piece = block, piece
        self.force_scale = block.mu * block.g

    def residual(self, mode):
        block, piece = self.block, self.piece

        def residual(t, y, yp, res):
            res[7:9] = y[7:9] - np.array(block.friction(mode, t, y, piece, SCALAR))
            res[:7] = yp[:7] - np.array(block.flow(mode, t, y, piece, SCALAR, friction=(y[7], y[8])))
            if mode == PlanarMode.SLIP:
                res[3:5] *= max(y[2], SLOW_SPEED)

        return residual

    def guards(self, mode, t, y, out):
        if mode == PlanarMode.STICK:
            n, _ = self.block.normal(t, self.piece, y)
            scale = self.block.guard_scale
            out[0], out[1] = scale * n, scale * (self.block.mu * n - math.sqrt(y[7] ** 2 + y[8] ** 2))
        else:
            out[:] = self.block.guards(mode, t, y, self.piece, SCALAR)

    def consistent(self, mode, t, y):
        """(y, y') at ``t``: y' from the model's flow, F from its friction; F' = d sigma/dt
        in stick, -f (n' e + n e') in slip, 0 in flight."""
        block, piece = self.block, self.piece
        rate = np.array(block.flow(mode, t, y, piece, SCALAR), dtype=float)
        friction = block.friction(mode, t, y, piece, SCALAR)
        if mode == PlanarMode.STICK:
            friction_rate = block.demand(t, piece)[1]
        elif mode == PlanarMode.SLIP:
            n, n_rate = block.normal(t, piece, y)
            size = math.sqrt(y[3] ** 2 + y[4] ** 2)
            friction_rate = tuple(-block.friction_kinetic * (n_rate * c + n * c_rate) / size
                                  for c, c_rate in ((y[3], rate[3]), (y[4], rate[4])))
        else:
            friction_rate = (0.0, 0.0)
        return np.concatenate([y, friction]), np.concatenate([rate, friction_rate])
