"""IDA backend: each model as the DAE its ``dae_form`` gives, on the hybrid driver.

A form has the model's states followed by ``n_friction`` algebraic variables (a
friction or support force per unit mass, so that IDA solves the natural DAE of the
model: :class:`~blockdae.sliding.SlidingDAEForm`, :class:`~blockdae.planar.PlanarDAEForm`,
:class:`~blockdae.upthrow.SpringDAEForm`), its residual per mode, its guards and a
consistent (y, y') at a restart; a model without one runs as the explicit ODE y' = flow
(:class:`~blockdae.core.ExplicitForm`). Nothing here knows a model.
"""

import dataclasses

import numpy as np
import sksundae.ida

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
class IDA(SundialsBackend):
    """SUNDIALS IDA on the hybrid driver: the model's DAE (its ``dae_form``: for a
    SlidingBlock u, v and the friction force per unit mass F, for a PlanarBlock (F_x,
    F_y), as algebraic variables; the explicit ODE for a model without one);
    ``backend="ida"``. IDA restarts at every piece of a(t), each time from a first step
    of :data:`FIRST_STEP` [s].

    Args:
        rtol=1e-10: relative tolerance [-], in [1e-14, 1e-2].
        atol=1e-14: absolute tolerance [m, m/s] (the model's state units), > 0; on an
            algebraic force [m/s²] at least rtol times the form's force scale (mu g).
        max_step=None: largest internal step [s]; None: no bound besides the stops at
            every piece of a(t) and every turning point of v.
        max_num_steps=5000: most internal steps between two stops [-].
        max_events_at_one_instant=5: most consecutive events at one instant [-]; more
            (chatter) raises an error.
        event_resolution=1e-9: events closer than this are one instant [s].
    """

    name = "ida"

    def _integrator(self, block, piece):
        form = block.dae_form(piece)
        options = self.solver_options()
        # F is measured against the friction capacity mu g: an absolute tolerance of
        # atol [m/s²] would force steps of ~1e-16 s wherever the demand crosses zero
        friction_atol = max(self.atol, self.rtol * form.force_scale)
        options["atol"] = np.array([self.atol] * form.n_states + [friction_atol] * form.n_friction)
        return _IDAIntegrator(form, options)


class _IDAGuards(Guards):
    def __init__(self, block, piece, mode):
        super().__init__(block, piece, mode)
        self.form = block.dae_form(piece)

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
        return sksundae.ida.IDA(form.residual(mode), eventsfn=guards, num_events=len(guards.direction),
                                algebraic_idx=algebraic, first_step=FIRST_STEP, **options)

    def _initialise(self, solver, mode, t, y):
        """Consistent (y, y') at ``t`` from the model's state (the DAE form's)."""
        return solver.init_step(t, *self.form.consistent(mode, t, y))
