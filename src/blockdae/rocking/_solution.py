"""Results of a free-standing block: impacts, the Zeno rest, overturning, max |theta|/alpha."""

import dataclasses
import functools
import warnings

import numpy as np

from ..core import AbstractEvent, DriverSolution, compact_repr
from ..excitation import outside_blockdae


class ContactWarning(UserWarning):
    """The contact force of a rocking block left its limits (N <= 0 or |F| > mu N)."""


@dataclasses.dataclass(frozen=True)
class RockingEvent(AbstractEvent):
    """A located event of a :class:`RockingBlock`.

    Attributes:
        t: time [s].
        mode_before, mode_after: the modes on either side.
        kind: "release", "uplift", "apex", "return", "beyond_alpha", "impact", "zeno"
            (the rest of the impacts summed), "rest", "overturn", "slide", "stick".
        q: theta [rad] (a rocking block) or u [m] (a sliding one).
        rate: theta' [rad/s] (or u' [m/s]) before the event.
        rate_after: theta' [rad/s] after it (r times ``rate`` through an impact).
    """

    kind: str
    q: float
    rate: float
    rate_after: float

    def __str__(self):
        return (f"t = {self.t:.9f} s  {self.kind:<12} q = {self.q:+.6e}  rate = {self.rate:+.6e}  "
                f"after = {self.rate_after:+.6e}")


@dataclasses.dataclass(frozen=True, eq=False)
class BlockSolution(DriverSolution):
    """What the solutions of a free-standing block share: their events by kind, the
    impacts and their times, the rest and the overturn."""

    def __repr__(self):
        return compact_repr(self)

    def events_of(self, kind: str) -> tuple:
        """The events of one ``kind`` (see the solution's event class)."""
        return tuple(e for e in self.events if e.kind == kind)

    @property
    def impacts(self) -> tuple:
        """The impacts located one by one, each with the rates before and after it (the
        Zeno tail's summed ones are not among them)."""
        return self.events_of("impact")

    @property
    def rest_time(self) -> float:
        """Time [s] of the last rest after rocking (a Zeno accumulation point); nan if none."""
        rests = self.events_of("rest")
        return rests[-1].t if rests else float("nan")

    @property
    def impact_times(self) -> np.ndarray:
        """Times of the located impacts [s]."""
        return np.array([e.t for e in self.impacts])

    @property
    def overturned(self) -> bool:
        """Whether the block overturned."""
        return bool(self.events_of("overturn"))

    @property
    def overturn_time(self) -> float:
        """Time it reached |theta| = pi/2 [s]; nan if it did not."""
        events = self.events_of("overturn")
        return events[0].t if events else float("nan")


@dataclasses.dataclass(frozen=True, eq=False)
class RockingSolution(BlockSolution):
    """The motion of a free-standing block.

    Attributes:
        t: knot times [s], shape (n,).
        state: (theta [rad], theta' [rad/s]) of a rocking block, (u [m], u' [m/s]) of a
            sliding one, at the knots, shape (n, 2).
        mode: mode right after each knot, shape (n,) (:class:`RockingMode`).
        events: located events (:class:`RockingEvent`), in time order.
        block, motion: the model and the base motion (set by :func:`blockdae.simulate`).
    """

    @property
    def zeno_tail(self) -> float:
        """Duration [s] of the last summed tail of impacts (rest time minus the last
        located impact); nan if none."""
        zeno, rests = self.events_of("zeno"), self.events_of("rest")
        return rests[-1].t - zeno[-1].t if zeno and rests else float("nan")

    @property
    def time_beyond_alpha(self) -> float:
        """First time |theta| passed alpha [s] (gravity no longer restores); nan if never."""
        events = self.events_of("beyond_alpha")
        return events[0].t if events else float("nan")

    @property
    def rocks(self) -> bool:
        """Whether the state is a rotation (theta) rather than a slide (u)."""
        return not self.block.slides if self.block is not None else not any(
            abs(int(m)) == 1 for m in self.mode)

    @property
    def max_theta_over_alpha(self) -> float:
        """max |theta| / alpha over the run [-] (at the knots and events; a rotation's
        extremes are apexes, which are located events); 0 for a sliding block."""
        if self.block is None or self.block.slides:
            return 0.0
        return float(np.max(np.abs(self.state[:, 0]))) / self.block.alpha

    @functools.cached_property
    def contact_events(self) -> tuple:
        """Where the contact force left its limits while the block rocked: rows (t [s],
        kind, theta [rad], theta' [rad/s], F [m/s²], N [m/s²]), kind "lift_limit" (N fell
        to 0: the pivot would lift) or "slip_limit" (|F| reached mu N: it would slip),
        located on the dense output; Housner's model goes on through them. Empty for a
        sliding block."""
        from ._contact import locate_contact_events

        if self.block is None or self.block.slides:
            return ()
        return tuple(locate_contact_events(self))

    def check_contact(self, strict=None) -> tuple:
        """:attr:`contact_events`, with a :class:`ContactWarning` naming the first of each
        kind (its time, theta, theta', F and N) and how many there are, or a ValueError with
        ``strict`` (None: the block's own ``strict``). :func:`blockdae.simulate` calls it
        after every run."""
        events = self.contact_events
        strict = self.block.strict if strict is None else strict
        under = f" under {self.motion.name}" if getattr(self.motion, "name", None) else ""
        for kind in ("lift_limit", "slip_limit"):
            rows = [row for row in events if row[1] == kind]
            if not rows:
                continue
            t, _, theta, rate, force, normal = rows[0]
            what = "N <= 0: the pivot would lift" if kind == "lift_limit" else "|F| >= mu N: the pivot would slip"
            more = f" (the first of {len(rows)} times; solution.contact_events lists them)" if len(rows) > 1 else ""
            message = (f"at t = {t:.9f} s{under} the contact force leaves its limits ({what}; theta = {theta:+.6g} "
                       f"rad, theta' = {rate:+.6g} rad/s, F = {force:+.6g} m/s², N = {normal:+.6g} m/s², mu = "
                       f"{self.block.mu}){more}; Housner's model keeps its pivot")
            if strict:
                raise ValueError(message)
            warnings.warn(message, ContactWarning, stacklevel=outside_blockdae())
        return events

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """theta / alpha (or u) against time with the impacts, over a_x (``excitation``
        and ``block`` unused); a matplotlib Figure."""
        from ._figures import rocking_figure

        return rocking_figure(self, n_points=n_points, title=title)

    def event_table(self, events=None) -> str:
        """``events`` (default: all) as an aligned text table with units (q: theta [rad]
        or u [m]; rates in rad/s or m/s)."""
        lines = [f"{'t [s]':>14}  {'kind':<12}  {'q [rad|m]':>13}  {'rate [1/s|m/s]':>14}  {'after':>13}"]
        lines += [f"{e.t:14.9f}  {e.kind:<12}  {e.q:13.6e}  {e.rate:14.6e}  {e.rate_after:13.6e}"
                  for e in (self.events if events is None else events)]
        return "\n".join(lines)

    def to_dataframe(self):
        """The events as a pandas DataFrame: kind, t_s [s], q (theta [rad] or u [m]),
        rate, rate_after (rad/s or m/s)."""
        import pandas as pd

        rows = [(e.kind, e.t, e.q, e.rate, e.rate_after) for e in self.events]
        return pd.DataFrame(rows, columns=["kind", "t_s", "q", "rate", "rate_after"])

