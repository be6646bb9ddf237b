"""Writing a map: NetCDF (.nc), Zarr (.zarr) or GeoTIFF (.tif), chunk by chunk where the
map is Dask-backed, its CRS and units kept."""

import contextlib
import pathlib


def write_map(dataset, path, variables=None, *, progress: bool = False):
    """Write ``dataset`` (a map of :func:`displacement_map`) to ``path`` by its suffix.

    Args:
        dataset: an xarray Dataset (Dask-backed ones are computed chunk by chunk as written).
        path: ``.nc`` (NetCDF4 through h5netcdf), ``.zarr`` (a Zarr store) or ``.tif``/``.tiff``
            (GeoTIFF: one file per variable, ``<stem>_<variable>.tif``, a band per threshold
            or member of a 3-D variable).
        variables: the names to write; None: all.
        progress: a progress bar on stderr while a Dask-backed map computes (the default scheduler).

    Returns: the paths written (a list of pathlib.Path).
    """
    path = pathlib.Path(path)
    chosen = dataset if variables is None else dataset[list(variables)]
    suffix = path.suffix.lower()
    with _progress(progress):
        if suffix == ".nc":
            chosen.to_netcdf(path, engine="h5netcdf")
            return [path]
        if suffix == ".zarr":
            chosen.to_zarr(path, mode="w", zarr_format=2)
            return [path]
        if suffix in (".tif", ".tiff"):
            return [_geotiff(chosen[name], path.with_name(f"{path.stem}_{name}{suffix}")) for name in chosen.data_vars]
    raise ValueError(f"{path}: write a map to .nc (NetCDF), .zarr (Zarr) or .tif (GeoTIFF)")


def _geotiff(array, path):
    if array.ndim == 3:
        band = array.dims[0]
        array = array.assign_coords({band: range(1, array.sizes[band] + 1)}).rename({band: "band"})
    if array.dtype.kind == "f":
        array = array.rio.write_nodata(float("nan"))
    array.rio.to_raster(path, tiled=True)
    return path


def _progress(enabled):
    if not enabled:
        return contextlib.nullcontext()
    from dask.diagnostics import ProgressBar

    return ProgressBar()
