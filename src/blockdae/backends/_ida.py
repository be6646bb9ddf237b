"""IDA backend: the natural DAE with the friction force as an algebraic variable.

States (u, v, F): F [m/s²] is the friction force per unit mass the base exerts on the
block. With the demand sigma(t) (the model's :func:`~blockdae.model.demand`) and the
mode's relative acceleration dv/dt (the model's ``flow``), Newton's law reads

    u' = v,    v' = F - sigma(t),    0 = F - (sigma(t) + dv/dt),

so F = sigma in stick (v' = 0) and F = -mode f g in slip. Stick guards are the model's
:func:`~blockdae.model.stick_guards` on the algebraic F; slip guards are mode * v.
"""

import dataclasses

import numpy as np
from sksundae.ida import IDA

from .._driver import SCALAR
from ..model import Mode, stick_guards
from ._sundials import Guards, SundialsBackend, SundialsIntegrator


@dataclasses.dataclass(frozen=True)
class IDABackend(SundialsBackend):
    """SUNDIALS IDA on the hybrid driver; see :class:`SundialsBackend` for the settings
    (``rtol``, ``atol`` [m, m/s, m/s²], ``max_step`` [s], ...)."""

    name = "ida"

    def _integrator(self, block, piece):
        options = self.solver_options()
        # F is measured against the friction capacity mu g: an absolute tolerance of
        # atol [m/s²] would force steps of ~1e-16 s wherever the demand crosses zero
        friction_atol = max(self.atol, self.rtol * block.mu * block.g)
        options["atol"] = np.array([self.atol, self.atol, friction_atol])
        return _IDAIntegrator(block, piece, options)


class _IDAGuards(Guards):
    def __call__(self, t, y, yp, out):
        block = self.block
        if self.mode == Mode.STICK:
            out[:] = stick_guards(y[2], block.mu, block.g, block.allow_negative, block.allow_positive, SCALAR)
        else:
            out[:] = block.guards(self.mode, t, y, self.piece, SCALAR)


class _IDAIntegrator(SundialsIntegrator):
    label = "IDA"
    guards_class = _IDAGuards

    def _build(self, mode, guards, options):
        block, piece = self.block, self.piece

        def residual(t, y, yp, res):
            sigma = block.demand(t, piece, SCALAR)
            res[0] = yp[0] - y[1]
            res[1] = yp[1] - (y[2] - sigma)
            res[2] = y[2] - sigma - block.flow(mode, t, y, piece, SCALAR)[1]

        return IDA(residual, eventsfn=guards, num_events=len(guards.direction), algebraic_idx=[2], **options)

    def _initialise(self, solver, mode, t, y):
        """Consistent (y, y') at ``t``: F from the algebraic equation; F' = da/dt in
        stick (F = sigma) and 0 in slip (F constant)."""
        rate = self.block.flow(mode, t, y, self.piece, SCALAR)[1]
        friction = self.block.demand(t, self.piece, SCALAR) + rate
        friction_rate = self.piece.acceleration_rate(t) if mode == Mode.STICK else 0.0
        return solver.init_step(t, np.array([y[0], y[1], friction]), np.array([y[1], rate, friction_rate]))
