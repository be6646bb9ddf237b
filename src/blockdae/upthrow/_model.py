"""A compact mass on a unilateral spring-dashpot support, shaken vertically (Newmark 1969,
Newmark on upthrow).

The support has natural circular frequency omega = 2 pi f [rad/s], damping ratio zeta
and static deflection u0 = g / omega² [m]. With the vertical base acceleration y''(t)
[m/s², upward positive] and u = x - y the displacement of the mass relative to the
ground from its static position (upward positive), the support force per unit mass
(compression positive) is

    n = omega² (u0 - u) - 2 zeta omega u'            [m/s²],

and Newton's law reads u'' = n - g - y''. In CONTACT this is the oscillator
u'' + 2 zeta omega u' + omega² u = -y'' (seed eq. 4 with damping); it holds while n > 0.
When n reaches 0 from above the mass flies (n = 0: u'' = -g - y'').

Landing rule: the support is the clamped Kelvin-Voigt law, n = max(0, omega² (u0 - u)
- 2 zeta omega u') while the mass is within the unloaded length (u <= u0), and 0
above it. Contact therefore resumes when the mass is at or below u0 and the law pushes:
a falling mass lands where u returns to u0 from above (n = -2 zeta omega u' > 0 there,
so contact is consistent); with damping a mass can lift off below u0 (the dashpot pulls
it off while the spring still pushes) and, if it does not rise above u0, it lands while
still rising, where the law's n returns to 0 from below. Without damping both reduce to
the paper's rule: separation and landing at u = u0.

The law and the landing rows are :class:`~blockdae.SpringSupport`'s, which a
:class:`~blockdae.PlanarBlock` can stand on too (one rule for both).

Flight is split at its top (u' = 0) into FLIGHT_UP and FLIGHT_DOWN so that every guard
is affine in the state (u, u') within a mode: the top of each flight is then a located
event like liftoff and landing.
"""

import dataclasses
import math

import numpy as np

from ..units import STANDARD_GRAVITY
from ._solution import UpthrowEvent, UpthrowSolution
from ..core.contract import (KNOTS_PER_RADIAN, SCALAR, BatchedModel, DifferentiableModel, LinearModesModel,
                             scale_factor_units)
from ..core import set_batch_fields, set_real_fields
from ._modes import EVENT_KINDS, UpthrowMode
from ._support import SpringSupport

_U, _V = range(2)


