"""Results of a spring-supported mass: located liftoffs, tops and landings, dense output."""

import dataclasses

import numpy as np

from ..core import AbstractEvent, DriverSolution, compact_repr
from ._modes import UpthrowMode


@dataclasses.dataclass(frozen=True)
class UpthrowEvent(AbstractEvent):
    """A located event of a :class:`~blockdae.SpringSupportedMass`.

    Attributes:
        t: time [s].
        mode_before, mode_after: the modes on either side.
        kind: "liftoff", "top", "landing" or "bottom" (a flight that rises again
            because the ground falls faster than g).
        u: displacement relative to the ground from the static position [m].
        u_rate: u' [m/s] (at liftoff the paper's u'0; at landing the impact velocity).
        height: u - u0 [m], the height above the unloaded support (at a top: the
            flight's height; 0 at a falling landing).
    """

    kind: str
    u: float
    u_rate: float
    height: float

    def __str__(self):
        return (f"t = {self.t:.6f} s  {self.kind:<8} u = {self.u:+.6e} m  u' = {self.u_rate:+.6e} m/s  "
                f"height = {self.height:+.6e} m")


@dataclasses.dataclass(frozen=True)
class Flight:
    """One flight: liftoff to landing.

    Attributes:
        liftoff, landing: times [s] (landing nan if still flying at the end).
        liftoff_velocity: u' at liftoff [m/s]; impact_velocity: u' at landing [m/s].
        height: largest u - u0 during the flight [m] (< 0 for a damped flight that
            lands still rising, below u0; nan if still rising at the end).
    """

    liftoff: float
    landing: float
    liftoff_velocity: float
    impact_velocity: float
    height: float

    @property
    def duration(self) -> float:
        """landing - liftoff [s]."""
        return self.landing - self.liftoff


@dataclasses.dataclass(frozen=True, eq=False)
class UpthrowSolution(DriverSolution):
    """The motion of a spring-supported mass relative to the ground.

    Attributes:
        t: knot times [s], shape (n,).
        state: (u [m], u' [m/s]) at the knots, shape (n, 2).
        mode: mode right after each knot, shape (n,) of int (:class:`UpthrowMode`).
        events: located events, in time order.
        backend: name of the backend that produced it.
        stats: counters.
        block, motion: the model and the ground motion (set by :func:`blockdae.simulate`).
    """

    def __repr__(self):
        return compact_repr(self)

    @property
    def u(self) -> np.ndarray:
        """u at the knots [m], shape (n,)."""
        return self.state[:, 0]

    @property
    def u_rate(self) -> np.ndarray:
        """u' at the knots [m/s], shape (n,)."""
        return self.state[:, 1]

    @property
    def displacement(self) -> float:
        """u at t_end [m]: the mass relative to the ground, from its static position (what
        :func:`blockdae.crosscheck` compares; not a permanent offset, the mass oscillates)."""
        return float(self.state[-1, 0])

    def events_of(self, kind: str) -> tuple:
        """The events of one kind ("liftoff", "top", "landing", "bottom")."""
        return tuple(e for e in self.events if e.kind == kind)

    @property
    def flights(self) -> tuple[Flight, ...]:
        """The flights, in time order (the last one may not have landed)."""
        flights, start, height = [], None, -np.inf
        for event in self.events:
            if event.kind == "liftoff":
                start, height = event, -np.inf
            elif event.kind == "top":
                height = max(height, event.height)
            elif event.kind == "landing" and start is not None:
                height = max(height, start.height, event.height)  # no top: it landed rising
                flights.append(Flight(start.t, event.t, start.u_rate, event.u_rate, height))
                start = None
        if start is not None:
            flights.append(Flight(start.t, np.nan, start.u_rate, np.nan, height if height > -np.inf else np.nan))
        return tuple(flights)

    def __call__(self, t):
        """(u [m], u' [m/s], gap [m], n [m/s²]) at times ``t`` in [0, t_end] [s]: the
        gap u - u0 above the unloaded support in flight (0 in contact and below u0) and
        the support force per unit mass n (0 in flight)."""
        state, mode = self.dense_state(t)
        u, u_rate = state[..., 0], state[..., 1]
        block = self.block
        flying = mode != UpthrowMode.CONTACT
        law = block.support.law(block.g, u, u_rate)
        gap = np.where(flying, np.maximum(u - block.static_deflection, 0.0), 0.0)
        return u, u_rate, gap, np.where(flying, 0.0, law)

    def event_table(self, events=None) -> str:
        """``events`` (default: all of them) as an aligned text table with units."""
        lines = [f"{'t [s]':>12}  {'kind':<8}  {'u [m]':>13}  {'u_rate [m/s]':>13}  {'height [m]':>13}"]
        lines += [f"{e.t:12.6f}  {e.kind:<8}  {e.u:13.6e}  {e.u_rate:13.6e}  {e.height:13.6e}"
                  for e in (self.events if events is None else events)]
        return "\n".join(lines)

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """A flight history: ground and mass [m], gap [m], support force [m/s²];
        liftoffs and landings marked (``excitation`` and ``block`` unused); a matplotlib Figure."""
        from ._figures import flight_figure

        return flight_figure(self, n_points=n_points, title=title)

    def to_dataframe(self):
        """The events as a pandas DataFrame: kind, t_s [s], u_m [m], u_rate_m_s [m/s],
        height_m [m]."""
        import pandas as pd

        rows = [(e.kind, e.t, e.u, e.u_rate, e.height) for e in self.events]
        return pd.DataFrame(rows, columns=["kind", "t_s", "u_m", "u_rate_m_s", "height_m"])
