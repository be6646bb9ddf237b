"""The hybrid driver: one loop that runs a step-wise ODE/DAE integrator through the modes.

The driver owns the hybrid logic; an integrator (CVODE, IDA, ...) only integrates one
mode and reports guard roots. Per piece of the excitation the driver

1. lets a block at rest re-take ``mode_at_rest`` from the piece's right-hand limits,
2. restarts the integrator and runs it with a hard stop (``tstop``) at the piece end,
   and in a slip mode also at the turning point of v, so that every guard is monotone
   between two stops and a sign change at the end of an internal step cannot hide two
   roots,
3. at a guard root logs the :class:`Event`, asks the model for the next mode and
   restarts the integrator.

Callbacks see a :class:`PieceExcitation` (one closed form) and the :data:`SCALAR`
namespace, so the model's own ``flow``/``guards`` run on Python floats in a few µs.
"""

import abc
import math
import types

import numpy as np

from ._solution import Event, Solution
from .backends._base import never_rests_error
from .excitation._pieces import accel, accel_rate
from .model import Mode, comes_to_rest

#: array namespace for the model's xp-generic rules on Python floats
SCALAR = types.SimpleNamespace(stack=tuple, where=lambda cond, a, b: a if cond else b)

_EPS = np.finfo(float).eps
_TURN_BISECTIONS = 60  # halves a piece below 1e-18 of its length
_ULPS = 8  # intervals shorter than this many ulps are not integrated
_KNOTS_PER_RADIAN = 32  # dense-output knots on sine pieces
# global error of v in local tolerances: |v'| |t_stop - t_exact| / (rtol max|v| + atol)
# at every stop on the 18 sample records (two-way mu 0.15, f 0.12, bias 0.03 and
# one-way mu 0.1) at rtol 1e-10 reaches 1.1 for CVODE and 9.2 for IDA
_V_ERROR_FACTOR = 10.0


class PieceExcitation:
    """a(t) [m/s²] on one monotone piece, in closed form; stands in for the excitation
    in the model's rules inside solver callbacks (``acceleration``, ``acceleration_rate``)."""

    __slots__ = ("t0", "coefficients")

    def __init__(self):
        self.t0, self.coefficients = 0.0, (0.0,) * 5

    def set(self, t0, coefficients):
        """Switch to the piece starting at ``t0`` [s] with (p0, p1, s, w, phi)."""
        self.t0, self.coefficients = float(t0), tuple(float(c) for c in coefficients)

    def acceleration(self, t):
        return accel(*self.coefficients, t - self.t0, math)

    def acceleration_rate(self, t):
        return accel_rate(*self.coefficients, t - self.t0, math)


class SolverError(RuntimeError):
    """An integrator failed (negative flag); the message names time, mode and flag."""


class AbstractIntegrator(abc.ABC):
    """One solver in one mode at a time, as the driver sees it.

    Built by a backend for one run with the block and the driver's
    :class:`PieceExcitation`, whose coefficients change between calls.
    """

    @abc.abstractmethod
    def restart(self, mode: Mode, t: float, y: np.ndarray) -> None:
        """Start afresh in ``mode`` at ``t`` [s] from y = (u [m], v [m/s])."""

    @abc.abstractmethod
    def step(self, t_out: float, t_stop: float) -> tuple[float, np.ndarray, int | None]:
        """Integrate to ``t_out`` <= ``t_stop`` [s] or to the first guard root, with no
        internal step past ``t_stop``.

        Returns (t [s], (u, v), index of the guard that reached zero, or None when
        ``t_out`` was reached). Raises :class:`SolverError` on failure.
        """

    @property
    @abc.abstractmethod
    def stats(self) -> dict:
        """Solver counters (steps, right-hand-side calls, ...)."""


