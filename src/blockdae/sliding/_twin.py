"""The 1-D block's JAX twin (what the "jax" backend runs a :class:`~blockdae.SlidingBlock` on):
diffrax integration of its automaton in one compiled kernel (:mod:`blockdae.sliding._jax_kernel`),
events by root finding, dense output in closed form from the located events."""

import jax
import numpy as np

from ..core import BatchSolution, SolveItem, jax_context
from . import _jax_kernel as kernel
from ._exact_jax import _device
from ._results import DenseOutput, max_run
from ._model import never_rests_error
from ._solution import EventLog, Solution


class TwinEngine:
    """The twin's compiled kernel, with the backend's settings (``solver`` (default
    "tsit5"), ``rtol``, ``atol``, ``max_segments``, ``max_steps``)."""

    def solve(self, block, excitation, horizon, backend):
        pieces = excitation.pieces(horizon.integration_end(excitation))
        with jax_context():
            out = kernel.run(block.engine_parameters()[0], _device(pieces, 1), cfg=_config(block, pieces, backend),
                             until_rest=horizon.until_rest, full_output=True)
            final, t_final, rests, flags, knots = jax.device_get(out)
        _check(block, rests, flags, backend)
        return _solution(block, pieces, knots, float(t_final), int(flags.n_steps), backend.name)

    def solve_batch(self, block, excitation, horizon, backend):
        pieces = excitation.pieces(horizon.integration_end(excitation))
        params = tuple(block.engine_parameters().T)
        with jax_context():
            out = kernel.run_batch(params, _device(pieces, 1), cfg=_config(block, pieces, backend),
                                   until_rest=horizon.until_rest, full_output=False)
            final, t_final, rests, flags, _ = jax.device_get(out)
        for i in np.flatnonzero((flags.n_overflow > 0) | (flags.n_failed > 0) | ~rests):
            _check(block.item(i), rests[i], jax.tree.map(lambda x: x[i], flags), backend, f" (parameter set {i})")
        return BatchSolution(
            displacement=np.asarray(final.u), max_abs_displacement=np.asarray(final.max_abs_u),
            n_events=np.asarray(final.n_events), t_end=np.asarray(t_final), backend=backend.name,
            solve_one=SolveItem(self, block, excitation, horizon, backend))


def _config(block, pieces, backend):
    """The kernel's static settings for ``block`` under ``pieces``."""
    return kernel.Config(block.allow_negative, block.allow_positive, pieces.has_sine, backend.solver or "tsit5",
                         float(backend.rtol), float(backend.atol), backend.max_segments, backend.max_steps)


def _check(block, rests, flags, backend, where=""):
    """Raise if the run hit a bound or never came to rest."""
    if int(flags.n_overflow) > 0:
        raise RuntimeError(
            f"{int(flags.n_overflow)} piece(s) of the excitation needed more than "
            f"max_segments={backend.max_segments} segments{where}: chatter; raise max_segments")
    if int(flags.n_failed) > 0:
        raise RuntimeError(
            f"{int(flags.n_failed)} segment(s) failed in diffrax{where} (e.g. more than "
            f"max_steps={backend.max_steps} steps); raise max_steps or loosen rtol={backend.rtol}")
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
