"""Velocity, displacement and intensity measures of a ground motion, in closed form.

Every excitation is a chain of monotone pieces a(τ) = p0 + p1 τ + s sin(w τ + φ)
(``blockdae.excitation.Pieces``): a record is piecewise linear between samples. Its
velocity is piecewise quadratic and its displacement piecewise cubic, so the peaks are
located exactly, between samples: PGA at a piece end, PGV where a changes sign inside a
piece, PGD where v changes sign inside a piece (a monotone root, found to the last bit).
"""

import dataclasses

import numpy as np

from ..units import STANDARD_GRAVITY
from ..excitation import accel, accel_int1, accel_int2
from . import _checks
from ..core import compact_repr

_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)  # exact for a² of linear pieces


@dataclasses.dataclass(frozen=True)
class IntensityMeasures:
    """Peak values with the times where they occur, Arias intensity and duration, in SI units.

    Attributes:
        name: the record's name ("" for analytic excitations).
        pga, t_pga: max |a| [m/s²] and its time [s].
        pgv, t_pgv: max |v| [m/s] and its time [s].
        pgd, t_pgd: max |d| [m] and its time [s].
        d_max, t_d_max: largest (signed) displacement [m] and its time [s].
        d_min, t_d_min: smallest (signed) displacement [m] and its time [s].
        arias: Arias intensity I_A = π/(2g) ∫ a² dt [m/s] (Arias 1970).
        t_start, t_stop: times where the cumulative Arias intensity reaches the
            lower and upper fractions of ``band`` (5 % and 95 %) [s].
        significant_duration: t_stop - t_start [s] (Trifunac & Brady 1975, D5-95).
        t_end: end of the analysed window [s].
        g: the value of g used in the Arias intensity [m/s²].
    """

    def __repr__(self):
        return compact_repr(self)

    name: str
    pga: float
    t_pga: float
    pgv: float
    t_pgv: float
    pgd: float
    t_pgd: float
    d_max: float
    t_d_max: float
    d_min: float
    t_d_min: float
    arias: float
    t_start: float
    t_stop: float
    significant_duration: float
    t_end: float
    g: float

    def as_dict(self) -> dict:
        return dataclasses.asdict(self)


def motion_histories(motion, t):
    """Ground acceleration [m/s²], velocity [m/s] and displacement [m] at times ``t`` [s].

    The closed forms of the excitation (exact between samples of a record); each
    output has the shape of ``t``. The ground is at rest before t = 0 (d(0) = 0).
    """
    motion = _checks.excitation(motion)
    t = _checks.array("t", t, "s", low=0.0)
    return motion.acceleration(t), motion.velocity(t), motion.displacement(t)


class _Chain:
    """The pieces of a motion on [0, t_end] with the velocity and displacement at their starts."""

    def __init__(self, motion, t_end):
        p = motion.pieces(t_end)
        self.pieces = p
        self.coeffs = (p.p0, p.p1, p.s, p.w, p.phi)
        dv = accel_int1(*self.coeffs, p.h)
        self.v0 = motion.initial_velocity + np.concatenate([[0.0], np.cumsum(dv)])[:-1]
        dx = accel_int2(*self.coeffs, p.h) + self.v0 * p.h
        self.x0 = np.concatenate([[0.0], np.cumsum(dx)])[:-1]

    def a(self, k, tau):
        return accel(*(c[k] for c in self.coeffs), tau)

    def v(self, k, tau):
        return self.v0[k] + accel_int1(*(c[k] for c in self.coeffs), tau)

    def x(self, k, tau):
        return self.x0[k] + self.v0[k] * tau + accel_int2(*(c[k] for c in self.coeffs), tau)


