"""What every solution shares (:class:`AbstractSolution`, :class:`AbstractEvent`), and the
solution of any model run by the hybrid driver: knots, events and dense output."""

import abc
import dataclasses
from typing import Callable

import numpy as np
from ..excitation import AbstractExcitation
from ._repr import compact_repr
from ._states import state_columns, state_labels, unit_suffix


@dataclasses.dataclass(frozen=True)
class AbstractEvent:
    """The one event shape: time [s] and the modes on either side, then the named values
    each system adds (u, v for the 1-D block; u_x, ..., v_z on a plane; kind, u, u',
    height for a mass on a spring; the whole state by default)."""

    t: float
    mode_before: object
    mode_after: object


@dataclasses.dataclass(frozen=True)
class HybridEvent(AbstractEvent):
    """A located mode change of any model run by the driver; ``state``: the model's state
    at ``t`` (in the units of its ``state_names``)."""

    state: tuple

    def __str__(self):
        values = "  ".join(f"{v:+.6g}" for v in self.state)
        return f"t = {self.t:.6f} s  {self.mode_before.name:>8} -> {self.mode_after.name:<8}  state = {values}"


class AbstractSolution(abc.ABC):
    """What every solution has, and all the package reads of one (:func:`blockdae.simulate`,
    crosscheck, batches, :func:`blockdae.plot`): knot times ``t`` [s], located ``events``,
    the ``backend`` that produced it, ``displacement`` and ``max_abs_displacement``;
    ``t_end``, ``t_events`` and, per system, ``event_table()`` (text with units),
    ``to_dataframe()`` (pandas, units in the column names) and ``figure()``, with named
    views (u, v; u_x, u_y; flights) on top. :func:`blockdae.simulate` sets ``block`` and ``motion`` (the
    model and the base motion) on it."""

    #: knot times [s], shape (n,), increasing from 0 to t_end
    t: np.ndarray
    #: the located events, in time order (:class:`AbstractEvent` each)
    events: tuple
    #: the name of the backend that produced it
    backend: str

    @property
    @abc.abstractmethod
    def displacement(self):
        """The displacement at t_end: a float [m] (u of the 1-D block), or the model's
        displacement vector (its ``displacement_states``, e.g. (u_x, u_y) [m])."""

    @property
    @abc.abstractmethod
    def max_abs_displacement(self) -> float:
        """The largest size of the displacement over the run [m] (its Euclidean norm for
        a vector), at the knots."""

    @property
    def t_end(self) -> float:
        """Final time [s]."""
        return float(self.t[-1])

    @property
    def t_events(self) -> np.ndarray:
        """Event times [s], shape (n_events,)."""
        times = getattr(self.events, "t", None)  # an event log keeps them as an array
        return np.array(times, dtype=float) if times is not None else np.array([e.t for e in self.events])

    @abc.abstractmethod
    def event_table(self, events=None) -> str:
        """``events`` (default: all of them) as an aligned text table with units."""

    @abc.abstractmethod
    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """Its own figure (what :func:`blockdae.plot` draws), ``n_points`` samples in time;
        a matplotlib Figure."""

    @abc.abstractmethod
    def to_dataframe(self):
        """A pandas DataFrame with units in the column names."""


