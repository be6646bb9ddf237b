"""Solutions from located events: knots, the event log and dense output in closed form.

Shared by the exact engines (numba and JAX) and the JAX twin.
"""

import dataclasses

import numpy as np

from ._solution import EventLog, Solution
from ..excitation import Pieces, evaluate
from ._model import never_rests_error, slip_constant


def exact_solution(block, pieces: Pieces, knots, max_run: int, backend: str) -> Solution:
    """The Solution of an exact engine, without a loop over events.

    ``knots``: (5, n_events + 2) rows of t [s], u [m], v [m/s], mode after and mode
    before: the start, every event (v = 0) and the end.
    """
    knots = np.asarray(knots, dtype=float)
    knots.flags.writeable = False  # its rows are the Solution's arrays
    modes = knots[3:].astype(int)
    modes.flags.writeable = False
    t, u, v = knots[:3]
    after, before = modes
    n = t.shape[0] - 2
    events = EventLog.of_read_only(t[1:-1], before[1:-1], after[1:-1], u[1:-1], v[1:-1])
    return Solution(t=t, u=u, v=v, mode=after, events=events, backend=backend,
                    dense=DenseOutput(block, pieces, events.t, events.u, events.mode_after),
                    stats={"max_events_at_one_instant": max_run, "n_events": n})


def check(block, rests, finished, where: str = ""):
    """Raise if an exact engine stopped early (chatter) or the block never rests."""
    if not bool(finished):
        raise RuntimeError(f"the exact kernel stopped before the end of the excitation{where}: "
                           "events accumulate (chatter) faster than it can advance")
    if not bool(rests):
        raise never_rests_error(block, where)


def max_run(times) -> int:
    """The most events at one instant in event times ``times`` [s] (sorted)."""
    if times.size == 0:
        return 0
    edges = np.flatnonzero(np.diff(times) != 0)
    return int(np.max(np.diff(np.concatenate([[-1], edges, [times.size - 1]]))))


@dataclasses.dataclass(frozen=True, eq=False)
class DenseOutput:
    """u(t), v(t) in closed form from the last event before t.

    In slip from an event at t_e with u_e (v_e = 0), with the base's velocity vb and
    displacement xb (integrals of a):
    v = c (t - t_e) - (vb(t) - vb(t_e)) and
    u = u_e + c (t - t_e)²/2 - (xb(t) - xb(t_e) - vb(t_e) (t - t_e)).
    """

    block: object  # the 1-D block
    pieces: Pieces
    t_events: np.ndarray
    u_events: np.ndarray
    mode_after: np.ndarray

    def mode_at(self, t):
        """The mode at ``t`` [s]: the last event's mode after, STICK (0) before the first."""
        if not self.mode_after.size:  # no event: at rest relative to the base throughout
            return np.zeros(np.shape(t), dtype=int)
        i = np.searchsorted(self.t_events, t, side="right") - 1
        return np.where(i >= 0, self.mode_after[np.maximum(i, 0)], 0).astype(int)

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        i = np.searchsorted(self.t_events, t, side="right") - 1
        started = i >= 0
        j = np.maximum(i, 0)
        t_e = np.where(started, self.t_events[j] if self.t_events.size else 0.0, 0.0)
        u_e = np.where(started, self.u_events[j] if self.u_events.size else 0.0, 0.0)
        mode = self.mode_at(t)
        _, _, vb, xb = evaluate(self.pieces, t)
        _, _, vb_e, xb_e = evaluate(self.pieces, t_e)
        c = slip_constant(mode, self.block.bias, self.block.friction_kinetic, self.block.g)
        d = t - t_e
        v = c * d - (vb - vb_e)
        u = u_e + 0.5 * c * d**2 - (xb - xb_e - vb_e * d)
        stick = mode == 0
        return np.where(stick, u_e, u), np.where(stick, 0.0, v)
