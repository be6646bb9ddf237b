"""The infinite slope of Jibson et al. (2000): factor of safety and yield acceleration per cell.

    FS = c' / (γ t sin α) + tan φ' / tan α - m γ_w tan φ' / (γ tan α),   ky = (FS - 1) sin α [g]

c' effective cohesion [kPa], φ' effective friction angle [deg], γ unit weight of the
material [kN/m³], t thickness of the failure surface normal to the slope [m], m the
saturated fraction of t [-], γ_w the unit weight of water [kN/m³], α the slope [deg]
(Jibson, Harp & Michael 2000, eqs. 2-3). Every cell falls in one category
(:data:`CATEGORIES`), kept explicit in every output: a cell with FS < 1 is statically
unstable (no yield acceleration: it slides without shaking), a flat cell (α = 0) cannot
slide downslope, a cell with no elevation or strength is nodata.
"""

import numba
import numpy as np
from numba.extending import register_jitable

from ..units import STANDARD_GRAVITY

#: unit weight of water [kN/m³]: 1000 kg/m³ under standard gravity
WATER_UNIT_WEIGHT = STANDARD_GRAVITY

NODATA, STABLE, UNSTABLE, FLAT = 0, 1, 2, 3
#: category code -> name, as stored in a map's ``category`` variable
CATEGORIES = {NODATA: "nodata", STABLE: "stable", UNSTABLE: "statically_unstable", FLAT: "flat"}


def infinite_slope(slope_deg, cohesion_kpa, friction_deg, unit_weight_kn_m3, thickness_m, saturated_fraction,
                   water_unit_weight_kn_m3=WATER_UNIT_WEIGHT):
    """FS [-], ky [g] and the category of each cell of an infinite slope (Jibson et al. 2000).

    Args (numpy arrays or numbers, broadcast together; NaN marks a nodata cell):
        slope_deg: slope α [deg], in [0, 90).
        cohesion_kpa: effective cohesion c' [kPa], >= 0.
        friction_deg: effective friction angle φ' [deg], in (0, 90).
        unit_weight_kn_m3: unit weight γ [kN/m³], > 0.
        thickness_m: failure-surface thickness t [m], > 0.
        saturated_fraction: m [-], in [0, 1].
        water_unit_weight_kn_m3: γ_w [kN/m³] (1000 kg/m³ under standard gravity by default).

    Returns:
        (fs, ky, category): FS [-] (+inf on a flat cell, NaN on nodata); ky [g] (NaN
        where the cell is not :data:`STABLE`); category: int8 codes of :data:`CATEGORIES`.
    """
    given = [np.asarray(v, dtype=float) for v in (slope_deg, cohesion_kpa, friction_deg, unit_weight_kn_m3,
                                                   thickness_m, saturated_fraction)]
    shape = np.broadcast_shapes(*(v.shape for v in given))
    alpha, c, phi, gamma, t, m = (np.broadcast_to(v, shape) for v in given)
    fs, ky = np.empty(alpha.shape), np.empty(alpha.shape)
    category = np.empty(alpha.shape, dtype=np.int8)
    rows = lambda v: v.reshape(-1, v.shape[-1] if v.ndim else 1)  # a view of a broadcast 2-D input: no copy
    bad = _cells(*(rows(v) for v in (alpha, c, phi, gamma, t, m)), float(water_unit_weight_kn_m3),
                 rows(fs), rows(ky), rows(category))
    if bad >= 0:
        name, values, ok, message = _RANGES[bad](alpha, c, phi, gamma, t, m)
        _check(name, values, ok, message)
    return fs, ky, category


#: the check of each input (its index in _cells' flag): (name, values, in range, message)
_RANGES = (lambda a, c, p, g, t, m: ("slope_deg", a, (a >= 0) & (a < 90), "must lie in [0, 90) degrees"),
           lambda a, c, p, g, t, m: ("cohesion_kpa", c, c >= 0, "must be >= 0 kPa"),
           lambda a, c, p, g, t, m: ("friction_deg", p, (p > 0) & (p < 90), "must lie in (0, 90) degrees"),
           lambda a, c, p, g, t, m: ("unit_weight_kn_m3", g, g > 0, "must be > 0 kN/m³"),
           lambda a, c, p, g, t, m: ("thickness_m", t, t > 0, "must be > 0 m"),
           lambda a, c, p, g, t, m: ("saturated_fraction", m, (m >= 0) & (m <= 1), "must lie in [0, 1]"))


