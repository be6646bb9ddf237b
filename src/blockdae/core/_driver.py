"""The hybrid driver: one loop that runs a step-wise ODE/DAE integrator through the modes.

The driver owns the hybrid logic; an integrator (CVODE, IDA, ...) only integrates one
mode and reports guard roots. Per piece of the excitation the driver

1. lets a block at rest re-take ``mode_at_rest`` from the piece's right-hand limits,
2. in a mode whose state is constant (stick), locates the first guard root in time
   alone, by bisection to adjacent floats on parts where the guards are monotone;
   otherwise restarts the integrator and runs it with a hard stop (``tstop``) at the piece end,
   and in a slip mode also at the turning point of v, so that every guard is monotone
   between two stops and a sign change at the end of an internal step cannot hide two
   roots,
3. at a guard root logs the :class:`Event`, asks the model for the next mode and
   restarts the integrator.

Callbacks see a :class:`PieceExcitation` (one closed form per component) and the
:data:`SCALAR` namespace, so the model's own ``flow``/``guards`` run on Python floats in
a few µs. Everything that depends on the model's state (which modes keep it constant,
what a stop resets, where a guard may turn) is asked of the model, so one loop serves
every :class:`~blockdae.AbstractHybridModel`.
"""

import abc
import math
import sys
import time

import numpy as np

from ..excitation import accel, accel_rate, monotone_rate, piece_direction
from .events import (ROUNDING, left_at_once, static_root, stop_uncertainty, too_short, turning_point,
                               velocity_error)
from .contract import KNOTS_PER_RADIAN, SCALAR


#: a run shows its progress on a terminal after this long [s], refreshed this often [s]
PROGRESS_DELAY, PROGRESS_INTERVAL = 2.0, 0.5


class PieceExcitation:
    """The base acceleration [m/s²] on one monotone piece, in closed form, one
    (p0, p1, s, w, phi) per component; stands in for the excitation in the model's
    rules inside solver callbacks. ``acceleration``/``acceleration_rate`` give the first
    component (a 1-D motion), ``component``/``component_rate`` any of them."""

    __slots__ = ("t0", "h", "coefficients", "directions", "project_rates")

    def __init__(self, n_components=1, project_rates=True):
        self.t0, self.h, self.coefficients = 0.0, math.inf, ((0.0,) * 5,) * n_components
        self.directions, self.project_rates = (0.0,) * n_components, project_rates

    def set(self, t0, coefficients, h=math.inf):
        """Switch to the piece [t0, t0 + h] [s] with one (p0, p1, s, w, phi) per component."""
        self.t0, self.h = float(t0), float(h)
        self.coefficients = tuple(tuple(float(c) for c in component) for component in coefficients)
        project = self.project_rates and self.h < math.inf
        self.directions = tuple(float(piece_direction(c, self.h)) if project else 0.0 for c in self.coefficients)

    def local_time(self, t):
        """``t`` [s] from the piece's start, at most its length: the piece's end ``t0 +
        h`` may round to a time whose distance from ``t0`` exceeds ``h`` (0.05 - 0.04 =
        0.010000000000000002), where a(t) would overshoot the next sample by an ulp, as
        the exact backend's local times never do."""
        return min(t - self.t0, self.h)

    def component(self, index, t):
        """Component ``index`` of the base acceleration at ``t`` [m/s²]."""
        return accel(*self.coefficients[index], self.local_time(t), math)

    def component_rate(self, index, t):
        """Its rate just after ``t`` [m/s³], with rounding projected out (unless built with
        ``project_rates=False``): a component is monotone on a piece, so a rate against
        its direction (a cosine that rounds to 6e-17 at an extremum) is zero, and a
        demand that touches a threshold at an extremum turns back, as the exact backend
        decides. The integrators' callbacks get the rates as the closed form gives
        them: a flow is no decision (IDA's consistent start moves its events by 1e-9 s
        on Elms's pulse with vertical shaking when F' is 1e-14 instead of 0)."""
        rate = accel_rate(*self.coefficients[index], self.local_time(t), math)
        return monotone_rate(rate, self.directions[index], SCALAR)

    def acceleration(self, t):
        return self.component(0, t)

    def acceleration_rate(self, t):
        return self.component_rate(0, t)

    @property
    def highest_frequency(self):
        """Largest angular frequency of a sine term on the piece [rad/s] (0: none)."""
        return max((c[3] for c in self.coefficients if c[2] != 0), default=0.0)


