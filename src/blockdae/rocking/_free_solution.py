"""Results of the complete free-standing block: its events (an impact's jump as one event,
with the velocities before and after) and the energy balance."""

import dataclasses

import numpy as np

from ..core import AbstractEvent, state_columns, state_labels
from ._free_modes import INSTANT, event_kind, impact_kind
from ._slide_rock_laws import base_slip
from ._solution import BlockSolution

#: the kinds of event whose velocity jump dissipates energy (the balance's impact term)
JUMP_KINDS = ("impact", "land", "zeno", "chatter", "overturn")


@dataclasses.dataclass(frozen=True)
class FreeEvent(AbstractEvent):
    """A located event of a :class:`~blockdae.rocking.FreeStandingBlock`.

    Attributes:
        t: time [s].
        mode_before, mode_after: the modes on either side (an impact's instant mode
            between them is ``via``).
        kind: "release", "uplift", "slide", "stick", "reverse", "slip", "lift", "apex",
            "return", "beyond_alpha", "impact", "land", "zeno", "chatter", "rest",
            "overturn".
        state: (x [m], z [m], theta [rad], x' [m/s], z' [m/s], theta' [rad/s]) before it.
        state_after: the same after it (an impact's or landing's velocity jump).
        via: the instant mode of an impact or landing (None for other events).
    """

    kind: str
    state: tuple
    state_after: tuple
    via: object = None

    @classmethod
    def make(cls, t, before, after, state, state_after):
        """The event of the mode change ``before`` -> ``after`` at ``t`` [s]."""
        return cls(t, before, after, event_kind(before, after), tuple(map(float, state)),
                   tuple(map(float, state_after)))

    @classmethod
    def merge(cls, events):
        """``events`` with each change into an instant mode and the change out of it merged
        into one event (an impact, a landing, the release), restarts within a mode left out."""
        merged, i = [], 0
        while i < len(events):
            e = events[i]
            if e.mode_before == e.mode_after:  # a restart (a corner that grazes the base in flight)
                i += 1
                continue
            if e.mode_after in INSTANT and i + 1 < len(events) and events[i + 1].mode_before == e.mode_after:
                out = events[i + 1]
                merged.append(cls(e.t, e.mode_before, out.mode_after, impact_kind(e.mode_before, e.mode_after,
                                                                                  out.mode_after),
                                  e.state, out.state_after, e.mode_after))
                i += 2
            else:
                merged.append(e)
                i += 1
        return tuple(merged)

    def __str__(self):
        return (f"t = {self.t:.9f} s  {self.kind:<12} {str(self.mode_before):<18} -> {str(self.mode_after):<18} "
                f"theta = {self.state[2]:+.6e} rad  theta' = {self.state[5]:+.6e} -> {self.state_after[5]:+.6e} rad/s")


