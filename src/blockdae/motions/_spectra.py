"""Response spectra, exact for piecewise-linear input (Nigam & Jennings 1969).

The oscillator u'' + 2ζω u' + ω² u = -a_g(t) (u: displacement relative to the ground)
is solved in closed form on every piece of the excitation (the Nigam-Jennings
recurrence for linear pieces, with the particular solution of a sine for sine pieces),
so the response at the samples is exact; between samples each response is a known
function (polynomial + damped sinusoid) and its largest magnitude is located there
(branch and bound, ``_kernels``), not taken at the samples: no resampling rule (eqsig
interpolates to dt/4; gmprocess issue 532) is needed at short periods.
"""

import dataclasses

import numpy as np

from ..core import compact_repr, notice_numba
from ..excitation import accel_int1, accel_int2
from . import _checks


@dataclasses.dataclass(frozen=True)
class ResponseSpectrum:
    """Spectra of one or several motions. Arrays have shape ``batch + damping + periods``:
    batch () for one motion, (n_motions,) for a list; damping () for a scalar, (n_d,) for
    a 1-D array; periods () or (n_T,).

    Attributes:
        periods: T [s]; damping: ζ [-]; names: motion names, shape batch.
        sd: max |u|, relative displacement [m]; t_sd: its time [s].
        sv: max |u'|, relative velocity [m/s]; t_sv: its time [s].
        sa: max |u'' + a_g|, absolute acceleration [m/s²]; t_sa: its time [s].
        sd_abs: max |u + x_g|, absolute displacement (the SMiRT paper on Newmark's formula) [m]; t_sd_abs [s].
        psv = ω Sd [m/s], psa = ω² Sd [m/s²] (ω = 2π/T).
        t_end: end of each analysed window [s], shape batch.
    """

    def __repr__(self):
        return compact_repr(self)

    periods: np.ndarray
    damping: np.ndarray
    names: object
    sd: np.ndarray
    sv: np.ndarray
    sa: np.ndarray
    sd_abs: np.ndarray
    t_sd: np.ndarray
    t_sv: np.ndarray
    t_sa: np.ndarray
    t_sd_abs: np.ndarray
    t_end: object

    @property
    def omega(self):
        """2π/T [rad/s], shape of ``periods``."""
        return 2 * np.pi / self.periods

    @property
    def psv(self):
        return self.omega * self.sd

    @property
    def psa(self):
        return self.omega**2 * self.sd

    def table(self):
        """Rows (dicts) of a one-motion, one-damping spectrum, for CSV output."""
        if self.sd.ndim > 1:
            raise ValueError("table() needs one motion and one damping value; index the spectrum first")
        periods = np.atleast_1d(self.periods)
        cols = {k: np.atleast_1d(getattr(self, k)) for k in
                ("sd", "sv", "sa", "psv", "psa", "sd_abs", "t_sd", "t_sa")}
        return [{"period_s": float(T), "damping": float(self.damping), "sd_m": float(cols["sd"][i]),
                 "sv_m_s": float(cols["sv"][i]), "sa_m_s2": float(cols["sa"][i]),
                 "psv_m_s": float(cols["psv"][i]), "psa_m_s2": float(cols["psa"][i]),
                 "sd_abs_m": float(cols["sd_abs"][i]), "t_sd_s": float(cols["t_sd"][i]),
                 "t_sa_s": float(cols["t_sa"][i])} for i, T in enumerate(periods)]


def response_spectrum(motion, periods, damping=0.05, *, t_end=None) -> ResponseSpectrum:
    """Exact response spectra of one motion or a batch, over periods and dampings.

    Args:
        motion: an excitation (``bd.Record``, a pulse, ``bd.Harmonic``) or a list of them.
        periods: oscillator periods T > 0 [s], scalar or 1-D.
        damping: fractions of critical damping 0 <= ζ < 1 [-], scalar or 1-D.
        t_end: end of the window [s] (default each motion's duration; required for an
            excitation without end). A later ``t_end`` adds the free vibration after the
            record (the ground then moves at its final velocity).

    Returns:
        :class:`ResponseSpectrum`, arrays of shape ``batch + damping + periods``.

    The oscillator starts at rest relative to the ground. Values are exact to rounding
    for piecewise-linear and sine pieces (the maxima are located between samples).
    """
    motions, batch = _checks.excitations(motion)
    T = _checks.array("periods", periods, "s", low=0.0, low_open=True)
    zeta = _checks.array("damping", damping, "-", low=0.0, high=1.0)
    if T.ndim > 1 or zeta.ndim > 1:
        raise ValueError(f"periods and damping must be scalars or 1-D arrays, got shapes {T.shape} and {zeta.shape}")
    omegas = 2 * np.pi / np.atleast_1d(T)
    zetas = np.atleast_1d(zeta)
    chains = []
    ends = []
    for i, m in enumerate(motions):
        end = _checks.horizon(m, t_end)
        p = m.pieces(end)
        if p.has_sine and np.any(zetas == 0):
            resonant = np.intersect1d(p.w[p.s != 0], omegas)
            if resonant.size:
                raise ValueError(f"damping = 0 at the period {2 * np.pi / resonant[0]!r} s of motion[{i}]'s "
                                 "sine: the undamped response grows without bound; use damping > 0")
        coeffs = (p.p0, p.p1, p.s, p.w, p.phi)
        vg = m.initial_velocity + np.concatenate([[0.0], np.cumsum(accel_int1(*coeffs, p.h))])
        xg = np.concatenate([[0.0], np.cumsum(accel_int2(*coeffs, p.h) + vg[:-1] * p.h)])
        chains.append((p, xg, vg))
        ends.append(end)
    starts = np.concatenate([[0], np.cumsum([c[0].h.size for c in chains])]).astype(np.int64)
    cat = [np.ascontiguousarray(np.concatenate([getattr(c[0], f) for c in chains]), dtype=float)
           for f in ("t0", "h", "p0", "p1", "s", "w", "phi")]
    xg = np.concatenate([c[1] for c in chains])
    vg = np.concatenate([c[2] for c in chains])
    best = np.zeros((len(chains), zetas.size, omegas.size, 4))
    when = np.zeros_like(best)
    from . import kernels as _kernels

    notice_numba("the response kernels", 10, _kernels.spectra)
    _kernels.spectra(*cat, xg, vg, starts, omegas, zetas, best, when)
    shape = batch + zeta.shape + T.shape
    out = [best[..., q].reshape(shape) for q in range(4)] + [when[..., q].reshape(shape) for q in range(4)]
    names = [getattr(m, "name", "") for m in motions]
    return ResponseSpectrum(T, zeta, names[0] if not batch else names, *out,
                            t_end=ends[0] if not batch else np.array(ends))