class SolverError(RuntimeError):
    """An integrator failed (negative flag); the message names time, mode and flag."""


class ModelContractError(ValueError):
    """A model's hook broke the contract in a run (a flow or guards of the wrong shape, a
    mode the enumeration lacks, a mode entered with a guard already below zero); the
    message names the hook, the mode and the values."""


class InconsistentStateError(RuntimeError):
    """The integrated state contradicts its mode (a slide moving against its direction):
    a missed event; the message names the time, the mode and the values."""


class AbstractIntegrator(abc.ABC):
    """One solver in one mode at a time, as the driver sees it.

    Built by a backend for one run with the model and the driver's
    :class:`PieceExcitation`, whose coefficients change between calls.
    """

    @abc.abstractmethod
    def restart(self, mode, t: float, y: np.ndarray) -> None:
        """Start afresh in ``mode`` at ``t`` [s] from the model's state ``y``."""

    @abc.abstractmethod
    def step(self, t_out: float, t_stop: float) -> tuple[float, np.ndarray, int | None]:
        """Integrate to ``t_out`` <= ``t_stop`` [s] or to the first guard root, with no
        internal step past ``t_stop``.

        Returns (t [s], state (the model's states first), index of the guard that
        reached zero, or None when ``t_out`` was reached). Raises :class:`SolverError`
        on failure.
        """

    @property
    @abc.abstractmethod
    def stats(self) -> dict:
        """Solver counters (steps, right-hand-side calls, ...)."""


def drive(model, excitation, horizon, integrator_factory, backend_name, max_events_at_one_instant,
          event_resolution, velocity_tolerance, trace=None):
    """Run ``model`` under ``excitation`` to ``horizon`` with one integrator.

    Args:
        integrator_factory: ``(model, piece) -> AbstractIntegrator``.
        backend_name: recorded in the solution.
        max_events_at_one_instant: most consecutive events at one instant [-]; more
            (chatter) raises an error instead of looping.
        event_resolution: events closer than this [s] are one instant: a stop where
            a threshold is crossed within it grazes or reverses (the model's
            ``mode_after_guard``), and chatter is counted over it.
        velocity_tolerance: (rtol [-], atol [m/s]) of the integrator; a stop is
            uncertain by the time the guard needs to change by a few of these (see
            ``_Run.stop_uncertainty``), which widens ``event_resolution`` at grazes.
        trace: a list to append the run's steps to, in order (for derivatives along the
            located trajectory, :mod:`blockdae.solvers._trajectory`); each a tuple
            ("flow", mode, t_from, y_from, t_to, piece) (the integrator ran ``mode``
            from ``y_from``), ("guard", mode, index, t, y, piece) (guard ``index``
            reached zero at ``t`` in state ``y``) or ("entry", before, after, t, y, piece) (the mode
            changed at ``t``; ``y`` before ``state_on_entry``); ``piece`` is the piece's
            (t0 [s], coefficients).
    """
    components = model.excitation_pieces(excitation, horizon.integration_end(excitation))
    run = _Run(model, len(components), integrator_factory, max_events_at_one_instant, event_resolution,
               velocity_tolerance, trace)
    t0, h = components[0].t0, components[0].h
    starts = np.append(t0[1:], t0[-1] + h[-1])
    progress = Progress(backend_name, float(starts[-1]))
    try:
        for k in range(len(t0)):
            run.piece(t0[k], starts[k], h[k], tuple(tuple(c[k] for c in p[2:]) for p in components))
            progress.update(run.t, len(run.events))
        if horizon.until_rest:
            run.tail_to_rest(float(starts[-1]))
    finally:
        progress.close()
    return run.solution(backend_name)


