"""The exact backend of a flexible sliding mass whose ky is a table of the sliding
displacement (:class:`~._ky_table.KyTable`).

On one piece of ky, ky(s) = k0 + k1 s [g, g/m], and one piece of a record, a(t) = p0
+ p1 tau, every mode is linear with constant coefficients in the augmented state
z = (u, u', s, w, a, a', 1): z' = M z, so z(tau) = expm(M tau) z(0), the matrix
exponential (Taylor's series, scaled and squared, accurate to rounding) of a 7 x 7 matrix per
(mode, piece of ky). Softening pieces (k1 < 0) add growing and decaying exponentials
to the sliding, hardening ones (k1 > 0) a slow oscillation; the matrix exponential
needs no case for either, nor for k1 = 0 (a Jordan block).

The generic driver (:mod:`blockdae.core._driver`) runs the modes, the events and the
knots (at the record's samples and the events only); this integrator steps it in closed
form and finds the first root of each guard (a linear form c z: the onset guard ky(s) g -
HEA in STICK, w and the next breakpoint minus s in SLIP) on a step: an interval is
dropped where bounds of the guard's derivatives (Taylor at its start, the fourth
derivative bounded by the norm of the subsystem it reads, in scaled units) show the
guard rising, falling, convex or concave, else halved; a crossing is refined by
bisection to adjacent floats. The next breakpoint minus s falls monotonically in SLIP
(w >= 0): its crossing is bracketed by its values.

``bd.flexible``'s rows run the same systems (:func:`system_arrays`) on the compiled
kernel of :mod:`._table_kernel` (:func:`slide_compiled`, :func:`response_compiled`);
``bd.simulate`` runs this module's Python engine, whose solution has dense output.
"""

import dataclasses
import math

import numpy as np

from ..core import AbstractIntegrator, InconsistentStateError, SolverError, drive, first_nonpositive, notice_numba
from ..solvers import CHATTER, UNSETTLED, linear_pieces
from . import _table_kernel
from ._column import MODE_PARTICIPATION, SLIP_MASS_FRACTION
from ._modes import FlexibleMode
from ._table_kernel import (EVENT_RESOLUTION, LOWER, MAX_EVENTS_AT_ONE_INSTANT, MAX_INTERVALS,
                            TAYLOR_DEGREE as _TAYLOR_DEGREE, UPPER, _bound)

_U, _V, _S, _W, _A, _AR, _ONE = range(7)
_EPS = float(np.finfo(float).eps)
#: derivatives of a guard kept at an interval's start: g, g', g'', g''' and the bound row of g''''
_ORDERS = 5


def _closure(M, start):
    """The states (a mask (7,)) that those in ``start`` depend on through z' = M z, with
    them: the smallest subsystem that evolves alone and holds ``start``."""
    found = start.copy()
    while True:
        more = found | (np.abs(M[found]).sum(axis=0) != 0)
        if (more == found).all():
            return found
        found = more


