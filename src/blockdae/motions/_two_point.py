"""Relative motion of two surface points during an earthquake (Christian 1973).

The second point feels the same ground motion τ = b/c seconds later and is at rest before
it arrives: D(t) = d(t) - d(t - τ), d(s) = 0 for s < 0. Between the breakpoints of d(t)
and of d(t - τ) both are single closed-form pieces (cubic for a record), so the largest
|D| is located exactly: endpoints, and inside a sub-interval only where a bound on |D''|
allows a larger value (branch and bound + Newton on D', ``_kernels.max_abs``). Past
t_end + τ, D = v(t_end) τ is constant.
"""

import dataclasses

import numpy as np

from ..core import compact_repr, notice_numba
from ..excitation import accel_int1, accel_int2, rebase
from . import _checks
from ._intensity import _Chain, intensity_measures

_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)


@dataclasses.dataclass(frozen=True)
class RelativeMotion:
    """Largest relative displacement of two points for each lag, with the paper's estimates.

    Arrays have the shape of ``lags``. SI units.

    Attributes:
        lags: τ = b/c [s].
        r: max over t of |d(t) - d(t - τ)| [m] (exact); t_r: where it occurs [s].
        pga, pgv, pgd: a_m [m/s²], v_m [m/s], d_m = max |d| [m] of the motion.
        d_max, d_min: largest and smallest displacement [m] (d_min <= 0 <= d_max).
            The peaks are those of the record window [0, t_end]; D spans [0, t_end + τ],
            where a drifting record keeps moving, so R <= max d - min d holds over that
            longer window (baseline-correct the record first).
        twice_pgd: method (a), 2 d_m [m].
        newmark: method (b), d_max - d_min [m] (Newmark 1967).
        eq1_minus, eq1_plus: method (c), v_m τ ∓ a_m τ²/2 [m] (seed eq. 1, Table I).
        fourier: method (d), twice the Fourier amplitude of d at T = 2τ [m] (the amplitude
            (2/T_w) |∫_0^T_w d(t) e^(-iπt/τ) dt| over the window T_w, which gives D0 for a
            sine of amplitude D0 with whole periods in the window).
        spectral: method (d), 2 Sd(T = 2τ, ``damping``) [m].
        envelope: the proposed bound min(v_m τ, d_m) (seed eqs. 2-3) [m].
        t_end: end of the record window [s]; damping: ζ of ``spectral`` [-].
    """

    def __repr__(self):
        return compact_repr(self)

    name: str
    lags: np.ndarray
    r: np.ndarray
    t_r: np.ndarray
    pga: float
    pgv: float
    pgd: float
    d_max: float
    d_min: float
    fourier: np.ndarray
    spectral: np.ndarray
    t_end: float
    damping: float

    @property
    def twice_pgd(self):
        return np.full(self.lags.shape, 2 * self.pgd)

    @property
    def newmark(self):
        return np.full(self.lags.shape, self.d_max - self.d_min)

    @property
    def velocity_bound(self):
        """v_m τ [m] (seed eq. 2)."""
        return self.pgv * self.lags

    @property
    def eq1_minus(self):
        return self.pgv * self.lags - 0.5 * self.pga * self.lags**2

    @property
    def eq1_plus(self):
        return self.pgv * self.lags + 0.5 * self.pga * self.lags**2

    @property
    def envelope(self):
        return np.minimum(self.pgv * self.lags, self.pgd)

    def table(self):
        """Rows (dicts) for CSV output, one per lag."""
        fields = ("r", "t_r", "velocity_bound", "eq1_minus", "eq1_plus", "twice_pgd", "newmark", "fourier",
                  "spectral", "envelope")
        cols = {f: np.atleast_1d(getattr(self, f)) for f in fields}
        units = {"t_r": "s"}
        return [{"lag_s": float(lag), **{f"{f}_{units.get(f, 'm')}": float(cols[f][i]) for f in fields}}
                for i, lag in enumerate(np.atleast_1d(self.lags))]


