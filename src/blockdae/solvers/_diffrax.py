"""The JAX twin for any hybrid model: diffrax integrates one mode at a time under the
generic driver (:func:`blockdae.core._driver.drive`) and stops at the first guard root.

Per (model type, mode, solver settings) one compiled function integrates
``model.flow(mode, t, y, piece, jnp)`` from ``t`` to ``t_out`` with a diffrax
Runge-Kutta solver under a PID controller; a ``diffrax.Event`` on the smallest of the
model's guards (each left crossing zero downwards) ends it at the first root, which
``optimistix.Bisection`` locates on the solver's dense output. The model's parameters
(:meth:`~blockdae.AbstractHybridModel.parameters`) and the piece's coefficients
are arguments, so nothing recompiles per block or per piece of a(t).
"""

import functools
from typing import NamedTuple

import diffrax
import jax
import jax.numpy as jnp
import numpy as np
import optimistix as optx

from ..core import AbstractIntegrator, SolverError, jax_context
from ..excitation import accel, accel_rate
from .diffrax_solvers import SOLVERS

# guards decrease through their roots (flip=True); 1e-13 s is far below the event
# accuracy the driver's tolerances allow
ROOT_FINDER = optx.Bisection(rtol=1e-15, atol=1e-13, flip=True)


class JaxPieceExcitation:
    """The driver's :class:`~blockdae.core._driver.PieceExcitation` with JAX values.

    Args:
        t0: start of the piece [s].
        coefficients: (n_components, 5): (p0 [m/s²], p1 [m/s³], s [m/s²], w [rad/s],
            phi [rad]) of each component on the piece.
        scales: (n_components,) factors on each component [-] (1: the motion as given).
    """

    def __init__(self, t0, coefficients, scales):
        self.t0, self.coefficients, self.scales = t0, coefficients, scales

    def component(self, index, t):
        """Component ``index`` of the base acceleration at ``t`` [m/s²]."""
        return self.scales[index] * accel(*self.coefficients[index], t - self.t0, jnp)

    def component_rate(self, index, t):
        """Its rate [m/s³]."""
        return self.scales[index] * accel_rate(*self.coefficients[index], t - self.t0, jnp)

    def acceleration(self, t):
        return self.component(0, t)

    def acceleration_rate(self, t):
        return self.component_rate(0, t)


class Settings(NamedTuple):
    """Static settings of the compiled segment functions (hashable)."""

    solver: str
    rtol: float
    atol: float
    max_steps: int


def model_parameters(model) -> dict:
    """The model's parameters as float64 scalars, the compiled functions' arguments."""
    return {name: np.float64(value) for name, value in model.parameters().items()}


def segment_function(model, mode, settings):
    """The compiled segment integration of ``mode`` for models of ``model``'s type (one
    per type, mode and settings, for every parameter set). Called
    as ``(parameters, t0, coefficients, scales, t_start [s], t_out [s], y0)``, it returns
    (t [s], y, whether a guard was reached, the index of the smallest guard there,
    diffrax result, accepted steps).
    """
    return _segment_function(type(model), mode, settings, ModelTemplate(model))


class ModelTemplate:
    """A model of a type, standing for every model of that type with the same parameter
    names in a cache key (a PlanarBlock on a spring names the spring's too, and its
    rules differ): the compiled functions rebuild the model from their ``parameters``
    argument by ``with_parameters`` (every value the rules read)."""

    def __init__(self, model):
        self.model = model
        self.key = (type(model), tuple(model.parameters()))

    def __hash__(self):
        return hash(self.key)

    def __eq__(self, other):
        return self.key == other.key


@functools.cache
def _segment_function(model_type, mode, settings, template):
    del model_type  # part of the cache key only
    template = template.model

    def run(parameters, t0, coefficients, scales, t_start, t_out, y0):
        model = template.with_parameters(parameters)
        piece = JaxPieceExcitation(t0, coefficients, scales)
        guards = lambda t, y: model.guards(mode, t, y, piece, jnp)
        sol = diffrax.diffeqsolve(
            diffrax.ODETerm(lambda t, y, args: model.flow(mode, t, y, piece, jnp)), SOLVERS[settings.solver](),
            t0=t_start, t1=t_out, dt0=None, y0=y0, saveat=diffrax.SaveAt(t1=True),
            stepsize_controller=diffrax.PIDController(rtol=settings.rtol, atol=settings.atol),
            event=diffrax.Event(lambda t, y, args, **_: _started(t, t_start, jnp.min(guards(t, y))),
                                root_finder=ROOT_FINDER, direction=False),
            max_steps=settings.max_steps, throw=False)
        t, y = sol.ts[-1], sol.ys[-1]
        return t, y, sol.event_mask, jnp.argmin(guards(t, y)), sol.result._value, sol.stats["num_accepted_steps"]

    return jax.jit(run)


def _started(t, t_start, guard):
    """The event's condition: the smallest guard, counted as positive at the segment's
    start. diffrax reports a downward crossing only from a positive value, and the
    driver starts a flow with a guard at zero after every mode entry on a guard (a
    slide from v = 0), having checked that none falls there
    (``guard_left_at_once``): its return through zero within the first segment is a
    crossing, as SUNDIALS' root finders (which look just past a zero at the start) see it."""
    return jnp.where(t == t_start, jnp.maximum(guard, 1.0), guard)


class DiffraxIntegrator(AbstractIntegrator):
    """The driver's integrator: one compiled diffrax segment per call of ``step``.

    Every ``step`` starts afresh from the state the driver holds (an explicit
    Runge-Kutta method keeps no history), so a restart only records the mode.
    """

    def __init__(self, model, piece, settings: Settings):
        self.model, self.piece, self.settings = model, piece, settings
        self.parameters = model_parameters(model)
        self.scales = np.ones(len(piece.coefficients))
        self.mode, self.t, self.y = model.initial_mode, 0.0, None
        self.counts = {"n_calls": 0, "n_steps": 0}

    def restart(self, mode, t, y):
        self.mode, self.t, self.y = mode, float(t), np.asarray(y, dtype=float)

    def step(self, t_out, t_stop):
        del t_stop  # diffrax steps onto t_out <= t_stop and never past it
        run = segment_function(self.model, self.mode, self.settings)
        with jax_context():
            out = run(self.parameters, np.float64(self.piece.t0), np.asarray(self.piece.coefficients, dtype=float),
                      self.scales, np.float64(self.t), np.float64(t_out), self.y)
            t, y, hit, index, result, steps = jax.device_get(out)
        if result not in (diffrax.RESULTS.successful._value, diffrax.RESULTS.event_occurred._value):
            raise SolverError(f"diffrax failed at t = {self.t:.12g} s in mode {self.mode.name}: "
                              f"diffrax result {int(result)} (more than max_steps={self.settings.max_steps} steps, "
                              "or a step size underflow)")
        self.counts["n_calls"] += 1
        self.counts["n_steps"] += int(steps)
        self.t, self.y = float(t), np.asarray(y, dtype=float)
        return self.t, self.y, (int(index) if bool(hit) else None)

    @property
    def stats(self):
        return dict(self.counts)