def drive(block, excitation, horizon, integrator_factory, backend_name, max_events_at_one_instant,
          event_resolution, velocity_tolerance):
    """Run ``block`` under ``excitation`` to ``horizon`` with one integrator.

    Args:
        integrator_factory: ``(block, piece) -> AbstractIntegrator``.
        backend_name: recorded in the :class:`Solution`.
        max_events_at_one_instant: most consecutive events at one instant [-]; more
            (chatter) raises an error instead of looping.
        event_resolution: events closer than this [s] are one instant: a stop where
            a threshold is crossed within it grazes or reverses (the model's
            ``stop_mode``), and chatter is counted over it.
        velocity_tolerance: (rtol [-], atol [m/s]) of the integrator; a stop is
            uncertain by the time v needs to change by a few of these (see
            ``_Run.stop_uncertainty``), which widens ``event_resolution`` at grazes.
    """
    pieces = excitation.pieces(horizon.integration_end(excitation))
    run = _Run(block, integrator_factory, max_events_at_one_instant, event_resolution, velocity_tolerance)
    starts = np.append(pieces.t0[1:], pieces.t_end)
    for k in range(len(pieces.t0)):
        run.piece(pieces.t0[k], starts[k], tuple(c[k] for c in pieces[2:]))
    if horizon.until_rest:
        run.tail_to_rest(pieces.t_end)
    return run.solution(backend_name)


