"""IDA backend: the natural DAE with the friction force as an algebraic variable.

The model's states y are followed by the friction force per unit mass the base exerts
on the block, F [m/s²] (one component per horizontal axis of the model), an algebraic
variable. With the demand sigma(t) (the model's ``demand``), Newton's law reads

    relative horizontal acceleration = F - sigma(t),

and the mode's algebraic equation fixes F. The DAE form of each model type:

* :class:`~blockdae.SlidingBlock`, states (u, v, F)::

      u' = v,    v' = F - sigma(t),    0 = F - (sigma(t) + dv/dt),

  so F = sigma in stick (v' = 0) and F = -mode f g in slip. Stick guards are the
  model's :func:`~blockdae.model.stick_guards` on the algebraic F; slip guards are
  mode * v.

* :class:`~blockdae.PlanarBlock`, states (u_x, u_y, s, c_x, c_y, w, w', F_x, F_y): the
  model's flow with the algebraic F in place of its friction (``flow(..., friction=F)``),
  0 = F - the model's ``friction`` (sigma in stick, -f n e in slip, 0 in flight). Stick
  guards are (n, mu n - |F|) on the algebraic F, times the model's ``guard_scale``; the
  others are the model's.

  The direction rows (c_x', c_y') are multiplied by max(s, SLOW_SPEED): the rate of e,
  (e_perp . (F - sigma)) / max(s, SLOW_SPEED), is stiff as s falls, and in this scaling
  IDA steps through every stop of Kobe TAK-090 x with Duzce 375-090 y at rtol 1e-10 to
  1e-12 (unscaled: out of steps at 1e-11) and of Elms's pulses.
"""

import dataclasses
import math

import numpy as np
from sksundae.ida import IDA

from .._driver import SCALAR
from ..model import Mode, PlanarBlock, PlanarMode, SlidingBlock, SpringSupportedMass, UpthrowMode, stick_guards
from ..model._planar import SLOW_SPEED
from ._sundials import Guards, SundialsBackend, SundialsIntegrator

#: IDA's first step after every (re)start [s]. IDA starts at order 1 and, while no step
#: fails, raises the order and doubles the step each step until its error estimates
#: say a lower order would do (its "phase 0"). Its own first step, 0.5 / ||y'||, is
#: ~1e-10 s at rtol 1e-10, where the 2nd and 3rd differences of u, v that this test
#: compares are rounding noise: in 12 % of the slip pieces (Chi-Chi, Kobe, Landers)
#: the order drops to 1 and the step keeps doubling at order 1 (no order raise while
#: the step changes) until the error reaches the tolerance, ~4e-10 in v per piece
#: (Chi-Chi one-way, mu 0.1: stop 2.4e-9 s off). From 1e-7 s the differences stand
#: above rounding (largest error in v over those 6848 pieces: 1.7e-11 m/s), while the
#: two order-1 steps commit ~h² |da/dt|, ~1e-14 m/s. Worst event-time error over the
#: 18 sample records at rtol 1e-10: 1.0e-9 s with IDA's own first step, 7.5e-11 s
#: from 1e-7 s. Smaller first steps are luck: 1e-8 s gives 1.1e-11 s there but
#: 5.4e-9 s on Chi-Chi one-way (mu 0.05), where rounding still decides the order.
FIRST_STEP = 1e-7


@dataclasses.dataclass(frozen=True)
class IDABackend(SundialsBackend):
    """SUNDIALS IDA on the hybrid driver; see :class:`SundialsBackend` for the settings
    (``rtol``, ``atol`` [m, m/s, m/s²], ``max_step`` [s], ...). IDA restarts at every
    piece of a(t), each time from a first step of :data:`FIRST_STEP` [s]."""

    name = "ida"
    models = (SlidingBlock, PlanarBlock, SpringSupportedMass)

    def _integrator(self, block, piece):
        form = dae_form(block, piece)
        options = self.solver_options()
        # F is measured against the friction capacity mu g: an absolute tolerance of
        # atol [m/s²] would force steps of ~1e-16 s wherever the demand crosses zero
        friction_atol = max(self.atol, self.rtol * form.force_scale)
        options["atol"] = np.array([self.atol] * form.n_states + [friction_atol] * form.n_friction)
        return _IDAIntegrator(form, options)


def dae_form(block, piece):
    """The DAE form of ``block``'s type on the driver's excitation ``piece``."""
    for model, form in _FORMS:
        if isinstance(block, model):
            return form(block, piece)
    raise TypeError(f"IDA has no DAE form for a {type(block).__name__}")


class _LineForm:
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


class _PlanarForm:
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


class _SpringForm:
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


_FORMS = ((SlidingBlock, _LineForm), (PlanarBlock, _PlanarForm), (SpringSupportedMass, _SpringForm))


class _IDAGuards(Guards):
    def __init__(self, block, piece, mode):
        super().__init__(block, piece, mode)
        self.form = dae_form(block, piece)

    def __call__(self, t, y, yp, out):
        self.form.guards(self.mode, t, y, out)


class _IDAIntegrator(SundialsIntegrator):
    label = "IDA"
    guards_class = _IDAGuards

    def __init__(self, form, options):
        self.form = form
        super().__init__(form.block, form.piece, options)

    def _build(self, mode, guards, options):
        form = self.form
        algebraic = list(range(form.n_states, form.n_states + form.n_friction))
        return IDA(form.residual(mode), eventsfn=guards, num_events=len(guards.direction),
                   algebraic_idx=algebraic, first_step=FIRST_STEP, **options)

    def _initialise(self, solver, mode, t, y):
        """Consistent (y, y') at ``t`` from the model's state (the DAE form's)."""
        return solver.init_step(t, *self.form.consistent(mode, t, y))
