"""The displacement map: the infinite slope's FS and ky, each record's rigid-block D scaled
to every cell's PGA, its statistics over the suite and the regressions, as one xarray
Dataset on the terrain's grid; lazy and chunk by chunk where the terrain is Dask-backed."""

import functools
import hashlib
import pathlib
import warnings

import numba
import numpy as np

from . import _infinite_slope, _tables
from ._infinite_slope import CATEGORIES, FLAT, NODATA, STABLE, WATER_UNIT_WEIGHT, cell, friction_tangent, infinite_slope
from ._pairs import ProjectedPairs, RecordPair
from ._tables import DisplacementTables, cell_displacements, median_of, statistics_of
from ._terrain import _crs, _floats, _with_crs, slope_and_azimuth

#: the largest PGA accepted [g]: above it the values are likely in m/s² or %g
MAX_PGA_G = 2.0
_STRENGTH = ("cohesion_kpa", "friction_deg", "unit_weight_kn_m3")
_REGRESSIONS = {"jibson_2007_median_m": "Jibson (2007) eq. 6, median",
                "saygili_rathje_2008_median_m": "Saygili & Rathje (2008) PGA model, median (fitted for ky 0.05-0.30 g)"}


def strength_from_zones(zones, table):
    """Strength per cell from a zone raster and a table of zones.

    Args:
        zones: an xarray DataArray of zone codes (integers; NaN: nodata).
        table: a pandas DataFrame (or a mapping of columns) with ``zone`` and
            ``cohesion_kpa`` [kPa], ``friction_deg`` [deg], ``unit_weight_kn_m3`` [kN/m³].

    Returns: an xarray Dataset of the three fields on the zones' grid (NaN where a cell has
    no zone); a ValueError names a zone of the raster missing from the table.
    """
    import pandas as pd
    import xarray as xr

    frame = pd.DataFrame(table)
    missing = [c for c in ("zone",) + _STRENGTH if c not in frame.columns]
    if missing:
        raise ValueError(f"the zone table lacks the column(s) {missing}; it needs zone, cohesion_kpa [kPa], "
                         "friction_deg [deg], unit_weight_kn_m3 [kN/m³]")
    codes = frame["zone"].to_numpy(dtype=float)
    if np.unique(codes).size != codes.size:
        raise ValueError(f"the zone table repeats a zone: {sorted(codes)}")
    order = np.argsort(codes)
    codes = codes[order]
    columns = np.array([frame[name].to_numpy(dtype=float)[order] for name in _STRENGTH])

    def lookup(z):
        z = _floats(z)
        out = tuple(np.empty(z.shape) for _ in _STRENGTH)  # apart: a block's arrays stay under malloc's mmap size
        unknown = _zone_lookup(z.reshape(-1), codes, columns, tuple(field.reshape(-1) for field in out))
        if unknown == unknown:
            raise ValueError(f"zone {unknown:g} of the raster is not in the zone table (zones {codes.tolist()})")
        return out

    units = {"cohesion_kpa": "kPa", "friction_deg": "deg", "unit_weight_kn_m3": "kN/m3"}
    looked_up = xr.apply_ufunc(lookup, zones, dask="parallelized", output_core_dims=[[]] * len(_STRENGTH),
                               output_dtypes=[float] * len(_STRENGTH))
    fields = {name: field.assign_attrs(units=units[name]) for name, field in zip(_STRENGTH, looked_up)}
    return _with_crs(xr.Dataset(fields), zones)


