"""``blockdae map``: the Newmark displacement of every cell of a terrain (a DEM, a zone
raster and its strength table, a failure-surface thickness, a PGA) over a record suite,
written to NetCDF, Zarr or GeoTIFF."""

import pathlib
import time

from ._common import UsageError, checked, files_or_set, folder_files, positive, read, record_arguments, \
    recursive_argument, save_figure, set_argument


def add_map_parser(sub):
    """The ``map`` subcommand."""
    p = sub.add_parser("map", help="Newmark displacement of every cell of a terrain over a record suite "
                                   "(infinite slope; NetCDF, Zarr or GeoTIFF)")
    p.add_argument("dem", type=pathlib.Path, metavar="DEM",
                   help="elevations [m]: GeoTIFF or ESRI ASCII grid, in a projected CRS with metre cells")
    p.add_argument("records", type=pathlib.Path, nargs="*", metavar="RECORD",
                   help="accelerogram files or folders of them; or --set NAME")
    p.add_argument("--zones", type=pathlib.Path, default=None, metavar="RASTER",
                   help="zone codes on the DEM's grid (with --zone-table); without it: --zone-table's one row")
    p.add_argument("--zone-table", type=pathlib.Path, required=True, metavar="CSV",
                   help="CSV with columns zone, cohesion_kpa [kPa], friction_deg [deg], unit_weight_kn_m3 [kN/m³]")
    p.add_argument("--thickness", required=True, metavar="T_M",
                   help="failure-surface thickness t [m]: a number or a raster on the DEM's grid")
    p.add_argument("--saturated", default="0", metavar="M",
                   help="saturated fraction m of t [-]: a number or a raster (default 0)")
    p.add_argument("--pga", required=True, metavar="PGA_G",
                   help="peak ground acceleration [g]: a number, a raster on the DEM's grid in g, or a ShakeMap "
                        "grid.xml (its PGA, in the units it states, interpolated onto the DEM's grid)")
    p.add_argument("--thresholds", type=positive("--thresholds"), nargs="+", default=[0.05], metavar="D_M",
                   help="displacements d [m] of the maps P(D > d) (default 0.05)")
    p.add_argument("--method", choices=("table", "exact"), default=None,
                   help="table (default: each record's D(ky/PGA) tabulated within max(1e-6 D, 1e-6 m)) or exact "
                        "(the only method with --components)")
    p.add_argument("--components", type=float, nargs=2, default=None, metavar=("AZ1", "AZ2"),
                   help="the two RECORD files are one record's orthogonal horizontal components, of azimuths AZ1 "
                        "and AZ2 [deg clockwise from north]: projected on each cell's dip azimuth, the pair scaled "
                        "so that its larger component's peak is the cell's PGA, exact engine per cell")
    p.add_argument("--polarity", choices=("both", "normal", "inverse"), default="both",
                   help="both (default: each record as given and inverted), normal or inverse")
    p.add_argument("--first", type=int, default=None, metavar="N", help="only the first N records of the suite")
    p.add_argument("--per-record", action="store_true", help="also D of every record and polarity")
    p.add_argument("--chunks", type=int, default=None, metavar="CELLS",
                   help="compute chunk by chunk (Dask) in squares of CELLS x CELLS (default: in memory)")
    p.add_argument("--out", type=pathlib.Path, required=True, metavar="PATH",
                   help="the map: .nc (NetCDF), .zarr (Zarr) or .tif (GeoTIFF, a file per variable)")
    p.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG",
                   help="save median D and Jibson (2007)'s over the hillshade")
    p.add_argument("--g", type=positive("--g"), default=9.80665,
                   help="the unit 'g' [m/s²] of the files (default 9.80665)")
    record_arguments(p)
    recursive_argument(p)
    set_argument(p)
    p.set_defaults(command=_map)


