"""The JAX twin: the hybrid automaton integrated with diffrax, events by root finding.

A model whose ``engines`` name "sliding" here (the 1-D block) runs in one compiled
kernel (:mod:`._jax_kernel`); any other model runs on the generic driver with a diffrax integrator per mode
(:mod:`._jax_hybrid`)."""

import dataclasses

import jax
import numpy as np

from ..core._driver import drive
from ..core._jax_config import jax_context
from ..sliding._solution import BatchSolution, EventLog, Solution
from ..engines import _jax_kernel as kernel
from ..sliding._model import never_rests_error
from ._diffrax import DiffraxIntegrator, Settings
from ..backends._base import AbstractBackend
from ..engines._exact_jax import _device
from ..engines._results import DenseOutput, max_run


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
        if self.solver is not None and self.solver not in kernel.SOLVERS:
            raise ValueError(f"solver must be one of {tuple(kernel.SOLVERS)}, got {self.solver!r}")
        if not (isinstance(self.event_resolution, (int, float)) and 0 <= self.event_resolution < 1):
            raise ValueError(f"event_resolution must be a time in [0, 1) [s], got {self.event_resolution!r}")
        for field, least in (("max_segments", 2), ("max_steps", 1), ("max_events_at_one_instant", 1)):
            value = getattr(self, field)
            if not (isinstance(value, int) and value >= least):
                raise ValueError(f"{field} must be an integer >= {least}, got {value!r}")

    def config(self, block, pieces):
        """The kernel's static settings for ``block`` under ``pieces``."""
        return kernel.Config(block.allow_negative, block.allow_positive, pieces.has_sine, self.solver or "tsit5",
                             float(self.rtol), float(self.atol), self.max_segments, self.max_steps)

    def solve(self, block, excitation, horizon):
        if self.engine(block) != "sliding":
            return drive(block, excitation, horizon, self.integrator, self.name, self.max_events_at_one_instant,
                         self.event_resolution, (self.rtol, self.atol))
        pieces = excitation.pieces(horizon.integration_end(excitation))
        with jax_context():
            out = kernel.run(block.engine_parameters()[0], _device(pieces, 1), cfg=self.config(block, pieces),
                             until_rest=horizon.until_rest, full_output=True)
            final, t_final, rests, flags, knots = jax.device_get(out)
        self.check(block, rests, flags)
        return _solution(block, pieces, knots, float(t_final), int(flags.n_steps), self.name)

    def integrator(self, model, piece):
        """The generic driver's integrator for ``model`` (``piece``: its excitation)."""
        settings = Settings(self.solver or "dopri8", float(self.rtol), float(self.atol), self.max_steps)
        return DiffraxIntegrator(model, piece, settings)

    def solve_batch(self, block, excitation, horizon):
        if self.engine(block) != "sliding":  # one driver run per parameter set
            return super().solve_batch(block, excitation, horizon)
        pieces = excitation.pieces(horizon.integration_end(excitation))
        params = tuple(block.engine_parameters().T)
        with jax_context():
            out = kernel.run_batch(params, _device(pieces, 1), cfg=self.config(block, pieces),
                                   until_rest=horizon.until_rest, full_output=False)
            final, t_final, rests, flags, _ = jax.device_get(out)
        for i in np.flatnonzero((flags.n_overflow > 0) | (flags.n_failed > 0) | ~rests):
            self.check(block.item(i), rests[i], jax.tree.map(lambda x: x[i], flags), f" (parameter set {i})")
        return BatchSolution(
            displacement=np.asarray(final.u), max_abs_displacement=np.asarray(final.max_abs_u),
            n_events=np.asarray(final.n_events), t_end=np.asarray(t_final), backend=self.name,
            solve_one=lambda i: self.solve(block.item(i), excitation, horizon))

    def check(self, block, rests, flags, where=""):
        """Raise if the run hit a bound or never came to rest."""
        if int(flags.n_overflow) > 0:
            raise RuntimeError(
                f"{int(flags.n_overflow)} piece(s) of the excitation needed more than "
                f"max_segments={self.max_segments} segments{where}: chatter; raise max_segments")
        if int(flags.n_failed) > 0:
            raise RuntimeError(
                f"{int(flags.n_failed)} segment(s) failed in diffrax{where} (e.g. more than "
                f"max_steps={self.max_steps} steps); raise max_steps or loosen rtol={self.rtol}")
        if not bool(rests):
            raise never_rests_error(block, where)


def _solution(block, pieces, knots, t_final, n_steps, backend):
    """Knots at the start, every event, every piece end and the end; dense output in
    closed form from the last event (as the exact backend's)."""
    valid = knots.valid.ravel() & (knots.t.ravel() <= t_final)
    take = lambda x: np.asarray(x).ravel()[valid]
    t, u, v, before, after, is_event = (take(x) for x in (knots.t, knots.u, knots.v, knots.mode_before,
                                                          knots.mode_after, knots.is_event))
    ev = np.flatnonzero(is_event)
    events = EventLog(t[ev], before[ev], after[ev], u[ev], v[ev])
    dense = DenseOutput(block, pieces, events.t, events.u, events.mode_after)
    stats = {"max_events_at_one_instant": max_run(events.t), "n_events": len(events), "n_steps": n_steps}
    return Solution(t=np.concatenate([[0.0], t]), u=np.concatenate([[0.0], u]), v=np.concatenate([[0.0], v]),
                    mode=np.concatenate([[0], after]).astype(int), events=events, backend=backend,
                    dense=dense, stats=stats)