@numba.njit(cache=True, nogil=True)
def _zone_lookup(zones, codes, values, out):
    """``values[k, j]`` of each cell's zone ``codes[j]`` among the sorted ``codes`` into ``out[k][cell]``
    (NaN where the zone is NaN; zones float32 or float64, compared as float64); returns the first zone
    not among the codes, or NaN."""
    for i in range(zones.size):
        z = float(zones[i])
        if z != z:
            for k in range(values.shape[0]):
                out[k][i] = np.nan
            continue
        lo, hi = 0, codes.size  # bisection: the first code >= z
        while lo < hi:
            mid = (lo + hi) // 2
            if codes[mid] < z:
                lo = mid + 1
            else:
                hi = mid
        if lo == codes.size or codes[lo] != z:
            return z
        for k in range(values.shape[0]):
            out[k][i] = values[k, lo]
    return np.nan


def displacement_map(terrain, strength, records, pga_g, *, thickness_m, saturated_fraction=0.0,
                     thresholds_m=(0.05,), method: str | None = None, polarity: str = "both", per_record: bool = False,
                     regressions: bool = True, tables: DisplacementTables | None = None, resample: bool = False,
                     rtol: float = 1e-6, atol_m: float = 1e-6):
    """Newmark displacement of every cell of a terrain over a record suite.

    Args:
        terrain: a DEM (DataArray of elevations [m], projected CRS, metre cells) or a
            Dataset with ``slope_deg`` (e.g. from :func:`slope_and_azimuth`).
        strength: a Dataset or mapping with ``cohesion_kpa`` [kPa], ``friction_deg`` [deg],
            ``unit_weight_kn_m3`` [kN/m³], each a number or a DataArray on the terrain's
            grid (see :func:`strength_from_zones`).
        records: the suite (a Record, a sequence or mapping of them, a RecordSet), each
            scaled to every cell's PGA; unused where ``tables`` is given. Or the two
            horizontal components of records, projected on each cell's dip azimuth: a
            :class:`RecordPair` or a sequence of them (each pair scaled so that its larger
            component's peak is the cell's PGA; the terrain needs ``dip_azimuth_deg``).
        pga_g: peak ground acceleration [g]: a number or a DataArray on the terrain's grid
            (for record pairs, the peak of the larger horizontal component).
        thickness_m: failure-surface thickness t [m]; saturated_fraction: m [-]
            (numbers or DataArrays on the grid).
        thresholds_m: displacements d [m] of the exceedance maps P(D > d).
        method: "table" (the default for records: each record's tabulated D(ky/PGA),
            within the bound max(rtol · D, atol_m), see :class:`DisplacementTables`) or
            "exact" (the exact engine for every cell; the only method, and the default, for
            record pairs: each cell's projected record is its own).
        polarity: "both" (each record as given and inverted, pooled in the statistics),
            "normal" or "inverse".
        per_record: also D of every (record, polarity) [m] (a ``member`` dimension).
        regressions: also the medians of Jibson (2007) and Saygili & Rathje (2008) [m].
        tables: tables built before (:meth:`DisplacementTables.build`), reused.
        resample: a raster on another grid is reprojected onto the terrain's grid
            (rioxarray's ``reproject_match``, bilinear); False: refused, naming both grids.

    Returns:
        An xarray Dataset on the terrain's grid and CRS: slope_deg, factor_of_safety,
        ky_g, category (int8: 0 nodata, 1 stable, 2 statically unstable, 3 flat;
        ``flag_values``/``flag_meanings``), pga_g, median_displacement_m, exceedance
        (threshold_m, y, x) [-], displacement_m (member, y, x) where asked, and the
        regression medians; units in each variable's attrs. D and P are NaN on nodata
        (a cell without PGA is nodata too) and statically unstable cells; 0 on flat ones.
        Dask-backed where the inputs are (nothing computed until written or ``.compute()``).
    """
    import xarray as xr

    pairs = isinstance(records, RecordPair) or (isinstance(records, (list, tuple)) and len(records) > 0
                                                 and all(isinstance(r, RecordPair) for r in records))
    method = ("exact" if pairs else "table") if method is None else method
    if method not in ("table", "exact"):
        raise ValueError(f"method must be 'table' or 'exact', got {method!r}")
    if pairs and (method != "exact" or tables is not None):
        raise ValueError("record pairs run on the exact engine (method='exact', no tables): each cell's motion "
                         "projected on its dip azimuth is a record of its own")
    thresholds = np.asarray(thresholds_m, dtype=float).reshape(-1)
    if np.any(~np.isfinite(thresholds) | (thresholds <= 0)):
        raise ValueError(f"thresholds_m={thresholds.tolist()} must be positive displacements [m]")
    slopes = terrain if isinstance(terrain, xr.Dataset) else slope_and_azimuth(terrain)
    grid = slopes["slope_deg"]
    fields = {name: _on_grid(name, _field(strength, name), grid, resample) for name in _STRENGTH}
    fields.update(thickness_m=_on_grid("thickness_m", thickness_m, grid, resample),
                  saturated_fraction=_on_grid("saturated_fraction", saturated_fraction, grid, resample),
                  pga_g=_on_grid("pga_g", pga_g, grid, resample))
    _check_pga(fields["pga_g"])
    if pairs and "dip_azimuth_deg" not in slopes:
        raise ValueError("record pairs are projected on each cell's dip azimuth: give a DEM, or a terrain Dataset "
                         "with dip_azimuth_deg [deg clockwise from north]")
    azimuth = slopes["dip_azimuth_deg"] if pairs else np.nan
    if pairs:
        tables = ProjectedPairs(records, polarity)
    elif tables is None:
        tables = DisplacementTables.build(records, polarity, rtol=rtol, atol_m=atol_m / MAX_PGA_G)
    names = _quantities(tables, thresholds, per_record, regressions)
    order = ("cohesion_kpa", "friction_deg", "unit_weight_kn_m3", "thickness_m", "saturated_fraction", "pga_g")
    dtypes = [np.int8 if name == "category" else float for name in names]
    outputs = xr.apply_ufunc(
        _cells, grid, *(fields[k] for k in order), azimuth, output_core_dims=[[]] * len(names), dask="parallelized",
        kwargs=dict(tables=tables, thresholds=thresholds, method=method, per_record=per_record,
                    regressions=regressions), output_dtypes=dtypes)
    return _dataset(outputs, names, slopes, fields["pga_g"], tables, thresholds, method, per_record, regressions)