class Progress:
    """One line on a terminal (stderr) for a long run: the time reached, the events and
    the wall time, shown once a run has taken :data:`PROGRESS_DELAY` [s] and refreshed
    every :data:`PROGRESS_INTERVAL` [s]; nothing where stderr is not a terminal."""

    def __init__(self, label, t_end):
        self.label, self.t_end = label, t_end
        self.show = sys.stderr.isatty()
        self.start = self.last = time.monotonic()
        self.shown = False

    def update(self, t, n_events):
        """The run has reached ``t`` [s] with ``n_events`` events."""
        if not self.show:
            return
        now = time.monotonic()
        if now - self.start < PROGRESS_DELAY or (self.shown and now - self.last < PROGRESS_INTERVAL):
            return
        self.last, self.shown = now, True
        share = f" ({100 * t / self.t_end:.0f} %)" if self.t_end > 0 else ""
        sys.stderr.write(f"\r{self.label}: t = {t:.6g} s of {self.t_end:.6g} s{share}, {n_events:,} events, "
                         f"{now - self.start:.0f} s elapsed")
        sys.stderr.flush()

    def close(self):
        """End the line, if one was shown."""
        if self.shown:
            sys.stderr.write("\n")


class _Run:
    """State of one run: time, state, mode, knots and events."""

    #: every mode's ``flow`` and ``guards`` checked for shape before the run (else each
    #: where the run enters it)
    checks_modes_at_start = True

    def __init__(self, model, n_components, integrator_factory, max_events_at_one_instant, event_resolution,
                 velocity_tolerance, trace=None):
        self.model, self.resolution, self.trace = model, event_resolution, trace
        self.velocity_tolerance, self.v_max = velocity_tolerance, 0.0
        self.piece_excitation = PieceExcitation(n_components)  # the driver's decisions
        self.flow_excitation = PieceExcitation(n_components, project_rates=False)  # the integrator's
        self.cap = max_events_at_one_instant
        self.n_states = len(model.state_names)
        self.mode = self.to_mode(model.initial_mode, "initial_mode")
        self.y = np.array(model.initial_state(), dtype=float)
        if self.y.shape != (self.n_states,):
            raise ModelContractError(f"{type(model).__name__}.initial_state gave shape {self.y.shape}; it must give "
                                     f"one value per state, shape ({self.n_states},)")
        self.t = 0.0
        self.checked_modes, self.entry_pending, self.entry_tolerance = set(), True, 0.0
        if self.checks_modes_at_start:  # before the integrator sizes its buffers from them
            for mode in model.modes:
                self.check_shapes(mode, self.y, self.piece_excitation, at_start=True)
        self.integrator = integrator_factory(model, self.flow_excitation)
        self.events, self.run_length, self.max_run = [], 0, 0
        self.restarted = True
        self.knots = _Knots()
        self.knots.add(self.t, self.y, self.mode, self.y, self.y)

    # ---- model rules on the current piece ---------------------------------
    def rate(self, mode, t, y):
        """dy/dt in ``mode`` from the model's flow, as an array."""
        return np.array(self.model.flow(mode, t, y, self.piece_excitation, SCALAR), dtype=float)

    def to_mode(self, value, hook):
        """``value`` as a member of the model's mode enumeration; :class:`ModelContractError`
        naming ``hook`` (what gave it) where the enumeration lacks it."""
        try:
            return self.model.modes(int(value))
        except (ValueError, TypeError):
            raise ModelContractError(
                f"{type(self.model).__name__}.{hook} gave the mode {value!r}, which {self.model.modes.__name__} "
                f"lacks (its modes: {', '.join(f'{m.name}={int(m)}' for m in self.model.modes)})") from None

    def check_shapes(self, mode, y, excitation, at_start=False):
        """``flow`` and ``guards`` of ``mode`` in state ``y`` of the right shape, checked once
        per mode and run (:class:`ModelContractError`); ``at_start``: a check of every mode
        before the run, from the initial state at rest, skipped for a mode whose hooks
        raise there (checked again where the mode is entered)."""
        if mode in self.checked_modes:
            return
        model, name = self.model, type(self.model).__name__
        try:
            flow = np.shape(model.flow(mode, self.t, y, excitation, SCALAR))
            guards = np.shape(model.guards(mode, self.t, y, excitation, SCALAR))
        except Exception:
            if at_start:
                return
            raise
        if flow != (self.n_states,):
            raise ModelContractError(
                f"{name}.flow in mode {mode.name} gave shape {flow}; it must give one rate per state, "
                f"shape ({self.n_states},) (state_names {tuple(model.state_names)})")
        if len(guards) != 1:
            raise ModelContractError(
                f"{name}.guards in mode {mode.name} gave shape {guards}; it must give a 1-D sequence, shape "
                "(n_guards,) (xp.stack([...]) of one value per guard)")
        self.checked_modes.add(mode)

    def check_entry(self):
        """The current mode, just entered at ``t``: its ``flow`` and ``guards`` of the
        right shape (checked once per mode and run), and no guard below zero beyond what the
        located event's uncertainty allows (a guard written with the wrong sign: the
        mode would have been left before it was entered). Raises :class:`ModelContractError`."""
        model, mode, name = self.model, self.mode, type(self.model).__name__
        self.check_shapes(mode, self.y, self.piece_excitation)
        values = () if mode in model.instant_modes else model.guards(mode, self.t, self.y, self.piece_excitation,
                                                                      SCALAR)
        for index, value in enumerate(values):
            if value < 0:
                slope, curvature = model.guard_rates(mode, index, self.t, self.y, self.piece_excitation)
                within = max(self.stop_uncertainty(index), self.entry_tolerance)
                allowed = self.velocity_error() + ROUNDING + abs(slope) * within + 0.5 * abs(curvature) * within**2
                if -value > allowed:
                    raise ModelContractError(
                        f"{name}: mode {mode.name} entered at t = {self.t:.12g} s with guard {index} = "
                        f"{float(value):.6g} below zero (by more than {allowed:.3g}, what the located event's "
                        "uncertainty allows): a guard "
                        "is positive in its mode and the mode is left where it crosses zero downwards; check its sign "
                        f"in {name}.guards, or the mode that {name}.mode_after_guard/mode_at_rest/initial_mode chose; "
                        f"state {dict(zip(model.state_names, map(float, self.y)))}")
        self.entry_pending = False

    def current_piece(self):
        """The current piece of the excitation: (t0 [s], coefficients)."""
        return self.piece_excitation.t0, self.piece_excitation.coefficients

    def record(self, *step):
        """Append ``step`` to the trace, if one is kept (see :func:`drive`)."""
        if self.trace is not None:
            self.trace.append(step)

    # ---- the loop ----------------------------------------------------------
    def enter_piece(self, t0, h, coefficients):
        """Switch to the piece [t0, t0 + h] [s]; a block at rest re-takes the mode the
        right-hand limits of the excitation give.

        The integrator restarts at every piece, in every mode: a multistep history
        carried across a kink or jump of a(t) fits one polynomial to two pieces
        (CVODE at rtol 1e-10, worst event time over the 18 sample records: 1.7e-9 s
        carrying it, 4.8e-12 s restarting), and IDA's algebraic F follows a(t), whose
        slope jumps there (from IDA's own first step: 8.8e-9 s restarting in stick
        only, 1.0e-9 s in every mode).
        """
        self.piece_excitation.set(t0, coefficients, h)
        self.flow_excitation.set(t0, coefficients, h)
        self.knots.set_right_rate(self.rate(self.mode, self.t, self.y))
        self.restarted = True
        if self.model.at_rest(self.mode, self.y):
            self.retake_rest(t0)

    def retake_rest(self, t0):
        """A block at rest takes the mode the right-hand limits of the piece that starts at
        ``t0`` [s] give (an event where that mode is another)."""
        rest = self.to_mode(self.model.mode_at_rest(t0, self.piece_excitation, SCALAR, y=self.y), "mode_at_rest")
        if rest != self.mode:
            self.y, self.entry_tolerance = self.model.rest_state(self.y), 0.0
            self.log_event(float(t0), rest)

    def piece(self, t0, end, h, coefficients):
        """Integrate over one piece [t0, end] [s] of the excitation, of local length ``h`` [s]."""
        self.enter_piece(t0, h, coefficients)
        self.advance_to(float(end))

    def advance_to(self, end, until_rest=False):
        turn = self.turning_point(end)
        while self.t < end and not (until_rest and self.model.is_static(self.mode)):
            if self.entry_pending:
                self.check_entry()
            if self.model.is_static(self.mode):
                root = self.static_root(end)
                if root is None:
                    self.t, self.restarted = end, True  # the state is constant and stays in the mode
                    self.knots.add(end, self.y, self.mode, np.zeros(self.n_states), np.zeros(self.n_states))
                    return
                self.t, index = root
                self.on_guard(index)
                turn = self.turning_point(end)
                continue
            if self.restarted:
                index = self.guard_left_at_once()
                if index is not None:
                    before = self.mode
                    self.on_guard(index)
                    turn = self.turning_point(end)
                    if self.mode != before:
                        continue
                self.integrator.restart(self.mode, self.t, self.y)
                self.restarted = False
            target = end if turn is None or turn <= self.t else turn
            if too_short(self.t, target):
                # too short for a solver step (SUNDIALS refuses it): nothing can happen
                self.t, self.restarted = target, True
                continue
            t_out = min(target, self.t + self.output_step())
            t, y, root = self.integrator.step(t_out, target)
            if root is not None and float(t) >= end:
                # a guard reaching zero at the end of the piece is left to the next piece's
                # right-hand limits (``guard_left_at_once``), as in a static mode: n
                # touching zero at a sample where a_z turns is no liftoff
                root, t_out = None, end
            t_from, y_from = self.t, self.y
            self.t, self.y = (t_out if root is None else float(t)), np.array(y[:self.n_states], dtype=float)
            self.record("flow", self.mode, t_from, y_from, self.t, self.current_piece())
            self.v_max = max(self.v_max, self.model.speed(self.y))
            self.check_consistent(t_from)
            if root is None:
                rate = self.rate(self.mode, self.t, self.y)
                self.knots.add(self.t, self.y, self.mode, rate, rate)
            else:
                self.on_guard(root)
                turn = self.turning_point(end)

    def guard_left_at_once(self):
        """The first guard of the current mode that is at or below zero and falling as a
        flow starts (a slide entered at a sample where its velocity turns against it at
        once; see :func:`~blockdae.core.events.falls`): it is reached now. An
        integrator would not see it: its roots are sign changes, and a guard that starts at
        zero has none (SUNDIALS: "root functions identically 0"). None if there is none."""
        values = self.model.guards(self.mode, self.t, self.y, self.piece_excitation, SCALAR)
        rates = lambda _, index: self.model.guard_rates(self.mode, index, self.t, self.y, self.piece_excitation)
        index = left_at_once(values, rates, None, self.resolution)
        return None if index < 0 else index

    def output_step(self):
        """Largest gap between knots [s]: cubic Hermite is exact for the cubic u of a
        linear piece; on a sine piece of angular frequency w, 1 / (32 w) keeps its
        error near 1e-9 of the amplitude (h^4 w^4 / 384); at most the model's own
        ``output_step`` (an oscillator's)."""
        w = self.piece_excitation.highest_frequency
        return min(1.0 / (KNOTS_PER_RADIAN * w) if w > 0 else math.inf, self.model.output_step())

    def static_root(self, end):
        """The first guard root in (t, end] [s] of a static mode, located in t alone (the
        state is constant): (time, guard index), or None. The model's ``turn_rate``
        splits the piece where a guard may turn, so that each guard is monotone on
        both parts and a root is bracketed where it goes from > 0 to < 0."""
        guards = lambda _, t: self.model.guards(self.mode, t, self.y, self.piece_excitation, SCALAR)
        guard = lambda pair, t: guards(None, t)[pair[1]]
        turn = self.turning_point(end)
        root, index = static_root(guards, guard, None, self.t, math.nan if turn is None else turn, end)
        return None if index < 0 else (root, index)

    def turning_point(self, end):
        """The time in (t, end) [s] where the model's ``turn_rate`` changes sign (it is
        monotone on a piece), so that the guards are monotone between stops; None if
        there is none or the mode has no turn rate there (None at any time asked)."""
        root = turning_point(self._turn_rate, None, self.t, end)
        return None if math.isnan(root) else root

    def _turn_rate(self, _, t):
        """(the model's turn rate at ``t``, whether it has one), as :func:`turning_point`
        takes it."""
        value = self.model.turn_rate(self.mode, t, self.y, self.piece_excitation, SCALAR)
        return (0.0, False) if value is None else (value, True)

    def on_guard(self, index):
        """Guard ``index`` of the current mode reached zero at ``self.t``."""
        model, before = self.model, self.mode
        self.record("guard", before, index, self.t, self.y, self.current_piece())
        self.y = model.state_at_guard(before, index, self.y)
        time_tol = self.stop_uncertainty(index)
        after = self.to_mode(model.mode_after_guard(before, index, self.t, self.y, self.piece_excitation,
                                                    SCALAR, time_tol), "mode_after_guard")
        self.entry_tolerance = time_tol
        rate = self.rate(before, self.t, self.y)
        self.knots.add(self.t, self.y, before, rate, rate)
        if after != before or model.guard_restarts(before, index):
            self.log_event(self.t, after)

    def velocity_error(self):
        """The error [m/s] of the integrated velocities (:func:`~blockdae.core.events.velocity_error`)."""
        return velocity_error(*self.velocity_tolerance, self.v_max)

    def check_consistent(self, t_from):
        """Raise :class:`InconsistentStateError` if the state just integrated from
        ``t_from`` [s] contradicts its mode beyond the velocity error (the model's
        ``contradiction``): a missed event must never become a returned result."""
        tolerance = self.velocity_error() + ROUNDING * self.v_max
        problem = self.model.contradiction(self.mode, self.y, tolerance)
        if problem is not None:
            raise InconsistentStateError(
                f"at t = {self.t:.12g} s (integrated from {t_from:.12g} s) the state contradicts mode "
                f"{self.mode.name}: {problem} (beyond the velocity error {tolerance:.3g} m/s); "
                f"state {dict(zip(self.model.state_names, map(float, self.y)))}: a missed event, please report")

    def stop_uncertainty(self, index):
        """How far [s] the located root of guard ``index`` may lie from the true one, at
        least the event resolution (:func:`~blockdae.core.events.stop_uncertainty`,
        with the guard's rate and curvature from the model and the velocity error)."""
        slope, curvature = self.model.guard_rates(self.mode, index, self.t, self.y, self.piece_excitation)
        return stop_uncertainty(slope, curvature, self.velocity_error(), self.resolution)

    def log_event(self, t, after):
        same_instant = bool(self.events) and abs(t - self.events[-1].t) <= self.resolution
        self.run_length = self.run_length + 1 if same_instant else 1
        self.max_run = max(self.max_run, self.run_length)
        before, model = self.mode, self.model
        self.events.append(model.event(float(t), before, after, self.y))
        self.record("entry", before, after, float(t), self.y, self.current_piece())
        self.y = np.array(model.state_on_entry(before, after, t, self.y, self.piece_excitation, SCALAR), dtype=float)
        if self.run_length > self.cap:
            modes = " -> ".join(e.mode_before.name for e in self.events[-self.run_length:])
            raise RuntimeError(
                f"{self.run_length} events at t = {t:.12g} s ({modes} -> {after.name}): chatter; "
                f"raise max_events_at_one_instant={self.cap}")
        self.mode, self.restarted, self.entry_pending = after, True, True
        self.knots.add(t, self.y, after, np.zeros(self.n_states), self.rate(after, t, self.y))

    def tail_to_rest(self, t_end):
        """After the excitation (zero acceleration): run until the model is at rest in a
        static mode, within the model's bound on the time that takes."""
        self.enter_piece(t_end, math.inf, ((0.0,) * 5,) * len(self.piece_excitation.coefficients))
        if self.model.is_static(self.mode):
            return
        bound = self.t + self.model.time_to_rest(self.mode, self.y)
        self.advance_to(bound, until_rest=True)
        if not self.model.is_static(self.mode):
            raise RuntimeError(f"{self.mode.name} found no rest by t = {bound:.6g} s after the excitation")

    def solution(self, backend_name):
        t, y, mode, rate_start, rate_end = self.knots.arrays()
        stats = {"max_events_at_one_instant": self.max_run, "n_events": len(self.events),
                 **self.integrator.stats}
        return self.model.solution(t=t, y=y, mode=mode, events=tuple(self.events), backend=backend_name,
                                   dense=HermiteDense(t, y, rate_start, rate_end), stats=stats)


