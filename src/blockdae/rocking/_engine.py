"""The rocking block's compiled engines, each run made a :class:`RockingSolution` with dense
output: the linearised block's closed form (:mod:`._kernel`, ``backend="exact"``) on a
piecewise-linear horizontal record, and the integrated engine of either equation
(:mod:`._compiled`, ``backend="compiled"``) on any piecewise motion, horizontal and
vertical."""

import math

import numpy as np

from ..core import AbstractBackend, HermiteDense, notice_numba
from ..core.contract import SCALAR
from ..excitation import evaluate
from . import _compiled as compiled
from ._block import RATE_FLOOR
from ._kernel import KNOT_COLUMNS, kernel
from ._modes import RockingMode

#: knot rows first allocated per piece of a(t) (the log grows if a run needs more)
ROWS_PER_PIECE = 4


def record_pieces(model, excitation, horizon):
    """(t0, h, p0, p1) of a_x [s, s, m/s², m/s³], with a rest-seeking tail (h = inf,
    a_x = 0) when ``horizon`` runs until rest; ValueError for a motion the engine cannot
    take (a sine piece or a vertical component)."""
    ax, az = model.excitation_pieces(excitation, horizon.integration_end(excitation))
    if ax.has_sine or az.has_sine or np.any(az.p0 != 0) or np.any(az.p1 != 0):
        raise ValueError("the exact engine of a rocking block takes piecewise-linear horizontal records "
                         "(no sine pieces, no vertical component): use backend='cvode'")
    t0, h, p0, p1 = ax.t0, ax.h, ax.p0, ax.p1
    if horizon.until_rest:
        t0, h = np.append(t0, t0[-1] + h[-1]), np.append(h, math.inf)
        p0, p1 = np.append(p0, 0.0), np.append(p1, 0.0)
    return tuple(np.ascontiguousarray(a, dtype=float) for a in (t0, h, p0, p1))


def final_numbers(rows):
    """(theta(t_end) (n, 1) [rad], max |theta| (n,) [rad], events (n,), t_end (n,) [s]) of n
    rows of an engine's ``solve_final``."""
    return rows[:, 0:1], rows[:, 1], rows[:, 2].astype(int), rows[:, 3]


def _final_row(theta, t, n_events):
    """A row of ``solve_final``: theta(t_end), max |theta| over the knots, events, t_end."""
    return theta[-1], np.max(np.abs(theta)), n_events, t[-1]


def parameter_sets(model) -> list:
    """The blocks of one parameter set each that ``model`` holds: itself, or a batch's items."""
    return [model.item(j) for j in range(model.batch_shape[0])] if model.batch_shape else [model]


class _OneSetEngine:
    """An engine that runs one parameter set a call: a batch runs set by set, through the
    backend (each set's solution kept, as one run of it gives)."""

    def solve_batch(self, model, excitation, horizon, backend):
        """A :class:`~blockdae.core.BatchSolution`: the backend's loop over the sets, each
        set's run by :meth:`solve` kept (its ``solve_one``)."""
        return AbstractBackend.solve_batch(backend, model, excitation, horizon)

    def solve_final(self, model, excitations, horizons, scale, backend) -> np.ndarray:
        """Final numbers (:func:`final_numbers`) of every excitation under every parameter
        set (m of them, 1 for one block) at every factor of ``scale`` on a(t):
        (len(excitations), m * len(scale), 4), set j at factor k in column j * len(scale) + k."""
        sets = parameter_sets(model)
        out = np.empty((len(excitations), len(sets) * len(scale), 4))
        for i, (excitation, horizon) in enumerate(zip(excitations, horizons)):
            for j, block in enumerate(sets):
                for k, factor in enumerate(scale):
                    out[i, j * len(scale) + k] = self._final_row(block, excitation, horizon, factor, backend)
        return out

    final_numbers = staticmethod(final_numbers)