class _System:
    """z' = M z in one mode on one piece of ky, and its guards as rows c (g = c z) with
    c M^k, k < 4, and what bounds g'''' = c M^4 z (see :meth:`fourth_bound`): |c M^4
    scale|_1, the weights 1 / scale on the subsystem that c M^4 z reads (zero elsewhere:
    s and w in STICK, s under a flat ky) and that subsystem's scaled norm."""

    def __init__(self, model, mode, intercept, slope, breakpoint):
        k, c, g = model.omega**2, 2.0 * model.damping * model.omega, model.g
        kappa, friction = slope * g, intercept * g  # ky(s) g = friction + kappa s
        participation = model.mass_participation  # of u'' in HEA: 2/pi; 0 for a rigid column (HEA = a)
        M = np.zeros((7, 7))
        M[_U, _V] = M[_A, _AR] = 1.0
        if mode == FlexibleMode.SLIP and model.coupled:  # d1 u'' = -(4/pi) ky(s) g - c u' - k u
            M[_V, [_U, _V, _S, _ONE]] = np.array([-k, -c, -MODE_PARTICIPATION * kappa,
                                                  -MODE_PARTICIPATION * friction]) / SLIP_MASS_FRACTION
        else:
            M[_V, [_U, _V, _A]] = -k, -c, -MODE_PARTICIPATION
        if mode == FlexibleMode.SLIP:  # s' = w, w' = a - ky(s) g + (2/pi) u''
            M[_S, _W] = 1.0
            M[_W] = participation * M[_V]
            M[_W, _A] += 1.0
            M[_W, _S] -= kappa
            M[_W, _ONE] -= friction
            guards = [np.eye(7)[_W]]
            if math.isfinite(breakpoint):
                guards.append(breakpoint * np.eye(7)[_ONE] - np.eye(7)[_S])
        else:  # ky(s) g - HEA, HEA = a + (2/pi) u''
            onset = -participation * M[_V]
            onset[_A] -= 1.0
            onset[_S] += kappa
            onset[_ONE] += friction
            guards = [onset]
        self.M, self.guards, self.monotone = M, guards, [False, True][:len(guards)]
        fast = model.omega / math.sqrt(SLIP_MASS_FRACTION) if model.coupled else model.omega
        rate = max(fast, math.sqrt(abs(kappa)))
        # z~ = z / scale: every entry of M~ = M scaled is (a number of order one) x rate
        self.scale = np.array([1.0, rate, 1.0, rate, rate**2, rate**3, rate**2 / g])
        self.scaled = M * self.scale[None, :] / self.scale[:, None]
        self.norm = np.abs(self.scaled).sum(axis=1).max()
        self.rows = [self.guard_row(row) for row in guards]
        self._maps = {}

    def guard_row(self, row):
        """What the search takes of the form g = ``row`` z (7,): c M^k (4, 7) (k < 4), and
        what bounds c M^4 z (:meth:`fourth_bound`): |c M^4 scale|_1, the weights 1 / scale
        on the subsystem J that c M^4 z reads (0 elsewhere), |M~_JJ| [1/s]."""
        powers = [np.asarray(row, dtype=float)]
        for _ in range(_ORDERS - 1):
            powers.append(powers[-1] @ self.M)
        fourth = powers[-1]
        relevant = _closure(self.M, fourth != 0)
        inner = np.abs(self.scaled[np.ix_(relevant, relevant)]).sum(axis=1).max() if relevant.any() else 0.0
        return (np.array(powers[:-1]), float(np.abs(fourth * self.scale).sum()),
                np.where(relevant, 1.0 / self.scale, 0.0), float(inner))

    def transition(self, tau):
        """expm(M tau), remembered for the step lengths that recur."""
        found = self._maps.get(tau)
        if found is None:
            if len(self._maps) > 512:
                self._maps.clear()
            found = self._maps[tau] = self.exponential(tau)
        return found

    def exponential(self, tau):
        """expm(M tau) by Taylor's series (degree 16) with scaling and squaring, on the
        balanced M~ = M scaled (|M~ tau| / 2^squarings <= 1/2: truncation below 1e-20)."""
        x = self.scaled * tau
        squarings = max(0, math.ceil(math.log2(max(self.norm * tau, 1e-300) / 0.5)))
        x = x / 2.0**squarings
        term, total = np.eye(7), np.eye(7)
        for k in range(1, _TAYLOR_DEGREE + 1):
            term = term @ x / k
            total = total + term
        for _ in range(squarings):
            total = total @ total
        return total * self.scale[:, None] / self.scale[None, :]

    def fourth_bound(self, index, z, length):
        """A bound of |g''''| on [0, length] [s] of guard ``index`` from z at its start:
        with J the subsystem that c M^4 z reads (it evolves alone), |c M^4 z(tau)| <= |c M^4
        scale|_1 |z~_J(tau)|_inf <= ... exp(|M~_JJ| length) |z~_J(0)|_inf."""
        _, row4, weights, inner = self.rows[index]
        growth = inner * length
        if growth > 50.0:
            return math.inf
        return row4 * math.exp(growth) * float(np.abs(z * weights).max()) * (1.0 + 1e-9)


