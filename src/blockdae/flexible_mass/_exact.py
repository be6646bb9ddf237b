"""The exact backend of the flexible sliding mass: its compiled engine (:mod:`._engine`)
on a record's linear pieces, the solution with dense output in closed form."""

import numpy as np

from ..core import SolverError, notice_numba
from . import _engine
from ._damped_slip import COMPILED_RESPONSE_LIMIT, UNDERDAMPED_LIMIT, slip_underdamped, solve_damped_slip
from ._table_engine import record_pieces

#: knot-log rows per piece of a(t) at the start (grown if a run needs more)
_ROWS_PER_PIECE = 2


def engine_settings(model):
    """The engine's parameters of ``model``: omega [rad/s], xi [-], ky g [m/s²], coupled;
    raises ValueError where the no-sliding response (STICK) has no underdamped closed
    form (a slip too damped for it runs on :mod:`._damped_slip`)."""
    omega, xi, coupled = float(model.omega), float(model.damping), model.coupled
    if not 0 < xi < UNDERDAMPED_LIMIT:
        raise ValueError(f"damping={xi!r} (total): the exact engine needs a total damping ratio in (0, "
                         f"{UNDERDAMPED_LIMIT!r}) (an underdamped column); use backend 'cvode' or 'ida'")
    return omega, xi, float(model.yield_acceleration), coupled


def check(outcome, where=""):
    """Raise on a run that did not finish: chatter or a root search that did not settle."""
    status = int(outcome[_engine.OUTCOME_FIELDS.index("status")])
    last = outcome[_engine.OUTCOME_FIELDS.index("t_last_event")]
    if status == _engine.CHATTER:
        raise RuntimeError(f"more than {_engine.MAX_EVENTS_AT_ONE_INSTANT} events at t = {last:.12g} s within "
                           f"{_engine.EVENT_RESOLUTION:g} s{where}: chatter of the flexible sliding mass")
    if status == _engine.UNSETTLED:
        raise SolverError(f"a root or peak search did not settle in {_engine.MAX_INTERVALS} intervals{where} "
                          "(a degenerate touch of zero); use backend 'cvode' or 'ida'")


class ExactEngine:
    """The flexible mass's exact engine (numba); the backend's settings are not read."""

    def solve(self, model, excitation, horizon, backend):
        return solve_exact(model, excitation, horizon, backend.name)


def solve_exact(model, excitation, horizon, name):
    """``model`` under ``excitation`` (a record) to ``horizon``: its solution, every onset
    and stop located to adjacent floats; a slip too damped for the closed forms, or a
    total damping in [COMPILED_RESPONSE_LIMIT, 1), on :mod:`._damped_slip`."""
    if COMPILED_RESPONSE_LIMIT <= float(model.damping) < 1:  # STICK too: its response on matrix exponentials as well
        return solve_damped_slip(model, excitation, horizon, name)
    settings = engine_settings(model)
    if not slip_underdamped(settings[1], settings[3]):
        return solve_damped_slip(model, excitation, horizon, name)
    pieces, arrays = record_pieces(excitation, horizon, "the exact flexible engine")
    run = _engine.kernels()[0]
    notice_numba("the flexible sliding mass's history engine", _engine.COMPILE_SECONDS, run)
    capacity = _ROWS_PER_PIECE * len(pieces.t0) + 8
    while True:
        log = np.empty((capacity, len(_engine.KNOT_FIELDS)))
        outcome, n_rows = run(*arrays, 1.0, *settings, log)
        if outcome[_engine.OUTCOME_FIELDS.index("status")] != _engine.LOG_FULL:
            break
        capacity *= 4
    check(outcome)
    log = log[:n_rows]
    t, state = log[:, 0], log[:, 1:5]
    mode, before = log[:, 5].astype(int), log[:, 6].astype(int)
    events = tuple(model.event(float(t[i]), model.modes(before[i]), model.modes(mode[i]), state[i])
                   for i in np.flatnonzero(log[:, 7]))
    stats = {"max_events_at_one_instant": int(outcome[_engine.OUTCOME_FIELDS.index("max_events_at_one_instant")]),
             "n_events": len(events), "n_knots": len(t)}
    return model.solution(t=t, y=state, mode=mode, events=events, backend=name,
                          dense=_Dense(t, state, mode.astype(float), arrays[0], arrays[2], arrays[3], settings),
                          stats=stats)


class _Dense:
    """The exact engine's dense output from its knots (t [s], state (n, 4), mode) and the
    record's pieces: ``__call__(times)`` -> the 4 states at ``times``, each of their shape;
    picklable (the compiled kernel is looked up on use)."""

    def __init__(self, t, state, mode, t0, a0, slope, settings):
        self.t, self.state, self.mode = t, state, mode
        self.t0, self.a0, self.slope, self.settings = t0, a0, slope, settings

    def __call__(self, times):
        times = np.asarray(times, dtype=float)
        values = _engine.kernels()[1](self.t, self.state, self.mode, self.t0, self.a0, self.slope, 1.0,
                                      *self.settings, times.ravel())
        return tuple(values[:, k].reshape(times.shape) for k in range(4))
