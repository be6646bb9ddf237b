"""Regional maps of seismic slope displacement: terrain rasters (slope and dip azimuth by
Horn's method), strength by geological zone, the infinite slope of Jibson et al. (2000)
(FS, ky, the statically unstable and flat cells kept as categories), and each cell's
rigid-block Newmark displacement over a record suite, exact or by each record's table of
D(ky/PGA) (D_s(ky) = s · D_1(ky/s) for a record scaled by s), with its median,
exceedance probabilities and the regressions beside it (or two horizontal components
projected on each cell's dip azimuth, exact per cell); xarray Datasets, Dask chunk by
chunk. Needs the ``regional`` extra (xarray, rioxarray, dask)."""

from ._infinite_slope import CATEGORIES, WATER_UNIT_WEIGHT, count_categories, factor_of_safety, infinite_slope
from ._figures import map_figure
from ._io import write_map
from ._map import MAX_PGA_G, displacement_map, strength_from_zones, summarize
from ._pairs import RecordPair
from ._shakemap import read_shakemap, shakemap_on_terrain
from ._tables import DisplacementTables
from ._terrain import read_raster, slope_and_azimuth

__all__ = ["CATEGORIES", "DisplacementTables", "MAX_PGA_G", "RecordPair", "WATER_UNIT_WEIGHT", "count_categories",
           "displacement_map", "factor_of_safety", "infinite_slope", "map_figure", "read_raster", "read_shakemap",
           "shakemap_on_terrain", "slope_and_azimuth", "strength_from_zones", "summarize", "write_map"]
