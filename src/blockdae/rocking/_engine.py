"""The exact engine of the linearised rocking block (``backend="exact"``): its compiled
closed form (:mod:`._kernel`) on a piecewise-linear horizontal record, the knots made a
:class:`RockingSolution` with dense output."""

import math

import numpy as np

from ..core import HermiteDense
from ._kernel import KNOT_COLUMNS, kernel
from ._modes import RockingMode

#: knot rows first allocated per piece of a(t) (the log grows if a run needs more)
ROWS_PER_PIECE = 4


def record_pieces(model, excitation, horizon):
    """(t0, h, p0, p1) of a_x [s, s, m/s², m/s³], with a rest-seeking tail (h = inf,
    a_x = 0) when ``horizon`` runs until rest; ValueError for a motion the engine cannot
    take (a sine piece or a vertical component)."""
    ax, az = model.excitation_pieces(excitation, horizon.integration_end(excitation))
    if ax.has_sine or az.has_sine or np.any(az.p0 != 0) or np.any(az.p1 != 0):
        raise ValueError("the exact engine of a rocking block takes piecewise-linear horizontal records "
                         "(no sine pieces, no vertical component): use backend='cvode'")
    t0, h, p0, p1 = ax.t0, ax.h, ax.p0, ax.p1
    if horizon.until_rest:
        t0, h = np.append(t0, t0[-1] + h[-1]), np.append(h, math.inf)
        p0, p1 = np.append(p0, 0.0), np.append(p1, 0.0)
    return tuple(np.ascontiguousarray(a, dtype=float) for a in (t0, h, p0, p1))


class LinearisedEngine:
    """Runs a linearised, rocking :class:`RockingBlock` in closed form (the engine of
    ``backend="exact"``)."""

    def solve(self, model, excitation, horizon, backend):
        if not model.linearised or model.slides:
            raise ValueError("backend='exact' runs the linearised rocking block (linearised=True, mu >= b/h); "
                             "use backend='cvode'")
        pieces = record_pieces(model, excitation, horizon)
        run = kernel()
        rows = ROWS_PER_PIECE * len(pieces[0]) + 64
        while True:
            log = np.empty((rows, KNOT_COLUMNS))
            n = run(*pieces, model.alpha, model.frequency, model.g, model.r, model.zeno_arc, model.theta0, log)
            if n <= rows:
                break
            rows = 2 * n
        solution = knots_solution(model, excitation, log[:n], backend.name)
        if model.strict:  # located on the closed form's dense output
            object.__setattr__(solution, "block", model)
            object.__setattr__(solution, "motion", excitation)
            solution.check_contact(strict=True)
        return solution


def knots_solution(model, excitation, log, backend_name):
    """A :class:`RockingSolution` from the kernel's knot rows."""
    t, state = log[:, 0], log[:, 1:3]
    mode = log[:, 3].astype(int)
    events = []
    for k in np.flatnonzero(log[:, 5] == 1.0):
        before, after = RockingMode(int(log[k, 4])), RockingMode(int(log[k, 3]))
        pre = k > 0 and before != RockingMode.RELEASE and log[k - 1, 0] == log[k, 0] and log[k - 1, 3] == log[k, 4] \
            and log[k - 1, 5] == 0.0
        row = log[k - 1 if pre else k]
        events.append(model.event(row[0], before, after, (row[1], row[2])))
    events = tuple(events)
    rate_start = np.column_stack([state[:, 1], log[:, 6]])
    # the interval after knot i ends at knot i + 1 in mode i: that knot's theta'' where the
    # mode holds (a piece's end, an event's pre-knot); an event's zero-length step else
    rate_end = np.append(rate_start[1:], np.zeros((1, 2)), axis=0)
    stats = {"n_events": len(events), "n_knots": len(t)}
    return model.solution(t=t, y=state, mode=mode, events=events, backend=backend_name,
                          dense=HermiteDense(t, state, rate_start, rate_end), stats=stats)