class _Outside(AbstractIntegrator):
    """No integrator: an :class:`EventRun`'s engine integrates the modes itself."""

    stats = {}

    def restart(self, mode, t, y):
        pass

    def step(self, t_out, t_stop):
        raise NotImplementedError("an EventRun's engine integrates the modes itself")


class EventRun(_Run):
    """The driver's run (its events, knots, checks and rules at each event) for an engine
    that integrates the modes and locates the guards itself (a compiled one), then hands
    the run each event as the driver's loop would: ``on_guard``, ``guard_left_at_once``,
    ``log_event`` with ``t``, ``y``, ``mode`` and ``v_max`` set, the current piece in
    ``piece_excitation`` and ``flow_excitation``. The engine sizes nothing from the model's
    hooks: a mode's are checked where the driver's code enters it."""

    checks_modes_at_start = False

    def __init__(self, model, n_components, max_events_at_one_instant, event_resolution, velocity_tolerance):
        super().__init__(model, n_components, lambda *_: _Outside(), max_events_at_one_instant, event_resolution,
                         velocity_tolerance)


class _Knots:
    """Knots of a run. Interval i = [t_i, t_i+1] runs in ``mode[i]``; dy/dt is
    ``rate_start[i]`` just after t_i and ``rate_end[i]`` just before t_i+1."""

    def __init__(self):
        self.rows, self.rate_end = [], []

    def add(self, t, y, mode_after, rate_left, rate_right):
        """A knot at ``t`` [s]; ``rate_left`` ends the previous interval."""
        if self.rows:
            self.rate_end.append(np.array(rate_left, dtype=float))
        self.rows.append([t, np.array(y, dtype=float), int(mode_after), np.array(rate_right, dtype=float)])

    def set_right_rate(self, rate_right):
        """dy/dt just after the last knot, once the excitation's next piece is known."""
        self.rows[-1][3] = np.array(rate_right, dtype=float)

    def arrays(self):
        """t (n,), y (n, k), mode (n,), rate_start (n, k), rate_end (n, k)."""
        t, y, mode, rate_start = zip(*self.rows)
        rate_end = np.array(self.rate_end + [np.zeros_like(y[0])]).reshape(len(t), -1)
        return np.array(t), np.array(y), np.array(mode, dtype=int), np.array(rate_start), rate_end


class HermiteDense:
    """The state between knots by cubic Hermite interpolation of each component of y
    with slopes dy/dt; ``__call__(t)`` returns a tuple of k arrays of t's shape."""

    def __init__(self, t, y, rate_start, rate_end):
        self.t, self.y = t, y
        self.rate_start, self.rate_end = rate_start, rate_end

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        i = np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, len(self.t) - 2)
        h = self.t[i + 1] - self.t[i]
        s = np.where(h > 0, (t - self.t[i]) / np.where(h > 0, h, 1.0), 0.0)
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        y0, y1 = np.moveaxis(self.y[i], -1, 0), np.moveaxis(self.y[i + 1], -1, 0)
        d0, d1 = np.moveaxis(self.rate_start[i], -1, 0), np.moveaxis(self.rate_end[i], -1, 0)
        return tuple(h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1)
