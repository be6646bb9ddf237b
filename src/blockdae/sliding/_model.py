"""The 1-D rigid block on an accelerating base (Sawicki & Chybicki 2005), as a hybrid automaton.

State y = (u, v): displacement and velocity of the block relative to its base
[m, m/s]. With the base acceleration a(t) [m/s²] and the bias R/Q (a constant force
on the block in +x as a fraction of its weight), the friction force per unit mass the
base must supply to carry the block along is the *demand*

    sigma(t) = a(t) - (R/Q) g            [m/s²].

Stick holds while |sigma| <= mu g. In slip+ / slip- the kinetic friction f g opposes
the relative velocity, so dv/dt = (R/Q -/+ f) g - a(t).
"""

import copy
import dataclasses

import numpy as np

from ..units import STANDARD_GRAVITY
from ._solution import Event, Solution
from ..core import LazyEngine
from ..core.contract import SCALAR, BatchedModel, DifferentiableModel, EngineModel, StudyModel
from ._modes import Mode

_DIRECTIONS = ("both", "positive", "negative")
#: the names a block is differentiated by -> their units ("A": the peak of a(t) in g;
#: "scale": a factor on a(t))
PARAMETER_UNITS = {"mu": "-", "mu_kinetic": "-", "bias": "-", "A": "g", "scale": "-"}
#: the names differentiated by default
DEFAULT_WRT = ("mu", "mu_kinetic", "bias", "A")


def demand(a, bias, g):
    """Friction force per unit mass needed to carry the block with the base [m/s²]."""
    return a - bias * g


def slip_constant(mode, bias, mu_kinetic, g):
    """The part of dv/dt that does not depend on a(t) in a slip mode [m/s²]."""
    return (bias - mode * mu_kinetic) * g


def relative_acceleration(mode, a, bias, mu_kinetic, g, xp):
    """dv/dt [m/s²] in ``mode`` under base acceleration ``a`` [m/s²]: zero in stick,
    slip_constant - a while sliding."""
    dv = slip_constant(mode, bias, mu_kinetic, g) - a
    return xp.where(mode == 0, 0.0 * dv, dv)


def comes_to_rest(v, mode, bias, mu_kinetic, g):
    """Whether a block sliding at ``v`` [m/s] in ``mode`` stops once a(t) = 0: dv/dt is
    then the constant slip_constant, so it stops iff that opposes v (or v = 0)."""
    return (v == 0) | (v * slip_constant(mode, bias, mu_kinetic, g) < 0)


def never_rests_error(block, where: str = "") -> ValueError:
    """The error for a block that slides on forever after a finite excitation."""
    return ValueError(
        f"the block never comes to rest after the excitation{where}: kinetic friction "
        f"mu_kinetic={block.friction_kinetic} does not exceed |bias|={abs(block.bias)}; give t_end [s]")


def rest_mode(sigma, sigma_rate, mu, g, allow_neg, allow_pos, xp):
    """Mode of a block at rest (v = 0) under friction demand ``sigma`` [m/s²].

    Static friction holds while |sigma| <= mu g. On the threshold itself the rate
    ``sigma_rate`` [m/s³] decides: the block slides only if the demand is moving
    outwards, so a demand that touches the threshold and turns back never slides.
    """
    limit = mu * g
    neg = (sigma > limit) | ((sigma == limit) & (sigma_rate > 0))
    pos = (sigma < -limit) | ((sigma == -limit) & (sigma_rate < 0))
    return xp.where(neg & allow_neg, -1, xp.where(pos & allow_pos, 1, 0))


def stick_guards(friction, mu, g, allow_neg, allow_pos, xp):
    """Stick guards on the friction force per unit mass ``friction`` [m/s²] that holds
    the block: (mu g - F -> slip-, mu g + F -> slip+); a disallowed side is the constant 1."""
    limit = mu * g
    return xp.stack([xp.where(allow_neg, limit - friction, 1.0),
                     xp.where(allow_pos, limit + friction, 1.0)])


