"""The 1-D block's exact engine (numba): closed forms on every piece, events to machine
precision; what the "exact" backend runs a :class:`~blockdae.SlidingBlock` on."""

import dataclasses

import numpy as np

from ..core import BatchSolution, SolveItem, cached_per_excitation, notice_numba, run_items
from ..excitation import Pieces, accel
from ..solvers import Exact
from . import _exact_numba as engine
from ._results import check, exact_solution


#: the first compile of one of the engine's two entry points [s] (one core; benchmarks/cold_start.py)
_COMPILE_SECONDS = 8

#: pieces x parameter sets above which a batch is shared among threads (~0.2 ms on one
#: core; waking a worker thread costs ~45 us on a 2-core VM)
_THREADED_WORK = 2e5


class ExactEngine:
    """The 1-D block's closed forms compiled with numba (float64; batches shared among
    threads), with the backend's settings (``window``: pieces of a(t) per block of the onset
    search's bounds)."""

    def solve(self, block, excitation, horizon, backend):
        pieces, exc = _engine_input(excitation, horizon.integration_end(excitation), backend.window)
        if isinstance(backend, Uncompiled):
            run_one = engine.run_one_uncompiled
        else:
            run_one = engine.kernels()[0]
            notice_numba("the exact engine", _COMPILE_SECONDS, run_one)
        outcome, knots = run_one(exc, backend.window, block.engine_parameter_set(), _flags(block, horizon), 64)
        check(block, outcome[6], outcome[7])
        return exact_solution(block, pieces, knots, int(outcome[8]), backend.name)

    def solve_batch(self, block, excitation, horizon, backend):
        u, largest, n_events, t_end = self.final_numbers(self.solve_final(block, [excitation], [horizon], (1.0,),
                                                                          backend)[0])
        return BatchSolution(displacement=u[:, 0], max_abs_displacement=largest, n_events=n_events, t_end=t_end,
                             backend=backend.name, solve_one=SolveItem(self, block, excitation, horizon, backend))

    @staticmethod
    def final_numbers(rows):
        """(u(t_end) (n, 1) [m], max |u| (n,) [m], events (n,), t_end (n,) [s]) of n rows of
        :meth:`solve_final`'s outcomes."""
        return rows[:, 0:1], rows[:, 3], rows[:, 4].astype(int), rows[:, 5]

    def solve_final(self, block, excitations, horizons, scale, backend) -> np.ndarray:
        """Final numbers only, for every excitation under every parameter set of
        ``block`` (a batch of m, or one) at every factor of ``scale`` on a(t) (s of
        them), shared among threads.

        Returns:
            (len(excitations), m * s, 9), the engine's outcomes (``OUTCOME_FIELDS``);
            parameter set j at factor k in column j * s + k.
        """
        inputs = [_engine_input(e, h.integration_end(e), backend.window)[1] for e, h in zip(excitations, horizons)]
        exc, offsets = _concatenated(inputs)
        params = block.engine_parameters(scale)
        run = engine.kernels()[1]
        notice_numba("the exact engine", _COMPILE_SECONDS, run)
        flags = (block.allow_negative, block.allow_positive, np.array([h.until_rest for h in horizons]))
        out = np.empty((len(inputs), len(params), len(engine.OUTCOME_FIELDS)))
        # item j * n_exc + i is excitation i under parameter set j: each excitation's in a row
        items = np.arange(out.size // out.shape[2], dtype=np.int64).reshape(len(params), len(inputs)).T.ravel()
        run_items(lambda part: run(exc, offsets, backend.window, params, flags, part, out), items,
                  len(params) * len(exc[0]), _THREADED_WORK)
        if not out[:, :, 6:8].all():  # rests, finished
            for i, j in zip(*np.nonzero((out[:, :, 6] == 0) | (out[:, :, 7] == 0))):
                where = f" (excitation {i}, parameter set {j})" if len(inputs) > 1 else f" (parameter set {j})"
                j_set = j // len(scale)
                check(block.item(j_set) if block.batch_shape else block, out[i, j, 6], out[i, j, 7], where)
        return out


@dataclasses.dataclass(frozen=True)
class Uncompiled(Exact):
    """The "exact" backend whose 1-D block engine runs one parameter set by the Python
    interpreter (:func:`._exact_numba.run_one_uncompiled`): the same numbers, no compile
    wait, for a motion of a few pieces."""


def _flags(block, horizon):
    return block.allow_negative, block.allow_positive, horizon.until_rest


@cached_per_excitation
def _engine_input(excitation, t_end, window):
    """The pieces of ``excitation`` up to ``t_end`` [s] and the engine's input built from them."""
    pieces = excitation.pieces(t_end)
    return pieces, prepare(pieces, window)


def prepare(pieces: Pieces, window: int) -> tuple:
    """The engine's ``exc`` (see :mod:`._exact_numba`): the pieces (sine terms None if
    there are none) and the range of a(t) per piece and per block of ``window`` pieces."""
    sine = (pieces.s, pieces.w, pieces.phi) if pieces.has_sine else (None, None, None)
    coefficients = (pieces.p0, pieces.p1, *sine)
    ends = (accel(*coefficients, 0.0), accel(*coefficients, pieces.h))  # monotone: extrema at the ends
    a_hi, a_lo = np.maximum(*ends), np.minimum(*ends)
    pad = -len(pieces.t0) % window
    per_block = lambda x, fill, reduce: reduce(np.append(x, np.full(pad, fill)).reshape(-1, window), axis=1)
    return tuple(np.ascontiguousarray(x, dtype=float) if x is not None else None
                 for x in (pieces.t0, pieces.h, *coefficients, a_hi, a_lo, per_block(a_hi, -np.inf, np.max),
                           per_block(a_lo, np.inf, np.min)))


def _concatenated(inputs):
    """One ``exc`` from several and their (piece start, end, block start, end) offsets."""
    if len(inputs) == 1:
        return inputs[0], np.array([[0, len(inputs[0][0]), 0, len(inputs[0][9])]], dtype=np.int64)
    if any(x[4] is not None for x in inputs):
        inputs = [x if x[4] is not None else x[:4] + tuple(np.zeros_like(x[0]) for _ in range(3)) + x[7:]
                  for x in inputs]
    exc = tuple(None if inputs[0][f] is None else np.concatenate([x[f] for x in inputs]) for f in range(11))
    pieces = np.cumsum([0] + [len(x[0]) for x in inputs])
    blocks = np.cumsum([0] + [len(x[9]) for x in inputs])
    return exc, np.stack([pieces[:-1], pieces[1:], blocks[:-1], blocks[1:]], axis=1).astype(np.int64)
