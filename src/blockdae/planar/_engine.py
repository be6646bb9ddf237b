"""The planar block's compiled engine (what the "compiled" backend runs a
:class:`~blockdae.PlanarBlock` on a rigid support on): the numba kernel of
:mod:`blockdae.planar._compiled`.

``solve`` returns the model's own solution (events, knots, the driver's cubic Hermite
dense output); ``solve_final`` runs parameter sets x motions x factors on a(t) in one
compiled call, shared among threads, and returns final numbers only.
"""

import numpy as np

from ..core import BatchSolution, SolveItem, HermiteDense, notice_numba, run_items
from . import _compiled as engine

#: analyses x pieces above which a batch is shared among threads
_PARALLEL_WORK = 1e5
#: the engine's name in the compile notice, and its compile time on one core [s]
_ENGINE, _COMPILE_SECONDS = "the compiled planar engine", 35


class PlanarEngine:
    """The compiled planar engine (numba; batches shared among threads), with the backend's
    settings (``rtol``, ``atol``, ``max_events_at_one_instant``, ``event_resolution``)."""

    def solve(self, block, excitation, horizon, backend):
        _check_support(block)
        T0, H, CF = engine_input(block, excitation, horizon)
        notice_numba(_ENGINE, _COMPILE_SECONDS, engine.kernel())
        outcome, knots, events = engine.run_one(T0, H, CF, block.engine_parameters()[0],
                                                _options(backend, horizon.until_rest))
        _check(block, outcome, events, backend.max_events_at_one_instant, horizon)
        t, y, mode = knots[:, 0].copy(), knots[:, 1:8].copy(), knots[:, 8].astype(int)
        logged = tuple(block.event(float(e[0]), block.modes(int(e[1])), block.modes(int(e[2])), e[3:10])
                       for e in events)
        stats = {"max_events_at_one_instant": int(outcome[9]), "n_events": len(logged),
                 "n_steps": int(outcome[10]), "n_rejected_steps": int(outcome[11]), "n_rhs_evals": int(outcome[12])}
        return block.solution(t=t, y=y, mode=mode, events=logged, backend=backend.name,
                              dense=HermiteDense(t, y, knots[:, 9:16].copy(), knots[:, 16:23].copy()), stats=stats)

    def solve_batch(self, block, excitation, horizon, backend):
        u, largest, n_events, t_end = self.final_numbers(self.solve_final(block, [excitation], [horizon], (1.0,),
                                                                          backend)[0])
        return BatchSolution(displacement=u, max_abs_displacement=largest, n_events=n_events, t_end=t_end,
                             backend=backend.name, solve_one=SolveItem(self, block, excitation, horizon, backend))

    @staticmethod
    def final_numbers(rows):
        """((u_x, u_y)(t_end) (n, 2) [m], max |u| (n,) [m], events (n,), t_end (n,) [s]) of n
        rows of :meth:`solve_final`'s outcomes."""
        return rows[:, 0:2], rows[:, 2], rows[:, 4].astype(int), rows[:, 6]

    def solve_final(self, block, excitations, horizons, scale, backend) -> np.ndarray:
        """Final numbers of every excitation under every parameter set of ``block`` (a
        batch of m, or one) at every factor of ``scale`` on a(t) (s of them), in one
        compiled call, in parallel over cores.

        Returns:
            (len(excitations), m * s, 13): the engine's outcomes (``OUTCOME_FIELDS``:
            u_x, u_y, max |u| [m], slide distance [m], events, liftoffs, t_final [s], ...);
            parameter set j at factor k in column j * s + k.
        """
        _check_support(block)
        inputs = [engine_input(block, e, h) for e, h in zip(excitations, horizons)]
        lengths = np.cumsum([0] + [len(x[0]) for x in inputs])
        T0, H = (np.concatenate([x[f] for x in inputs]) for f in (0, 1))
        CF = np.ascontiguousarray(np.concatenate([x[2] for x in inputs]))
        offsets = np.stack([lengths[:-1], lengths[1:]], axis=1).astype(np.int64)
        params = block.engine_parameters(scale)
        until_rest = np.array([float(h.until_rest) for h in horizons])
        out = np.empty((len(inputs), len(params), len(engine.OUTCOME_FIELDS)))
        _run_parallel(T0, H, CF, offsets, params, _options(backend, False), until_rest, out)
        bad = np.argwhere(out[:, :, 8] != engine.FINISHED)
        if len(bad):
            i, j = bad[0]
            one = block.item(j // len(scale)) if block.batch_shape else block
            where = f" (excitation {i}, parameter set {j // len(scale)}, factor {scale[j % len(scale)]!r})"
            _check(one, out[i, j], np.empty((0, 10)), backend.max_events_at_one_instant, horizons[i], where)
        return out


def _options(backend, until_rest) -> np.ndarray:
    """The engine's ``options`` (``OPTION_FIELDS``) from the backend's settings."""
    return np.array([backend.rtol, backend.atol, backend.event_resolution, backend.max_events_at_one_instant,
                     float(until_rest)])


def _run_parallel(T0, H, CF, offsets, params, options, until_rest, out):
    """The engine's kernel over every item of ``out``, shared among threads (the kernel
    releases the GIL) where the work is large enough."""
    run = engine.kernel()
    notice_numba(_ENGINE, _COMPILE_SECONDS, run)
    items = np.arange(out.shape[0] * out.shape[1], dtype=np.int64)
    run_items(lambda part: run(T0, H, CF, offsets, params, options, until_rest, part, out, False), items,
              len(params) * len(T0), _PARALLEL_WORK, parts_per_thread=8)


def engine_input(block, excitation, horizon):
    """(t0 (n,), h (n,) [s], coefficients (n, 3, 5): p0, p1, s, w, phi of a_x, a_y, a_z)
    on the model's common partition up to the end of the excitation (or ``t_end``)."""
    pieces = block.excitation_pieces(excitation, horizon.integration_end(excitation))
    CF = np.ascontiguousarray(np.stack([np.stack([p.p0, p.p1, p.s, p.w, p.phi], axis=-1) for p in pieces], axis=1),
                              dtype=float)
    return np.ascontiguousarray(pieces[0].t0, dtype=float), np.ascontiguousarray(pieces[0].h, dtype=float), CF


def _check_support(block):
    if block.support.compliant:
        raise ValueError("the compiled planar engine runs a block on a rigid support; for a SpringSupport use "
                         "backend='ida', 'cvode' or 'jax'")


def _check(block, outcome, events, cap, horizon, where=""):
    """Raise as the driver does where the engine stopped early."""
    status = int(outcome[8])
    if status == engine.FINISHED:
        return
    t = outcome[6]
    if status == engine.CHATTER:
        modes = " -> ".join(block.modes(int(e[1])).name for e in events[-cap - 1:])
        after = block.modes(int(events[-1][2])).name if len(events) else "?"
        raise RuntimeError(f"{cap + 1} events at t = {t:.12g} s ({modes} -> {after}): chatter{where}; "
                           f"raise max_events_at_one_instant={cap}")
    if status == engine.NEVER_RESTS:
        block.time_to_rest(block.modes(int(outcome[7])), np.zeros(7))  # raises the model's own error
    if status == engine.NO_REST:
        raise RuntimeError(f"{block.modes(int(outcome[7])).name} found no rest by t = {t:.6g} s after the "
                           f"excitation{where}")
    problem = {engine.INCONSISTENT: "the slide's speed turned negative beyond the tolerance (a missed stop)",
               engine.STEP_TOO_SMALL: "the slip's step fell below rounding"}[status]
    raise RuntimeError(f"the compiled planar engine stopped at t = {t:.12g} s{where}: {problem}; please report")
