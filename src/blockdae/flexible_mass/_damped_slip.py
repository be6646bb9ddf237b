"""A sliding mass whose slip is too damped for the compiled engine's underdamped closed
forms (coupled: xi / sqrt(d1) >= 1 - 1e-6, total damping xi >= about 0.4352): its slides
run on the matrix-exponential engine of the ky tables (:mod:`._table_engine`, which
needs no case for any eigen-structure), with ky as a one-piece flat table; the
no-sliding response (STICK, underdamped while xi < 1) stays on the compiled engine up to a
total damping of :data:`COMPILED_RESPONSE_LIMIT`, beyond which it runs on matrix
exponentials too.
"""

import dataclasses
import math

import numpy as np

from ._column import SLIP_MASS_FRACTION

#: the compiled engine's closed forms need the column's damping ratio below this
UNDERDAMPED_LIMIT = 1 - 5e-9
#: the no-sliding response (and so everything) runs on matrix exponentials from this total
#: damping on (measured: at 1 - 1e-7 the compiled response's sup |u| search settles and
#: agrees with them to 5e-10, at 1 - 1e-8 it no longer settles on Northridge PAC-175)
COMPILED_RESPONSE_LIMIT = 1 - 1e-6
#: SLIP runs on the compiled engine while its damping ratio is below this, else here
#: (measured: at 1 - 1e-7 its slides agree with this engine's to 4e-14, at 1 - 3e-8 its
#: root search no longer settles, the underdamped forms too ill-conditioned)
COMPILED_SLIP_LIMIT = 1 - 1e-6


def slip_underdamped(xi, coupled) -> bool:
    """Whether SLIP's damping ratio (coupled: xi / sqrt(d1); decoupled: xi [-]) is below
    :data:`COMPILED_SLIP_LIMIT` (the compiled engine's slides)."""
    return xi / (math.sqrt(SLIP_MASS_FRACTION) if coupled else 1.0) < COMPILED_SLIP_LIMIT


def flat_table_model(model):
    """``model`` (a constant ky) as the table engine takes it: ky a one-piece table (no
    breakpoint, slope 0) and a fifth state, the breakpoints passed (always 0)."""
    flat = model.with_parameters({})
    object.__setattr__(flat, "table", ((), (float(model.ky),), (0.0,)))
    object.__setattr__(flat, "state_names", tuple(model.state_names) + ("breakpoints_passed",))
    return flat


def solve_damped_slip(model, excitation, horizon, name):
    """``model`` (a constant ky) under ``excitation`` (a record) by the table engine: its
    solution with the model's own four states (u, u', s, w), every onset and stop
    located to adjacent floats."""
    from ._table_engine import solve_table_exact

    solution = solve_table_exact(flat_table_model(model), excitation, horizon, name)
    dense = solution.dense
    return dataclasses.replace(solution, state=np.ascontiguousarray(solution.state[:, :4]),
                               dense=lambda times: dense(times)[:4])