def _field(strength, name):
    try:
        return strength[name]
    except (KeyError, TypeError):
        raise ValueError(f"strength lacks {name!r}: it needs cohesion_kpa [kPa], friction_deg [deg], "
                         "unit_weight_kn_m3 [kN/m³]") from None


def _on_grid(name, value, grid, resample):
    """``value`` as a number or a DataArray on ``grid``'s cells (reprojected where asked)."""
    import xarray as xr

    if not isinstance(value, xr.DataArray):
        return float(value)
    if set(value.dims) == set(grid.dims):
        value = value.transpose(*grid.dims)
    same = value.dims == grid.dims and all(value.sizes[d] == grid.sizes[d] for d in grid.dims) and all(
        np.allclose(value[d].values, grid[d].values, rtol=0, atol=1e-6 * abs(float(grid[d][1] - grid[d][0])))
        for d in grid.dims)
    crs, grid_crs = _crs(value), _crs(grid)
    same_crs = crs is None or grid_crs is None or crs == grid_crs
    if same and same_crs:
        value = value.assign_coords({d: grid[d] for d in grid.dims})
        return value.chunk(dict(zip(grid.dims, grid.chunks))) if grid.chunks and not value.chunks else value
    if resample:
        return value.rio.reproject_match(grid, resampling=_bilinear())
    raise ValueError(f"{name} is on another grid than the terrain ({_describe(value)} against {_describe(grid)}); "
                     "give it on the terrain's grid or pass resample=True")


def _describe(array):
    crs = _crs(array)
    x, y = array["x"].values, array["y"].values
    return (f"{array.sizes['y']} x {array.sizes['x']} cells, x {x[0]:g}..{x[-1]:g}, y {y[0]:g}..{y[-1]:g}, "
            f"CRS {crs.to_string() if crs is not None else 'none'}")


