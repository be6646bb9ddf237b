"""Results of a flexible sliding mass: located onsets and stops, sliding episodes, dense output."""

import dataclasses

import numpy as np

from ..core import AbstractEvent, DriverSolution, compact_repr
from ._modes import FlexibleMode


@dataclasses.dataclass(frozen=True)
class FlexibleEvent(AbstractEvent):
    """A located onset or stop of sliding.

    Attributes:
        t: time [s]; mode_before, mode_after: the modes on either side.
        kind: "onset", "stop" or "breakpoint" (s crossed a breakpoint of a ky table).
        u: modal displacement (top relative to base) [m]; u_rate: u' [m/s].
        s: sliding displacement, downslope positive [m]; w: sliding velocity [m/s] (0 at both).
    """

    kind: str
    u: float
    u_rate: float
    s: float
    w: float

    @property
    def state(self) -> tuple:
        """(u, u', s, w) as the model's states."""
        return self.u, self.u_rate, self.s, self.w

    def __str__(self):
        return f"t = {self.t:.6f} s  {self.kind:<5}  u = {self.u:+.6e} m  s = {self.s:.6e} m"


@dataclasses.dataclass(frozen=True)
class Episode:
    """One sliding episode: onset to stop [s] (stop nan if still sliding at the end) and
    the displacement it adds [m]."""

    onset: float
    stop: float
    displacement: float


@dataclasses.dataclass(frozen=True, eq=False)
class FlexibleSolution(DriverSolution):
    """The motion of a flexible sliding mass.

    Attributes:
        t: knot times [s], shape (n,); state: (u [m], u' [m/s], s [m], w [m/s]) at the
            knots, shape (n, 4); mode: mode right after each knot, shape (n,)
            (:class:`FlexibleMode`); events: onsets and stops; backend, stats; block,
            motion: the model and the ground motion (set by :func:`blockdae.simulate`).
    """

    def __repr__(self):
        return compact_repr(self, f"D = {self.sliding_displacement:.6g} m, {len(self.episodes)} episodes")

    @property
    def sliding_displacement(self) -> float:
        """s at t_end [m], downslope positive."""
        return float(self.state[-1, 2])

    @property
    def episodes(self) -> tuple[Episode, ...]:
        """The sliding episodes in time order (the last may still be sliding at t_end)."""
        found, start = [], None
        for event in self.events:
            if event.kind == "onset":
                start = event
            elif event.kind == "stop" and start is not None:
                found.append(Episode(start.t, event.t, event.s - start.s))
                start = None
        if start is not None:
            found.append(Episode(start.t, np.nan, self.sliding_displacement - start.s))
        return tuple(found)

    def hea(self, t) -> np.ndarray:
        """HEA = a + (2/pi) u'' [m/s²] at times ``t`` [s] (the base shear per unit mass)."""
        state, mode = self.dense_state(t)
        a = np.asarray(self.motion.acceleration(np.asarray(t, dtype=float)), dtype=float)
        stick = self.block.hea(FlexibleMode.STICK, a, np.moveaxis(state, -1, 0))
        slip = self.block.hea(FlexibleMode.SLIP, a, np.moveaxis(state, -1, 0))
        return np.where(mode == FlexibleMode.SLIP, slip, stick)

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """HEA against ±ky g [g], sliding velocity [m/s] and displacement [m] against
        time, episodes shaded (``excitation`` and ``block`` unused); a matplotlib Figure."""
        from ._figures import sliding_figure

        return sliding_figure(self, n_points=n_points, title=title)

    def event_table(self, events=None) -> str:
        """``events`` (default: all of them) as an aligned text table with units."""
        lines = [f"{'t [s]':>12}  {'kind':<10}  {'u [m]':>13}  {'u_rate [m/s]':>13}  {'s [m]':>13}"]
        lines += [f"{e.t:12.6f}  {e.kind:<10}  {e.u:13.6e}  {e.u_rate:13.6e}  {e.s:13.6e}"
                  for e in (self.events if events is None else events)]
        return "\n".join(lines)

    def to_dataframe(self):
        """The events as a pandas DataFrame: kind, t_s [s], u_m [m], u_rate_m_s [m/s], s_m [m]."""
        import pandas as pd

        rows = [(e.kind, e.t, e.u, e.u_rate, e.s) for e in self.events]
        return pd.DataFrame(rows, columns=["kind", "t_s", "u_m", "u_rate_m_s", "s_m"])