class LinearisedEngine(_OneSetEngine):
    """Runs a linearised, rocking :class:`RockingBlock` in closed form (the engine of
    ``backend="exact"``)."""

    def _final_row(self, model, excitation, horizon, factor, backend):
        """A run of the scaled copy."""
        solution = self.solve(model, excitation.scaled(factor), horizon, backend)
        return _final_row(solution.state[:, 0], solution.t, len(solution.events))

    def solve(self, model, excitation, horizon, backend):
        if not model.linearised or model.slides:
            raise ValueError("backend='exact' runs the linearised block that rocks (linearised=True, mu >= b/h); "
                             "the exact equation runs on backend='compiled'")
        pieces = record_pieces(model, excitation, horizon)
        run = kernel()
        rows = ROWS_PER_PIECE * len(pieces[0]) + 64
        while True:
            log = np.empty((rows, KNOT_COLUMNS))
            n = run(*pieces, model.alpha, model.frequency, model.g, model.r, model.zeno_arc, model.theta0, log)
            if n <= rows:
                break
            rows = 2 * n
        solution = knots_solution(model, excitation, log[:n], backend.name)
        if model.strict:  # located on the closed form's dense output
            object.__setattr__(solution, "block", model)
            object.__setattr__(solution, "motion", excitation)
            solution.check_contact(strict=True)
        return solution


def knots_solution(model, excitation, log, backend_name):
    """A :class:`RockingSolution` from the kernel's knot rows."""
    t, state = log[:, 0], log[:, 1:3]
    mode = log[:, 3].astype(int)
    events = []
    for k in np.flatnonzero(log[:, 5] == 1.0):
        before, after = RockingMode(int(log[k, 4])), RockingMode(int(log[k, 3]))
        pre = k > 0 and before != RockingMode.RELEASE and log[k - 1, 0] == log[k, 0] and log[k - 1, 3] == log[k, 4] \
            and log[k - 1, 5] == 0.0
        row = log[k - 1 if pre else k]
        events.append(model.event(row[0], before, after, (row[1], row[2])))
    events = tuple(events)
    rate_start = np.column_stack([state[:, 1], log[:, 6]])
    # the interval after knot i ends at knot i + 1 in mode i: that knot's theta'' where the
    # mode holds (a piece's end, an event's pre-knot); an event's zero-length step else
    rate_end = np.append(rate_start[1:], np.zeros((1, 2)), axis=0)
    stats = {"n_events": len(events), "n_knots": len(t)}
    return model.solution(t=t, y=state, mode=mode, events=events, backend=backend_name,
                          dense=HermiteDense(t, state, rate_start, rate_end), stats=stats)


#: mode value -> RockingMode (a dict: faster than the enum's call, per event)
_MODES = {float(mode): mode for mode in RockingMode}
#: the engine's name in the compile notice, and its compile time on one core [s]
_ENGINE, _COMPILE_SECONDS = "the compiled rocking engine", 20


class CompiledEngine(_OneSetEngine):
    """Runs a :class:`RockingBlock` that rocks (mu >= b/h), exact or linearised, on the
    compiled integrated engine (``backend="compiled"``: its ``rtol``, ``atol``,
    ``event_resolution``, ``max_events_at_one_instant``)."""

    def solve(self, model, excitation, horizon, backend):
        outcome, knots, events, pieces = self._run(model, excitation, horizon, backend)
        t, y, mode = knots[:, 0].copy(), knots[:, 1:3].copy(), knots[:, 3].astype(int)
        logged = tuple(model.event(when, _MODES[before], _MODES[after], state)
                       for when, before, after, *state in events.tolist())
        stats = {"max_events_at_one_instant": int(outcome[3]), "n_events": len(logged), "n_steps": int(outcome[4]),
                 "n_rejected_steps": int(outcome[5]), "n_rhs_evals": int(outcome[6])}
        solution = model.solution(t=t, y=y, mode=mode, events=logged, backend=backend.name,
                                  dense=HermiteDense(t, y, knots[:, 4:6].copy(), knots[:, 6:8].copy()), stats=stats)
        if model.strict:  # the first contact limit on the dense output stops the run, as the driver's guard
            object.__setattr__(solution, "block", model)
            object.__setattr__(solution, "motion", excitation)
            if solution.contact_events:
                t, kind, theta, rate, _, _ = min(solution.contact_events)
                raise model._contact_error(1 if theta > 0 else -1, t, (theta, rate), _Components(pieces, 1.0),
                                           kind == "lift_limit")
        return solution

    def _final_row(self, model, excitation, horizon, factor, backend):
        """One run, ``factor`` on a(t) in the kernel."""
        if model.strict:  # the contact check reads the solution and its motion
            solution = self.solve(model, excitation.scaled(factor), horizon, backend)
            return _final_row(solution.state[:, 0], solution.t, len(solution.events))
        _, knots, events, _ = self._run(model, excitation, horizon, backend, factor)
        return _final_row(knots[:, 1], knots[:, 0], len(events))

    @staticmethod
    def _run(model, excitation, horizon, backend, factor=1.0):
        """The kernel's (outcome, knots, events) of ``model`` under ``excitation`` times
        ``factor``, checked, and the pieces (a_x, a_z) it ran on."""
        if model.slides:
            raise ValueError(f"backend='compiled' runs a rocking block; with mu={model.mu} below b/h = "
                             f"{model.b / model.h:.6g} this one slides: use backend='cvode'")
        ax, az = model.excitation_pieces(excitation, horizon.integration_end(excitation))
        CF = np.ascontiguousarray(np.stack([np.stack([c.p0, c.p1, c.s, c.w, c.phi], axis=-1) for c in (ax, az)],
                                           axis=1), dtype=float)
        if factor != 1.0:
            CF[:, :, :3] *= factor  # p0, p1 and the sine's amplitude
        T0, H = (np.ascontiguousarray(a, dtype=float) for a in (ax.t0, ax.h))
        run = compiled.kernel()
        notice_numba(_ENGINE, _COMPILE_SECONDS, run)
        outcome, knots, events = run(T0, H, CF, engine_parameters(model), _options(model, backend, horizon))
        _check(model, (ax, az), outcome, events, backend.max_events_at_one_instant, factor)
        return outcome, knots, events, (ax, az)