class _Search:
    """The first tau in (0, h] [s] where g = c z falls to <= 0 from > 0, z(tau) = expm(M
    tau) z0 (None: no crossing)."""

    def __init__(self, system, index, z0, t0):
        self.system, self.z0, self.t0 = system, z0, t0
        self.powers, self.index = system.rows[index][0], index
        self.budget = MAX_INTERVALS

    def state(self, tau):
        return self.system.transition(tau) @ self.z0

    def value(self, tau, order=0):
        return float(self.powers[order] @ self.state(tau))

    def bisect(self, lo, hi):
        """The first tau in (lo, hi] where g <= 0, to adjacent floats of t0 + tau, for g
        > 0 at lo, <= 0 at hi and one crossing between."""
        return first_nonpositive(lambda _, tau: self.value(tau), None, lo, hi, self.t0)

    def search(self, lo, z_lo, hi):
        """The first crossing in (lo, hi] from the state ``z_lo`` at lo (None: none): an
        interval where g is shown > 0, g' >= 0 or <= 0, or g'' of one sign is decided at
        once, others are halved, the earlier half first."""
        self.budget -= 1
        if self.budget < 0:
            raise SolverError(f"the ky-table engine's root search did not settle by t = {self.t0 + lo:.12g} s "
                              f"(more than {MAX_INTERVALS} intervals); use backend 'cvode'")
        length = hi - lo
        d = self.powers @ z_lo
        z_hi = self.system.transition(length) @ z_lo
        g_lo, g_hi = float(d[0]), float(self.powers[0] @ z_hi)
        if self.t0 + lo + length <= self.t0 + lo or length <= 4 * _EPS * max(abs(self.t0) + abs(hi), 1.0):
            return hi if g_lo > 0 >= g_hi else None
        if g_lo == g_hi == 0 and not np.any(d[1:]):
            return None  # a guard that stays at zero (HEA = ky g = 0 at rest): no fall through it
        b4 = self.system.fourth_bound(self.index, z_lo, length)
        if _bound([d[0], d[1], d[2] / 2, d[3] / 6, -b4 / 24], length, LOWER) > 0:
            return None  # positive all along
        if _bound([d[1], d[2], d[3] / 2, -b4 / 6], length, LOWER) >= 0:
            return None  # rising all along: no fall through zero
        if _bound([d[1], d[2], d[3] / 2, b4 / 6], length, UPPER) <= 0:  # falling all along
            return self.bisect(lo, hi) if g_lo > 0 >= g_hi else None
        if _bound([d[2], d[3], -b4 / 2], length, LOWER) > 0:  # convex: falls, then rises
            if g_lo > 0:
                turn = self.bisect_rate(lo, hi)
                if self.value(turn) <= 0:
                    return self.bisect(lo, turn)
                return None
        if _bound([d[2], d[3], b4 / 2], length, UPPER) < 0 and g_lo > 0:  # concave: one crossing at most
            return self.bisect(lo, hi) if g_hi <= 0 else None
        mid = lo + 0.5 * length
        first = self.search(lo, z_lo, mid)
        if first is not None:
            return first
        return self.search(mid, self.state(mid), hi)

    def bisect_rate(self, lo, hi):
        """Where g' (rising on [lo, hi]) crosses zero; lo or hi if it does not."""
        if self.value(lo, 1) >= 0:
            return lo
        if self.value(hi, 1) <= 0:
            return hi
        return first_nonpositive(lambda _, tau: -self.value(tau, 1), None, lo, hi, self.t0)


class _Systems:
    """The :class:`_System` of each (mode, breakpoints passed) of ``model``, built once."""

    def __init__(self, model):
        self.model = model
        self.breakpoints, self.intercepts, self.slopes = (np.asarray(x, dtype=float) for x in model.table)
        self.built = {}

    def __call__(self, mode, passed):
        key = (int(mode), passed)
        if key not in self.built:
            breakpoint = self.breakpoints[passed] if passed < len(self.breakpoints) else math.inf
            self.built[key] = _System(self.model, mode, self.intercepts[passed], self.slopes[passed], breakpoint)
        return self.built[key]


def system_arrays(model):
    """The systems of ``model`` (ky a table) as :func:`._table_kernel._slides` takes them:
    (systems (k, SYSTEM_ROWS, 7): per system (mode * pieces + passed) M~ [1/s], scale,
    weights and rows c M^k of each guard, its numbers (see :mod:`._table_kernel`); pieces
    of ky; ky g at s = 0 [m/s²]; HEA at rest as a share of a [-])."""
    systems = _Systems(model)
    n_pieces = len(systems.intercepts)
    built = [systems(mode, passed) for mode in FlexibleMode for passed in range(n_pieces)]
    packed = np.zeros((len(built), _table_kernel.SYSTEM_ROWS, 7))
    for k, system in enumerate(built):
        _pack(packed[k], system, system.rows)
    return packed, n_pieces, float(model.yield_acceleration), float(model.hea_share_at_rest)


