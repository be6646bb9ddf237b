"""Saygili & Rathje (2008) and Rathje & Saygili (2009): rigid-block displacement as a
polynomial in ky/PGA.

    ln D = a1 + a2 r + a3 r² + a4 r³ + a5 r⁴ + a6 ln PGA + (a term in PGV, Ia or M),  r = ky/PGA

D in cm, ky and PGA in g, PGV in cm/s, Ia in m/s. Saygili, G. & Rathje, E.M. (2008).
Empirical predictive models for earthquake-induced sliding displacements of slopes. J.
Geotech. Geoenviron. Eng. 134(6), 790-803 (eq. 6 with the coefficients of its tables; the
same in Saygili's 2008 dissertation, Tables 4.2-4.4). Rathje, E.M. & Saygili, G. (2009).
Probabilistic assessment of earthquake-induced sliding displacements of natural slopes.
Bull. NZ Soc. Earthq. Eng. 42(1), 18-27 (eqs. 8-9). Fitted for ky = 0.05-0.30 g.
"""

import numpy as np

from ._common import finite, positive, ratio_model, result, warn_outside

KY_RANGE = (0.05, 0.30)  # [g]


def _polynomial(a, r):
    return a[0] + a[1] * r + a[2] * r**2 + a[3] * r**3 + a[4] * r**4


def _checked(model, ky_g, pga_g):
    ky, pga = positive("ky_g", ky_g, "g"), positive("pga_g", pga_g, "g")
    warn_outside(model, "ky_g", ky, *KY_RANGE, "g")
    return ky, pga


def saygili_rathje_2008_pga(ky_g, pga_g):
    """Saygili & Rathje (2008), the scalar PGA model: a = (5.52, -4.43, -20.39, 42.61,
    -28.74), a6 = 0.72; σ_ln = 1.13.

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        pga_g: peak ground acceleration [g].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 1 where ky >= PGA).
    """
    ky, pga = _checked("saygili_rathje_2008_pga", ky_g, pga_g)
    a = (5.52, -4.43, -20.39, 42.61, -28.74)
    _, median, p0 = ratio_model(ky, pga, lambda r: _polynomial(a, r) + 0.72 * np.log(pga))
    return result(median, 1.13, p0)


def saygili_rathje_2008_pga_pgv(ky_g, pga_g, pgv_cm_s):
    """Saygili & Rathje (2008), the PGA-PGV vector model: a = (-1.56, -4.58, -20.84, 44.75,
    -30.50), a6 = -0.64, + 1.55 ln PGV; σ_ln = 0.41 + 0.52 r.

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        pga_g: peak ground acceleration [g].
        pgv_cm_s: peak ground velocity [cm/s].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 1 where ky >= PGA).
    """
    ky, pga = _checked("saygili_rathje_2008_pga_pgv", ky_g, pga_g)
    pgv = positive("pgv_cm_s", pgv_cm_s, "cm/s")
    a = (-1.56, -4.58, -20.84, 44.75, -30.50)
    r, median, p0 = ratio_model(ky, pga, lambda r: _polynomial(a, r) - 0.64 * np.log(pga) + 1.55 * np.log(pgv))
    return result(median, 0.41 + 0.52 * r, p0)


def saygili_rathje_2008_pga_arias(ky_g, pga_g, arias_m_s):
    """Saygili & Rathje (2008), the PGA-Ia vector model: a = (2.39, -5.24, -18.78, 42.01,
    -29.15), a6 = -1.56, + 1.38 ln Ia; σ_ln = 0.46 + 0.56 r.

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        pga_g: peak ground acceleration [g].
        arias_m_s: Arias intensity Ia [m/s].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 1 where ky >= PGA).
    """
    ky, pga = _checked("saygili_rathje_2008_pga_arias", ky_g, pga_g)
    ia = positive("arias_m_s", arias_m_s, "m/s")
    a = (2.39, -5.24, -18.78, 42.01, -29.15)
    r, median, p0 = ratio_model(ky, pga, lambda r: _polynomial(a, r) - 1.56 * np.log(pga) + 1.38 * np.log(ia))
    return result(median, 0.46 + 0.56 * r, p0)


def rathje_saygili_2009_pga_m(ky_g, pga_g, magnitude):
    """Rathje & Saygili (2009) eq. 8, the PGA-M model: a = (4.89, -4.85, -19.64, 42.49,
    -29.06), a6 = 0.72, + 0.89 (M - 6); eq. 9: σ_ln = 0.73 + 0.789 r - 0.539 r².

    The arguments broadcast together.

    Args:
        ky_g: yield acceleration [g].
        pga_g: peak ground acceleration [g].
        magnitude: moment magnitude M [-].

    Returns:
        An :class:`EmpiricalDisplacement` (median [m], σ_ln; p_negligible is 1 where ky >= PGA).
    """
    ky, pga = _checked("rathje_saygili_2009_pga_m", ky_g, pga_g)
    m = finite("magnitude", magnitude, "-")
    a = (4.89, -4.85, -19.64, 42.49, -29.06)
    r, median, p0 = ratio_model(ky, pga, lambda r: _polynomial(a, r) + 0.72 * np.log(pga) + 0.89 * (m - 6.0))
    return result(median, 0.73 + 0.789 * r - 0.539 * r**2, p0)