@register_jitable
def factor_of_safety(sin_a, tan_a, tan_phi, cohesion_kpa, unit_weight_kn_m3, thickness_m, saturated_fraction,
                     water_unit_weight_kn_m3):
    """(FS [-], (FS - 1) sin α [g]) of the infinite slope (Jibson et al. 2000, eqs. 2-3)
    from sin α, tan α, tan φ' and c' [kPa], γ [kN/m³], t [m], m [-], γ_w [kN/m³]: plain
    arithmetic on numbers or arrays (numpy, JAX, inside numba), so that every caller,
    and JAX's derivatives, use this one formula. The second value is ky only where FS >= 1."""
    fs = (cohesion_kpa / (unit_weight_kn_m3 * thickness_m * sin_a) + tan_phi / tan_a
          - saturated_fraction * water_unit_weight_kn_m3 * tan_phi / (unit_weight_kn_m3 * tan_a))
    return fs, (fs - 1.0) * sin_a


@numba.njit(cache=True, nogil=True)
def _cells(alpha, c, phi, gamma, t, m, gamma_w, fs, ky, category):
    """FS, ky and category of every cell (2-D arrays, written in place); returns the index
    in :data:`_RANGES` of the first input out of range (the caller raises), or -1."""
    last_phi, tan_phi = np.nan, np.nan
    for i in np.ndindex(alpha.shape):
        if phi[i] != last_phi:  # a zone's cells share φ': its tangent is computed once
            last_phi, tan_phi = phi[i], friction_tangent(phi[i])
        fs[i], ky[i], category[i], bad = cell(alpha[i], c[i], phi[i], tan_phi, gamma[i], t[i], m[i], gamma_w)
        if bad >= 0:
            return bad
    return -1


@numba.njit(cache=True, nogil=True, inline="always")
def friction_tangent(p):
    """tan φ' of the friction angle ``p`` [deg] (NaN where p is NaN)."""
    return np.tan(np.radians(p))


@numba.njit(cache=True, nogil=True, inline="always")
def cell(a, c, p, tan_phi, gamma, t, m, gamma_w):
    """(FS [-], ky [g], category, the index in :data:`_RANGES` of an input out of range or -1) of one cell;
    ``tan_phi``: :func:`friction_tangent` of ``p`` (computed once by the caller for the cells that share p)."""
    if a != a or c != c or p != p or gamma != gamma or t != t or m != m:
        return np.nan, np.nan, NODATA, -1
    if not (0.0 <= a < 90.0):
        return np.nan, np.nan, NODATA, 0
    if not c >= 0.0:
        return np.nan, np.nan, NODATA, 1
    if not (0.0 < p < 90.0):
        return np.nan, np.nan, NODATA, 2
    if not gamma > 0.0:
        return np.nan, np.nan, NODATA, 3
    if not t > 0.0:
        return np.nan, np.nan, NODATA, 4
    if not (0.0 <= m <= 1.0):
        return np.nan, np.nan, NODATA, 5
    if a == 0.0:
        return np.inf, np.nan, FLAT, -1
    ar = np.radians(a)
    f, k = factor_of_safety(np.sin(ar), np.tan(ar), tan_phi, c, gamma, t, m, gamma_w)
    if f >= 1.0:
        return f, k, STABLE, -1
    return f, np.nan, UNSTABLE, -1


def count_categories(category) -> dict:
    """Number of cells of each category: name -> count (every name of :data:`CATEGORIES`)."""
    codes = np.asarray(category)
    return {name: int(np.count_nonzero(codes == code)) for code, name in CATEGORIES.items()}


def _check(name, values, ok, message):
    bad = ~(ok | np.isnan(values))
    if np.any(bad):
        raise ValueError(f"{name}={float(values[bad].flat[0])!r} {message} "
                         f"({np.count_nonzero(bad)} cell(s) out of range)")