def _map(args) -> int:
    try:
        from .. import regional
    except ImportError as err:
        raise UsageError(f"blockdae map needs the regional extra: pip install 'blockdae[regional]' ({err})") from None
    import pandas as pd

    chunks = None if args.chunks is None else {"x": args.chunks, "y": args.chunks}
    dem = checked(lambda: regional.read_raster(args.dem, chunks=chunks), str(args.dem))
    table = checked(lambda: pd.read_csv(args.zone_table), str(args.zone_table))
    if args.zones is None:
        if len(table) != 1:
            raise UsageError(f"{args.zone_table}: {len(table)} zones but no --zones raster to place them")
        strength = {k: float(table[k].iloc[0]) for k in ("cohesion_kpa", "friction_deg", "unit_weight_kn_m3")
                    if k in table.columns}
    else:
        zones = checked(lambda: regional.read_raster(args.zones, chunks=chunks), str(args.zones))
        strength = checked(lambda: regional.strength_from_zones(zones, table), str(args.zone_table))
    fields = {name: _number_or_raster(regional, getattr(args, name), f"--{name}", chunks, dem)
              for name in ("thickness", "saturated", "pga")}
    if isinstance(fields["pga"], float) and not 0 <= fields["pga"] <= regional.MAX_PGA_G:
        raise UsageError(f"--pga: pga_g={fields['pga']!r} must lie in [0, {regional.MAX_PGA_G:g}] g (a value above "
                         f"{regional.MAX_PGA_G:g} is likely in m/s² or %g: convert it to g)")
    record_set = files_or_set(args, args.records)
    if record_set is not None:
        records = [record_set[name] for name in record_set.names]
    else:
        paths = [p for arg in args.records for p in (folder_files(arg, args) if arg.is_dir() else [arg])]
        records = [read(path, args) for path in paths]
    records = records[:args.first] if args.first else records
    if args.components is not None:
        motion, tables = _pair(regional, records, args), None
    else:
        motion, tables = None, _tables(regional, records, args)
    ds = checked(lambda: regional.displacement_map(
        dem, strength, motion, fields["pga"], thickness_m=fields["thickness"], saturated_fraction=fields["saturated"],
        thresholds_m=args.thresholds, method=args.method, polarity=args.polarity, per_record=args.per_record,
        tables=tables), "")
    start = time.perf_counter()
    paths = checked(lambda: regional.write_map(ds, args.out, progress=chunks is not None), str(args.out))
    print(f"map of {dem.sizes['y']} x {dem.sizes['x']} cells computed and written in "
          f"{time.perf_counter() - start:.1f} s: {', '.join(str(p) for p in paths)}")
    summary = regional.summarize(ds)
    print("cells: " + ", ".join(f"{n} {name.replace('_', ' ')}" for name, n in summary["cells"].items()))
    median = ds["median_displacement_m"]
    stable = ds["category"] == 1
    print(f"median D over the stable cells: largest {float(median.where(stable).max()):.4g} m; "
          + "; ".join(f"P(D > {d:g} m) >= 0.5 on {int((ds['exceedance'].sel(threshold_m=d) >= 0.5).sum())} cells"
                      for d in args.thresholds))
    if args.plot is not None:
        save_figure(regional.map_figure(ds, dem), args.plot)
        print(f"figure: {args.plot}")
    return 0


def _tables(regional, records, args):
    """Each record's table of D(ky/PGA), built and reported."""
    start = time.perf_counter()
    tables = checked(lambda: regional.DisplacementTables.build(records, args.polarity, g=args.g,
                                                               atol_m=1e-6 / regional.MAX_PGA_G), "records")
    print(f"{len(records)} records, {args.polarity} polarities: {len(tables.members)} tables of D(ky/PGA), "
          f"{int(tables.counts.sum())} knots, in {time.perf_counter() - start:.1f} s")
    return tables


def _pair(regional, records, args):
    """The two RECORD files as one record's horizontal components (--components)."""
    if len(records) != 2:
        raise UsageError(f"--components: give exactly the two horizontal components of one record as RECORD files, "
                         f"got {len(records)} record(s)")
    if args.method == "table":
        raise UsageError("--components runs on the exact engine (each cell's projected record is its own): "
                         "leave --method out or give --method exact")
    pair = checked(lambda: regional.RecordPair(*records, azimuths_deg=args.components), "--components")
    print(f"{pair!r}: projected on each cell's dip azimuth, exact engine per cell")
    return pair


def _number_or_raster(regional, text, name, chunks, dem):
    """A number, a raster file, or (for --pga) a ShakeMap grid.xml interpolated onto the DEM's grid."""
    try:
        return float(text)
    except ValueError:
        path = pathlib.Path(text)
        if not path.is_file():
            raise UsageError(f"{name} {text}: neither a number nor a raster file") from None
        if name == "--pga" and path.suffix.lower() == ".xml":
            return checked(lambda: regional.shakemap_on_terrain(path, dem), f"{name} {path}")
        return checked(lambda: regional.read_raster(path, chunks=chunks), f"{name} {path}")
