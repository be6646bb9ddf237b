"""The contact force at the pivot of a rocking block against its limits: where N falls to 0
(the pivot would lift: a flight) and where |F| reaches mu N (the pivot would slip), located
on a solution's dense output. Housner's model goes on through them (its pivot holds, as
the literature's overturning spectra assume); they are reported.

Every rocking interval between knots is sampled at its ends and middle on its own cubic
(the state just before an event at its end, not after), all intervals at once, and the
crossings found are located together: a run of thousands of knots costs a few NumPy
passes."""

import numpy as np

from ..excitation import accel, accel_rate

#: how closely a limit is located on the dense output [s]
TIME_TOLERANCE = 1e-14
#: the most secant steps locating one (each at least halves the bracket every other step)
MAX_ITERATIONS = 120
#: the kinds of a contact event, in the order of the block's ``contact_margins``
KINDS = ("lift_limit", "slip_limit")
#: where each rocking interval is sampled, as fractions of it
FRACTIONS = np.array([0.0, 0.5, 1.0])


class MotionAt:
    """A base motion as the model's rules read an excitation: a_x and a_z [m/s²] and
    their rates [m/s³] at any times in [0, ``t_end``] [s], from the block's pieces of it
    (made once; the pieces of the times last asked for are kept, as the rules ask for
    the four values at one array of times in turn)."""

    def __init__(self, block, motion, t_end):
        self.pieces = block.excitation_pieces(motion, t_end)
        self._times, self._located = None, None

    def _at(self, index, t, value):
        if t is not self._times:
            self._times, self._located = t, [self._locate(pieces, np.asarray(t, dtype=float)) for pieces in self.pieces]
        inside, tau, coefficients = self._located[index]
        return np.where(inside, value(*coefficients, tau), 0.0)

    @staticmethod
    def _locate(pieces, t):
        """(t inside the pieces, t - the start of its piece [s], that piece's coefficients)."""
        k = np.clip(np.searchsorted(pieces.t0, t, side="right") - 1, 0, len(pieces.h) - 1)
        columns = (pieces.p0, pieces.p1, pieces.s, pieces.w, pieces.phi)
        coefficients = tuple(None if c is None else c[k] for c in columns)
        return t < pieces.t_end, t - pieces.t0[k], coefficients

    def component(self, index, t):
        return self._at(index, t, accel)

    def component_rate(self, index, t):
        return self._at(index, t, accel_rate)


class RockingIntervals:
    """The rocking intervals [t_i, t_i+1] of a solution (t_i+1 > t_i) and the state on each
    by its own cubic Hermite (the solution's dense output, a
    :class:`~blockdae.core.HermiteDense`)."""

    def __init__(self, solution):
        dense, mode = solution.dense, np.asarray(solution.mode, dtype=int)
        rocking = np.isin(np.abs(mode), (2, 3, 4))
        self.index = np.flatnonzero(rocking[:-1] & (dense.t[1:] > dense.t[:-1]))
        self.starts_episode = (self.index == 0) | ~rocking[np.maximum(self.index - 1, 0)]
        self.side = np.sign(mode[self.index])
        self.dense = dense

    def at(self, rows, fractions):
        """(theta [rad], theta' [rad/s], t [s]) at ``fractions`` of the intervals ``rows``
        (1-D arrays of one size; the order of the block's ``contact_margins``)."""
        d, i = self.dense, self.index[rows]
        t0, h = d.t[i], d.t[i + 1] - d.t[i]
        s = fractions
        h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
        g00, g10, g01, g11 = (6 * s**2 - 6 * s) / h, 3 * s**2 - 4 * s + 1, (6 * s - 6 * s**2) / h, 3 * s**2 - 2 * s
        y0, y1, d0, d1 = (np.moveaxis(a, -1, 0) for a in (d.y[i], d.y[i + 1], d.rate_start[i], d.rate_end[i]))
        theta = h00 * y0[0] + h10 * h * d0[0] + h01 * y1[0] + h11 * h * d1[0]
        rate = g00 * y0[0] + g10 * d0[0] + g01 * y1[0] + g11 * d1[0]
        return theta, rate, t0 + s * h