@dataclasses.dataclass(frozen=True, eq=False)
class FreeStandingSolution(BlockSolution):
    """The motion of a complete free-standing block.

    Attributes:
        t: knot times [s], shape (n,).
        state: (x [m], z [m], theta [rad], x' [m/s], z' [m/s], theta' [rad/s], base work
            [J/kg], friction work [J/kg]) at the knots, shape (n, 8).
        mode: mode right after each knot, shape (n,) (:class:`FreeMode`).
        events: located events (:class:`FreeEvent`), in time order.
    """

    def event_table(self, events=None) -> str:
        """``events`` (default: all) as an aligned text table: time [s], kind, the mode after
        and the state before the event in its units (theta' also after it)."""
        events = self.events if events is None else events
        names = state_labels(self.block, 6)[:6] + ["theta_rate after [rad/s]"]
        lines = [f"{'t [s]':>14}  {'kind':<12}  {'after':<18}  " + "  ".join(f"{n:>24}" for n in names)]
        lines += [f"{e.t:14.9f}  {e.kind:<12}  {e.mode_after.name:<18}  "
                  + "  ".join(f"{v:24.12e}" for v in (*e.state, e.state_after[5])) for e in events]
        return "\n".join(lines)

    def to_dataframe(self):
        """The events as a pandas DataFrame: kind, t_s [s], mode_before, mode_after, the
        state before (x_m, z_m, theta_rad, x_rate_m_s, z_rate_m_s, theta_rate_rad_s) and
        after it (the same names ending in _after)."""
        import pandas as pd

        names = state_columns(self.block)[:6]
        rows = [(e.kind, e.t, e.mode_before.name, e.mode_after.name, *e.state, *e.state_after) for e in self.events]
        return pd.DataFrame(rows, columns=["kind", "t_s", "mode_before", "mode_after", *names,
                                           *(f"{name}_after" for name in names)])

    @property
    def time_beyond_alpha(self) -> float:
        """First time |theta| passed alpha while rocking [s] (gravity no longer restores); nan if never."""
        events = self.events_of("beyond_alpha")
        return events[0].t if events else float("nan")

    @property
    def max_theta_over_alpha(self) -> float:
        """max |theta| / alpha over the run [-] (at the knots and events)."""
        return float(np.max(np.abs(self.state[:, 2]))) / self.block.alpha

    @property
    def slip(self) -> np.ndarray:
        """The base's slip at the knots [m], shape (n,) (:func:`base_slip`)."""
        return base_slip(self.state[:, 0], self.state[:, 2], self.block.b, self.block.h, np)

    @property
    def final_slip(self) -> float:
        """The base's slip at t_end [m] (:func:`base_slip`)."""
        return float(self.slip[-1])

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """theta [rad], the slip [m], the corners' heights [m] and a_x [m/s²] against t [s],
        shaded by the motion (slide, rock, slide-rock, flight; ``excitation`` and ``block``
        unused); a matplotlib Figure (:func:`._figures.free_standing_figure`)."""
        from ._figures import free_standing_figure

        return free_standing_figure(self, n_points=n_points, title=title)

    def energy_balance(self) -> dict:
        """The energy balance per unit mass at the knots away from events (section 9 of the
        formulation): E(t) - E(0) = W_base + W_friction + the impacts' jumps.

        Returns name -> array over those knots: "t" [s], "energy_change" E(t) - E(0)
        [J/kg] (E = ½(x'² + z'²) + (R²/6) theta'² + g z, E(0) after a release),
        "base_work" ∫ (-a_x x' - a_z z') dt, "friction_work" ∫ F u' dt (<= 0), "impact"
        the sum of the velocity jumps' KE+ - KE- (<= 0: impacts, landings, the Zeno and
        chatter tails, overturning) and "residual" [J/kg] what the balance leaves."""
        block = self.block
        energy = np.array([block.energy(m, y) for m, y in zip(self.mode, self.state)])
        reference = energy[0]
        jumps = []
        for e in self.events:
            if e.kind == "release":
                reference = block.energy(e.mode_after, e.state_after)
            elif e.kind in JUMP_KINDS:
                jumps.append((e.t, block.energy(e.mode_after, e.state_after) - block.energy(e.mode_before, e.state)))
        event_times = {e.t for e in self.events}
        keep = np.array([t not in event_times for t in self.t])
        keep[-1] = True
        t = self.t[keep]
        impact = np.array([sum(dE for te, dE in jumps if te < ti) for ti in t])
        change = energy[keep] - reference
        base, friction = self.state[keep, 6], self.state[keep, 7]
        return {"t": t, "energy_change": change, "base_work": base, "friction_work": friction, "impact": impact,
                "residual": change - base - friction - impact}

    @property
    def energy_scale(self) -> float:
        """The balance's scale [J/kg]: the largest of g h, the kinetic energy and |each work|."""
        balance = self.energy_balance()
        block = self.block
        kinetic = [block.energy(m, y) - block.g * y[1] for m, y in zip(self.mode, self.state)]
        return float(max(block.g * block.h, max(kinetic), np.max(np.abs(balance["base_work"])),
                         np.max(np.abs(balance["friction_work"]))))

    @property
    def energy_residual(self) -> float:
        """max |residual| of :meth:`energy_balance` [J/kg]."""
        return float(np.max(np.abs(self.energy_balance()["residual"])))
