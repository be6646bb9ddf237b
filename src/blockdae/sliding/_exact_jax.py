"""The 1-D block's exact engine compiled with JAX (what the "exact-jax" backend runs it on):
for derivatives and accelerators.

The same closed forms and rules as the numba engine of ``backend="exact"``; the two are
cross-checked in the tests.
"""

import jax
import numpy as np

from ..core import BatchSolution, SolveItem, cached_per_excitation, jax_context
from ..excitation import Pieces
from . import _exact_kernel as kernel
from ._results import check, exact_solution, max_run


class ExactJaxEngine:
    """The 1-D block's closed forms compiled with JAX (float64), with the backend's
    settings (``window``: pieces of a(t) examined per loop iteration)."""

    def solve(self, block, excitation, horizon, backend):
        pieces, device = _pieces_on_device(excitation, horizon.integration_end(excitation), backend.window)
        capacity = _bucket(len(pieces.t0))  # one event per piece; grows if ever needed
        while True:
            out = _run(kernel.run, block.engine_parameters()[0], device, len(pieces.t0), horizon, block, pieces,
                       capacity, backend.window)
            u, v, mode, max_abs_u, n_events, t_final, rests, finished = out.scalars
            if n_events < capacity:  # a full log may have lost its last row
                break
            capacity *= 2
        check(block, rests, finished)
        log = out.log[: int(n_events)]
        knots = _knots(log, (float(u), float(v), int(mode)), float(t_final))
        return exact_solution(block, pieces, knots, max_run(log[:, 0]), backend.name)

    def solve_batch(self, block, excitation, horizon, backend):
        pieces, device = _pieces_on_device(excitation, horizon.integration_end(excitation), backend.window)
        params = tuple(block.engine_parameters().T)
        out = _run(kernel.run_batch, params, device, len(pieces.t0), horizon, block, pieces, 0, backend.window)
        u, _, _, max_abs_u, n_events, t_final, rests, finished = out.scalars.T
        for i in np.flatnonzero(~(rests.astype(bool) & finished.astype(bool))):
            check(block.item(i), rests[i], finished[i], f" (parameter set {i})")
        return BatchSolution(
            displacement=u, max_abs_displacement=max_abs_u, n_events=n_events.astype(int), t_end=t_final,
            backend=backend.name,
            solve_one=SolveItem(self, block, excitation, horizon, backend))


def _run(fn, params, device, n_pieces, horizon, block, pieces, capacity, window):
    with jax_context():
        out = fn(params, (block.allow_negative, block.allow_positive), device, n_pieces,
                 horizon.until_rest, window=window, log_capacity=capacity, is_sine=pieces.has_sine)
        return kernel.Summary(*map(np.asarray, out))  # ~100 us faster than jax.device_get here


def _bucket(n: int) -> int:
    """n rounded up to at least 64 and to one of four sizes per octave, so that few
    distinct shapes get compiled (all short excitations share one)."""
    n = max(n, 64)
    step = 2 ** (int(np.log2(n)) - 2)
    return int(-(-n // step) * step)


@cached_per_excitation
def _pieces_on_device(excitation, t_end, window):
    """The pieces of ``excitation`` up to ``t_end`` [s], and the kernel's input built
    from them on the JAX device (building it for a long record costs as much as a run)."""
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


def _knots(log, final, t_final):
    """The exact engines' knots (see :func:`._results.exact_solution`) from the kernel's
    ``log`` ((n_events, 4) rows of t [s], mode before, mode after, u [m]) and the final
    (u [m], v [m/s], mode) at ``t_final`` [s]."""
    t_ev, before, after, u_ev = log.T
    u_end, v_end, mode_end = final
    n = t_ev.shape[0]
    return np.stack([np.concatenate([[0.0], t_ev, [t_final]]), np.concatenate([[0.0], u_ev, [u_end]]),
                     np.concatenate([np.zeros(n + 1), [v_end]]), np.concatenate([[0], after, [mode_end]]),
                     np.concatenate([[0], before, [mode_end]])])
