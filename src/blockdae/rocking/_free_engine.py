"""The complete free-standing block's compiled engine (``backend="compiled"``): the kernel
of :mod:`._free_compiled` integrates the modes, locates their guards and takes the apexes
and the sticking impacts of a rocking block with the model's rules; at every other event
the hybrid driver's own code (:class:`blockdae.core.EventRun`) takes the model's decisions
(the mode after a guard, the states on the guard and on entry, a motion started from rest,
a guard left at once, chatter, the checks), so that the events, their kinds and the
solution are those of every other backend."""

import math

import numpy as np

from ..core import EventRun, HermiteDense, notice_numba
from . import _free_compiled as compiled
from ._block import RATE_FLOOR
from ._engine import _OneSetEngine, _final_row
from ._free_model import BASE_WORK, X
from ._free_modes import FreeMode, event_kind
from ._free_solution import FreeEvent

#: the engine's name in the compile notice, and its compile time on one core [s]
_ENGINE, _COMPILE_SECONDS = "the compiled free-standing engine", 15
#: knot rows first allocated, event rows
_FIRST_ROWS, _FIRST_EVENTS = 1024, 256
#: the modes by value, the kinds of the mode changes met so far (what ``FreeEvent.make``
#: computes, for the thousands of events of a record that the kernel takes)
_MODES, _KINDS = {int(m): m for m in FreeMode}, {}


class _Knots:
    """The driver's knots, kept in the kernel's rows (:data:`._free_compiled.KNOT_WIDTH`)."""

    def __init__(self, counters, rows):
        self.rows, self.counters = np.empty((rows, compiled.KNOT_WIDTH)), counters

    def add(self, t, y, mode_after, rate_left, rate_right):
        """:func:`._free_compiled.add_knot` in NumPy (its rows, the buffer doubled when full)."""
        n = self.counters[compiled.C_NK]
        if n == len(self.rows):
            self.rows = np.concatenate([self.rows, np.empty_like(self.rows)])
        row = self.rows[n]
        row[0], row[compiled._MODE_COL] = t, int(mode_after)
        row[compiled._Y:compiled._MODE_COL], row[compiled._RIGHT:compiled._LEFT] = y, rate_right
        row[compiled._LEFT:] = 0.0
        if n > 0:
            self.rows[n - 1, compiled._LEFT:] = rate_left
        self.counters[compiled.C_NK] = n + 1

    def set_right_rate(self, rate_right):
        n = self.counters[compiled.C_NK] - 1
        self.rows[n, compiled._RIGHT:compiled._LEFT] = rate_right

    def arrays(self):
        """t (n,), y (n, 8), mode (n,), rate_start (n, 8), rate_end (n, 8)."""
        rows = self.rows[:self.counters[compiled.C_NK]]
        return (rows[:, 0].copy(), rows[:, compiled._Y:compiled._MODE_COL].copy(),
                rows[:, compiled._MODE_COL].astype(int), rows[:, compiled._RIGHT:compiled._LEFT].copy(),
                rows[:, compiled._LEFT:].copy())


def engine_parameters(model) -> np.ndarray:
    """The kernel's ``params`` (:data:`._free_compiled.PARAM_FIELDS`) of ``model``."""
    p = model.frequency
    return np.array([model.b, model.h, model.mu, model.friction_kinetic, model.g, model.R, model.alpha,
                     model.slenderness_ratio, model.output_step(), RATE_FLOOR * p * model.alpha,
                     RATE_FLOOR * p * model.R, model.zeno_arc])


