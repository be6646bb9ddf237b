"""Terrain rasters: read GeoTIFF and ESRI ASCII grids as xarray DataArrays with their CRS;
slope [deg] and dip azimuth [deg clockwise from north] from a DEM by Horn's method (Horn
1981, the 3 x 3 weighted differences of GDAL's ``gdaldem slope``/``aspect``) in a projected
CRS with metre cells."""

import numba
import numpy as np


def read_raster(path, *, chunks=None):
    """One band of a GeoTIFF or ESRI ASCII grid (any format rasterio reads) as a 2-D
    xarray DataArray (dims y, x; coordinates the cell centres in the file's CRS, kept in
    ``.rio.crs``); nodata cells as NaN (float64). ``chunks``: as for xarray (e.g.
    ``{"x": 2048, "y": 2048}``: a Dask-backed array read chunk by chunk); None: in memory.
    The units of the values are the file's: say them where you use the array."""
    try:
        import rioxarray
    except ImportError:
        raise ImportError("reading rasters needs rioxarray: pip install 'blockdae[regional]'") from None
    array = rioxarray.open_rasterio(path, masked=True, chunks=chunks)
    if array.sizes.get("band", 1) != 1:
        raise ValueError(f"{path}: {array.sizes['band']} bands; a terrain raster has one")
    array = array.squeeze("band", drop=True).astype(float)
    array.attrs.pop("_FillValue", None)
    return array


def slope_and_azimuth(dem):
    """Slope [deg] and dip azimuth [deg clockwise from north, the direction of steepest
    descent] of each cell of ``dem`` (a DataArray of elevations [m], dims y, x, in a
    projected CRS with metre cells) by Horn's method; the cells of the border and those
    next to a nodata cell are NaN (nodata); a flat cell has slope 0 and azimuth NaN.
    Dask-backed arrays stay lazy (one cell of overlap between chunks).

    Returns: an xarray Dataset with ``slope_deg`` and ``dip_azimuth_deg`` on dem's grid and CRS.
    """
    import xarray as xr

    dx, dy = cell_size(dem)
    data = dem.data
    if hasattr(data, "map_overlap"):
        import dask.array as da

        floats = data if data.dtype in _FLOATS else data.astype(float)
        # each block with one cell of its neighbours (NaN past the raster's edges) gives its own cells
        overlapped = da.overlap.overlap(floats, depth=1, boundary=np.nan)
        stacked = [overlapped.map_blocks(_horn_of_block, dx=dx, dy=dy, which=which, chunks=data.chunks, dtype=float,
                                         meta=np.array((), dtype=float)) for which in (0, 1)]
    else:
        stacked = [_horn(np.asarray(data), dx, dy, which) for which in (0, 1)]
    coords = {k: dem.coords[k] for k in dem.coords if k in dem.dims or k == "spatial_ref"}
    out = xr.Dataset({"slope_deg": (dem.dims, stacked[0], {"units": "deg", "long_name": "slope (Horn 1981)"}),
                      "dip_azimuth_deg": (dem.dims, stacked[1], {
                          "units": "deg", "long_name": "dip azimuth, clockwise from north (Horn 1981)"})},
                     coords=coords)
    return _with_crs(out, dem)


def cell_size(dem) -> tuple[float, float]:
    """(dx, dy) [m]: the signed spacing of dem's x and y coordinates (dy < 0 for a
    north-up raster); a ValueError for a geographic CRS, an uneven grid or one of fewer
    than 3 x 3 cells."""
    if dem.dims != ("y", "x"):
        raise ValueError(f"the DEM must have dims ('y', 'x'), got {dem.dims}")
    crs = _crs(dem)
    if crs is not None and not crs.is_projected:
        raise ValueError(f"the DEM's CRS {crs.to_string()} is geographic (cells in degrees): slope needs metre "
                         "cells; reproject it to a projected CRS first, e.g. "
                         "dem.rio.reproject(dem.rio.estimate_utm_crs())")
    if crs is not None:
        unit = crs.linear_units
        if unit not in ("metre", "meter"):
            raise ValueError(f"the DEM's CRS {crs.to_string()} has cells in {unit}: slope needs metre cells; "
                             "reproject it to a CRS in metres (e.g. its UTM zone)")
    if dem.sizes["x"] < 3 or dem.sizes["y"] < 3:
        raise ValueError(f"the DEM has {dem.sizes['y']} x {dem.sizes['x']} cells: Horn's method needs at least 3 x 3")
    spacing = []
    for axis in ("x", "y"):
        steps = np.diff(np.asarray(dem[axis], dtype=float))
        if not np.allclose(steps, steps[0], rtol=1e-9, atol=0):
            raise ValueError(f"the DEM's {axis} coordinates are not evenly spaced "
                             f"({steps.min():g} to {steps.max():g} m)")
        spacing.append(float(steps[0]))
    return tuple(spacing)


def _horn(z, dx, dy, which):
    """The slope [deg] (``which`` 0) or dip azimuth [deg from north] (1) of the interior
    cells of ``z`` (rows along y, columns along x, spacings dx, dy [m], signed), NaN on
    the border; shaped as z."""
    out = np.full(z.shape, np.nan)
    out[1:-1, 1:-1] = _horn_of_block(z, dx, dy, which)
    return out


def _horn_of_block(z, dx, dy, which):
    """:func:`_horn` of the interior cells of ``z`` alone (a block with one cell of overlap on
    every side): shape (rows - 2, columns - 2)."""
    out = np.empty((z.shape[0] - 2, z.shape[1] - 2))
    _horn_cells(np.ascontiguousarray(_floats(z)), float(dx), float(dy), which, out)
    return out


@numba.njit(cache=True, nogil=True)
def _horn_cells(z, dx, dy, which, out):
    """Horn's slope or dip azimuth of z's interior cells into ``out`` (shaped as z less its
    border); z float32 or float64, each elevation taken as float64."""
    for r in range(1, z.shape[0] - 1):
        for k in range(1, z.shape[1] - 1):
            a, b, c = float(z[r - 1, k - 1]), float(z[r - 1, k]), float(z[r - 1, k + 1])
            d, f = float(z[r, k - 1]), float(z[r, k + 1])
            g, h, i = float(z[r + 1, k - 1]), float(z[r + 1, k]), float(z[r + 1, k + 1])
            dz_dx = ((c + 2 * f + i) - (a + 2 * d + g)) / (8 * dx)
            dz_dy = ((g + 2 * h + i) - (a + 2 * b + c)) / (8 * dy)
            if which == 0:
                out[r - 1, k - 1] = np.degrees(np.arctan(np.hypot(dz_dx, dz_dy)))
            elif dz_dx == 0 and dz_dy == 0:
                out[r - 1, k - 1] = np.nan
            else:
                out[r - 1, k - 1] = np.degrees(np.arctan2(-dz_dx, -dz_dy)) % 360.0


#: the dtypes that the compiled kernels read as they are (each value taken as float64)
_FLOATS = (np.dtype(np.float32), np.dtype(np.float64))


def _floats(values):
    """``values`` as a float32 or float64 array, as given where it is one of them (no copy),
    else converted to float64."""
    values = np.asarray(values)
    return values if values.dtype in _FLOATS else values.astype(float)


def _crs(array):
    try:
        import rioxarray  # noqa: F401  (registers the .rio accessor)
    except ImportError:
        return None
    return array.rio.crs


def _with_crs(dataset, like):
    """``dataset`` (built by the caller, so written in place: no copy of its data) with ``like``'s CRS."""
    crs = _crs(like)
    return dataset if crs is None else dataset.rio.write_crs(crs, inplace=True)