def locate_contact_events(solution):
    """[(t [s], kind, theta [rad], theta' [rad/s], F [m/s²], N [m/s²])] in time order: each
    time the contact force leaves its limits while the block rocks (N falls through 0, or
    mu N - |F| does), located on the dense output (a bracketing secant, Illinois's, to
    :data:`TIME_TOLERANCE`); a limit already broken as a rocking episode starts is reported
    at its start."""
    block, excitation = solution.block, MotionAt(solution.block, solution.motion, float(solution.t[-1]))
    intervals = RockingIntervals(solution)
    n, m = intervals.index.size, FRACTIONS.size
    if n == 0:
        return []
    rows, fractions = np.repeat(np.arange(n), m), np.tile(FRACTIONS, n)
    margins = block.contact_margins(intervals.side[rows], *intervals.at(rows, fractions), excitation, np)
    starts, brackets = [], []
    for k in range(len(KINDS)):
        values = margins[k].reshape(n, m)
        at_start = intervals.starts_episode & (values[:, 0] <= 0)
        crosses = (values[:, :-1] > 0) & (values[:, 1:] <= 0)
        which = np.flatnonzero(~at_start & crosses.any(axis=1))
        first = np.argmax(crosses[which], axis=1)
        starts += [(row, k) for row in np.flatnonzero(at_start)]
        brackets += [(row, k, FRACTIONS[j], FRACTIONS[j + 1], values[row, j], values[row, j + 1])
                     for row, j in zip(which, first)]
    found = [(row, 0.0, k) for row, k in starts]
    if brackets:
        row, k, *bracket = (np.array(column) for column in zip(*brackets))
        found += list(zip(row, _illinois(block, excitation, intervals, row, k, *bracket), k))
    if not found:
        return []
    rows, fractions, kinds = (np.array(column) for column in zip(*found))
    theta, rate, t = intervals.at(rows, fractions.astype(float))
    force, normal = block.contact_force(intervals.side[rows], theta, rate, t, excitation, np)
    order = np.argsort(t, kind="stable")
    return [(float(t[j]), KINDS[kinds[j]], float(theta[j]), float(rate[j]), float(force[j]), float(normal[j]))
            for j in order]


def _illinois(block, excitation, intervals, rows, kinds, low, high, f_low, f_high):
    """The fractions of the intervals ``rows`` where contact margin ``kinds`` (0: N, 1: mu N
    - |F|) first falls to 0, from brackets [low, high] with the margins f_low > 0 >=
    f_high there: the side where it is broken (<= 0), within :data:`TIME_TOLERANCE`."""
    width = intervals.dense.t[intervals.index[rows] + 1] - intervals.dense.t[intervals.index[rows]]
    side = np.zeros(rows.size)  # the side kept last: +1 high moved, -1 low moved
    for _ in range(MAX_ITERATIONS):
        if np.all((high - low) * width <= TIME_TOLERANCE):
            break
        mid = (low * f_high - high * f_low) / (f_high - f_low)
        mid = np.where((mid > low) & (mid < high), mid, 0.5 * (low + high))
        values = block.contact_margins(intervals.side[rows], *intervals.at(rows, mid), excitation, np)
        f_mid = np.where(kinds == 0, values[0], values[1])
        broken = f_mid <= 0
        f_low = np.where(broken & (side == 1), 0.5 * f_low, np.where(broken, f_low, f_mid))
        f_high = np.where(~broken & (side == -1), 0.5 * f_high, np.where(broken, f_mid, f_high))
        low, high = np.where(broken, low, mid), np.where(broken, mid, high)
        side = np.where(broken, 1.0, -1.0)
    return high
