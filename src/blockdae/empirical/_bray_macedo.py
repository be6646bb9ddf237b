"""Bray & Macedo (2019): shear-induced slope displacement for shallow crustal earthquakes,
ordinary ground motions, from Sa(1.3 Ts), with a probability of negligible displacement.

Bray, J.D. & Macedo, J. (2019). Procedure for estimating shear-induced seismic slope
displacement for shallow crustal earthquakes. J. Geotech. Geoenviron. Eng. 145(12),
04019106. D in cm, ky and Sa in g; "negligible" is D < 0.5 cm. The paper's near-fault
(pulse) models for D100 and D50 and its general model with a PGV term are not here:
the public transcriptions of their coefficients disagree with one another (see
tests/test_empirical.py).
"""

import numpy as np

from ._common import finite, positive, result

STIFF_TS = 0.1  # [s]: below it the short-period coefficients apply
LONG_TS = 0.7  # [s]: above it the long-period P(D < 0.5 cm) applies
SIGMA_LN = 0.72


def bray_macedo_2019(ky_g, ts_s, sa_g, magnitude):
    """Bray & Macedo (2019), ordinary motions: eq. 3 (median) and eq. 2 (P(D < 0.5 cm)).

    ln D = a1 - 2.482 ln ky - 0.244 (ln ky)² + 0.344 ln ky ln Sa + 2.649 ln Sa - 0.090 (ln Sa)²
    + a2 Ts + a3 Ts² + 0.603 M, with (a1, a2, a3) = (-4.684, -9.471, 0) for Ts < 0.1 s and
    (-5.981, 3.223, -0.945) for Ts >= 0.1 s; σ_ln = 0.72.
    P(D < 0.5 cm) = 1 - Φ(-2.48 - 2.97 ln ky - 0.12 (ln ky)² - 0.72 Ts ln ky + 1.70 Ts + 2.78 ln Sa)
    for Ts <= 0.7 s, 1 - Φ(-3.42 - 4.93 ln ky - 0.30 (ln ky)² - 0.35 Ts ln ky - 0.62 Ts
    + 2.86 ln Sa) above.

    The arguments broadcast together. No range warning: the paper's range is not
    transcribed here.

    Args:
        ky_g: yield coefficient [g].
        ts_s: initial fundamental period Ts >= 0 of the sliding mass [s]; 0 is a rigid
            block, with the Ts < 0.1 s coefficients, as OpenSRA has it after the authors'
            spreadsheet.
        sa_g: 5 %-damped spectral acceleration (RotD50) at 1.3 Ts [g] (PGA for Ts = 0).
        magnitude: moment magnitude M [-].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is P(D < 0.5 cm)).
    """
    ky, sa = positive("ky_g", ky_g, "g"), positive("sa_g", sa_g, "g")
    ts, m = finite("ts_s", ts_s, "s", minimum=0.0), finite("magnitude", magnitude, "-")
    lk, ls = np.log(ky), np.log(sa)
    stiff = ts < STIFF_TS
    a1, a2, a3 = (np.where(stiff, short, long)
                  for short, long in ((-4.684, -5.981), (-9.471, 3.223), (0.0, -0.945)))
    ln_d = (a1 - 2.482 * lk - 0.244 * lk**2 + 0.344 * lk * ls + 2.649 * ls - 0.090 * ls**2
            + a2 * ts + a3 * ts**2 + 0.603 * m)
    short_z = -2.48 - 2.97 * lk - 0.12 * lk**2 - 0.72 * ts * lk + 1.70 * ts + 2.78 * ls
    long_z = -3.42 - 4.93 * lk - 0.30 * lk**2 - 0.35 * ts * lk - 0.62 * ts + 2.86 * ls
    from scipy.stats import norm  # on use: importing scipy.stats takes about a second

    p0 = norm.sf(np.where(ts <= LONG_TS, short_z, long_z))
    return result(np.exp(ln_d), SIGMA_LN, p0)
