"""The JAX twin: the hybrid automaton integrated with diffrax, events by root finding.

A model with an engine of its own here (its ``engines``; the 1-D block's compiled kernel) runs
on it; any other model runs on the generic driver with a diffrax integrator per mode
(:mod:`._diffrax`)."""

import dataclasses

import numpy as np

from ..core import AbstractBackend, drive
from ._diffrax import DiffraxIntegrator, Settings
from .diffrax_solvers import SOLVERS


@dataclasses.dataclass(frozen=True)
class JaxTwin(AbstractBackend):
    """The JAX twin (``backend="jax"``): a diffrax twin of the hybrid automaton,
    compiled with JAX (float64).

    Integrates each mode with a diffrax Runge-Kutta solver under a PID controller,
    piece by piece of a(t); guards are ``diffrax.Event`` roots (bisection on the dense
    output, then one Newton step). Independent of the exact backend's closed-form
    motion; both take the flow, guards and transition rules from the model.
    Differentiable in forward mode only (``jax.jvp``/``jacfwd``; see
    :func:`blockdae.sensitivities`). Other models (:class:`~blockdae.PlanarBlock`) run
    on the generic hybrid driver, one compiled diffrax segment per driver step.

    Args:
        rtol=1e-10: relative tolerance of the step-size controller [-], in (0, 1).
        atol=1e-12: absolute tolerance [m, m/s], in (0, 1).
        solver=None: the diffrax solver [-]: "tsit5", "dopri5", "dopri8" (explicit) or
            "kvaerno5" (implicit; its third-order dense output locates events on sine
            pieces only to ~1e-9 s); None: "tsit5" for a SlidingBlock, "dopri8" for
            other models (the polar slide of a PlanarBlock is stiff just after an
            onset, where a high order keeps the steps few).
        max_segments=8: most segments (events + 1) one piece of a(t) may hold [-]; more
            raises an error instead of looping (SlidingBlock).
        max_steps=4096: most solver steps per segment [-].
        max_events_at_one_instant=5: most consecutive events at one instant [-] (other
            models; more: chatter, an error).
        event_resolution=1e-9: events closer than this are one instant [s] (other models).
    """

    rtol: float = 1e-10
    atol: float = 1e-12
    solver: str | None = None
    max_segments: int = 8
    max_steps: int = 4096
    max_events_at_one_instant: int = 5
    event_resolution: float = 1e-9
    name = "jax"

    def __post_init__(self):
        for field in ("rtol", "atol"):
            value = getattr(self, field)
            if not (isinstance(value, (int, float)) and np.isfinite(value) and 0 < value < 1):
                raise ValueError(f"{field} must be a number in (0, 1), got {value!r}")
        if self.solver is not None and self.solver not in SOLVERS:
            raise ValueError(f"solver must be one of {tuple(SOLVERS)}, got {self.solver!r}")
        if not (isinstance(self.event_resolution, (int, float)) and 0 <= self.event_resolution < 1):
            raise ValueError(f"event_resolution must be a time in [0, 1) [s], got {self.event_resolution!r}")
        for field, least in (("max_segments", 2), ("max_steps", 1), ("max_events_at_one_instant", 1)):
            value = getattr(self, field)
            if not (isinstance(value, int) and value >= least):
                raise ValueError(f"{field} must be an integer >= {least}, got {value!r}")

    def solve(self, block, excitation, horizon):
        engine = self.engine(block)
        if engine is not None:
            return engine.solve(block, excitation, horizon, self)
        return drive(block, excitation, horizon, self.integrator, self.name, self.max_events_at_one_instant,
                     self.event_resolution, (self.rtol, self.atol))

    def integrator(self, model, piece):
        """The generic driver's integrator for ``model`` (``piece``: its excitation)."""
        settings = Settings(self.solver or "dopri8", float(self.rtol), float(self.atol), self.max_steps)
        return DiffraxIntegrator(model, piece, settings)

    def trajectory_sensitivities(self, model, motion, horizon):
        """The trajectory this twin locates for ``model`` on the generic driver and its
        derivatives by :func:`~blockdae.core.contract.parameter_names`: (solution,
        dy(t_end)/dp of shape (n_y, n_p), one ``EventSensitivity`` per event)."""
        from ._trajectory import trajectory_sensitivities

        return trajectory_sensitivities(model, motion, horizon, self)

    def displacement_jacobian(self, model, motion, horizon):
        """d(final displacement)/dp [m per unit], shape (len(displacement_states), n_p),
        along the trajectory this twin locates."""
        from ._trajectory import displacement_jacobian

        return displacement_jacobian(model, motion, horizon, self)

    def solve_batch(self, block, excitation, horizon):
        engine = self.engine(block)
        if engine is not None:
            return engine.solve_batch(block, excitation, horizon, self)
        return super().solve_batch(block, excitation, horizon)  # one driver run per parameter set