def relative_motion(motion, lags, *, t_end=None, damping=0.05, estimates=True) -> RelativeMotion:
    """Largest relative displacement of two points a lag τ apart (Christian 1973), exact.

    Args:
        motion: an excitation (``bd.Record``, ``bd.Harmonic``, ...), e.g. baseline corrected.
        lags: τ = b/c >= 0 [s], scalar or 1-D (b: separation [m], c: wave velocity [m/s]).
        t_end: end of the record window [s] (default the duration; required for an
            excitation without end). The first point moves on [0, t_end], the second
            on [τ, t_end + τ]; the ground keeps its final velocity afterwards.
        damping: ζ of the spectral estimate 2 Sd(2τ) [-].
        estimates: compute the Fourier and spectral estimates (method d).

    Returns:
        :class:`RelativeMotion`.
    """
    motion = _checks.excitation(motion)
    tau = _checks.array("lags", lags, "s", low=0.0)
    if tau.ndim > 1:
        raise ValueError(f"lags must be a scalar or a 1-D array, got shape {tau.shape}")
    zeta = float(_checks.array("damping", damping, "-", low=0.0, high=1.0))
    end = _checks.horizon(motion, t_end)
    flat = np.atleast_1d(tau)
    r = np.zeros(flat.size)
    t_r = np.zeros(flat.size)
    for i, lag in enumerate(flat):
        r[i], t_r[i] = _max_lagged_difference(motion, float(lag), end)
    m = intensity_measures(motion, end)
    fourier = np.zeros(flat.size)
    spectral = np.zeros(flat.size)
    positive = flat > 0
    if estimates and np.any(positive):
        fourier[positive] = 2 * fourier_amplitude(motion, 1 / (2 * flat[positive]), end)
        from ._spectra import response_spectrum

        spectral[positive] = 2 * response_spectrum(motion, 2 * flat[positive], zeta, t_end=end).sd
    shape = tau.shape
    return RelativeMotion(getattr(motion, "name", ""), tau, r.reshape(shape), t_r.reshape(shape), m.pga, m.pgv,
                          m.pgd, m.d_max, m.d_min, fourier.reshape(shape), spectral.reshape(shape), end, zeta)


def _local(chain, k, offset, L_shape):
    """Coefficient rows (n, 10) of d(t) on pieces ``k`` from local time ``offset`` on, and w."""
    p = chain.pieces
    c = tuple(x[k] for x in (p.p0, p.p1, p.s, p.w, p.phi))
    v = chain.v0[k] + accel_int1(*c, offset)
    x = chain.x0[k] + chain.v0[k] * offset + accel_int2(*c, offset)
    q0, q1, s, w, phi = rebase(*c, offset)
    rows = np.zeros(L_shape + (10,))
    sine = s != 0
    ws = np.where(sine, w, 1.0)
    rows[:, 0] = x + np.where(sine, s / ws**2 * np.sin(phi), 0.0)
    rows[:, 1] = v + np.where(sine, s / ws * np.cos(phi), 0.0)
    rows[:, 2] = 0.5 * q0
    rows[:, 3] = q1 / 6.0
    rows[:, 6] = np.where(sine, -s / ws**2 * np.sin(phi), 0.0)
    rows[:, 7] = np.where(sine, -s / ws**2 * np.cos(phi), 0.0)
    return rows, np.where(sine, w, 0.0)


def _poly_sine(rows, w, x):
    """Values of rows (n, 10) without damped part at local times x (n,), sine frequency w."""
    return (rows[:, 0] + x * (rows[:, 1] + x * (rows[:, 2] + x * rows[:, 3]))
            + rows[:, 6] * np.cos(w * x) + rows[:, 7] * np.sin(w * x))