@dataclasses.dataclass(frozen=True, eq=False)
class SpringSupportedMass(LinearModesModel, DifferentiableModel, BatchedModel):
    """A mass resting on a unilateral spring-dashpot support under vertical ground motion.

    Args:
        frequency: natural frequency f of the mass on its support [Hz], > 0.
        damping: damping ratio zeta of the support [-], in [0, 1).
        g: gravitational acceleration [m/s²], > 0.

    ``frequency`` and ``damping`` may be 1-D arrays of one size (or one of them a
    number): a batch of parameter sets, which :func:`blockdae.simulate` runs into a
    :class:`~blockdae.core.BatchSolution` (``item(i)``: set i as a model of its own).

    The excitation's component 0 is the vertical ground acceleration y''(t) [m/s²,
    upward positive]. State y = (u [m], u' [m/s]).
    """

    frequency: float
    damping: float = 0.0
    g: float = STANDARD_GRAVITY

    state_names = ("u", "u_rate")
    state_units = ("m", "m/s")
    modes = UpthrowMode
    initial_mode = UpthrowMode.CONTACT
    horizontal_motion = False  # shaken vertically: a vertical component is its motion
    default_backend = "exact"
    engines = {"exact": "linear"}
    differentiates_displacement = False  # the derivatives of its flights

    def __post_init__(self):
        shape = set_batch_fields(self, ("frequency", "damping"))
        set_real_fields(self, ("g",))
        object.__setattr__(self, "_batch_shape", shape)
        if not shape:
            SpringSupport(self.frequency, self.damping)  # validates frequency and damping
        else:
            for i, (frequency, damping) in enumerate(zip(*self._batch_arrays())):
                try:
                    SpringSupport(float(frequency), float(damping))
                except ValueError as error:
                    raise ValueError(f"parameter set {i}: {error}") from None
        if self.g <= 0:
            raise ValueError(f"g={self.g!r} must be > 0 [m/s²]")

    @classmethod
    def from_static_deflection(cls, u0, damping=0.0, g=STANDARD_GRAVITY) -> "SpringSupportedMass":
        """The mass whose support deflects by ``u0`` [m] under its weight (seed eq. 9:
        f = sqrt(g / u0) / (2 pi))."""
        if isinstance(u0, bool) or not isinstance(u0, (int, float, np.floating, np.integer)) \
                or not math.isfinite(u0) or u0 <= 0:
            raise ValueError(f"u0={u0!r} must be a positive finite static deflection [m]")
        checked = cls(1.0, damping, g)  # validates damping and g
        return cls(math.sqrt(checked.g / u0) / (2 * math.pi), checked.damping, checked.g)

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """() for one parameter set, (n,) for a batch of n."""
        return getattr(self, "_batch_shape", ())  # a model of traced parameters has none

    def _batch_arrays(self):
        """(frequency, damping), each of shape ``batch_shape``."""
        return tuple(np.broadcast_to(np.asarray(p, dtype=float), self.batch_shape) for p in (self.frequency,
                                                                                           self.damping))

    def item(self, index: int) -> "SpringSupportedMass":
        """Parameter set ``index`` of a batch, as a model of one set."""
        frequency, damping = (float(p[index]) for p in self._batch_arrays())
        return dataclasses.replace(self, frequency=frequency, damping=damping)

    parameter_labels = {"frequency": "support frequency f [Hz]", "damping": "support damping ratio zeta [-]"}

    def batch_parameters(self) -> dict:
        """frequency [Hz] and damping [-], each of shape ``batch_shape``."""
        return dict(zip(("frequency", "damping"), self._batch_arrays()))

    @property
    def support(self) -> SpringSupport:
        """The spring-dashpot support, whose law and landing rule this model follows."""
        return SpringSupport.unchecked(self.frequency, self.damping)

    @property
    def omega(self) -> float:
        """Natural circular frequency omega = 2 pi f [rad/s]."""
        return self.support.omega

    @property
    def static_deflection(self) -> float:
        """u0 = g / omega² [m] (seed eq. 5)."""
        return self.support.static_deflection(self.g)

    #: the paper's name for the static deflection [m]
    u0 = static_deflection

    def replace(self, **changes) -> "SpringSupportedMass":
        """A copy with some parameters changed (validated again)."""
        return dataclasses.replace(self, **changes)

    # ---- the physics, affine in the state within a mode ---------------------
    def linear_flow(self, mode):
        """(k [1/s²], c [1/s], b [m/s²]) of u'' + c u' + k u = b - y''(t) in ``mode``."""
        if mode == UpthrowMode.CONTACT:
            return (*self.support.stiffness(), 0.0)
        return 0.0, 0.0, -self.g

    def affine_guards(self, mode):
        """The guards of ``mode`` as rows (alpha, beta, gamma): alpha u + beta u' + gamma.

        CONTACT: (n / omega² -> liftoff). FLIGHT_UP: (u' -> top, -n / omega² -> landing
        while rising). FLIGHT_DOWN: (u - u0 -> landing, -u' -> rising again).
        """
        liftoff, rising_landing, falling_landing = self.support.law_rows(self.g)
        if mode == UpthrowMode.CONTACT:
            return (liftoff,)
        if mode == UpthrowMode.FLIGHT_UP:
            return ((0.0, 1.0, 0.0), rising_landing)
        return (falling_landing, (0.0, -1.0, 0.0))

    def support_force(self, mode, t, y, excitation, xp=np):
        """n [m/s²] the support exerts per unit mass (compression positive; 0 in flight)."""
        if mode == UpthrowMode.CONTACT:
            return self.support.law(self.g, y[_U], y[_V])
        return 0.0 * y[_U]

    def relative_acceleration(self, t, force, excitation):
        """u'' = n - g - y''(t) [m/s²] with the support force ``force`` per unit mass."""
        return force - self.g - excitation.acceleration(t)

    # ---- hybrid automaton ----------------------------------------------------
    def flow(self, mode, t, y, excitation, xp=np):
        """(u', u'') in ``mode``."""
        k, c, b = self.linear_flow(mode)
        return xp.stack([y[_V], b - k * y[_U] - c * y[_V] - excitation.acceleration(t)])

    def guards(self, mode, t, y, excitation, xp=np):
        """The affine guards of ``mode`` (see :meth:`affine_guards`), each left when it
        crosses zero downwards."""
        return xp.stack([alpha * y[_U] + beta * y[_V] + gamma for alpha, beta, gamma in self.affine_guards(mode)])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        """A mass at rest on its support is in contact."""
        return UpthrowMode.CONTACT

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        """Contact -> FLIGHT_UP at liftoff; FLIGHT_UP -> FLIGHT_DOWN at the top or
        CONTACT at a rising landing; FLIGHT_DOWN -> CONTACT at landing or FLIGHT_UP
        when it rises again (base falling faster than g)."""
        if mode == UpthrowMode.CONTACT:
            return UpthrowMode.FLIGHT_UP
        if mode == UpthrowMode.FLIGHT_UP:
            return UpthrowMode.FLIGHT_DOWN if guard_index == 0 else UpthrowMode.CONTACT
        return UpthrowMode.CONTACT if guard_index == 0 else UpthrowMode.FLIGHT_UP

    # ---- what the hybrid driver asks -----------------------------------------
    def is_static(self, mode):
        return False

    def at_rest(self, mode, y):
        return False

    def rest_state(self, y):
        return np.array([y[_U], 0.0])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """A top or bottom has u' = 0 and a falling landing u = u0, exactly."""
        if mode != UpthrowMode.CONTACT and (mode == UpthrowMode.FLIGHT_UP) == (guard_index == 0):
            return xp.stack([y[_U], 0.0 * y[_V]])
        if mode == UpthrowMode.FLIGHT_DOWN:
            return xp.stack([0.0 * y[_U] + self.static_deflection, y[_V]])
        return y

    # ---- parameters, for JAX (compiled rules, derivatives) ------------------
    def parameters(self):
        """frequency [Hz], damping [-], g [m/s²]."""
        return {"frequency": self.frequency, "damping": self.damping, "g": self.g}

    def with_parameters(self, values):
        values = {**self.parameters(), **values}
        model = object.__new__(SpringSupportedMass)
        for name, value in values.items():
            object.__setattr__(model, name, value)
        return model

    # ---- derivatives (its own: of its flights) --------------------------------
    def default_wrt(self) -> tuple[str, ...]:
        """("frequency", "damping", "A")."""
        return ("frequency", "damping", "A")

    def parameter_units(self) -> dict:
        """frequency [Hz], damping [-], g [m/s²], A [g] and the scale factor of its motion [-]."""
        return {"frequency": "Hz", "damping": "-", "g": "m/s²", **scale_factor_units(self)}

    def sensitivities(self, motion, t_end, wrt, backend, of, options):
        """The derivatives of its flights, a :class:`~blockdae.Sensitivities` of the
        quantities ``of`` (see :func:`blockdae.sensitivities`)."""
        from ._sensitivities import flight_sensitivities

        return flight_sensitivities(self, motion, t_end, wrt, backend, of, options)

    def turn_rate(self, mode, t, y, excitation, xp=np):
        """None: the driver's knots (:meth:`output_step`) and the solvers' steps
        resolve the oscillation; the exact backend brackets every root itself."""
        return None

    def output_step(self):
        """Largest gap between dense-output knots [s]: 1 / (32 omega)."""
        return 1.0 / (KNOTS_PER_RADIAN * self.omega)

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(rate, curvature) of the guard from u', u'' and u''' of the flow."""
        alpha, beta, _ = self.affine_guards(mode)[guard_index]
        k, c, _ = self.linear_flow(mode)
        accel = self.flow(mode, t, y, excitation, SCALAR)[1]
        jerk = -k * y[_V] - c * accel - excitation.acceleration_rate(t)
        return alpha * y[_V] + beta * accel, alpha * accel + beta * jerk

    def contradiction(self, mode, y, velocity_error):
        """A rising flight that falls, or a falling one that rises: u' [m/s] of the
        wrong sign."""
        side = {UpthrowMode.FLIGHT_UP: 1, UpthrowMode.FLIGHT_DOWN: -1}.get(mode, 0)
        if side * y[_V] < -velocity_error:
            return f"u' = {y[_V]:+.6g} m/s points against {mode.name}"
        return None

    def speed(self, y):
        return abs(float(y[_V]))

    def time_to_rest(self, mode, y):
        raise ValueError("a mass on springs never comes to rest exactly after the excitation: give t_end [s]")

    def dae_form(self, piece):
        """(u, u', N) with the support force N as IDA's algebraic variable (:class:`SpringDAEForm`)."""
        return SpringDAEForm(self, piece)

    def event(self, t, mode_before, mode_after, y):
        return UpthrowEvent(float(t), mode_before, mode_after, EVENT_KINDS[(mode_before, mode_after)],
                            float(y[_U]), float(y[_V]), float(y[_U]) - self.static_deflection)

    def solution(self, *, t, y, mode, events, backend, dense, stats):
        return UpthrowSolution(t=t, state=y, mode=mode, events=events, backend=backend, dense=dense,
                               stats=stats)


class SpringDAEForm:
    """:class:`SpringSupportedMass`: (u, u', N), N the support force per unit mass
    [m/s²] (the model's ``support_force``: its law in contact, 0 in flight)::

        u' = u_rate,    u_rate' = relative_acceleration(t, N),    0 = N - support_force.

    The contact guard is N itself; the flight guards are the model's.
    """

    n_states, n_friction = 2, 1

    def __init__(self, block, piece):
        self.block, self.piece = block, piece
        self.force_scale = block.g

    def residual(self, mode):
        block, piece = self.block, self.piece

        def residual(t, y, yp, res):
            res[0] = yp[0] - y[1]
            res[1] = yp[1] - block.relative_acceleration(t, y[2], piece)
            res[2] = y[2] - block.support_force(mode, t, y, piece, SCALAR)

        return residual

    def guards(self, mode, t, y, out):
        if mode == UpthrowMode.CONTACT:
            out[0] = y[2]
        else:
            out[:] = self.block.guards(mode, t, y, self.piece, SCALAR)

    def consistent(self, mode, t, y):
        """(y, y') at ``t``: N from the model; N' from its law, affine in the state, at
        the rate (u', u'') minus its value at zero."""
        block, piece = self.block, self.piece
        rate = np.array(block.flow(mode, t, y, piece, SCALAR), dtype=float)
        force = block.support_force(mode, t, y, piece, SCALAR)
        force_rate = block.support_force(mode, t, rate, piece, SCALAR) - block.support_force(
            mode, t, np.zeros(2), piece, SCALAR)
        return np.array([y[0], y[1], force]), np.array([y[1], rate[1], force_rate])