def engine_parameters(model) -> np.ndarray:
    """The engine's ``params`` (:data:`._compiled.PARAM_FIELDS`) of ``model`` (alpha, p²
    and r as its rules compute them)."""
    alpha, _, p2, r = model._geometry(SCALAR)
    return np.array([alpha, p2, model.g, r, model.zeno_arc, model.theta0,
                     float(model.linearised), min(model.mu, model.rocking_threshold), model.rocking_threshold,
                     model.output_step(), RATE_FLOOR * model.frequency * model.alpha])


def _options(model, backend, horizon) -> np.ndarray:
    """The engine's ``options`` (:data:`._compiled.OPTION_FIELDS`)."""
    bound = model.time_to_rest(RockingMode.REST, None) if horizon.until_rest and model.r < 1 else math.inf
    return np.array([backend.rtol, backend.atol, backend.event_resolution, backend.max_events_at_one_instant,
                     float(horizon.until_rest), bound])


class _Components:
    """The pieces of (a_x, a_z) as the model's rules read an excitation at one instant."""

    def __init__(self, pieces, factor):
        self.pieces, self.factor = pieces, factor

    def component(self, index, t):
        return self.factor * float(evaluate(self.pieces[index], t)[0])

    def component_rate(self, index, t):
        return self.factor * float(evaluate(self.pieces[index], t)[1])


def _check(model, pieces, outcome, events, cap, factor=1.0):
    """Raise as the driver does where the engine stopped early; ``pieces``: (a_x, a_z),
    run at ``factor`` times."""
    status, t = int(outcome[2]), float(outcome[0])
    if status == compiled.FINISHED:
        return
    if status == compiled.FLIGHT:
        raise model._flight(t, _Components(pieces, factor))
    if status == compiled.CHATTER:
        modes = " -> ".join(RockingMode(int(e[1])).name for e in events[-cap - 1:])
        raise RuntimeError(f"{cap + 1} events at t = {t:.12g} s ({modes} -> {RockingMode(int(events[-1][2])).name}): "
                           f"chatter; raise max_events_at_one_instant={cap}")
    if status == compiled.NEVER_RESTS:
        model.time_to_rest(RockingMode(int(outcome[1])), None)  # raises the model's own error
    if status == compiled.NO_REST:
        raise RuntimeError(f"{RockingMode(int(outcome[1])).name} found no rest by t = {t:.6g} s after the excitation")
    problem = {compiled.INCONSISTENT: "theta' points against its mode beyond the velocity error (a missed event)",
               compiled.STEP_TOO_SMALL: "the step fell below rounding"}[status]
    raise RuntimeError(f"the compiled rocking engine stopped at t = {t:.12g} s: {problem}; please report")
