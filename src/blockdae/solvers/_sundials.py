"""What the CVODE and IDA backends share: settings, one solver per mode, root bookkeeping.

Each mode gets its own scikit-sundae solver, built once per run: its guards are the
SUNDIALS root functions with direction -1 (the model orients every guard so that the
mode is left when it crosses zero downwards), and the solver is re-initialised at every
restart in that mode.
"""

import abc
import dataclasses
import math
from numbers import Integral, Real

import numpy as np

from ..core import SCALAR, AbstractBackend, AbstractIntegrator, SolverError, drive

@dataclasses.dataclass(frozen=True)
class SundialsBackend(AbstractBackend):
    """Settings shared by the SUNDIALS backends.

    Args:
        rtol: relative tolerance [-], in [1e-14, 1e-2].
        atol: absolute tolerance [m, m/s, m/s²], > 0.
        max_step: largest internal step [s]; None: no bound besides the hard stops at
            every piece end of a(t) and at every turning point of v.
        max_num_steps: most internal steps between two stops [-].
        max_events_at_one_instant: most consecutive events at one instant [-]; more
            (chatter) raises an error.
        event_resolution: events closer than this are one instant [s]: a slip that
            stops within it of a threshold crossing grazes on or reverses at once
            instead of sticking for a moment (at rtol 1e-10 a stop is located to
            ~1e-10 s, so stop and re-start would otherwise be two events).
    """

    rtol: float = 1e-10
    atol: float = 1e-14
    max_step: float | None = None
    max_num_steps: int = 5000
    max_events_at_one_instant: int = 5
    event_resolution: float = 1e-9

    def __post_init__(self):
        _check_real("rtol", self.rtol, lambda x: 1e-14 <= x <= 1e-2, "must lie in [1e-14, 1e-2]")
        _check_real("atol", self.atol, lambda x: x > 0, "must be > 0")
        _check_real("event_resolution", self.event_resolution, lambda x: x >= 0, "must be >= 0 [s]")
        if self.max_step is not None:
            _check_real("max_step", self.max_step, lambda x: x > 0, "must be > 0 [s] or None")
        for name in ("max_num_steps", "max_events_at_one_instant"):
            value = getattr(self, name)
            if not (isinstance(value, Integral) and not isinstance(value, bool) and value >= 1):
                raise ValueError(f"{name} must be an integer >= 1, got {value!r}")

    def solve(self, block, excitation, horizon):
        return drive(block, excitation, horizon, self._integrator, self.name,
                     self.max_events_at_one_instant, self.event_resolution, (self.rtol, self.atol))

    def solver_options(self) -> dict:
        """Keyword arguments for the scikit-sundae solvers."""
        return dict(rtol=float(self.rtol), atol=float(self.atol), max_num_steps=int(self.max_num_steps),
                    max_step=0.0 if self.max_step is None else float(self.max_step))

    @abc.abstractmethod
    def _integrator(self, block, piece) -> AbstractIntegrator:
        """The integrator for one run of ``block`` (``piece``: the driver's excitation)."""


def _check_real(name, value, ok, message):
    if not (isinstance(value, Real) and not isinstance(value, bool) and math.isfinite(value) and ok(value)):
        raise ValueError(f"{name}={value!r} {message}")


class Guards:
    """The guards of one mode as a scikit-sundae events function (subclasses define
    ``__call__`` with the solver's signature).

    scikit-sundae keeps the history of located roots on the function object and never
    clears it (not between solves, not at a re-initialisation), so :meth:`forget` clears
    it at every restart and after every root: each root return then reports exactly
    the root just found.
    """

    def __init__(self, block, piece, mode):
        self.block, self.piece, self.mode = block, piece, mode
        count = len(block.guards(mode, piece.t0, np.zeros(len(block.state_names)), piece, SCALAR))
        self.terminal = [True] * count
        self.direction = [-1] * count  # every guard leaves its mode crossing zero downwards

    def forget(self):
        """Clear scikit-sundae's root history (its private attributes on this object)."""
        for name in ("_i", "_t", "_y"):
            getattr(self, name).clear()
        self._i_cnt[:] = 0

    def root_index(self, result) -> int:
        """Index of the guard that reached zero in a root return of ``result``."""
        if len(result.t_events) != 1:
            raise RuntimeError(f"stale root history: {len(result.t_events)} roots reported at once")
        index = int(np.flatnonzero(result.i_events[-1])[0])
        self.forget()
        return index


class SundialsIntegrator(AbstractIntegrator):
    """One scikit-sundae solver per mode; a step returns at ``t_out`` (interpolated)
    or at the first root, and no internal step passes ``t_stop`` (SUNDIALS ``tstop``)."""

    #: solver name in error messages
    label: str
    #: the :class:`Guards` subclass with the solver's events signature
    guards_class: type
    def __init__(self, block, piece, options):
        self.block, self.piece = block, piece
        self.guards = {mode: self.guards_class(block, piece, mode) for mode in block.modes}
        self.solvers = {mode: self._build(mode, self.guards[mode], options) for mode in block.modes}
        self.mode = block.initial_mode
        self.counts = {"n_restarts": 0, "n_calls": 0}

    @abc.abstractmethod
    def _build(self, mode, guards, options):
        """The scikit-sundae solver of ``mode``."""

    @abc.abstractmethod
    def _initialise(self, solver, mode, t, y):
        """``solver.init_step`` from the consistent state at ``t``."""

    def restart(self, mode, t, y):
        self.mode = mode
        self.guards[mode].forget()
        result = self._initialise(self.solvers[mode], mode, float(t), np.asarray(y, dtype=float))
        self._check(result)
        self.counts["n_restarts"] += 1

    def step(self, t_out, t_stop):
        result = self.solvers[self.mode].step(t_out, method="normal", tstop=t_stop)
        self._check(result)
        self.counts["n_calls"] += 1
        root = self.guards[self.mode].root_index(result) if result.status == 2 else None
        return float(result.t), result.y, root

    def _check(self, result):
        if result.status < 0:
            raise SolverError(f"{self.label} failed at t = {float(np.ravel(result.t)[-1]):.12g} s in mode "
                              f"{self.mode.name}: flag {result.status} ({result.message})")

    @property
    def stats(self):
        return dict(self.counts)
