"""CVODE backend: the ODE (u, v)' = flow(mode) on scikit-sundae, guards as root functions."""

import dataclasses

from sksundae.cvode import CVODE

from .._driver import SCALAR
from ._sundials import Guards, SundialsBackend, SundialsIntegrator


@dataclasses.dataclass(frozen=True)
class CVODEBackend(SundialsBackend):
    """SUNDIALS CVODE (Adams) on the hybrid driver; see :class:`SundialsBackend` for the
    settings (``rtol``, ``atol`` [m, m/s], ``max_step`` [s], ...)."""

    name = "cvode"

    def _integrator(self, block, piece):
        return _CVODEIntegrator(block, piece, self.solver_options())


class _CVODEGuards(Guards):
    def __call__(self, t, y, out):
        out[:] = self.block.guards(self.mode, t, y, self.piece, SCALAR)


class _CVODEIntegrator(SundialsIntegrator):
    label = "CVODE"
    guards_class = _CVODEGuards

    def _build(self, mode, guards, options):
        block, piece = self.block, self.piece

        def rhs(t, y, yp):
            yp[0], yp[1] = block.flow(mode, t, y, piece, SCALAR)

        return CVODE(rhs, eventsfn=guards, num_events=len(guards.direction), method="Adams", **options)

    def _initialise(self, solver, mode, t, y):
        return solver.init_step(t, y)
