"""CVODE backend: the ODE y' = flow(mode) of any model on scikit-sundae, guards as root functions."""

import dataclasses

import sksundae.cvode

from ..core import SCALAR
from ._sundials import Guards, SundialsBackend, SundialsIntegrator

#: CVODE's first step after every (re)start [s]. A restart begins at order 1, and
#: CVODE's own first step is sized so that its error already reaches the tolerance;
#: with a restart at every sample of a record these errors add up in v along a long
#: slip (5e-9 of max |v| over the 2.4 s slip of Chi-Chi one-way, mu = 0.1: its stop
#: 3.7e-9 s off at rtol 1e-10). From 1e-11 s (~5e4 ulps of t at 1 s, still ~5 at
#: 1e4 s) the step may grow 1e4 times, then 10 times per step, so the order-1 and
#: order-2 steps stay tiny and commit no error worth counting; by order 3 Adams is
#: exact for the polynomial u, v of a linear piece and the steps grow to its length.
FIRST_STEP = 1e-11


@dataclasses.dataclass(frozen=True)
class CVODE(SundialsBackend):
    """SUNDIALS CVODE (Adams) on the hybrid driver: the model's ODE y' = flow (for a
    SlidingBlock in u, v), its guards as root functions; ``backend="cvode"``. CVODE
    restarts at every piece of a(t), each time from a first step of :data:`FIRST_STEP` [s].

    Args:
        rtol=1e-10: relative tolerance [-], in [1e-14, 1e-2].
        atol=1e-14: absolute tolerance [m, m/s] (the model's state units), > 0.
        max_step=None: largest internal step [s]; None: no bound besides the stops at
            every piece of a(t) and every turning point of v.
        max_num_steps=5000: most internal steps between two stops [-].
        max_events_at_one_instant=5: most consecutive events at one instant [-]; more
            (chatter) raises an error.
        event_resolution=1e-9: events closer than this are one instant [s].
    """

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
            yp[:] = block.flow(mode, t, y, piece, SCALAR)

        return sksundae.cvode.CVODE(rhs, eventsfn=guards, num_events=len(guards.direction), method="Adams",
                                    first_step=FIRST_STEP, **options)

    def _initialise(self, solver, mode, t, y):
        return solver.init_step(t, y)