@dataclasses.dataclass(frozen=True, eq=False)
class DriverSolution(AbstractSolution):
    """Knots and located events of a model run by the hybrid driver.

    Attributes:
        t: knot times [s], shape (n,).
        state: the model's state at the knots, shape (n, k).
        mode: mode right after each knot, shape (n,) of int (the model's modes).
        events: located events, in time order.
        backend: name of the backend that produced it.
        dense: ``dense(t)`` -> the k states at times ``t`` [s] (tuple of arrays).
        stats: counters.
        block, motion: the model and the base motion (set by :func:`blockdae.simulate`).
    """

    def __repr__(self):
        return compact_repr(self)

    t: np.ndarray
    state: np.ndarray
    mode: np.ndarray
    events: tuple
    backend: str
    dense: Callable = dataclasses.field(repr=False)
    stats: dict = dataclasses.field(default_factory=dict)
    block: object = dataclasses.field(default=None, repr=False)
    motion: object = dataclasses.field(default=None, repr=False)

    def __call__(self, t):
        """The states at times ``t`` in [0, t_end] [s]: a tuple of arrays of t's shape, in
        the model's ``state_names`` order."""
        return tuple(np.moveaxis(self.dense_state(t)[0], -1, 0))

    def dense_state(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(state of shape t.shape + (k,), mode of shape t.shape) at times ``t`` in
        [0, t_end] [s]."""
        t = np.asarray(t, dtype=float)
        if np.any((t < self.t[0]) | (t > self.t[-1])):
            raise ValueError(f"t must lie in [{self.t[0]}, {self.t[-1]}] s")
        mode = self.mode[np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, len(self.t) - 1)]
        return np.stack(self.dense(t), axis=-1), mode

    @property
    def displacement(self):
        """The model's displacement states at t_end (its ``displacement_states``): a float
        for one, an array for several [their units]."""
        values = self.state[-1, list(self.block.displacement_states)] if self.block is not None else self.state[-1, :1]
        return float(values[0]) if len(values) == 1 else np.asarray(values, dtype=float)

    @property
    def max_abs_displacement(self) -> float:
        """The largest Euclidean norm of the displacement states at the knots [their units]."""
        states = list(self.block.displacement_states) if self.block is not None else [0]
        return float(np.max(np.linalg.norm(self.state[:, states], axis=1)))

    def event_table(self, events=None) -> str:
        """``events`` (default: all of them) as an aligned text table: time [s], modes
        and the state (in the model's units)."""
        events = self.events if events is None else events
        names = state_labels(self.block, len(events[0].state) if events else 0) if self.block is not None else ()
        lines = [f"{'t [s]':>12}  {'before':>10}  {'after':<10}  " + "  ".join(f"{n:>13}" for n in names)]
        lines += [f"{e.t:12.6f}  {e.mode_before.name:>10}  {e.mode_after.name:<10}  "
                  + "  ".join(f"{v:13.6e}" for v in e.state) for e in events]
        return "\n".join(lines)

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """Each state against time, events marked (``excitation`` and ``block``
        unused); a matplotlib Figure."""
        from ._figures import state_figure

        return state_figure(self, n_points=n_points, title=title)

    def to_dataframe(self):
        """The events as a pandas DataFrame: t_s [s], mode_before, mode_after and one
        column per state (:func:`state_columns`: the model's ``state_names``, each with
        its unit where the model declares ``state_units``)."""
        import pandas as pd

        names = state_columns(self.block) if self.block is not None else []
        rows = [(e.t, e.mode_before.name, e.mode_after.name, *e.state) for e in self.events]
        return pd.DataFrame(rows, columns=["t_s", "mode_before", "mode_after", *names])

    def history(self, t=None):
        """The run at times ``t`` [s] (default: the record's samples, or 2001 even steps for
        another motion, and every event), as a pandas DataFrame: t_s, the base acceleration
        where the motion is known (base_acceleration_m_s2; of a :class:`~blockdae.BaseMotion`
        base_acceleration_x_m_s2, _y_, _z_), one column per state (:func:`state_columns`)
        and mode (the mode's name)."""
        import pandas as pd

        if t is None:
            grid = getattr(self.motion, "times", None)
            grid = np.linspace(0.0, self.t_end, 2001) if grid is None else grid[grid <= self.t_end]
            t = np.union1d(np.append(grid, self.t_end), self.t_events)
        t = np.asarray(t, dtype=float)
        state, mode = self.dense_state(t)
        columns = {"t_s": t}
        if self.motion is not None:
            base = np.asarray(self.motion.acceleration(t), dtype=float)
            if base.ndim == t.ndim:
                columns["base_acceleration_m_s2"] = base
            else:  # a motion of components (x, y, z)
                columns |= {f"base_acceleration_{axis}_m_s2": a for axis, a in zip("xyz", base)}
        names = state_columns(self.block) if self.block is not None else [f"y{i}" for i in range(state.shape[-1])]
        columns |= {name: state[..., i] for i, name in enumerate(names)}
        modes = getattr(self.block, "modes", None)
        columns["mode"] = [modes(int(m)).name if modes is not None else int(m) for m in mode]
        return pd.DataFrame(columns)


@dataclasses.dataclass(frozen=True)
class SolveItem:
    """A batch's ``solve_one``: parameter set ``i`` of ``block`` run again by ``engine``
    (an object with ``solve(block, excitation, horizon, backend)``), picklable where they
    are (a process pool's workers, Dask)."""

    engine: object
    block: object
    excitation: AbstractExcitation
    horizon: object
    backend: object

    def __call__(self, index: int) -> AbstractSolution:
        return self.engine.solve(self.block.item(index), self.excitation, self.horizon, self.backend)


@dataclasses.dataclass(frozen=True, eq=False)
class BatchSolution:
    """Results for a batch of parameter sets over one excitation.

    Attributes:
        displacement: u(t_end) per parameter set [m], shape (n,); for a planar block
            (u_x, u_y)(t_end), shape (n, 2).
        max_abs_displacement: max |u| per parameter set [m], shape (n,).
        n_events: number of events per parameter set, shape (n,).
        t_end: final time per parameter set [s], shape (n,).
        backend: name of the backend that produced it.
        block: the parameter grid, a block whose parameters are arrays of shape (n,)
            (set by :func:`blockdae.simulate`; None if a backend was called directly).
        motion: the base excitation.
    """

    def __repr__(self):
        u = self.displacement
        return compact_repr(self, f"{u.size} parameter sets, u(t_end) from {np.min(u):.4g} to {np.max(u):.4g} "
                                  f"{self.unit} (signed)")

    displacement: np.ndarray
    max_abs_displacement: np.ndarray
    n_events: np.ndarray
    t_end: np.ndarray
    backend: str
    solve_one: Callable = dataclasses.field(repr=False)
    block: object = dataclasses.field(default=None, repr=False)  # the model, with array parameters
    motion: AbstractExcitation | None = dataclasses.field(default=None, repr=False)

    def __len__(self):
        return self.displacement.shape[0]

    @property
    def unit(self) -> str:
        """The unit of the displacement: the block's ``displacement_unit`` ("m"; "rad" for a
        rotation), "m" where the block is unknown."""
        return "m" if self.block is None else self.block.displacement_unit

    def __getitem__(self, index: int) -> AbstractSolution:
        """The full solution (events, dense output) of one parameter set."""
        solution = self.solve_one(index)
        if self.block is None:
            return solution
        return dataclasses.replace(solution, block=self.block.item(index), motion=self.motion)

    def parameters(self) -> dict:
        """The grid, each of shape (n,), as the model's ``batch_parameters`` names it
        (mu, mu_kinetic (the kinetic coefficient in effect) and bias [-] for a 1-D block);
        empty if the block is unknown."""
        return {} if self.block is None else self.block.batch_parameters()

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """u(t_end) and max |u| [its unit] against the parameter that varies (the arguments
        besides ``title`` are unused); a matplotlib Figure."""
        from ._figures import batch_figure

        return batch_figure(self, title=title)

    def to_dataframe(self):
        """A pandas DataFrame, one row per parameter set: the grid (mu, mu_kinetic, bias
        [-], g_m_s2 [m/s²], and the direction of a 1-D block; when the block is known),
        u_end_m (the signed u at the end [m]; displacement_x_m, displacement_y_m for a planar block;
        a rotation's <state>_end_rad, as an ensemble's table names it), max_abs_displacement_m
        [m] (_rad for a rotation), n_events, t_end_s [s]."""
        import pandas as pd

        columns = self.parameters()
        if self.block is not None:
            columns |= {"g_m_s2": float(self.block.g)}
            if hasattr(self.block, "direction"):  # the 1-D block's sliding directions
                columns |= {"direction": self.block.direction}
        u, suffix = np.asarray(self.displacement, dtype=float), unit_suffix(self.unit)
        if u.ndim == 2:
            columns |= {f"displacement_x_{suffix}": u[:, 0], f"displacement_y_{suffix}": u[:, 1]}
        elif suffix != "m":  # the state's own name, as an ensemble's table names it
            columns |= {f"{self.block.state_names[self.block.displacement_states[0]]}_end_{suffix}": u}
        else:
            columns |= {"u_end_m": u}
        columns |= {f"max_abs_displacement_{suffix}": np.asarray(self.max_abs_displacement, dtype=float),
                    "n_events": np.asarray(self.n_events, dtype=int),
                    "t_end_s": np.asarray(self.t_end, dtype=float)}
        return pd.DataFrame(columns, index=pd.RangeIndex(len(self)))


def of_run(result, block, motion):
    """``result`` (a solution: a frozen dataclass that checks nothing on construction) with
    its ``block`` and ``motion`` set: what ``dataclasses.replace`` makes, a shallow copy,
    without running ``__init__`` again."""
    copy = object.__new__(type(result))
    copy.__dict__.update(result.__dict__)
    object.__setattr__(copy, "block", block)
    object.__setattr__(copy, "motion", motion)
    return copy
