"""The "compiled" backend: a model's own compiled engine (its ``engines``) with the settings
of a compiled hybrid loop: tolerances of its integrated modes, the event rules' bounds."""

import dataclasses

from ..core import AbstractBackend
from ._sundials import _check_real


@dataclasses.dataclass(frozen=True)
class Compiled(AbstractBackend):
    """A model's own compiled engine (``backend="compiled"``: its ``engines["compiled"]``;
    the planar block's on a rigid support), numba, batches parallel over cores, with the
    settings of a compiled hybrid loop.

    Args:
        rtol=1e-12: relative tolerance of the integrated modes' steps [-], in [1e-14, 1e-2]
            (the planar block's slip by DOP853).
        atol=1e-14: absolute tolerance [m, m/s], > 0.
        max_events_at_one_instant=5: most consecutive events at one instant [-]; more
            (chatter) raises an error.
        event_resolution=1e-9: events closer than this are one instant [s] (as the driver's).
    """

    rtol: float = 1e-12
    atol: float = 1e-14
    max_events_at_one_instant: int = 5
    event_resolution: float = 1e-9
    name = "compiled"
    generic = False

    def __post_init__(self):
        _check_real("rtol", self.rtol, lambda x: 1e-14 <= x <= 1e-2, "must lie in [1e-14, 1e-2]")
        _check_real("atol", self.atol, lambda x: x > 0, "must be > 0")
        _check_real("event_resolution", self.event_resolution, lambda x: x >= 0, "must be >= 0 [s]")
        cap = self.max_events_at_one_instant
        if not (isinstance(cap, int) and not isinstance(cap, bool) and cap >= 1):
            raise ValueError(f"max_events_at_one_instant must be an integer >= 1, got {cap!r}")

    def solve(self, block, excitation, horizon):
        return block.engines[self.name].solve(block, excitation, horizon, self)

    def solve_batch(self, block, excitation, horizon):
        return block.engines[self.name].solve_batch(block, excitation, horizon, self)

    def solve_final(self, block, excitations, horizons, scale=(1.0,)):
        """Final numbers of every excitation under every parameter set at every factor of
        ``scale`` on a(t), in one compiled call (the engine's ``solve_final``)."""
        return block.engines[self.name].solve_final(block, excitations, horizons, scale, self)
