"""Bray & Travasarou (2007): deviatoric slope displacement from Sa(1.5 Ts), with a
probability of negligible displacement.

Bray, J.D. & Travasarou, T. (2007). Simplified procedure for estimating earthquake-induced
deviatoric slope displacements. J. Geotech. Geoenviron. Eng. 133(4), 381-392. D in cm,
ky and Sa in g. Its range (the authors' spreadsheet, note 6): ky 0.01-0.5 g, Ts 0-2 s,
Sa 0.002-2.7 g, M 4.5-9; a slope with Ts < 0.05 s is rigid (Ts = 0, note 7).
"""

import numpy as np

from ._common import finite, positive, result, warn_outside

RANGES = {"ky_g": (0.01, 0.5, "g"), "ts_s": (0.0, 2.0, "s"), "sa_g": (0.002, 2.7, "g"), "magnitude": (4.5, 9.0, "")}
RIGID_TS = 0.05  # [s]


def bray_travasarou_2007(ky_g, ts_s, sa_g, magnitude):
    """Bray & Travasarou (2007), eq. 5 and eq. 3.

    ln D = a1 - 2.83 ln ky - 0.333 (ln ky)² + 0.566 ln ky ln Sa + 3.04 ln Sa - 0.244 (ln Sa)²
    + 1.50 Ts + 0.278 (M - 7), a1 = -1.10 (-0.22 and Ts = 0 for Ts < 0.05 s), σ_ln = 0.66;
    P(D < 1 cm) = 1 - Φ(-1.76 - 3.22 ln ky - 0.484 Ts ln ky + 3.52 ln Sa).

    The arguments broadcast together.

    Args:
        ky_g: yield coefficient [g].
        ts_s: initial fundamental period Ts >= 0 of the sliding mass [s].
        sa_g: 5 %-damped spectral acceleration at 1.5 Ts [g] (PGA for a rigid mass).
        magnitude: moment magnitude M [-].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is P(D < 1 cm)).
    """
    ky, sa = positive("ky_g", ky_g, "g"), positive("sa_g", sa_g, "g")
    ts, m = finite("ts_s", ts_s, "s", minimum=0.0), finite("magnitude", magnitude, "-")
    for name, x in (("ky_g", ky), ("ts_s", ts), ("sa_g", sa), ("magnitude", m)):
        warn_outside("bray_travasarou_2007", name, x, *RANGES[name])
    rigid = ts < RIGID_TS
    ts = np.where(rigid, 0.0, ts)
    lk, ls = np.log(ky), np.log(sa)
    ln_d = (np.where(rigid, -0.22, -1.10) - 2.83 * lk - 0.333 * lk**2 + 0.566 * lk * ls + 3.04 * ls
            - 0.244 * ls**2 + 1.50 * ts + 0.278 * (m - 7.0))
    from scipy.stats import norm  # on use: importing scipy.stats takes about a second

    p0 = norm.sf(-1.76 - 3.22 * lk - 0.484 * ts * lk + 3.52 * ls)
    return result(np.exp(ln_d), 0.66, p0)
