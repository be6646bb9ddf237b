"""The exact backends: closed forms on every piece of the excitation, events to machine
precision, on the engine the model declares (its ``engines``) or, for a model of linear modes,
on the compiled linear engine."""

import dataclasses

from ..core import AbstractBackend, check_window
from ._closed_form_linear import solve_closed_form
from ._linear_solution import linear_pieces, solve_linear_compiled


@dataclasses.dataclass(frozen=True)
class Exact(AbstractBackend):
    """Closed-form integration (``backend="exact"``), compiled with numba (float64,
    parallel over cores for batches), on the engine the model declares for it (its
    ``engines["exact"]``), or, where that is "linear", on closed-form steps of its linear
    modes. :class:`~blockdae.ExactJax` runs the same closed forms compiled with JAX.

    Args:
        window=64: pieces of a(t) per block of the onset search's bounds [-], an
            integer >= 1 (the 1-D block's engine); a tuning knob that changes speed,
            never results.
        linear="compiled": the "linear" engine's path [-]: "compiled" (numba, for
            records) or "python" (closed-form steps on the generic driver, the
            reference; sine excitations always take it).
    """

    window: int = 64
    linear: str = "compiled"
    name = "exact"
    generic = False

    def __post_init__(self):
        check_window(self.window)
        if self.linear not in ("compiled", "python"):
            raise ValueError(f"linear must be 'compiled' or 'python', got {self.linear!r}")

    def solve(self, block, excitation, horizon):
        engine = block.engines[self.name]
        if engine != "linear":
            return engine.solve(block, excitation, horizon, self)
        found = linear_pieces(excitation, horizon.integration_end(excitation))
        if self.linear == "python" or found is None or horizon.until_rest:  # closed-form steps on the driver
            return solve_closed_form(block, excitation, horizon, self.name)
        return solve_linear_compiled(block, *found, self.name)

    def solve_batch(self, block, excitation, horizon):
        engine = block.engines[self.name]
        if hasattr(engine, "solve_batch"):
            return engine.solve_batch(block, excitation, horizon, self)
        return super().solve_batch(block, excitation, horizon)

    def solve_final(self, block, excitations, horizons, scale=(1.0,)):
        """Final numbers of every excitation under every parameter set at every factor of
        ``scale`` on a(t), where the model's engine computes them in one call (its
        ``solve_final``; the 1-D block's)."""
        return block.engines[self.name].solve_final(block, excitations, horizons, scale, self)


@dataclasses.dataclass(frozen=True)
class ExactJax(AbstractBackend):
    """Closed-form integration compiled with JAX (float64, ``backend="exact-jax"``), on
    the engine the model declares for it (its ``engines["exact-jax"]``): the closed forms
    and rules of :class:`~blockdae.Exact`; what :func:`blockdae.sensitivities`
    differentiates.

    Args:
        window=64: pieces of a(t) examined per loop iteration [-], an integer >= 1; a
            tuning knob that changes speed, never results.
    """

    window: int = 64
    name = "exact-jax"
    generic = False

    def __post_init__(self):
        check_window(self.window)

    def solve(self, block, excitation, horizon):
        return block.engines[self.name].solve(block, excitation, horizon, self)

    def solve_batch(self, block, excitation, horizon):
        return block.engines[self.name].solve_batch(block, excitation, horizon, self)
