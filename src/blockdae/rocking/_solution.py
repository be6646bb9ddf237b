"""Results of a free-standing block: impacts, the Zeno rest, overturning, max |theta|/alpha."""

import dataclasses
import functools
import typing

import numpy as np

from ..core import AbstractEvent, DriverSolution, compact_repr


class ContactLimit(typing.NamedTuple):
    """Where the contact force of Housner's rocking block left its limits: there the
    complete block (:class:`FreeStandingBlock`) would slip or lift, while Housner's keeps
    its pivot.

    Attributes:
        t: time [s], located on the dense output.
        kind: "lift_limit" (N fell to 0: the pivot would lift) or "slip_limit" (|F|
            reached mu N: it would slip).
        theta: the rotation [rad]; theta_rate: its rate [rad/s].
        force, normal: the contact force's F and N per unit mass [m/s²].
    """

    t: float
    kind: str
    theta: float
    theta_rate: float
    force: float
    normal: float

    def __str__(self):
        return f"at t = {self.t:.9f} s {self.describe()}"

    def describe(self, mu=None, under="") -> str:
        """"the contact force leaves its limits (what, theta, theta', F, N[, mu])", after
        the motion's name ``under``."""
        what = "N <= 0: the pivot would lift" if self.kind == "lift_limit" else "|F| >= mu N: the pivot would slip"
        friction = "" if mu is None else f", mu = {mu}"
        return (f"{under}the contact force leaves its limits ({what}; theta = {self.theta:+.6g} rad, theta' = "
                f"{self.theta_rate:+.6g} rad/s, F = {self.force:+.6g} m/s², N = {self.normal:+.6g} m/s²{friction})")


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
    impacts, rest and overturn, the figure and the event table (each subclass names its
    figure, :attr:`figure_name`, and its table's columns, ``event_columns()``: (header
    with its unit, width, format, the value of an event) each)."""

    def __repr__(self):
        return compact_repr(self)

    def events_of(self, kind: str) -> tuple:
        """The events of one ``kind`` (see the solution's event class)."""
        return tuple(e for e in self.events if e.kind == kind)

    @property
    def impact_times(self) -> np.ndarray:
        """Times of the located impacts [s]."""
        return np.array([e.t for e in self.impacts])

    @property
    def impacts(self) -> tuple:
        """The corner impacts located one by one (each with the rates before and after)."""
        return self.events_of("impact")

    @property
    def rest_time(self) -> float:
        """Time [s] of the last rest after rocking (a Zeno accumulation point); nan if none."""
        rests = self.events_of("rest")
        return rests[-1].t if rests else float("nan")

    @property
    def time_beyond_alpha(self) -> float:
        """First time |theta| passed alpha while rocking [s] (gravity no longer restores); nan if never."""
        events = self.events_of("beyond_alpha")
        return events[0].t if events else float("nan")

    @property
    def overturned(self) -> bool:
        """Whether the block overturned."""
        return bool(self.events_of("overturn"))

    @property
    def overturn_time(self) -> float:
        """Time it reached |theta| = pi/2 [s]; nan if it did not."""
        events = self.events_of("overturn")
        return events[0].t if events else float("nan")

    #: the name of the figure of :mod:`._figures` that draws this solution
    figure_name: typing.ClassVar[str]

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """The run against t [s] over a_x [m/s²] (``excitation`` and ``block`` unused): a
        matplotlib Figure (the figure :attr:`figure_name` of :mod:`._figures`)."""
        from . import _figures

        return getattr(_figures, self.figure_name)(self, n_points=n_points, title=title)

    def event_table(self, events=None) -> str:
        """``events`` (default: all) as an aligned text table, a column a quantity with its
        unit (``event_columns()``)."""
        columns = self.event_columns()
        lines = ["  ".join(f"{header:{'<' if 's' in spec else '>'}{width}}" for header, width, spec, _ in columns)]
        lines += ["  ".join(f"{value(e):{width}{spec}}" for _, width, spec, value in columns)
                  for e in (self.events if events is None else events)]
        return "\n".join(lines)


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
        """Where Housner's assumption broke: each time the contact force left its limits
        while the block rocked (:class:`ContactLimit`: t [s], kind "lift_limit" or
        "slip_limit", theta [rad], theta' [rad/s], F and N [m/s²]), in time order, located
        on the dense output; Housner's model goes on through them (the complete block would
        lift or slip there). Empty for a sliding block."""
        from ._contact import locate_contact_events

        if self.block is None or self.block.slides:
            return ()
        return tuple(ContactLimit(*row) for row in locate_contact_events(self))

    @property
    def contact_holds(self) -> bool:
        """Whether the contact force stayed within its limits all run (no
        :attr:`contact_events`): Housner's assumption held."""
        return not self.contact_events

    def check_contact(self, strict=None) -> tuple:
        """:attr:`contact_events`, located (and kept); with ``strict`` (None: the block's
        own) where there are any, the ValueError that ``strict=True`` raises, naming the
        first (its time, theta, theta', F and N) and how many there are.
        :func:`blockdae.simulate` calls it after every run."""
        events = self.contact_events
        if events and (self.block.strict if strict is None else strict):
            under = f"under {self.motion.name} " if getattr(self.motion, "name", None) else ""
            more = f" (the first of {len(events)}: solution.contact_events lists them)" if len(events) > 1 else ""
            raise ValueError(f"at t = {events[0].t:.9f} s {events[0].describe(self.block.mu, under)}{more}; "
                             "strict=True stops here")
        return events

    figure_name = "rocking_figure"

    def event_columns(self) -> tuple:
        """t [s], kind, q (theta [rad] or u [m]), its rate before and after [rad/s or m/s]."""
        return (("t [s]", 14, ".9f", lambda e: e.t), ("kind", 12, "s", lambda e: e.kind),
                ("q [rad|m]", 13, ".6e", lambda e: e.q), ("rate [1/s|m/s]", 14, ".6e", lambda e: e.rate),
                ("after", 13, ".6e", lambda e: e.rate_after))

    def to_dataframe(self):
        """The events as a pandas DataFrame: kind, t_s [s], q (theta [rad] or u [m]),
        rate, rate_after (rad/s or m/s)."""
        import pandas as pd

        rows = [(e.kind, e.t, e.q, e.rate, e.rate_after) for e in self.events]
        return pd.DataFrame(rows, columns=["kind", "t_s", "q", "rate", "rate_after"])