def stop_mode(mode, slip_rate, sigma_rate, t_stop, mu, f, g, allow_neg, allow_pos, xp, time_tol=0.0):
    """Mode after v returns to zero in slip ``mode`` at ``t_stop`` [s].

    ``slip_rate`` is dv/dt there [m/s²]; it cannot point away from rest, so the
    demand is sigma = -mode f g - slip_rate with rounding projected out. The block
    then takes :func:`rest_mode`, except where it would stick but the demand
    (rate ``sigma_rate`` [m/s³]) crosses a threshold outwards within ``time_tol`` [s]
    of the stop (``time_tol`` = 0: within rounding of ``t_stop``), as :func:`rest_mode`
    does for a demand exactly at a threshold: the same threshold is a graze (f = mu,
    v touches zero there) and the block keeps sliding; the other one is a reversal.
    """
    r = xp.where(mode * slip_rate > 0, 0.0, slip_rate)
    sigma = -mode * f * g - r
    after = rest_mode(sigma, sigma_rate, mu, g, allow_neg, allow_pos, xp)

    def crossed_soon(side):  # the threshold on ``side`` is reached outwards in time_tol
        outward = side * sigma_rate > 0
        wait = (side * mu * g - sigma) / xp.where(outward, sigma_rate, 1.0)
        allowed = xp.where(side > 0, allow_neg, allow_pos)
        return (after == 0) & outward & ((t_stop + wait) - t_stop <= time_tol) & allowed

    return xp.where(crossed_soon(-mode), mode, xp.where(crossed_soon(mode), -mode, after))


