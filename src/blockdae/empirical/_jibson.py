"""Jibson (2007): rigid-block Newmark displacement from ky/PGA, magnitude and Arias intensity.

Jibson, R.W. (2007). Regression models for estimating coseismic landslide displacement.
Engineering Geology 91(2-4), 209-218. D in cm, ky and PGA in g, Ia in m/s, log = log10;
the paper's σ are of log10 D (here × ln 10: σ of ln D). Its data: 2270 records of 30
earthquakes; the magnitude model is for M 5.3-7.6.
"""

import numpy as np

from ._common import LN10, finite, positive, ratio_model, result, warn_outside

MAGNITUDES = (5.3, 7.6)


def jibson_2007(ky_g, pga_g):
    """Jibson (2007) eq. 6: log D = 0.215 + log[(1 - ky/PGA)^2.341 (ky/PGA)^-1.438], σ_log = 0.510.

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        pga_g: peak ground acceleration [g].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 1 where ky >= PGA).
    """
    ky, pga = positive("ky_g", ky_g, "g"), positive("pga_g", pga_g, "g")
    _, median, p0 = ratio_model(ky, pga,
                                lambda r: LN10 * 0.215 + 2.341 * np.log1p(-r) - 1.438 * np.log(r))
    return result(median, 0.510 * LN10, p0)


def jibson_2007_m(ky_g, pga_g, magnitude):
    """Jibson (2007) eq. 7: log D = -2.710 + log[(1 - ky/PGA)^2.335 (ky/PGA)^-1.478] + 0.424 M,
    σ_log = 0.454; M outside 5.3-7.6: :class:`ValidityWarning`.

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        pga_g: peak ground acceleration [g].
        magnitude: moment magnitude M [-].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 1 where ky >= PGA).
    """
    ky, pga = positive("ky_g", ky_g, "g"), positive("pga_g", pga_g, "g")
    m = finite("magnitude", magnitude, "-")
    warn_outside("jibson_2007_m", "magnitude", m, *MAGNITUDES, "")
    _, median, p0 = ratio_model(ky, pga, lambda r: LN10 * (-2.710 + 0.424 * m)
                                + 2.335 * np.log1p(-r) - 1.478 * np.log(r))
    return result(median, 0.454 * LN10, p0)


def jibson_2007_arias(ky_g, arias_m_s):
    """Jibson (2007) eq. 9: log D = 2.401 log Ia - 3.481 log ky - 3.230, σ_log = 0.656.

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        arias_m_s: Arias intensity Ia [m/s].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 0, as the model has no PGA).
    """
    ky, ia = positive("ky_g", ky_g, "g"), positive("arias_m_s", arias_m_s, "m/s")
    ln_d = LN10 * (2.401 * np.log10(ia) - 3.481 * np.log10(ky) - 3.230)
    return result(np.exp(ln_d), 0.656 * LN10, 0.0)


def jibson_2007_arias_pga(ky_g, pga_g, arias_m_s):
    """Jibson (2007) eq. 10: log D = 0.561 log Ia - 3.833 log(ky/PGA) - 1.474, σ_log = 0.616.

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        pga_g: peak ground acceleration [g].
        arias_m_s: Arias intensity Ia [m/s].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 1 where ky >= PGA).
    """
    ky, pga = positive("ky_g", ky_g, "g"), positive("pga_g", pga_g, "g")
    ia = positive("arias_m_s", arias_m_s, "m/s")
    _, median, p0 = ratio_model(ky, pga,
                                lambda r: LN10 * (0.561 * np.log10(ia) - 3.833 * np.log10(r) - 1.474))
    return result(median, 0.616 * LN10, p0)