class _Run:
    """State of one run: time, state, mode, knots and events."""

    def __init__(self, block, integrator_factory, max_events_at_one_instant, event_resolution,
                 velocity_tolerance):
        self.block, self.resolution = block, event_resolution
        self.velocity_tolerance, self.v_max = velocity_tolerance, 0.0
        self.piece_excitation = PieceExcitation()
        self.integrator = integrator_factory(block, self.piece_excitation)
        self.cap = max_events_at_one_instant
        self.t, self.y, self.mode = 0.0, np.zeros(2), Mode.STICK
        self.events, self.run_length, self.max_run = [], 0, 0
        self.restarted = True
        self.knots = _Knots()
        self.knots.add(self.t, self.y, self.mode, 0.0, 0.0)

    # ---- model rules on the current piece ---------------------------------
    def slip_rate(self, mode, t, y):
        """dv/dt [m/s²] in ``mode`` from the model's flow."""
        return self.block.flow(mode, t, y, self.piece_excitation, SCALAR)[1]

    # ---- the loop ----------------------------------------------------------
    def enter_piece(self, t0, coefficients):
        """Switch to the piece starting at ``t0`` [s]; a block at rest re-takes the mode
        the right-hand limits of a(t) give.

        The integrator restarts at every piece, in every mode: a multistep history
        carried across a kink or jump of a(t) fits one polynomial to two pieces
        (CVODE at rtol 1e-10, worst event time over the 18 sample records: 1.7e-9 s
        carrying it, 4.8e-12 s restarting), and IDA's algebraic F follows a(t), whose
        slope jumps there (from IDA's own first step: 8.8e-9 s restarting in stick
        only, 1.0e-9 s in every mode).
        """
        self.piece_excitation.set(t0, coefficients)
        self.knots.set_right_rate(self.slip_rate(self.mode, self.t, self.y))
        self.restarted = True
        if self.mode == Mode.STICK or self.y[1] == 0:
            rest = Mode(int(self.block.mode_at_rest(t0, self.piece_excitation, SCALAR)))
            if rest != self.mode:
                self.y = np.array([self.y[0], 0.0])
                self.log_event(float(t0), rest)

    def piece(self, t0, end, coefficients):
        """Integrate over one piece [t0, end] [s] of a(t)."""
        self.enter_piece(t0, coefficients)
        self.advance_to(float(end))

    def advance_to(self, end, until_stick=False):
        if self.mode == Mode.STICK and not self.guard_changes_sign(end):
            self.t, self.restarted = end, True  # the state is constant in stick
            self.knots.add(end, self.y, self.mode, 0.0, 0.0)
            return
        turn = self.turning_point(end)
        while self.t < end and not (until_stick and self.mode == Mode.STICK):
            if self.restarted:
                self.integrator.restart(self.mode, self.t, self.y)
                self.restarted = False
            target = end if turn is None or turn <= self.t else turn
            if target - self.t <= _ULPS * _EPS * max(1.0, abs(target)):
                # too short for a solver step (SUNDIALS refuses it): nothing can happen
                self.t, self.restarted = target, True
                continue
            t_out = min(target, self.t + self.output_step())
            t, y, root = self.integrator.step(t_out, target)
            self.t, self.y = (t_out if root is None else float(t)), np.array(y[:2], dtype=float)
            self.v_max = max(self.v_max, abs(self.y[1]))
            if root is None:
                rate = self.slip_rate(self.mode, self.t, self.y)
                self.knots.add(self.t, self.y, self.mode, rate, rate)
            else:
                self.on_guard(root)
                turn = self.turning_point(end)

    def output_step(self):
        """Largest gap between knots [s]: cubic Hermite is exact for the cubic u of a
        linear piece; on a sine piece of angular frequency w, 1 / (32 w) keeps its
        error near 1e-9 of the amplitude (h^4 w^4 / 384)."""
        w = self.piece_excitation.coefficients[3]
        return 1.0 / (_KNOTS_PER_RADIAN * w) if self.piece_excitation.coefficients[2] != 0 else math.inf

    def guard_changes_sign(self, end):
        """Whether a guard of the mode may reach zero before ``end`` [s]. Stick guards
        are monotone on a piece, so positive values at both ends exclude a root and the
        integrator need not run (it restarts, exactly, where the state is constant)."""
        guards = lambda t: self.block.guards(self.mode, t, self.y, self.piece_excitation, SCALAR)
        return min(guards(end)) <= 0 or min(guards(self.t)) <= 0

    def turning_point(self, end):
        """In slip: the time in (t, end) [s] where dv/dt changes sign (dv/dt is monotone
        on a piece), so that v is monotone between stops; None if there is none."""
        if self.mode == Mode.STICK:
            return None
        lo, hi = self.t, end
        sign_lo = math.copysign(1.0, self.slip_rate(self.mode, lo, self.y))
        # before the turn: dv/dt strictly of the sign at lo (a zero of either sign, +0.0
        # or -0.0, counts as turned, so that a(t) -> -a(t) mirrors the turn exactly)
        before = lambda t: sign_lo * self.slip_rate(self.mode, t, self.y) > 0
        if before(hi):
            return None
        for _ in range(_TURN_BISECTIONS):
            mid = 0.5 * (lo + hi)
            if mid in (lo, hi):
                break
            lo, hi = (mid, hi) if before(mid) else (lo, mid)
        return hi if hi < end else None

    def on_guard(self, index):
        """A guard of the current mode reached zero at ``self.t``."""
        before = self.mode
        if before != Mode.STICK:
            self.y = np.array([self.y[0], 0.0])  # a stop: v = 0 by definition
        after = Mode(int(self.block.mode_after_guard(before, index, self.t, self.y, self.piece_excitation,
                                                     SCALAR, self.stop_uncertainty())))
        rate = self.slip_rate(before, self.t, self.y)
        self.knots.add(self.t, self.y, before, rate, rate)
        if after != before:
            self.log_event(self.t, after)

    def stop_uncertainty(self):
        """How far [s] the located stop may lie from the true one, at least the event
        resolution. With the velocity error e (``_V_ERROR_FACTOR`` local tolerances),
        v' at the stop and v'' = -da/dt, the root of v moves by the d that solves
        |v'| d + |v''| d²/2 = e: e / |v'| at a crossing, sqrt(2 e / |v''|) at a graze."""
        rtol, atol = self.velocity_tolerance
        error = _V_ERROR_FACTOR * (rtol * self.v_max + atol)
        slope = abs(self.slip_rate(self.mode, self.t, self.y))
        curvature = abs(self.piece_excitation.acceleration_rate(self.t))
        return max(self.resolution, 2 * error / (slope + math.sqrt(slope**2 + 2 * curvature * error)))

    def log_event(self, t, after):
        same_instant = bool(self.events) and abs(t - self.events[-1].t) <= self.resolution
        self.run_length = self.run_length + 1 if same_instant else 1
        self.max_run = max(self.max_run, self.run_length)
        self.events.append(Event(float(t), self.mode, after, float(self.y[0]), float(self.y[1])))
        if self.run_length > self.cap:
            modes = " -> ".join(e.mode_before.name for e in self.events[-self.run_length:])
            raise RuntimeError(
                f"{self.run_length} events at t = {t:.12g} s ({modes} -> {after.name}): chatter; "
                f"raise max_events_at_one_instant={self.cap}")
        self.mode, self.restarted = after, True
        self.knots.add(t, self.y, after, 0.0, self.slip_rate(after, t, self.y))

    def tail_to_rest(self, t_end):
        """After the excitation (a = 0): slide until the stop guard fires."""
        self.enter_piece(t_end, (0.0,) * 5)
        if self.mode == Mode.STICK:
            return
        block = self.block
        if not comes_to_rest(self.y[1], self.mode, block.bias, block.friction_kinetic, block.g):
            raise never_rests_error(block)
        rate = self.slip_rate(self.mode, self.t, self.y)
        bound = self.t + 2.0 * abs(self.y[1] / rate)  # dv/dt is constant: the stop is half-way
        self.advance_to(bound, until_stick=True)
        if self.mode != Mode.STICK:
            raise RuntimeError(f"{self.mode.name} found no stop by t = {bound:.6g} s after the excitation")

    def solution(self, backend_name):
        t, u, v, mode, rate_start, rate_end = self.knots.arrays()
        stats = {"max_events_at_one_instant": self.max_run, "n_events": len(self.events),
                 **self.integrator.stats}
        return Solution(t=t, u=u, v=v, mode=mode, events=tuple(self.events), backend=backend_name,
                        dense=HermiteDense(t, u, v, rate_start, rate_end), stats=stats)