class FreeCompiledEngine(_OneSetEngine):
    """Runs a :class:`FreeStandingBlock` on the compiled engine (``backend="compiled"``: its
    ``rtol``, ``atol``, ``event_resolution``, ``max_events_at_one_instant``)."""

    def solve(self, model, excitation, horizon, backend):
        ax, az = model.excitation_pieces(excitation, horizon.integration_end(excitation))
        CF = np.ascontiguousarray(np.stack([np.stack([c.p0, c.p1, c.s, c.w, c.phi], axis=-1) for c in (ax, az)],
                                           axis=1), dtype=float)
        T0, H = (np.ascontiguousarray(a, dtype=float) for a in (ax.t0, ax.h))
        run = compiled.kernel()
        notice_numba(_ENGINE, _COMPILE_SECONDS, run)
        driver = EventRun(model, 2, backend.max_events_at_one_instant, backend.event_resolution,
                          (backend.rtol, backend.atol))
        cnt = np.zeros(compiled.N_COUNTERS, dtype=np.int64)
        fl = np.array([0.0, 0.0, 0.0, math.nan, math.nan, backend.event_resolution])
        cnt[compiled.C_CAP] = backend.max_events_at_one_instant
        driver.knots = _Knots(cnt, 2 * len(T0) + _FIRST_ROWS)
        driver.knots.add(driver.t, driver.y, driver.mode, driver.y, driver.y)
        y = driver.y.copy()
        cnt[compiled.C_MODE], cnt[compiled.C_RESTARTED] = int(driver.mode), 1
        params = engine_parameters(model)
        options = np.array([backend.rtol, backend.atol])
        pieces = (T0, H, CF)
        self._advance(run, pieces, params, options, cnt, fl, y, driver)
        if horizon.until_rest:
            tail = (np.array([T0[-1] + H[-1]]), np.array([math.inf]), np.zeros((1, 2, 5)))
            cnt[compiled.C_PIECE], cnt[compiled.C_ENTERED], cnt[compiled.C_TAIL] = 0, 0, 1
            self._advance(run, tail, params, options, cnt, fl, y, driver)
            if not model.is_static(driver.mode):
                raise RuntimeError(f"{driver.mode.name} found no rest by t = {fl[compiled.F_END]:.6g} s after "
                                   "the excitation")
        t, state, mode, rate_start, rate_end = driver.knots.arrays()
        stats = {"max_events_at_one_instant": driver.max_run, "n_events": len(driver.events),
                 "n_steps": int(cnt[compiled.C_STEPS]), "n_rejected_steps": int(cnt[compiled.C_REJECTED]),
                 "n_rhs_evals": int(cnt[compiled.C_RHS])}
        return model.solution(t=t, y=state, mode=mode, events=tuple(driver.events), backend=backend.name,
                              dense=HermiteDense(t, state, rate_start, rate_end), stats=stats)

    def _final_row(self, model, excitation, horizon, factor, backend):
        solution = self.solve(model, excitation.scaled(factor), horizon, backend)
        return _final_row(solution.state[:, X], solution.t, len(solution.events))

    @staticmethod
    def _advance(run, pieces, params, options, cnt, fl, y, driver):
        """Run the kernel over ``pieces`` (t0 (n,), h (n,) [s], coefficients (n, 2, 5)), the
        driver taking each event; the run's state stays in ``cnt``, ``fl``, ``y`` and the
        driver."""
        T0, H, CF = pieces
        model, current = driver.model, -1
        tail = cnt[compiled.C_TAIL] != 0
        taken = np.empty((_FIRST_EVENTS, compiled.EVENT_WIDTH))
        while True:
            cnt[compiled.C_RUN], cnt[compiled.C_MAX_RUN] = driver.run_length, driver.max_run
            fl[compiled.F_LAST_EVENT] = driver.events[-1].t if driver.events else math.nan
            driver.knots.rows, taken, stop, index = run(T0, H, CF, params, options, cnt, fl, y, driver.knots.rows,
                                                        taken)
            _log_taken(driver, taken, cnt)
            if stop == compiled.DONE:
                return
            k = int(cnt[compiled.C_PIECE])
            if k != current:  # the driver's excitation on this piece
                coefficients = tuple(tuple(float(c) for c in CF[k, i]) for i in range(2))
                h = math.inf if tail else float(H[k])
                driver.piece_excitation.set(float(T0[k]), coefficients, h)
                driver.flow_excitation.set(float(T0[k]), coefficients, h)
                current = k
            driver.t, driver.y = float(fl[compiled.F_T]), y.copy()
            driver.mode = model.modes(int(cnt[compiled.C_MODE]))
            driver.v_max = float(fl[compiled.F_VMAX])
            driver.restarted = False
            if stop == compiled.GUARD:
                driver.on_guard(index)
            elif stop == compiled.ENTRY:  # a block at rest entering a piece that may start a motion
                driver.retake_rest(float(T0[k]))
                driver.restarted = True
            elif stop == compiled.RESTART:  # the driver's guard_left_at_once
                before = driver.mode
                at_once = driver.guard_left_at_once()
                if at_once is not None:
                    driver.on_guard(at_once)
                driver.restarted = driver.mode != before
            elif stop == compiled.BOUND:
                fl[compiled.F_END] = driver.t + model.time_to_rest(driver.mode, driver.y)
                driver.restarted = True
            elif stop == compiled.INCONSISTENT:
                driver.check_consistent(driver.t)
                raise RuntimeError(f"the compiled free-standing engine stopped at t = {driver.t:.12g} s: the state "
                                   f"contradicts {driver.mode.name}; please report")
            else:
                raise RuntimeError(f"the compiled free-standing engine stopped at t = {driver.t:.12g} s in "
                                   f"{driver.mode.name}: the step fell below rounding")
            if driver.entry_pending and driver.t < (fl[compiled.F_END] if tail else T0[-1] + H[-1]):
                driver.check_entry()
            fl[compiled.F_T] = driver.t
            y[:] = driver.y
            cnt[compiled.C_MODE] = int(driver.mode)
            cnt[compiled.C_RESTARTED] = int(driver.restarted)


def _log_taken(driver, taken, cnt):
    """The events the kernel took (rows of ``taken``: t, mode before, mode after, the
    centroid's states before and after) as the model's ``event`` records them, in order,
    after the driver's; the driver's count of events at one instant."""
    after = 3 + compiled.N
    for row in taken[:cnt[compiled.C_NE]].tolist():
        change = _MODES[int(row[1])], _MODES[int(row[2])]
        kind = _KINDS.get(change) or _KINDS.setdefault(change, event_kind(*change))
        driver.events.append(FreeEvent(row[0], *change, kind, tuple(row[3:3 + BASE_WORK]),
                                       tuple(row[after:after + BASE_WORK])))
    cnt[compiled.C_NE] = 0
    driver.run_length, driver.max_run = int(cnt[compiled.C_RUN]), int(cnt[compiled.C_MAX_RUN])
