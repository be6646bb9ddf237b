"""Results of a planar simulation: located events, knots and dense output."""

import dataclasses
import math

import numpy as np

from ..core import AbstractEvent, DriverSolution, compact_repr
from ..units import STANDARD_GRAVITY, length_units

from ._modes import PlanarMode, horizontal_velocity


@dataclasses.dataclass(frozen=True)
class PlanarEvent(AbstractEvent):
    """A located mode change of a :class:`~blockdae.PlanarBlock`.

    Attributes:
        t: time [s].
        mode_before, mode_after: the modes on either side (a landing that rebounds
            and a stop that slides on keep the mode).
        u_x, u_y: relative displacement [m].
        v_x, v_y: relative horizontal velocity just before the event [m/s] (0 at a stop).
        v_z: vertical relative velocity just before the event [m/s] (at a landing:
            the impact velocity, < 0).
    """

    t: float
    mode_before: PlanarMode
    mode_after: PlanarMode
    u_x: float
    u_y: float
    v_x: float
    v_y: float
    v_z: float

    @property
    def direction(self) -> float:
        """Direction of the relative horizontal velocity [degrees from +x]; nan at rest."""
        return math.degrees(math.atan2(self.v_y, self.v_x)) if (self.v_x or self.v_y) else math.nan

    def __str__(self):
        return (f"t = {self.t:.6f} s  {self.mode_before.name:>6} -> {self.mode_after.name:<6}"
                f"  u = ({self.u_x:+.6f}, {self.u_y:+.6f}) m")


@dataclasses.dataclass(frozen=True, eq=False)
class PlanarSolution(DriverSolution):
    """The motion of a planar block relative to its base.

    Attributes:
        t: knot times [s], shape (n,).
        state: the model's state at the knots, shape (n, 7) (see
            :class:`~blockdae.PlanarBlock`); read ``u_x``, ``u_y``, ``v_x``, ``v_y``,
            ``gap`` instead.
        mode: mode right after each knot, shape (n,) of int (see :class:`PlanarMode`).
        events: located events, in time order.
        backend: name of the backend that produced it.
        stats: counters.
        block, motion: the block and the base motion (set by :func:`blockdae.simulate`).
    """

    def __repr__(self):
        return compact_repr(self)

    @property
    def u_x(self) -> np.ndarray:
        """Relative displacement along x at the knots [m], shape (n,)."""
        return self.state[:, 0]

    @property
    def u_y(self) -> np.ndarray:
        """Relative displacement along y at the knots [m], shape (n,)."""
        return self.state[:, 1]

    @property
    def velocity(self) -> tuple[np.ndarray, np.ndarray]:
        """(v_x, v_y): relative horizontal velocity at the knots [m/s], each (n,)."""
        return horizontal_velocity(self.mode, self.state)

    @property
    def gap(self) -> np.ndarray:
        """Height w of the block above its rest on the support at the knots [m] (on a
        rigid support the gap above the base, 0 in contact; on a spring measured from
        the static position, upward positive)."""
        return self.state[:, 5]

    @property
    def displacement(self) -> np.ndarray:
        """Permanent relative displacement (u_x, u_y) at t_end [m], shape (2,)."""
        return self.state[-1, :2].copy()

    @property
    def max_abs_displacement(self) -> float:
        """Largest |u| = sqrt(u_x² + u_y²) at the knots [m]."""
        return float(np.max(np.hypot(self.u_x, self.u_y)))

    def __call__(self, t):
        """(u_x, u_y [m], v_x, v_y [m/s], gap [m]) at times ``t`` in [0, t_end] [s]."""
        state, mode = self.dense_state(t)
        vx, vy = horizontal_velocity(mode, state)
        return state[..., 0], state[..., 1], vx, vy, state[..., 5]

    def slide_directions(self) -> np.ndarray:
        """Direction of the slide on the base that each event starts (onset, landing
        into a slide) or else ends (stop, liftoff) [degrees from +x], shape (n_events,);
        nan where the block slides on neither side. Read from the knots at the event
        (the state before and after it), where the direction is known even at rest."""
        directions = np.full(len(self.events), math.nan)
        for k, e in enumerate(self.events):
            before, after = np.searchsorted(self.t, e.t, "left"), np.searchsorted(self.t, e.t, "right") - 1
            knot = after if e.mode_after == PlanarMode.SLIP else before if e.mode_before == PlanarMode.SLIP else None
            if knot is not None:
                c_x, c_y = self.state[knot, 3:5]
                directions[k] = math.degrees(math.atan2(c_y, c_x))
        return directions

    def event_table(self, events=None) -> str:
        """``events`` (default: all of them) as an aligned text table with units:
        direction: of the relative velocity just before the event [deg], blank where the
        block is at rest then (an onset, a stop); slide: of the slide it starts or ends
        [deg] (see :meth:`slide_directions`), blank where none is defined. Lengths are in
        m, or in g s² for a block with g = 1 (a dimensionless set-up, as Elms's)."""
        chosen = self.events if events is None else events
        slides = dict(zip((e.t for e in self.events), self.slide_directions()))
        length = length_units(self.block.g if self.block is not None else STANDARD_GRAVITY)[0]
        lines = [f"{'t [s]':>12}  {'from':>6}  {'to':<6}  {f'u_x [{length}]':>12}  {f'u_y [{length}]':>12}  "
                 f"{'direction [deg]':>15}  {'slide [deg]':>11}"]
        lines += [f"{e.t:12.6f}  {e.mode_before.name:>6}  {e.mode_after.name:<6}  {e.u_x:12.6f}  "
                  f"{e.u_y:12.6f}  {_angle_cell(e.direction, 15)}  {_angle_cell(slides.get(e.t, math.nan), 11)}"
                  for e in chosen]
        return "\n".join(line.rstrip() for line in lines)

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """The path (u_x, u_y) [m], u_x and u_y [m] and |v| [m/s] against time, events
        marked (``excitation`` and ``block`` unused; g s² and g s for a block with g = 1);
        a matplotlib Figure."""
        from ._figures import planar_figure

        return planar_figure(self, n_points=n_points, title=title)

    def to_dataframe(self):
        """The events as a pandas DataFrame: t_s [s], mode_before, mode_after, u_x_m,
        u_y_m [m], v_x_m_s, v_y_m_s, v_z_m_s [m/s], direction_deg, slide_deg (see
        :meth:`slide_directions`)."""
        import pandas as pd

        rows = [(e.t, e.mode_before.name, e.mode_after.name, e.u_x, e.u_y, e.v_x, e.v_y, e.v_z, e.direction, slide)
                for e, slide in zip(self.events, self.slide_directions())]
        columns = ["t_s", "mode_before", "mode_after", "u_x_m", "u_y_m", "v_x_m_s", "v_y_m_s", "v_z_m_s",
                   "direction_deg", "slide_deg"]
        return pd.DataFrame(rows, columns=columns)


def _angle_cell(degrees: float, width: int) -> str:
    """An angle [deg] right-aligned in ``width`` characters with 3 decimals; blanks if
    it is undefined (nan)."""
    return " " * width if math.isnan(degrees) else f"{degrees:{width}.3f}"