class _Knots:
    """Knots of a run. Interval i = [t_i, t_i+1] runs in ``mode[i]``; dv/dt is
    ``rate_start[i]`` just after t_i and ``rate_end[i]`` just before t_i+1 [m/s²]."""

    def __init__(self):
        self.rows, self.rate_end = [], []

    def add(self, t, y, mode_after, rate_left, rate_right):
        """A knot at ``t`` [s]; ``rate_left`` ends the previous interval."""
        if self.rows:
            self.rate_end.append(rate_left)
        self.rows.append([t, y[0], y[1], int(mode_after), rate_right])

    def set_right_rate(self, rate_right):
        """dv/dt just after the last knot, once the excitation's next piece is known."""
        self.rows[-1][4] = rate_right

    def arrays(self):
        t, u, v, mode, rate_start = (np.array(c) for c in zip(*self.rows))
        return t, u, v, mode.astype(int), rate_start, np.append(self.rate_end, 0.0)


class HermiteDense:
    """u(t), v(t) between knots by cubic Hermite interpolation of (u, v) with slopes
    (v, dv/dt) [m, m/s]."""

    def __init__(self, t, u, v, rate_start, rate_end):
        self.t, self.u, self.v = t, u, v
        self.rate_start, self.rate_end = rate_start, rate_end

    def __call__(self, t):
        i = np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, len(self.t) - 2)
        h = self.t[i + 1] - self.t[i]
        s = np.where(h > 0, (t - self.t[i]) / np.where(h > 0, h, 1.0), 0.0)
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        u = h00 * self.u[i] + h10 * h * self.v[i] + h01 * self.u[i + 1] + h11 * h * self.v[i + 1]
        v = (h00 * self.v[i] + h10 * h * self.rate_start[i] + h01 * self.v[i + 1]
             + h11 * h * self.rate_end[i])
        return u, v