def _pack(packed, system, rows):
    """Write ``system`` with the rows (:meth:`_System.guard_row`) of its guards, or of
    other forms c z, into ``packed`` (SYSTEM_ROWS, 7) (see :mod:`._table_kernel`)."""
    packed[_table_kernel.MATRIX:_table_kernel.MATRIX + 7] = system.scaled
    packed[_table_kernel.SCALE] = system.scale
    packed[_table_kernel.NUMBERS, :2] = system.norm, len(rows)
    for g, (powers, row4, weights, inner) in enumerate(rows):
        packed[_table_kernel.WEIGHTS + g] = weights
        packed[_table_kernel.POWERS + 4 * g:_table_kernel.POWERS + 4 * g + 4] = powers
        packed[_table_kernel.NUMBERS, 2 + 2 * g:4 + 2 * g] = row4, inner


def response_arrays(model):
    """``model``'s column without sliding as :func:`._table_kernel._response` takes it:
    (1, SYSTEM_ROWS, 7), STICK with the forms HEA = a + (2/pi) u'' [m/s²] and u [m]."""
    system = _System(model, FlexibleMode.STICK, 0.0, 0.0, math.inf)  # its guard at ky = 0: -HEA
    packed = np.zeros((1, _table_kernel.SYSTEM_ROWS, 7))
    _pack(packed[0], system, [system.guard_row(-system.guards[0]), system.guard_row(np.eye(7)[_U])])
    return packed


def response_compiled(model, arrays, slots, with_u, where=""):
    """``model``'s no-sliding response from rest over a record's linear pieces ``arrays``
    (t0, h, p0, p1; ``slots`` their :func:`._table_kernel.step_slots`) on matrix
    exponentials, for any damping: (max |HEA| at the pieces' ends [m/s²], sup |HEA| over
    time [m/s²], sup |u| [m] (nan without ``with_u``))."""
    kernel = _table_kernel.response_kernel()
    notice_numba("the ky-table kernel", 15, kernel)
    samples, sup, u_sup, settled = kernel(*arrays, slots, response_arrays(model), with_u)
    if not settled:
        raise SolverError(f"a peak search of the no-sliding response did not settle in {MAX_INTERVALS} intervals"
                          f"{where}; use backend 'cvode'")
    return samples, sup, u_sup


def slide_compiled(systems, arrays, log_rows=0, where="", slots=None):
    """One slide from rest by the compiled engine (:mod:`._table_kernel`) over a record's
    linear pieces ``arrays`` (t0, h, p0, p1) with ``systems`` from :func:`system_arrays`:
    (outcome (OUTCOME_FIELDS), event log (EVENT_FIELDS) of its first ``log_rows``
    events); ``slots``: :func:`._table_kernel.step_slots` of ``arrays`` where known.
    Raises as the driver does: chatter, an unsettled search, a slide upslope."""
    log = np.empty((log_rows, len(_table_kernel.EVENT_FIELDS)))
    if slots is None:
        slots = _table_kernel.step_slots(arrays[0], arrays[1])
    kernel = _table_kernel.kernel()
    notice_numba("the ky-table kernel", 15, kernel)
    outcome = kernel(*arrays, slots, *systems, log)
    field = dict(zip(_table_kernel.OUTCOME_FIELDS, outcome))
    status, last = int(field["status"]), field["t_last_event"]
    if status == CHATTER:
        raise RuntimeError(f"more than {MAX_EVENTS_AT_ONE_INSTANT} events at t = {last:.12g} s within "
                           f"{EVENT_RESOLUTION:g} s{where}: chatter of the flexible sliding mass")
    if status == UNSETTLED:
        raise SolverError(f"the ky-table engine's root search did not settle after t = {last:.12g} s (more than "
                          f"{MAX_INTERVALS} intervals){where}; use backend 'cvode'")
    if status == _table_kernel.INCONSISTENT:
        raise InconsistentStateError(f"by t = {field['t']:.12g} s the slide moves upslope (w = {field['w']:+.6g} "
                                     f"m/s){where}: a missed event, please report")
    return outcome, log[:min(log_rows, int(field["n_events"]))]


