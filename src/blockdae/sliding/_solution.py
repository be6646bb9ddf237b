"""Results of a simulation: located events, knots and dense output."""

import collections.abc
import dataclasses
from typing import Callable

import numpy as np

from ..core import AbstractEvent, AbstractSolution, compact_repr
from ..units import STANDARD_GRAVITY, column_suffixes, length_units
from ..excitation import AbstractExcitation
from ._modes import Mode


@dataclasses.dataclass(frozen=True)
class Event(AbstractEvent):
    """A located mode change.

    Attributes:
        t: time [s].
        mode_before, mode_after: the modes on either side.
        u: relative displacement at ``t`` [m].
        v: relative velocity at ``t`` [m/s] (0 at a stop, by definition).
    """

    t: float
    mode_before: Mode
    mode_after: Mode
    u: float
    v: float

    def __str__(self):
        return (f"t = {self.t:.6f} s  {self.mode_before.name:>8} -> {self.mode_after.name:<8}"
                f"  u = {self.u:+.6f} m")


class EventLog(collections.abc.Sequence):
    """Events kept as arrays, each (n,); the :class:`Event` objects are built when first
    read. Compares equal to any sequence of the same events (e.g. a tuple).

    Attributes:
        t: times [s]; mode_before, mode_after: ints (see :class:`Mode`); u: [m]; v: [m/s].
    """

    __slots__ = ("t", "mode_before", "mode_after", "u", "v", "_events")

    def __init__(self, t, mode_before, mode_after, u, v):
        fields = (("t", t, float), ("mode_before", mode_before, int), ("mode_after", mode_after, int),
                  ("u", u, float), ("v", v, float))
        for name, values, dtype in fields:
            array = np.asarray(values, dtype=dtype)
            if array.flags.writeable:  # a read-only view, never a copy
                array = array.view()
                array.flags.writeable = False
            object.__setattr__(self, name, array)
        object.__setattr__(self, "_events", None)

    @classmethod
    def of_read_only(cls, t, mode_before, mode_after, u, v) -> "EventLog":
        """The log on read-only arrays that already have its dtypes (float, int, int,
        float, float; an engine's knots), kept as they are without a check."""
        log = object.__new__(cls)
        keep = object.__setattr__
        keep(log, "t", t)
        keep(log, "mode_before", mode_before)
        keep(log, "mode_after", mode_after)
        keep(log, "u", u)
        keep(log, "v", v)
        keep(log, "_events", None)
        return log

    def __setattr__(self, name, value):
        raise AttributeError("an EventLog is immutable")

    def __reduce__(self):
        """Pickled as its five arrays (process pools, Dask); the events are built again on use."""
        return EventLog.of_read_only, (self.t, self.mode_before, self.mode_after, self.u, self.v)

    def _built(self) -> tuple:
        if self._events is None:
            modes = {int(m): m for m in Mode}
            object.__setattr__(self, "_events", tuple(
                Event(t, modes[b], modes[a], u, v) for t, b, a, u, v in zip(
                    self.t.tolist(), self.mode_before.tolist(), self.mode_after.tolist(), self.u.tolist(),
                    self.v.tolist())))
        return self._events

    def __len__(self):
        return self.t.shape[0]

    def __getitem__(self, index):
        return self._built()[index]

    def __iter__(self):
        return iter(self._built())

    def __eq__(self, other):
        if isinstance(other, collections.abc.Sequence) and not isinstance(other, str):
            return self._built() == tuple(other)
        return NotImplemented

    __hash__ = None

    def __repr__(self):
        return f"EventLog({list(self._built())!r})"