def _monotone_root(f, lo, hi):
    """Roots of functions monotone on [lo, hi] with f(lo) f(hi) <= 0 (vectorised bisection)."""
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)
    f_lo = f(lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        done = (mid <= lo) | (mid >= hi)
        if np.all(done):
            break
        f_mid = f(mid)
        same = np.sign(f_mid) == np.sign(f_lo)
        lo = np.where(same & ~done, mid, lo)
        f_lo = np.where(same & ~done, f_mid, f_lo)
        hi = np.where(~same & ~done, mid, hi)
    return 0.5 * (lo + hi)


def _sign_change_roots(chain, f, k, lo, hi, linear_root=False):
    """Interior roots of f(k, τ) on [lo, hi] where f is monotone and changes sign."""
    f_lo, f_hi = f(k, lo), f(k, hi)
    change = (f_lo * f_hi < 0)
    k, lo, hi = k[change], lo[change], hi[change]
    if k.size == 0:
        return k, lo
    linear = chain.pieces.s[k] == 0
    tau = np.empty(k.size)
    if linear_root:  # f = a on a linear piece: the root of p0 + p1 τ in closed form
        kl = k[linear]
        tau[linear] = np.clip(-chain.pieces.p0[kl] / chain.pieces.p1[kl], lo[linear], hi[linear])
        rest = ~linear
    else:
        rest = np.ones(k.size, bool)
    if np.any(rest):
        kr = k[rest]
        tau[rest] = _monotone_root(lambda x: f(kr, x), lo[rest], hi[rest])
    return k, tau


def _extrema(chain, k, tau, values):
    """(max, t_max, min, t_min) of ``values`` at pieces ``k``, local times ``tau``."""
    t = chain.pieces.t0[k] + tau
    i, j = int(np.argmax(values)), int(np.argmin(values))
    return float(values[i]), float(t[i]), float(values[j]), float(t[j])


def _peaks(chain):
    """Located extremes of a, v and d on the chain: three (max, t_max, min, t_min)."""
    p = chain.pieces
    n = p.h.size
    k_all = np.arange(n)
    ends_k = np.concatenate([k_all, k_all])
    ends_tau = np.concatenate([np.zeros(n), p.h])
    a_ext = _extrema(chain, ends_k, ends_tau, chain.a(ends_k, ends_tau))  # a is monotone per piece
    k_a, tau_a = _sign_change_roots(chain, chain.a, k_all, np.zeros(n), p.h.copy(), linear_root=True)
    vk, vtau = np.concatenate([ends_k, k_a]), np.concatenate([ends_tau, tau_a])
    v_ext = _extrema(chain, vk, vtau, chain.v(vk, vtau))
    # v is monotone on each piece split at the root of a
    split = np.full(n, np.nan)
    split[k_a] = tau_a
    has = ~np.isnan(split)
    sub_k = np.concatenate([k_all, k_all[has]])
    sub_lo = np.concatenate([np.zeros(n), split[has]])
    sub_hi = np.concatenate([np.where(has, split, p.h), p.h[has]])
    k_v, tau_v = _sign_change_roots(chain, chain.v, sub_k, sub_lo, sub_hi)
    dk, dtau = np.concatenate([vk, k_v]), np.concatenate([vtau, tau_v])
    d_ext = _extrema(chain, dk, dtau, chain.x(dk, dtau))
    return a_ext, v_ext, d_ext


def _square_integral(chain, k, tau):
    """∫_0^τ a(s)² ds on pieces ``k`` [m²/s³] (16-point Gauss-Legendre: exact for linear pieces)."""
    tau = np.asarray(tau, dtype=float)
    s = 0.5 * tau[..., None] * (_GL_X + 1.0)
    a = chain.a(np.asarray(k)[..., None], s)
    return 0.5 * tau * np.sum(_GL_W * a * a, axis=-1)


def cumulative_arias(motion, t, *, g=STANDARD_GRAVITY):
    """Cumulative Arias intensity π/(2g) ∫_0^t a² dt [m/s] at times ``t`` [s] (Husid plot).

    Exact for records (a² of a linear piece integrated in closed form); shape of ``t``.
    """
    motion = _checks.excitation(motion)
    t = _checks.array("t", t, "s", low=0.0)
    g = float(_checks.array("g", g, "m/s²", low=0.0, low_open=True))
    horizon = float(np.max(t)) if np.max(t) > 0 else 1.0
    if np.isfinite(motion.duration):
        horizon = max(horizon, motion.duration)
    chain = _Chain(motion, horizon)
    p = chain.pieces
    cum = np.concatenate([[0.0], np.cumsum(_square_integral(chain, np.arange(p.h.size), p.h))])
    k = np.clip(np.searchsorted(p.t0, t, side="right") - 1, 0, p.h.size - 1)
    tau = np.minimum(t - p.t0[k], p.h[k])
    return np.pi / (2 * g) * (cum[k] + _square_integral(chain, k, tau))


def intensity_measures(motion, t_end=None, *, g=STANDARD_GRAVITY, band=(0.05, 0.95)) -> IntensityMeasures:
    """PGA, PGV, PGD with their times, Arias intensity and significant duration.

    Args:
        motion: an excitation (``bd.Record``, ``bd.Harmonic``, ...).
        t_end: end of the window [s]; default the excitation's duration (required for
            an excitation without end). Past the record the ground keeps its final
            velocity, so a later ``t_end`` can raise PGD.
        g: gravitational acceleration for the Arias intensity [m/s²].
        band: fractions of the Arias intensity that bound the significant duration [-]
            (0.05, 0.95: D5-95 of Trifunac & Brady 1975).

    Returns:
        :class:`IntensityMeasures`. The peaks are located between samples (exact for
        the piecewise-linear record), not taken at the samples.
    """
    motion = _checks.excitation(motion)
    t_end = _checks.horizon(motion, t_end)
    g = float(_checks.array("g", g, "m/s²", low=0.0, low_open=True))
    lo, hi = (float(x) for x in _checks.array("band", band, "-", low=0.0, high=1.0, high_open=False))
    if not lo < hi:
        raise ValueError(f"band = {tuple(band)!r}; band must be two increasing fractions in [0, 1]")
    chain = _Chain(motion, t_end)
    (a_hi, ta_hi, a_lo, ta_lo), (v_hi, tv_hi, v_lo, tv_lo), (d_hi, td_hi, d_lo, td_lo) = _peaks(chain)
    pga, t_pga = (a_hi, ta_hi) if abs(a_hi) >= abs(a_lo) else (-a_lo, ta_lo)
    pgv, t_pgv = (v_hi, tv_hi) if abs(v_hi) >= abs(v_lo) else (-v_lo, tv_lo)
    pgd, t_pgd = (d_hi, td_hi) if abs(d_hi) >= abs(d_lo) else (-d_lo, td_lo)
    p = chain.pieces
    parts = _square_integral(chain, np.arange(p.h.size), p.h)
    cum = np.concatenate([[0.0], np.cumsum(parts)])
    total = cum[-1]
    times = [_arias_time(chain, cum, f * total) for f in (lo, hi)]
    return IntensityMeasures(
        name=getattr(motion, "name", ""), pga=abs(pga), t_pga=t_pga, pgv=abs(pgv), t_pgv=t_pgv,
        pgd=abs(pgd), t_pgd=t_pgd, d_max=max(d_hi, 0.0), t_d_max=td_hi if d_hi > 0 else 0.0,
        d_min=min(d_lo, 0.0), t_d_min=td_lo if d_lo < 0 else 0.0, arias=float(np.pi / (2 * g) * total),
        t_start=times[0], t_stop=times[1], significant_duration=times[1] - times[0], t_end=t_end, g=g)


def _arias_time(chain, cum, target):
    """First time where ∫_0^t a² dt reaches ``target`` [s] (located inside its piece)."""
    p = chain.pieces
    if target <= 0:
        k = int(np.argmax(np.diff(cum) > 0)) if cum[-1] > 0 else 0
        return float(p.t0[k])
    k = int(np.clip(np.searchsorted(cum, target, side="left") - 1, 0, p.h.size - 1))
    need = target - cum[k]
    kk = np.array([k])
    tau = _monotone_root(lambda x: _square_integral(chain, kk, x) - need, np.zeros(1), p.h[kk])
    return float(p.t0[k] + tau[0])