class TableIntegrator(AbstractIntegrator):
    """Steps the driver's runs in closed form (see the module's docstring): a step
    returns at ``t_out`` or at the first guard crossing located to adjacent floats."""

    def __init__(self, model, piece):
        self.model, self.piece = model, piece
        self.system = _Systems(model)
        self.counts = {"n_restarts": 0, "n_calls": 0}

    def restart(self, mode, t, y):
        self.mode, self.t, self.y = mode, float(t), np.array(y, dtype=float)
        self.counts["n_restarts"] += 1

    def step(self, t_out, t_stop):
        self.counts["n_calls"] += 1
        p0, p1, amplitude = self.piece.coefficients[0][:3]
        if amplitude != 0:
            raise ValueError("the ky-table engine takes records (linear pieces of a(t)); use backend 'cvode'")
        passed = int(round(self.y[4]))
        system = self.system(self.mode, passed)
        z0 = np.array([*self.y[:4], p0 + p1 * self.piece.local_time(self.t), p1, 1.0])
        h = t_out - self.t
        best, index = None, None
        for i, row in enumerate(system.guards):
            search = _Search(system, i, z0, self.t)
            if system.monotone[i]:
                root = self._monotone_root(search, h)
            else:
                root = search.search(0.0, z0, h if best is None else best)
            if root is not None and (best is None or root < best):
                best, index = root, i
        tau = h if best is None else best
        z = system.transition(tau) @ z0
        self.t = t_out if best is None else self.t + tau
        self.y = np.array([*z[:4], self.y[4]])
        return self.t, self.y.copy(), index

    @staticmethod
    def _monotone_root(search, h):
        """The crossing of a guard that only falls (the next breakpoint minus s)."""
        if search.value(0.0) > 0 >= search.value(h):
            return search.bisect(0.0, h)
        return None

    @property
    def stats(self):
        return dict(self.counts)


def record_pieces(excitation, horizon, engine):
    """(pieces, arrays) of a record's linear pieces to ``horizon``'s t_end [s] for
    ``engine`` (its name, for the errors): ValueError for a horizon until rest (the column
    oscillates on) or sine pieces."""
    if horizon.until_rest:
        raise ValueError("the column oscillates on after the record: give t_end [s]")
    found = linear_pieces(excitation, horizon.t_end)
    if found is None:
        raise ValueError(f"{engine} takes records (linear pieces); {type(excitation).__name__} has sine pieces: "
                         "use backend 'cvode'")
    return found


class TableEngine:
    """The exact engine of a flexible mass whose ky is a table (numba); the backend's
    settings are not read."""

    def solve(self, model, excitation, horizon, backend):
        return solve_table_exact(model, excitation, horizon, backend.name)


def solve_table_exact(model, excitation, horizon, name):
    """``model`` (ky a table) under ``excitation`` (a record) to ``horizon``: its solution,
    every onset, stop and breakpoint located to adjacent floats. The driver's knots are
    the pieces' ends and the events (steps in closed form need no others); the dense
    output is the closed form from the last knot (:class:`ExactDense`)."""
    found = record_pieces(excitation, horizon, "the ky-table engine")
    coarse = model.with_parameters({})
    object.__setattr__(coarse, "output_step", lambda: math.inf)  # knots at pieces and events only
    solution = drive(coarse, excitation, horizon, TableIntegrator, name, MAX_EVENTS_AT_ONE_INSTANT,
                     EVENT_RESOLUTION, (0.0, 0.0))
    return dataclasses.replace(solution, dense=ExactDense(_Systems(model), solution, found[0]))


class ExactDense:
    """The states at any times [s]: from the last knot at or before each, z(t) = expm(M
    (t - t_k)) z_k in the knot's mode and piece of ky, a(t) on the record's piece there."""

    def __init__(self, systems, solution, pieces):
        self.systems, self.t, self.y, self.mode = systems, solution.t, solution.state, solution.mode
        self.pieces = pieces

    def __call__(self, times):
        times = np.asarray(times, dtype=float)
        out = np.empty(times.shape + (self.y.shape[1],))
        knots = np.clip(np.searchsorted(self.t, times.ravel(), side="right") - 1, 0, len(self.t) - 1)
        flat = out.reshape(-1, self.y.shape[1])
        for n, (t, k) in enumerate(zip(times.ravel(), knots)):
            j = max(int(np.searchsorted(self.pieces.t0, self.t[k], side="right")) - 1, 0)
            rate = self.pieces.p1[j]
            a = self.pieces.p0[j] + rate * (self.t[k] - self.pieces.t0[j])
            system = self.systems(self.mode[k], int(round(self.y[k, 4])))
            z = system.exponential(t - self.t[k]) @ np.array([*self.y[k, :4], a, rate, 1.0])
            flat[n] = [*z[:4], self.y[k, 4]]
        return tuple(out[..., i] for i in range(out.shape[-1]))
