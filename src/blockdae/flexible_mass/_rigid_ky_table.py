"""Newmark's rigid block whose yield acceleration changes with the sliding displacement D
(a :class:`~blockdae.KyTable`), exact.

While it slides, D'' = a(t) - ky(D) g: on each piece of the table ky is linear in D and
a(t) is linear on each step of a record, so the slide is linear with constant
coefficients. It is the flexible sliding mass's decoupled slip with an infinitely stiff
column (its average acceleration HEA is then a(t) itself), and runs on that mass's
matrix-exponential engine (:mod:`blockdae.flexible_mass._table_engine`): onsets where a(t)
reaches ky(D) g, stops where the sliding rate returns to 0, and the table's breakpoints,
each located to adjacent floats.
"""

import dataclasses
import math

import numpy as np

from ..solvers import linear_pieces
from . import _table_kernel
from ._table_engine import slide_compiled, system_arrays

_FIELD = {name: k for k, name in enumerate(_table_kernel.OUTCOME_FIELDS)}


@dataclasses.dataclass(frozen=True)
class _RigidColumn:
    """What the ky-table engine reads of a model, for a column that does not deform:
    HEA = a(t) (no share of the column's own motion u, which is carried but read by no
    guard). ``table``: (breakpoints [m], intercepts [g], slopes [g/m]) of ky(D)."""

    table: tuple
    g: float
    omega: float = 1.0  # [rad/s]: u's own motion, which nothing reads
    damping: float = 0.0
    coupled: bool = False
    mass_participation: float = 0.0  # of u'' in HEA
    hea_share_at_rest: float = 1.0  # HEA = a at rest too

    @property
    def yield_acceleration(self) -> float:
        """ky g at D = 0 [m/s²]."""
        return float(self.table[1][0]) * self.g


def downslope_with_table(motion, table, g, t_end=None) -> float:
    """The downslope displacement D >= 0 [m] of the one-way rigid block under ``motion`` (a
    record or another excitation of linear pieces [m/s²]; sliding while a(t) > ky(D) g)
    with ky(D) the :class:`KyTable` ``table`` [g]; until ``t_end`` [s], or None: until the
    block rests after the motion (a ValueError if ky falls to 0 on the way: it never stops)."""
    systems = system_arrays(_RigidColumn(table.segments(), float(g)))
    end = motion.duration if t_end is None else float(t_end)
    outcome = _slide(systems, motion, end)
    if t_end is None and outcome[_FIELD["mode"]] != 0:  # still sliding when the motion ends
        d, rate = outcome[_FIELD["s"]], outcome[_FIELD["w"]]
        stopping = _stopping_time(table, d, rate, g)
        if stopping is None:
            raise ValueError(f"the block slides at {rate:.6g} m/s when the motion ends (D = {d:.6g} m) and ky falls "
                             "to 0 before the table's work can stop it: it never stops; give t_end [s]")
        outcome = _slide(systems, motion, end + 1.01 * stopping + 1e-3)
    return 0.0 + outcome[_FIELD["s"]]


def _slide(systems, motion, end):
    """The engine's outcome of one slide from rest under ``motion`` until ``end`` [s]."""
    found = linear_pieces(motion, end)
    if found is None:
        raise ValueError("a ky table runs on motions of linear pieces (records, pulses), not on a sine")
    t0, h, p0, p1 = found[1]
    keep = t0 < end  # the pieces up to the end, the last one cut there
    t0, h, p0, p1 = t0[keep], np.minimum(h[keep], end - t0[keep]), p0[keep], p1[keep]
    outcome, _ = slide_compiled(systems, (t0, h, p0, p1), where=f" ({getattr(motion, 'name', '') or 'motion'})")
    return outcome


def _stopping_time(table, d, rate, g):
    """A bound [s] of the time a block sliding at D = ``d`` [m], D' = ``rate`` [m/s] takes
    to stop on a still base (D'' = -ky(D) g): it stops at the D where the table's work
    g ∫ ky dD reaches rate² / 2, in at most rate / (g min ky) over the way; None if ky
    reaches 0 first (it never stops)."""
    rows_d = np.asarray(table.displacement_m, dtype=float)
    ahead = np.concatenate([[d], rows_d[rows_d > d]])
    ky = np.interp(ahead, rows_d, table.ky_g)
    work = rate * rate / (2.0 * g)  # [m]: the integral of ky [g] over D still to be done
    for (d0, d1), (k0, k1) in zip(zip(ahead, ahead[1:]), zip(ky, ky[1:])):
        if 0.5 * (k0 + k1) * (d1 - d0) >= work:  # it stops on this piece: where ky's area is the work
            slope = (k1 - k0) / (d1 - d0)
            step = work / k0 if slope == 0 else (math.sqrt(max(k0 * k0 + 2 * slope * work, 0.0)) - k0) / slope
            lowest = min(*ky[ahead <= d0], k0 + slope * step)
            return rate / (g * lowest) if lowest > 0 else None
        work -= 0.5 * (k0 + k1) * (d1 - d0)
    return rate / (g * float(ky.min())) if ky[-1] > 0 and ky.min() > 0 else None
