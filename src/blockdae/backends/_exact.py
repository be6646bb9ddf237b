"""The exact backend: closed forms on every piece, events to machine precision."""

import dataclasses
import functools

import jax
import numpy as np

from .._jax_config import jax_context
from .._solution import BatchSolution, Event, Solution
from ..excitation import Pieces
from ..excitation._pieces import evaluate
from ..model import Mode, SlidingBlock, slip_constant
from . import _exact_kernel as kernel
from ._base import AbstractBackend, batch_params, never_rests_error


@dataclasses.dataclass(frozen=True)
class ExactBackend(AbstractBackend):
    """Closed-form integration, compiled with JAX (float64).

    Args:
        window: pieces of a(t) examined per loop iteration; a tuning knob that
            changes speed, never results.
    """

    window: int = 64
    name = "exact"

    def __post_init__(self):
        if not (isinstance(self.window, int) and self.window >= 1):
            raise ValueError(f"window must be an integer >= 1, got {self.window!r}")

    def solve(self, block, excitation, horizon):
        pieces, device = _pieces_on_device(excitation, horizon.integration_end(excitation), self.window)
        capacity = _bucket(len(pieces.t0))  # one event per piece; grows if ever needed
        while True:
            out = self._run(kernel.run, _params(block), device, len(pieces.t0), horizon, block, pieces, capacity)
            u, v, mode, max_abs_u, n_events, t_final, rests, finished = out.scalars
            if n_events < capacity:  # a full log may have lost its last row
                break
            capacity *= 2
        _check(block, rests, finished)
        n = int(n_events)
        return _solution(block, pieces, out.log[:n], (float(u), float(v), int(mode)), float(t_final), self.name)

    def solve_batch(self, block, excitation, horizon):
        pieces, device = _pieces_on_device(excitation, horizon.integration_end(excitation), self.window)
        params = batch_params(block)
        out = self._run(kernel.run_batch, params, device, len(pieces.t0), horizon, block, pieces, 0)
        u, _, _, max_abs_u, n_events, t_final, rests, finished = out.scalars.T
        for i in np.flatnonzero(~(rests.astype(bool) & finished.astype(bool))):
            _check(block.item(i), rests[i], finished[i], f" (parameter set {i})")
        return BatchSolution(
            displacement=u, max_abs_displacement=max_abs_u, n_events=n_events.astype(int), t_end=t_final,
            backend=self.name,
            solve_one=lambda i: self.solve(block.item(i), excitation, horizon))

    def _run(self, fn, params, device, n_pieces, horizon, block, pieces, capacity):
        with jax_context():
            out = fn(params, (block.allow_negative, block.allow_positive), device, n_pieces,
                     horizon.until_rest, window=self.window, log_capacity=capacity, is_sine=pieces.has_sine)
            return kernel.Summary(*map(np.asarray, out))  # ~100 us faster than jax.device_get here


def _params(block: SlidingBlock, scale=1.0):
    """(mu, f, bias, g, scale) as one array: one transfer to the device, not five."""
    return np.array([block.mu, block.friction_kinetic, block.bias, block.g, scale], dtype=np.float64)


def _bucket(n: int) -> int:
    """n rounded up to at least 64 and to one of four sizes per octave, so that few
    distinct shapes get compiled (all short excitations share one)."""
    n = max(n, 64)
    step = 2 ** (int(np.log2(n)) - 2)
    return int(-(-n // step) * step)


def _pieces_on_device(excitation, t_end, window):
    """The pieces of ``excitation`` up to ``t_end`` [s], and the kernel's input built
    from them on the JAX device; kept for the last few excitations, which are immutable
    (building it for a long record costs as much as a run)."""
    try:
        return _cached_pieces_on_device(excitation, t_end, window)
    except TypeError:  # an unhashable user-defined excitation
        return _cached_pieces_on_device.__wrapped__(excitation, t_end, window)


@functools.lru_cache(maxsize=16)
def _cached_pieces_on_device(excitation, t_end, window):
    pieces = excitation.pieces(t_end)
    with jax_context():
        return pieces, jax.device_put(_kernel_input(pieces, window))


def _kernel_input(pieces: Pieces, window: int) -> kernel.Excitation:
    return kernel.prepare(_device(pieces, window), window, pieces.has_sine)


def _device(pieces: Pieces, window: int):
    """Pieces padded with empty, zero-acceleration pieces to a bucketed length plus one
    window, so that records of similar length share one compiled kernel."""
    n = len(pieces.t0)
    pad = _bucket(n) - n + window
    zeros = np.zeros(pad)
    padded = Pieces.concatenate([pieces, Pieces(zeros + pieces.t_end, *(zeros,) * 6)])
    return tuple(padded)


def _check(block, rests, finished, where=""):
    if not bool(finished):
        raise RuntimeError(f"the exact kernel stopped before the end of the excitation{where}: "
                           "events accumulate (chatter) faster than it can advance")
    if not bool(rests):
        raise never_rests_error(block, where)


def _solution(block, pieces, log, final, t_final, backend):
    """Knots at the start, every event and the end, straight from the kernel.

    ``log``: (n_events, 4) rows of t [s], mode before, mode after, u [m];
    ``final``: (u [m], v [m/s], mode) at ``t_final`` [s].
    """
    n = log.shape[0]
    t_ev, before, after, u_ev = log.T
    after = after.astype(int)
    events = _events(t_ev, before, after, u_ev, np.zeros(n))
    t = np.concatenate([[0.0], t_ev, [t_final]])
    u = np.concatenate([[0.0], u_ev, [final[0]]])
    v = np.concatenate([np.zeros(n + 1), [final[1]]])
    mode = np.concatenate([[0], after, [final[2]]]).astype(int)
    stats = {"max_events_at_one_instant": _max_run(t_ev), "n_events": n}
    return Solution(t=t, u=u, v=v, mode=mode, events=events, backend=backend,
                    dense=_DenseOutput(block, pieces, t_ev, u_ev, after), stats=stats)


def _events(t, before, after, u, v):
    """Events from arrays of times [s], modes before and after, u [m] and v [m/s]."""
    floats = lambda x: np.asarray(x, float).tolist()
    modes = lambda x: np.asarray(x).astype(int).tolist()
    return tuple(Event(t_i, Mode(b), Mode(a), u_i, v_i)
                 for t_i, b, a, u_i, v_i in zip(floats(t), modes(before), modes(after), floats(u), floats(v)))


def _max_run(times):
    if times.size == 0:
        return 0
    edges = np.flatnonzero(np.diff(times) != 0)
    return int(np.max(np.diff(np.concatenate([[-1], edges, [times.size - 1]]))))


@dataclasses.dataclass(frozen=True, eq=False)
class _DenseOutput:
    """u(t), v(t) in closed form from the last event before t.

    In slip from an event at t_e with (u_e, v_e = 0... or not), with the base's
    velocity vb and displacement xb (integrals of a):
    v = v_e + c (t - t_e) - (vb(t) - vb(t_e)) and
    u = u_e + v_e (t - t_e) + c (t - t_e)²/2 - (xb(t) - xb(t_e) - vb(t_e) (t - t_e)).
    """

    block: SlidingBlock
    pieces: Pieces
    t_events: np.ndarray
    u_events: np.ndarray
    mode_after: np.ndarray

    def mode_at(self, t):
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