@dataclasses.dataclass(frozen=True, eq=False)
class Solution(AbstractSolution):
    """The motion of the block relative to its base.

    Attributes:
        t: knot times [s], shape (n,): the start, every event and the end, in time
            order (a backend may add knots of its own); use ``sol(t)`` for any time.
        u, v: relative displacement [m] and velocity [m/s] at the knots, shape (n,).
        mode: mode right after each knot, shape (n,) of int (see :class:`Mode`).
        events: located mode changes, in time order (a tuple or an :class:`EventLog`).
        backend: name of the backend that produced it.
        stats: counters, e.g. ``max_events_at_one_instant`` and solver statistics.
        block, motion: the block and the base excitation it was computed for
            (set by :func:`blockdae.simulate`; None if a backend was called directly).
    """

    def __repr__(self):
        return compact_repr(self, f"u(t_end) = {self.displacement:.6g} m (signed: u = x_block - x_base), "
                                  f"{len(self.events)} events")

    t: np.ndarray
    u: np.ndarray
    v: np.ndarray
    mode: np.ndarray
    events: "tuple[Event, ...] | EventLog"
    backend: str
    dense: Callable = dataclasses.field(repr=False)
    stats: dict = dataclasses.field(default_factory=dict)
    block: object = dataclasses.field(default=None, repr=False)  # the SlidingBlock
    motion: AbstractExcitation | None = dataclasses.field(default=None, repr=False)

    @property
    def displacement(self) -> float:
        """Permanent relative displacement u(t_end) [m]."""
        return float(self.u[-1])

    @property
    def max_abs_displacement(self) -> float:
        """max |u(t)| over the whole run [m] (u has its extrema at knots)."""
        return float(np.max(np.abs(self.u)))

    def __call__(self, t):
        """(u(t) [m], v(t) [m/s]) at any times within [0, t_end], exactly."""
        t = np.asarray(t, dtype=float)
        if np.any((t < self.t[0]) | (t > self.t[-1])):
            raise ValueError(f"t must lie in [{self.t[0]}, {self.t[-1]}] s")
        return self.dense(t)

    def history(self, t=None):
        """The run at times ``t`` [s] (default: the record's samples, or 2001 even steps for
        another motion, and every event), as a pandas DataFrame: t_s, base_acceleration_m_s2
        (where the motion is known), u_m, v_m_s (signed: u = x_block - x_base) and mode; for a
        block with g = 1 (a dimensionless set-up) base_acceleration_g, u_g_s2 and v_g_s."""
        import pandas as pd

        if t is None:
            grid = getattr(self.motion, "times", None)
            grid = np.linspace(0.0, self.t_end, 2001) if grid is None else grid[grid <= self.t_end]
            t = np.union1d(np.append(grid, self.t_end), self.t_events)
        t = np.asarray(t, dtype=float)
        u, v = self(t)
        length, velocity, acceleration = self._column_suffixes()
        columns = {"t_s": t}
        if self.motion is not None:
            columns[f"base_acceleration_{acceleration}"] = np.asarray(self.motion.acceleration(t), dtype=float)
        after = np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, self.t.size - 1)
        return pd.DataFrame({**columns, f"u_{length}": u, f"v_{velocity}": v,
                             "mode": [Mode(int(m)).name for m in np.asarray(self.mode)[after]]})

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """Sawicki & Chybicki 2005 Figures 3-5: v, u and the phase plane, with ``excitation`` also the
        absolute motions (see :func:`blockdae.plot`); a matplotlib Figure."""
        from ._figures import solution_figure

        return solution_figure(self, excitation, block, n_points=n_points, title=title)

    def _column_suffixes(self) -> tuple[str, str, str]:
        return column_suffixes(self.block.g if self.block is not None else STANDARD_GRAVITY)

    def event_table(self, events=None) -> str:
        """``events`` (default: all of them) as an aligned text table with units (u in m, or
        in g s² for a block with g = 1, a dimensionless set-up)."""
        length = length_units(self.block.g if self.block is not None else STANDARD_GRAVITY)[0]
        lines = [f"{'t [s]':>12}  {'from':>8}  {'to':<8}  {f'u [{length}]':>12}"]
        lines += [f"{e.t:12.6f}  {e.mode_before.name:>8}  {e.mode_after.name:<8}  {e.u:12.6f}"
                  for e in (self.events if events is None else events)]
        return "\n".join(lines)

    def to_dataframe(self):
        """The events as a pandas DataFrame, one row per event: t_s [s], mode_before,
        mode_after (mode names), u_m [m], v_m_s [m/s] (u_g_s2, v_g_s for a block with g = 1)."""
        import pandas as pd

        length, velocity, _ = self._column_suffixes()
        return pd.DataFrame({
            "t_s": pd.Series([e.t for e in self.events], dtype=float),
            "mode_before": pd.Series([e.mode_before.name for e in self.events], dtype=object),
            "mode_after": pd.Series([e.mode_after.name for e in self.events], dtype=object),
            f"u_{length}": pd.Series([e.u for e in self.events], dtype=float),
            f"v_{velocity}": pd.Series([e.v for e in self.events], dtype=float),
        })