def _bilinear():
    from rasterio.enums import Resampling

    return Resampling.bilinear


def _check_pga(pga):
    import xarray as xr

    if isinstance(pga, xr.DataArray):
        return  # checked chunk by chunk in _cells
    _check_pga_values(np.asarray(pga))


def _check_pga_values(pga):
    bad = ~np.isnan(pga) & ~((pga >= 0) & (pga <= MAX_PGA_G))
    if np.any(bad):
        raise ValueError(f"pga_g={float(pga[bad].flat[0])!r} must lie in [0, {MAX_PGA_G:g}] g (a value above "
                         f"{MAX_PGA_G:g} is likely in m/s² or %g: convert it to g)")


def _quantities(tables, thresholds, per_record, regressions):
    names = ["factor_of_safety", "ky_g", "category", "median_displacement_m"]
    names += [("exceedance", d) for d in thresholds]
    if per_record:
        names += [("displacement_m", k) for k in range(len(tables.members))]
    if regressions:
        names += list(_REGRESSIONS)
    return names


def _cells(slope, cohesion, friction, unit_weight, thickness, saturated, pga, azimuth, *, tables, thresholds, method,
           per_record, regressions):
    """Every quantity of :func:`_quantities` at each cell of one block: a tuple of arrays shaped as the block
    (``azimuth``: the dip azimuth [deg], used by record pairs)."""
    inputs = (slope, cohesion, friction, unit_weight, thickness, saturated, pga)
    if isinstance(tables, DisplacementTables) and method == "table":
        fs, ky, category, median, exceed = _fused(inputs, tables, thresholds)
        shape = category.shape
        if per_record or regressions:
            flat, pga = (category == FLAT).ravel(), np.broadcast_to(np.asarray(pga, dtype=float), shape).ravel()
            ky_stable = np.where(category == STABLE, ky, np.nan).ravel()
        d = tables.displacement(ky_stable, pga) if per_record else None
    else:
        pga = np.asarray(pga, dtype=float)
        _check_pga_values(pga)
        fs, ky, category = infinite_slope(*inputs[:-1])
        shape = category.shape
        pga = np.broadcast_to(pga, shape)
        category[np.isnan(pga)] = NODATA  # no ground motion there: no displacement
        pga = pga.ravel()
        flat = (category == FLAT).ravel()
        ky_stable = np.where(category == STABLE, ky, np.nan).ravel()
        if isinstance(tables, ProjectedPairs):
            d = tables.exact(ky_stable, pga, np.broadcast_to(azimuth, shape).ravel())
            median, exceed = statistics_of(d, thresholds)
        else:
            median, exceed = tables.statistics(ky_stable, pga, thresholds, method)
            d = tables.displacement(ky_stable, pga, method) if per_record else None
        median[flat], exceed[:, flat] = 0.0, 0.0
    out = [fs, ky, category, median.reshape(shape), *(p.reshape(shape) for p in exceed)]
    if per_record:
        d[:, flat] = 0.0
        out += [member.reshape(shape) for member in d]
    if regressions:
        out += [r.reshape(shape) for r in _regressions(ky_stable, pga, flat).T]
    return tuple(out)


