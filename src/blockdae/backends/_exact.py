"""The exact backend: closed forms on every piece, events to machine precision."""

import dataclasses

import jax
import jax.numpy as jnp
import numpy as np

from .._solution import BatchSolution, Event, Solution
from ..excitation import AbstractExcitation, Pieces
from ..excitation._pieces import rebase
from ..model import Mode, SlidingBlock, slip_constant
from . import _exact_kernel as kernel
from ._base import AbstractBackend, Horizon
from ._closed_form import slip_motion


@dataclasses.dataclass(frozen=True)
class ExactBackend(AbstractBackend):
    """Closed-form integration, compiled with JAX (float64).

    Args:
        max_events_per_piece: most events one piece of a(t) (one sample interval of a
            record) may hold; more raises an error instead of looping.
    """

    max_events_per_piece: int = 6
    name = "exact"

    def __post_init__(self):
        if not (isinstance(self.max_events_per_piece, int) and self.max_events_per_piece >= 1):
            raise ValueError(f"max_events_per_piece must be an integer >= 1, got {self.max_events_per_piece!r}")

    def solve(self, block, excitation, horizon):
        pieces, static = self._prepare(block, excitation, horizon)
        with jax.enable_x64(True):
            final, t_final, rests, knots = kernel.run(
                _params(block), _device(pieces), horizon.until_rest, full_output=True, **static)
            final, t_final, rests, knots = jax.device_get((final, t_final, rests, knots))
        _check(block, final, rests, self.max_events_per_piece)
        return _solution(block, pieces, knots, final, self.name)

    def solve_batch(self, block, excitation, horizon):
        pieces, static = self._prepare(block, excitation, horizon)
        shape = block.batch_shape
        params = tuple(np.broadcast_to(np.asarray(p, dtype=float), shape)
                       for p in (block.mu, block.friction_kinetic, block.bias))
        params += (np.full(shape, float(block.g)), np.ones(shape))
        with jax.enable_x64(True):
            final, t_final, rests, _ = kernel.run_batch(
                params, _device(pieces), horizon.until_rest, full_output=False, **static)
            final, t_final, rests = jax.device_get((final, t_final, rests))
        for i in range(shape[0]):
            _check(block.item(i), jax.tree.map(lambda x: x[i], final), rests[i],
                   self.max_events_per_piece, f" (parameter set {i})")
        return BatchSolution(
            displacement=np.asarray(final.u), max_abs_displacement=np.asarray(final.max_abs_u),
            n_events=np.asarray(final.n_events), t_end=np.asarray(t_final), backend=self.name,
            solve_one=lambda i: self.solve(block.item(i), excitation, horizon))

    def _prepare(self, block, excitation, horizon):
        pieces = excitation.pieces(horizon.integration_end(excitation))
        static = dict(allow_neg=block.allow_negative, allow_pos=block.allow_positive,
                      max_events=self.max_events_per_piece, is_sine=pieces.has_sine)
        return pieces, static


def _params(block: SlidingBlock, scale=1.0):
    return tuple(np.float64(x) for x in (block.mu, block.friction_kinetic, block.bias, block.g, scale))


def _device(pieces: Pieces):
    """Pieces padded (with empty pieces at the end) to a few lengths, so that records
    of similar length share one compiled kernel."""
    n = len(pieces.t0)
    octave = 2 ** max(int(np.floor(np.log2(max(n, 1)))) - 2, 0)
    size = int(np.ceil(n / octave) * octave)
    end = pieces.t_end
    cf = rebase(*(c[-1] for c in pieces[2:]), pieces.h[-1])
    pad = Pieces(*(np.full(size - n, x) for x in (end, 0.0) + tuple(cf)))
    return tuple(jnp.asarray(x) for x in Pieces.concatenate([pieces, pad]))


def _check(block, final, rests, max_events, where=""):
    if int(final.n_overflow) > 0:
        raise RuntimeError(
            f"{int(final.n_overflow)} piece(s) of the excitation needed more than "
            f"max_events_per_piece={max_events} events{where}: chatter; raise max_events_per_piece")
    if not bool(rests):
        raise ValueError(
            f"the block never comes to rest after the excitation{where}: kinetic friction "
            f"mu_kinetic={block.friction_kinetic} does not exceed |bias|={abs(block.bias)}; give t_end [s]")


def _solution(block, pieces, knots, final, backend):
    valid = knots.valid.ravel()
    take = lambda x: np.asarray(x).ravel()[valid]
    t, u, v = take(knots.t), take(knots.u), take(knots.v)
    mode, is_event = take(knots.mode_after), take(knots.is_event)
    before = take(knots.mode_before)
    events = tuple(Event(float(t[i]), Mode(int(before[i])), Mode(int(mode[i])), float(u[i]), float(v[i]))
                   for i in np.flatnonzero(is_event))
    t = np.concatenate([[0.0], t])
    u, v = np.concatenate([[0.0], u]), np.concatenate([[0.0], v])
    mode = np.concatenate([[0], mode]).astype(int)
    dense = _DenseOutput(block, pieces, t, u, v, mode)
    stats = {"max_events_at_one_instant": _max_run(np.array([e.t for e in events])),
             "n_events": len(events)}
    return Solution(t=t, u=u, v=v, mode=mode, events=events, backend=backend, dense=dense, stats=stats)


def _max_run(times):
    if times.size == 0:
        return 0
    edges = np.flatnonzero(np.diff(times) != 0)
    return int(np.max(np.diff(np.concatenate([[-1], edges, [times.size - 1]]))))


@dataclasses.dataclass(frozen=True, eq=False)
class _DenseOutput:
    """u(t), v(t) from the last knot before t, in closed form."""

    block: SlidingBlock
    pieces: Pieces
    t: np.ndarray
    u: np.ndarray
    v: np.ndarray
    mode: np.ndarray

    def __call__(self, t):
        p = self.pieces
        i = np.searchsorted(self.t, t, side="right") - 1
        k = np.clip(np.searchsorted(p.t0, t, side="right") - 1, 0, len(p.t0) - 1)
        inside = t < p.t_end
        cf = tuple(np.where(inside, c[k], 0.0) for c in p[2:])
        cf = rebase(*cf, np.where(inside, self.t[i] - p.t0[k], 0.0))
        c = slip_constant(self.mode[i], self.block.bias, self.block.friction_kinetic, self.block.g)
        u, v = slip_motion(cf, t - self.t[i], self.u[i], self.v[i], c, xp=np)
        stick = self.mode[i] == 0
        return np.where(stick, self.u[i], u), np.where(stick, 0.0, v)
