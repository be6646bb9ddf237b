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

import numpy as np

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
    alpha, c, phi, gamma, t, m = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (
        slope_deg, cohesion_kpa, friction_deg, unit_weight_kn_m3, thickness_m, saturated_fraction)))
    _check("slope_deg", alpha, (alpha >= 0) & (alpha < 90), "must lie in [0, 90) degrees")
    _check("cohesion_kpa", c, c >= 0, "must be >= 0 kPa")
    _check("friction_deg", phi, (phi > 0) & (phi < 90), "must lie in (0, 90) degrees")
    _check("unit_weight_kn_m3", gamma, gamma > 0, "must be > 0 kN/m³")
    _check("thickness_m", t, t > 0, "must be > 0 m")
    _check("saturated_fraction", m, (m >= 0) & (m <= 1), "must lie in [0, 1]")
    nodata = np.isnan(alpha) | np.isnan(c) | np.isnan(phi) | np.isnan(gamma) | np.isnan(t) | np.isnan(m)
    flat = ~nodata & (alpha == 0)
    sloping = ~nodata & ~flat
    a = np.radians(np.where(sloping, alpha, 45.0))
    tan_phi, tan_a = np.tan(np.radians(phi)), np.tan(a)
    with np.errstate(invalid="ignore", divide="ignore"):
        fs = c / (gamma * t * np.sin(a)) + tan_phi / tan_a \
            - m * float(water_unit_weight_kn_m3) * tan_phi / (gamma * tan_a)
    fs = np.where(sloping, fs, np.where(flat, np.inf, np.nan))
    category = np.full(alpha.shape, NODATA, dtype=np.int8)
    category[sloping & (fs >= 1)] = STABLE
    category[sloping & (fs < 1)] = UNSTABLE
    category[flat] = FLAT
    ky = np.where(category == STABLE, (fs - 1.0) * np.sin(a), np.nan)
    return fs, ky, category


def count_categories(category) -> dict:
    """Number of cells of each category: name -> count (every name of :data:`CATEGORIES`)."""
    codes = np.asarray(category)
    return {name: int(np.count_nonzero(codes == code)) for code, name in CATEGORIES.items()}


def _check(name, values, ok, message):
    bad = ~(ok | np.isnan(values))
    if np.any(bad):
        raise ValueError(f"{name}={float(values[bad].flat[0])!r} {message} "
                         f"({np.count_nonzero(bad)} cell(s) out of range)")
