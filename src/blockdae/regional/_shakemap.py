"""USGS ShakeMap ``grid.xml``: a field (PGA, PGV, ...) on its longitude-latitude grid, its
units read from the file, and that field interpolated onto a terrain's grid."""

import xml.etree.ElementTree as ElementTree

import numpy as np

from ..units import STANDARD_GRAVITY

#: ShakeMap's units of acceleration -> factor to g
_TO_G = {"pctg": 0.01, "%g": 0.01, "g": 1.0, "cms2": 0.01 / STANDARD_GRAVITY, "cm/s2": 0.01 / STANDARD_GRAVITY,
         "gal": 0.01 / STANDARD_GRAVITY, "m/s2": 1.0 / STANDARD_GRAVITY}
#: ... of velocity -> factor to cm/s
_TO_CM_S = {"cms": 1.0, "cm/s": 1.0, "m/s": 100.0}


def read_shakemap(path, field: str = "PGA"):
    """One field of a ShakeMap ``grid.xml`` on its own grid (dims lat, lon [degrees], CRS
    EPSG:4326): PGA (and PSA*) in g, PGV in cm/s, converted from the units the file states
    for that field (``pctg``, ``g``, ``cms2`` ...; others are refused, naming them)."""
    import xarray as xr

    root = ElementTree.parse(path).getroot()
    spec = _child(root, "grid_specification", path)
    nlon, nlat = int(spec.get("nlon")), int(spec.get("nlat"))
    fields = {f.get("name").upper(): (int(f.get("index")) - 1, f.get("units", ""))
              for f in _children(root, "grid_field")}
    name = field.upper()
    if name not in fields:
        raise ValueError(f"{path}: no field {field!r} in the grid (fields {sorted(fields)})")
    column, units = fields[name]
    table = np.array(_child(root, "grid_data", path).text.split(), dtype=float)
    if table.size != nlon * nlat * len(fields):
        raise ValueError(f"{path}: grid_data holds {table.size} numbers; {nlon} x {nlat} points x {len(fields)} "
                         "fields expected")
    table = table.reshape(nlat * nlon, len(fields))
    factor, unit_out = _factor(name, units, path)
    lon = table[:, fields["LON"][0]].reshape(nlat, nlon)
    lat = table[:, fields["LAT"][0]].reshape(nlat, nlon)
    values = table[:, column].reshape(nlat, nlon) * factor
    array = xr.DataArray(values, dims=("lat", "lon"), coords={"lat": lat[:, 0], "lon": lon[0]},
                         name=name.lower(), attrs={"units": unit_out, "units_in_file": units, "source": str(path)})
    return array.sortby("lat").sortby("lon")


def shakemap_on_terrain(path, terrain, field: str = "PGA"):
    """A ShakeMap field (see :func:`read_shakemap`) interpolated bilinearly onto the cells of
    ``terrain`` (a DataArray in a projected CRS): its cell centres are transformed to
    longitude-latitude; a cell outside the ShakeMap's grid is refused."""
    from pyproj import Transformer
    from scipy.interpolate import RegularGridInterpolator

    grid = read_shakemap(path, field)
    to_lonlat = Transformer.from_crs(terrain.rio.crs, "EPSG:4326", always_xy=True)
    X, Y = np.meshgrid(np.asarray(terrain["x"]), np.asarray(terrain["y"]))
    lon, lat = to_lonlat.transform(X, Y)
    lons, lats = grid["lon"].values, grid["lat"].values
    if np.any((lon < lons[0]) | (lon > lons[-1]) | (lat < lats[0]) | (lat > lats[-1])):
        raise ValueError(f"{path}: the terrain reaches outside the ShakeMap's grid (lon {lons[0]:g} to {lons[-1]:g}, "
                         f"lat {lats[0]:g} to {lats[-1]:g} deg)")
    values = RegularGridInterpolator((lats, lons), grid.values)(np.stack([lat, lon], axis=-1))
    return terrain.copy(data=values).assign_attrs(units=grid.attrs["units"], long_name=f"{grid.name} (ShakeMap)",
                                                  source=str(path))


def _factor(name, units, path):
    key = units.strip().lower()
    if name == "PGV":
        table, unit_out = _TO_CM_S, "cm/s"
    elif name == "PGA" or name.startswith("PSA"):
        table, unit_out = _TO_G, "g"
    else:
        return 1.0, units
    if key not in table:
        raise ValueError(f"{path}: field {name} is in {units!r}, which is not one of {sorted(table)}")
    return table[key], unit_out


def _child(root, tag, path):
    found = _children(root, tag)
    if not found:
        raise ValueError(f"{path}: no <{tag}> element: not a ShakeMap grid.xml")
    return found[0]


def _children(root, tag):
    return [e for e in root if e.tag.split("}")[-1] == tag]