@dataclasses.dataclass(frozen=True, eq=False)
class SlidingBlock(BatchedModel, DifferentiableModel, EngineModel, StudyModel):
    """Rigid block on a base that accelerates along x (Sawicki & Chybicki 2005).

    Args:
        mu: static friction coefficient [-]; decides onset and re-sticking.
        mu_kinetic: kinetic friction coefficient f [-], acting while sliding;
            defaults to ``mu``. Must satisfy 0 <= f <= mu.
        bias: R/Q, a constant force on the block in +x as a fraction of its
            weight [-]. Must satisfy |bias| < mu (else it slides with the base at rest);
            mu = bias = 0 is a frictionless block, which never comes to rest once it
            moves (give ``t_end``).
        g: gravitational acceleration [m/s²]; standard gravity (9.80665) by default,
            the value the record readers use for the unit "g".
        direction: "both", or "positive"/"negative" to allow sliding only with u
            increasing / decreasing ("negative" with bias 0 is one-way Newmark).

    ``mu``, ``mu_kinetic`` and ``bias`` may be 1-D arrays (broadcast together): the
    block is then a batch of parameter sets, solved in one compiled call.
    """

    mu: float | np.ndarray
    mu_kinetic: float | np.ndarray | None = None
    bias: float | np.ndarray = 0.0
    g: float = STANDARD_GRAVITY
    direction: str = "both"

    state_names = ("u", "v")
    modes = Mode
    initial_mode = Mode.STICK
    default_backend = "exact"
    engines = {"exact": LazyEngine("blockdae.sliding._exact", "ExactEngine"),
               "exact-jax": LazyEngine("blockdae.sliding._exact_jax", "ExactJaxEngine"),
               "jax": LazyEngine("blockdae.sliding._twin", "TwinEngine")}
    differentiated_backends = ("exact", "exact-jax", "jax")

    def __post_init__(self):
        for name in ("mu", "mu_kinetic", "bias"):
            value = getattr(self, name)
            if value is None:
                continue
            array = np.asarray(value, dtype=float)
            if array.ndim > 1:
                raise ValueError(f"{name} must be a scalar or a 1-D array, got shape {array.shape}")
            if not np.all(np.isfinite(array)):
                raise ValueError(f"{name} must be finite, got {value!r}")
            object.__setattr__(self, name, float(array) if array.ndim == 0 else array)
        try:
            mu, f, bias = np.broadcast_arrays(self.mu, self.friction_kinetic, self.bias)
        except ValueError as err:
            raise ValueError(
                f"mu, mu_kinetic and bias must broadcast together: {err}") from None
        object.__setattr__(self, "_batch_shape", mu.shape)
        if not (np.isfinite(self.g) and self.g > 0):
            raise ValueError(f"g must be a positive acceleration [m/s²], got {self.g!r}")
        if self.direction not in _DIRECTIONS:
            raise ValueError(f"direction must be one of {_DIRECTIONS}, got {self.direction!r}")
        _check(mu < 0, "mu", mu, "must be >= 0")
        _check(f < 0, "mu_kinetic", f, "must be >= 0")
        _check(f > mu, "mu_kinetic", f,
               lambda bad: f"must not exceed mu={_first(mu, bad)} (kinetic above static friction chatters)")
        frictionless = (mu == 0) & (bias == 0)
        _check((np.abs(bias) >= mu) & ~frictionless, "bias", bias,
               lambda bad: f"must satisfy |bias| < mu={_first(mu, bad)} (else the block slides with the base at rest)")

    @classmethod
    def on_incline(cls, slope_angle, friction_angle, kinetic_friction_angle=None,
                   g=STANDARD_GRAVITY, direction="positive") -> "SlidingBlock":
        """A block on a plane inclined at ``slope_angle`` [degrees], shaken along the slope.

        x points downslope along the plane; the base acceleration is along the slope.
        The normal force is g cos(alpha) and gravity pulls downslope with g sin(alpha),
        so per unit of g: ``mu = tan(phi) cos(alpha)``, ``bias = sin(alpha)`` (likewise
        ``mu_kinetic`` from ``kinetic_friction_angle``). It slides downslope (u > 0)
        while the base accelerates upslope by more than
        k_y g = (tan(phi) cos(alpha) - sin(alpha)) g = (FS - 1) sin(alpha) g with
        FS = tan(phi) / tan(alpha) (Newmark 1965; Jibson 1993, eq. 2).

        Args:
            slope_angle: alpha [degrees], 0 <= alpha < friction_angle.
            friction_angle: static friction angle phi [degrees], < 90.
            kinetic_friction_angle: kinetic friction angle [degrees] (default phi).
            g: gravitational acceleration [m/s²].
            direction: "positive" (downslope only, the default) or "both".
        """
        alpha, phi = np.radians(float(slope_angle)), np.radians(float(friction_angle))
        if not 0 <= phi < np.pi / 2:
            raise ValueError(f"friction_angle={friction_angle!r} must lie in [0, 90) degrees")
        if not 0 <= alpha < np.pi / 2:
            raise ValueError(f"slope_angle={slope_angle!r} must lie in [0, 90) degrees")
        if alpha >= phi:
            raise ValueError(f"slope_angle={slope_angle!r} must be below friction_angle={friction_angle!r} "
                             "(else the block slides under gravity alone)")
        kinetic = None if kinetic_friction_angle is None else (
            np.tan(np.radians(float(kinetic_friction_angle))) * np.cos(alpha))
        return cls(mu=np.tan(phi) * np.cos(alpha), mu_kinetic=kinetic, bias=np.sin(alpha), g=g,
                   direction=direction)

    # ---- parameters --------------------------------------------------------
    @property
    def friction_kinetic(self):
        """Kinetic friction coefficient f [-] (``mu_kinetic``, or ``mu`` if None)."""
        return self.mu if self.mu_kinetic is None else self.mu_kinetic

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """() for one parameter set, (n,) for a batch of n."""
        return self._batch_shape

    @property
    def allow_negative(self) -> bool:
        """Whether slip- (u decreasing) is allowed."""
        return self.direction in ("both", "negative")

    @property
    def allow_positive(self) -> bool:
        """Whether slip+ (u increasing) is allowed."""
        return self.direction in ("both", "positive")

    parameter_labels = {"mu": "static friction coefficient mu [-]", "mu_kinetic": "kinetic friction coefficient f [-]",
                        "bias": "bias force R/Q [-]"}

    def tied_parameters(self) -> dict:
        """mu moves the kinetic friction too when ``mu_kinetic`` is None."""
        return {"mu": ("mu_kinetic",)} if self.mu_kinetic is None else {}

    def batch_parameters(self) -> dict:
        """The grid: mu, mu_kinetic (the coefficient in effect) and bias [-], each of
        shape ``batch_shape``."""
        values = (self.mu, self.friction_kinetic, self.bias)
        return {name: np.broadcast_to(np.asarray(p, dtype=float), self.batch_shape)
                for name, p in zip(("mu", "mu_kinetic", "bias"), values)}

    def engine_parameters(self, scale=(1.0,)) -> np.ndarray:
        """The 1-D engines' one parameter packing: (m * s, 5) rows of (mu, f, bias [-],
        g [m/s²], scale [-]) for the m parameter sets (1 for one set), each at the s
        factors of ``scale`` on a(t); set j at factor k is row j * s + k."""
        scale = np.asarray(scale, dtype=float).ravel()
        m = self.batch_shape[0] if self.batch_shape else 1
        rows = np.empty((m, scale.size, 5))
        for column, x in enumerate((self.mu, self.friction_kinetic, self.bias, self.g)):
            rows[:, :, column] = x.reshape(-1, 1) if isinstance(x, np.ndarray) else x
        rows[:, :, 4] = scale
        return rows.reshape(m * scale.size, 5)

    def engine_parameter_set(self) -> tuple[float, float, float, float, float]:
        """The row of :meth:`engine_parameters` of a block of one parameter set, as floats:
        (mu, f, bias [-], g [m/s²], scale 1 [-])."""
        return float(self.mu), float(self.friction_kinetic), float(self.bias), float(self.g), 1.0

    def item(self, index: int) -> "SlidingBlock":
        """The ``index``-th parameter set of a batch, as a scalar block (whose
        ``mu_kinetic`` stays None, following ``mu``, where the batch's does)."""
        mu, f, bias = (np.broadcast_to(p, self.batch_shape)[index]
                       for p in (self.mu, self.friction_kinetic, self.bias))
        return dataclasses.replace(self, mu=float(mu), mu_kinetic=None if self.mu_kinetic is None else float(f),
                                   bias=float(bias))

    def replace(self, **changes) -> "SlidingBlock":
        """A copy with some parameters changed (validated again)."""
        return dataclasses.replace(self, **changes)

    # ---- derivatives: its own, through the compiled kernels (``sensitivities`` and
    # ``finite_differences`` are attached by the package: the kernels import this module)
    def default_wrt(self) -> tuple[str, ...]:
        """("mu", "mu_kinetic", "bias", "A")."""
        return DEFAULT_WRT

    def parameter_units(self) -> dict:
        """mu, mu_kinetic, bias, scale [-] and A [g]."""
        return dict(PARAMETER_UNITS)

    def parameters(self) -> dict:
        """What :func:`bd.sensitivities` differentiates it by (besides the motion's A and
        scale): mu, mu_kinetic (f, the coefficient in effect), bias [-]."""
        return {"mu": self.mu, "mu_kinetic": self.friction_kinetic, "bias": self.bias}

    def with_parameters(self, values) -> "SlidingBlock":
        """This block with ``values`` (names of :meth:`parameters`), not validated; its
        ``mu_kinetic`` stays None (following mu) unless ``values`` gives it."""
        model = copy.copy(self)
        for name in ("mu", "mu_kinetic", "bias"):
            if name in values:
                object.__setattr__(model, name, values[name])
        object.__setattr__(model, "_batch_shape",
                           np.broadcast_shapes(*(np.shape(p) for p in (model.mu, model.friction_kinetic, model.bias))))
        return model

    #: what :func:`bd.study` sweeps: its keyword, the table's column, the unit
    study_parameter = ("mu", "mu", "-")
    #: a given block is studied under the motions as given
    study_polarities = ("normal",)

    def study_parameter_for(self, given) -> tuple[str, str, str]:
        """ky [g] (column ky_g) where ``ky`` alone is given to a block without bias (Newmark's
        rigid block: it slides where a(t) > ky g, mu = ky); else mu [-]."""
        if given.get("ky") is not None and given.get("mu") is None and np.all(np.asarray(self.bias) == 0):
            return "ky", "ky_g", "g"
        return self.study_parameter

    def study_batch(self, mu) -> "SlidingBlock":
        """This block at every friction coefficient ``mu`` [-] (1-D), for :func:`bd.study`
        (checks them against the other parameters)."""
        return self.replace(mu=mu)

    def study_columns(self, motions, t_end, scale, rtol=None) -> dict:
        """What :func:`bd.study` tabulates of this block (a batch of m parameter sets)
        on ``motions`` at the factors ``scale`` on a(t) [-]: one row per motion x set x
        factor, from the exact engine (``rtol`` is not used: nothing is integrated).
        A block sliding one way downslope (direction "negative"): D_m (the downslope
        displacement at the end, -u >= 0 [m]); else u_end_m (the signed u at the end [m]);
        then max_abs_displacement_m [m], n_events, n_slips (slip episodes, a block that
        slides one way: there stick and slip alternate, so n_slips = ceil(n_events / 2)),
        t_end_s [s]."""
        from ..core import Horizon, make_backend

        horizons = [Horizon.resolve(motion, t_end) for motion in motions]
        out = make_backend("exact").solve_final(self, list(motions), horizons, np.asarray(scale, dtype=float))
        u, n_events = out[..., 0].ravel(), out[..., 4].ravel().astype(int)
        end = dict(D_m=0.0 - u) if self.direction == "negative" else dict(u_end_m=u)  # 0.0 - u: no -0.0
        slips = {} if self.direction == "both" else dict(n_slips=(n_events + 1) // 2)
        return dict(**end, max_abs_displacement_m=out[..., 3].ravel(), n_events=n_events, **slips,
                    t_end_s=out[..., 5].ravel())

    # ---- hybrid automaton --------------------------------------------------
    def demand(self, t, excitation, xp=np):
        """Friction demand sigma(t) = a(t) - bias g [m/s²]."""
        return demand(excitation.acceleration(t), self.bias, self.g)

    def flow(self, mode, t, y, excitation, xp=np):
        """dy/dt = (v, dv/dt) in ``mode``; dv/dt = 0 in stick [m/s, m/s²]."""
        a = excitation.acceleration(t)
        return xp.stack([y[1], relative_acceleration(mode, a, self.bias, self.friction_kinetic, self.g, xp)])

    def guards(self, mode, t, y, excitation, xp=np):
        """Guards of ``mode``; each leaves the mode when it crosses zero downwards.

        Stick: (mu g - sigma) -> slip-, (mu g + sigma) -> slip+ (a guard of a
        disallowed direction is the constant 1). Slip+/-: (mode * v) -> stop.
        """
        if mode == Mode.STICK:
            return stick_guards(self.demand(t, excitation, xp), self.mu, self.g,
                                self.allow_negative, self.allow_positive, xp)
        return xp.stack([mode * y[1]])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        """Mode of the block at rest at ``t``, from the right-hand limits of a(t)."""
        return rest_mode(self.demand(t, excitation, xp), excitation.acceleration_rate(t),
                         self.mu, self.g, self.allow_negative, self.allow_positive, xp)

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        """Stick guard 0 -> slip-, guard 1 -> slip+; a slip stop -> :func:`stop_mode`.

        At a stop the relative acceleration cannot point away from rest, so the
        demand is at most f g on the stopping side; a reversal needs it beyond the
        other threshold; a threshold crossed outwards within ``time_tol`` [s] grazes
        on or reverses.
        """
        if mode == Mode.STICK:
            return Mode.SLIP_NEG if guard_index == 0 else Mode.SLIP_POS
        slip_rate = self.flow(mode, t, y, excitation, xp)[1]
        return Mode(int(stop_mode(mode, slip_rate, excitation.acceleration_rate(t), t, self.mu,
                                  self.friction_kinetic, self.g, self.allow_negative,
                                  self.allow_positive, xp, time_tol)))

    # ---- what the hybrid driver asks -----------------------------------------
    def is_static(self, mode):
        return mode == Mode.STICK

    def at_rest(self, mode, y):
        return mode == Mode.STICK or y[1] == 0

    def rest_state(self, y):
        return np.array([y[0], 0.0])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """A slip stop has v = 0 by definition; stick guards leave the state."""
        return y if mode == Mode.STICK else np.array([y[0], 0.0])

    def turn_rate(self, mode, t, y, excitation, xp=np):
        """In slip, dv/dt (monotone on a piece, so that v is monotone between its sign
        changes); stick guards are monotone on a piece (None)."""
        return None if mode == Mode.STICK else self.flow(mode, t, y, excitation, xp)[1]

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """The stop guard's (mode v) rate mode dv/dt and curvature -mode da/dt [m/s², m/s³]."""
        return mode * self.flow(mode, t, y, excitation, np)[1], -mode * excitation.acceleration_rate(t)

    def contradiction(self, mode, y, velocity_error):
        """A slide whose velocity points against it: v [m/s] of the other sign."""
        if mode != Mode.STICK and mode * y[1] < -velocity_error:
            return f"v = {y[1]:+.6g} m/s points against the slide"
        return None

    def speed(self, y):
        return abs(y[1])

    def time_to_rest(self, mode, y):
        """dv/dt is constant once a(t) = 0: the stop is half of 2 |v / (dv/dt)| [s]."""
        if not comes_to_rest(y[1], mode, self.bias, self.friction_kinetic, self.g):
            raise never_rests_error(self)
        return 2.0 * abs(y[1] / slip_constant(mode, self.bias, self.friction_kinetic, self.g))

    def dae_form(self, piece):
        """(u, v, F) with the friction force F as IDA's algebraic variable (:class:`SlidingDAEForm`)."""
        return SlidingDAEForm(self, piece)

    def event(self, t, mode_before, mode_after, y):
        return Event(t, mode_before, mode_after, float(y[0]), float(y[1]))

    def solution(self, *, t, y, mode, events, backend, dense, stats):
        return Solution(t=t, u=y[:, 0], v=y[:, 1], mode=mode, events=events, backend=backend, dense=dense,
                        stats=stats)


def _first(values, mask):
    """The first value where ``mask`` holds, as a float."""
    return float(np.asarray(values)[np.asarray(mask)].flat[0]) if np.any(mask) else values


def _check(bad, name, values, message):
    """ValueError where any of ``bad`` holds, naming the first bad value; ``message`` a text,
    or a function of ``bad`` giving it (built only on failure: models are built per call)."""
    if np.any(bad):
        raise ValueError(f"{name}={_first(values, bad)!r} {message(bad) if callable(message) else message}")


class SlidingDAEForm:
    """:class:`SlidingBlock`: (u, v, F)."""

    n_states, n_friction = 2, 1

    def __init__(self, block, piece):
        self.block, self.piece = block, piece
        self.force_scale = block.mu * block.g

    def residual(self, mode):
        block, piece = self.block, self.piece

        def residual(t, y, yp, res):
            sigma = block.demand(t, piece, SCALAR)
            res[0] = yp[0] - y[1]
            res[1] = yp[1] - (y[2] - sigma)
            res[2] = y[2] - sigma - block.flow(mode, t, y, piece, SCALAR)[1]

        return residual

    def guards(self, mode, t, y, out):
        block = self.block
        if mode == Mode.STICK:
            out[:] = stick_guards(y[2], block.mu, block.g, block.allow_negative, block.allow_positive, SCALAR)
        else:
            out[:] = block.guards(mode, t, y, self.piece, SCALAR)

    def consistent(self, mode, t, y):
        """(y, y') at ``t``: F from the algebraic equation; F' = da/dt in stick
        (F = sigma) and 0 in slip (F constant)."""
        rate = self.block.flow(mode, t, y, self.piece, SCALAR)[1]
        friction = self.block.demand(t, self.piece, SCALAR) + rate
        friction_rate = self.piece.acceleration_rate(t) if mode == Mode.STICK else 0.0
        return np.array([y[0], y[1], friction]), np.array([y[1], rate, friction_rate])