def _max_lagged_difference(motion, lag, end):
    """(max |d(t) - d(t - lag)|, t) over t >= 0 [m, s]."""
    if lag == 0:
        return 0.0, 0.0
    stop = end + lag
    chain = _Chain(motion, stop)
    t0 = chain.pieces.t0
    edges = np.unique(np.concatenate([t0, lag + t0[lag + t0 < stop], [lag, stop]]))
    ta, tb = edges[:-1], edges[1:]
    L = tb - ta
    keep = L > 1e-12 * stop
    ta, L = ta[keep], L[keep]
    mid = ta + 0.5 * L
    k1 = np.clip(np.searchsorted(t0, mid, side="right") - 1, 0, t0.size - 1)
    rows1, w1 = _local(chain, k1, ta - t0[k1], ta.shape)
    second = mid > lag
    k2 = np.clip(np.searchsorted(t0, mid - lag, side="right") - 1, 0, t0.size - 1)
    rows2, w2 = _local(chain, k2, ta - lag - t0[k2], ta.shape)
    rows2[~second] = 0.0
    w2 = np.where(second, w2, 0.0)
    rows = np.zeros(rows1.shape)
    rows[:, :4] = rows1[:, :4] - rows2[:, :4]
    rows[:, 6:8] = rows1[:, 6:8]
    rows[:, 8:10] = -rows2[:, 6:8]
    f_a = _poly_sine(rows1, w1, 0.0 * L) - _poly_sine(rows2, w2, 0.0 * L)
    f_b = _poly_sine(rows1, w1, L) - _poly_sine(rows2, w2, L)
    ends = np.maximum(np.abs(f_a), np.abs(f_b))
    i = int(np.argmax(ends))
    best = float(ends[i])
    t_best = float(ta[i] if abs(f_a[i]) >= abs(f_b[i]) else ta[i] + L[i])
    m2 = (np.maximum(np.abs(2 * rows[:, 2]), np.abs(2 * rows[:, 2] + 6 * rows[:, 3] * L))
          + w1**2 * np.hypot(rows[:, 6], rows[:, 7]) + w2**2 * np.hypot(rows[:, 8], rows[:, 9]))
    cand = np.flatnonzero(ends + 0.125 * m2 * L**2 > best * (1 + 1e-15))
    if cand.size:
        from . import kernels as _kernels

        notice_numba("the response kernels", 10, _kernels.max_abs_many)
        params = np.zeros((cand.size, 4))
        params[:, 2], params[:, 3] = w1[cand], w2[cand]
        b, tb_ = _kernels.max_abs_many(np.ascontiguousarray(rows[cand]), params, np.ascontiguousarray(L[cand]),
                                       np.full(cand.size, best), np.full(cand.size, -1.0))
        j = int(np.argmax(b))
        if tb_[j] >= 0 and b[j] > best:
            best, t_best = float(b[j]), float(ta[cand[j]] + tb_[j])
    return best, t_best


def fourier_amplitude(motion, frequencies, t_end=None):
    """Fourier amplitude of the displacement, (2/T_w) |∫_0^T_w d(t) e^(-2πi f t) dt| [m].

    Exact to rounding: 8-point Gauss-Legendre on every piece (split so that 2πf h <= 1),
    on the closed-form displacement. A sine of amplitude D0 with whole periods in the
    window [0, T_w] has amplitude D0 at its frequency.

    Args:
        motion: an excitation; frequencies: f > 0 [Hz], 1-D; t_end: T_w [s] (default the duration).
    """
    motion = _checks.excitation(motion)
    f = np.atleast_1d(_checks.array("frequencies", frequencies, "Hz", low=0.0, low_open=True))
    end = _checks.horizon(motion, t_end)
    p = motion.pieces(end)
    split = max(1, int(np.ceil(2 * np.pi * f.max() * p.h.max())))
    sub = np.arange(split)
    a = (p.t0[:, None] + p.h[:, None] * sub / split).ravel()
    hs = np.repeat(p.h / split, split)
    nodes = a[:, None] + 0.5 * hs[:, None] * (_GL_X + 1.0)
    weights = 0.5 * hs[:, None] * _GL_W
    d = motion.displacement(nodes.ravel()).reshape(nodes.shape)
    out = np.empty(f.size)
    for i, fi in enumerate(f):
        out[i] = 2 / end * abs(np.sum(weights * d * np.exp(-2j * np.pi * fi * nodes)))
    return out.reshape(np.shape(frequencies)) if np.ndim(frequencies) else out[0]