def _fused(inputs, tables, thresholds):
    """(FS [-], ky [g], category, median D [m], P(D > d) [-]) of one block in one compiled pass per cell:
    the infinite slope, every member's table and the statistics over the suite; the few cells with
    ky/PGA < r_min then run on the exact engine."""
    shape = np.broadcast_shapes(*(np.shape(v) for v in inputs))
    if len(shape) != 2:
        raise ValueError(f"a map's block is 2-D (y, x), got the shape {shape}")
    fields = [np.broadcast_to(_floats(v), shape) for v in inputs]
    fs, ky, median = np.empty(shape), np.empty(shape), np.empty(shape)
    category = np.empty(shape, dtype=np.int8)
    exceed = np.empty((thresholds.size,) + shape)
    low = np.empty(fs.size, dtype=np.int64)
    bad, n_low = _map_kernel()(*fields, WATER_UNIT_WEIGHT, *tables._lookup(), thresholds, fs, ky, category, median,
                             exceed, low)
    if bad >= 0:  # one of them raises, naming the field and the value
        _check_pga_values(fields[6])
        infinite_slope(*fields[:-1])
    if n_low:
        cells = low[:n_low]
        rows, columns = np.unravel_index(cells, shape)
        d = tables.exact(ky[rows, columns], fields[6][rows, columns])
        median[rows, columns], exceed[:, rows, columns] = statistics_of(d, thresholds)
    return fs, ky, category, median, exceed


@functools.cache
def _map_kernel():
    """The compiled pass over a block's cells (compiled on first use or loaded from numba's cache,
    keyed also by the sources of the modules whose functions it inlines, which numba would not check)."""
    fingerprint = hashlib.sha256(b"".join(pathlib.Path(m.__file__).read_bytes()
                                          for m in (_infinite_slope, _tables))).hexdigest()

    def kernel(slope, cohesion, friction, unit_weight, thickness, saturated, pga, gamma_w, pieces, index, per_log,
               tops, r_min, thresholds, fs, ky, category, median, exceed, low):
        """Every cell of a block (2-D arrays of float32 or float64, each value taken as float64;
        outputs written in place): FS, ky and category, then for a stable cell each member's D
        from its table, the median and the exceedance counts (NaN on nodata and statically
        unstable cells, 0 on flat ones). Returns (the index of an input out of range, 6 for the
        PGA, or -1; the number of cells with ky/PGA < r_min, listed by flat index in ``low``:
        their D is left to the exact engine)."""
        fingerprint  # noqa: B018 -- numba keys its disk cache by the closure's contents
        n = pieces.shape[0]
        buffer, values, order = np.empty(n), np.empty(n), np.arange(n)
        n_low = 0
        columns = slope.shape[1]
        top = tops.max()  # ky/PGA at or above it: D = 0 for every member
        last_phi, tan_phi = np.nan, np.nan
        for i in range(slope.shape[0]):
            for j in range(columns):
                p, phi = float(pga[i, j]), float(friction[i, j])
                if not (p != p or 0.0 <= p <= MAX_PGA_G):
                    return 6, n_low
                if phi != last_phi:  # a zone's cells share φ': its tangent is computed once
                    last_phi, tan_phi = phi, friction_tangent(phi)
                f, k, c, bad = cell(float(slope[i, j]), float(cohesion[i, j]), phi, tan_phi, float(unit_weight[i, j]),
                                    float(thickness[i, j]), float(saturated[i, j]), gamma_w)
                if bad >= 0:
                    return bad, n_low
                if p != p:
                    c = NODATA
                fs[i, j], ky[i, j], category[i, j] = f, k, c
                if c == FLAT or (c == STABLE and k >= top * p):
                    median[i, j] = 0.0
                    for t in range(thresholds.size):
                        exceed[t, i, j] = 0.0
                elif c != STABLE:
                    median[i, j] = np.nan
                    for t in range(thresholds.size):
                        exceed[t, i, j] = np.nan
                elif k < r_min * p:
                    low[n_low] = i * columns + j
                    n_low += 1
                else:
                    cell_displacements(pieces, index, per_log, tops, r_min, k, p, buffer)
                    for t in range(thresholds.size):
                        above = 0
                        for m in range(n):
                            above += buffer[m] > thresholds[t]
                        exceed[t, i, j] = above / n
                    median[i, j] = median_of(buffer, order, values)
        return -1, n_low

    return numba.njit(cache=True, nogil=True)(kernel)


def _regressions(ky, pga, flat):
    from ..empirical import ValidityWarning, jibson_2007, saygili_rathje_2008_pga

    out = np.full((ky.size, 2), np.nan)
    ok = np.isfinite(ky) & (pga > 0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)  # the range is stated in the variable's attrs
        if np.any(ok):
            out[ok, 0] = jibson_2007(ky[ok], pga[ok]).median_m
            out[ok, 1] = saygili_rathje_2008_pga(ky[ok], pga[ok]).median_m
    out[np.isfinite(ky) & (pga == 0)] = 0.0
    out[flat] = 0.0
    return out


def _dataset(outputs, names, slopes, pga, tables, thresholds, method, per_record, regressions):
    import xarray as xr

    take = lambda k: outputs[k]
    index = {name: k for k, name in enumerate(names)}
    data = {"slope_deg": slopes["slope_deg"]}
    if "dip_azimuth_deg" in slopes:
        data["dip_azimuth_deg"] = slopes["dip_azimuth_deg"]
    data["factor_of_safety"] = take(0).assign_attrs(units="1", long_name="static factor of safety (infinite slope)")
    data["ky_g"] = take(1).assign_attrs(units="g", long_name="yield acceleration (NaN unless stable)")
    codes = list(CATEGORIES)
    data["category"] = take(2).assign_attrs(
        flag_values=np.array(codes, dtype=np.int8), flag_meanings=" ".join(CATEGORIES[c] for c in codes),
        long_name="cell category")
    data["pga_g"] = (pga if isinstance(pga, xr.DataArray) else xr.full_like(take(0), pga)).assign_attrs(
        units="g", long_name="peak ground acceleration")
    members = [f"{name} ({pol})" for name, pol in tables.members]
    data["median_displacement_m"] = take(3).assign_attrs(
        units="m", long_name=f"median Newmark displacement over {len({r for r, _ in tables.members})} record(s) "
                             f"x {len({p for _, p in tables.members})} polarities")
    exceed = [take(index[("exceedance", d)]) for d in thresholds]
    data["exceedance"] = xr.concat(exceed, dim="threshold_m").assign_coords(threshold_m=("threshold_m", thresholds, {
        "units": "m"})).assign_attrs(units="1", long_name="P(D > threshold) over the suite")
    if per_record:
        d = [take(index[("displacement_m", k)]) for k in range(len(members))]
        data["displacement_m"] = xr.concat(d, dim="member").assign_coords(member=members).assign_attrs(
            units="m", long_name="Newmark displacement of each record and polarity")
    if regressions:
        for name, title in _REGRESSIONS.items():
            data[name] = take(index[name]).assign_attrs(units="m", long_name=title)
    attrs = {"method": method, "members": len(members), "polarities": ", ".join(sorted({p for _, p in tables.members})),
             "table_bound": (f"|D_table - D_exact| <= max({tables.rtol:g} D, {tables.atol_m:g} m x PGA/1 g) at the "
                             "check points of every table interval" if method == "table" else "exact engine per cell"),
             "slope_method": "Horn (1981)", "stability": "infinite slope, Jibson et al. (2000)"}
    if isinstance(tables, ProjectedPairs):
        attrs["ground_motion"] = ("two horizontal components projected on each cell's dip azimuth, each pair scaled "
                                  "so that its larger component's peak |a| is the cell's PGA")
    dataset = xr.Dataset(data, attrs=attrs)
    return _with_crs(dataset, slopes["slope_deg"])


def summarize(dataset):
    """Cells of each category of a map (nodata, stable, statically unstable, flat): a
    pandas DataFrame indexed by category (computes a Dask-backed map's category)."""
    import pandas as pd

    codes = np.asarray(dataset["category"].values)
    rows = [{"category": name, "cells": int(np.count_nonzero(codes == code))} for code, name in CATEGORIES.items()]
    return pd.DataFrame(rows).set_index("category")
