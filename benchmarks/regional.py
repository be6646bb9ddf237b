"""A regional map: a 10,000 x 10,000 synthetic terrain (10^8 cells, 10 m cells, two
geological zones, a PGA field) on disk, 10 records of the FEMA P695 far-field set in both
polarities, median D and P(D > 0.05 m) written to a Zarr store chunk by chunk on 2 threads;
the bar: the tables and the map in under 60 s of wall time and under 4 GB of peak memory.
Each stage is timed alone (wall and CPU: process time over both threads). Then
pyNewmarkDisp's spatial_newmark against blockdae on the same 10^4 cells and record (the
median of three calls), its time per cell over the map's per cell and record-polarity both
everything included (the bar: 10^4x) and without the DEM's read and slope, and the
rectangular pulse against its closed form. Exit status 1 when a bar is not met.

    python benchmarks/regional.py [--quick] [--size N] [--chunk N] [--out FOLDER]
"""

import argparse
import os
import resource
import tempfile
import time
import warnings

import numpy as np

import blockdae as bd
from _common import print_table, verdict

BAR_S = 60.0
BAR_GB = 4.0
BAR_SPEED_UP = 1e4
PEER_CALLS = 3  # pyNewmarkDisp's calls on the 10^4 cells, the median timed
RECORDS = 10
THRESHOLD_M = 0.05
CELL_M = 10.0
CHUNK = 2000
THREADS = 2


class Stage:
    """Wall [s], CPU [s] (process time: every thread) and the system's part of it [s] of a ``with`` block."""

    def __enter__(self):
        self.wall, self.cpu = time.perf_counter(), time.process_time()
        self.system = resource.getrusage(resource.RUSAGE_SELF).ru_stime
        return self

    def __exit__(self, *exc):
        self.wall, self.cpu = time.perf_counter() - self.wall, time.process_time() - self.cpu
        self.system = resource.getrusage(resource.RUSAGE_SELF).ru_stime - self.system


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a 400 x 400 terrain and 2 records (smoke run)")
    parser.add_argument("--size", type=int, default=None, help="cells along each side (default 10,000)")
    parser.add_argument("--peer-side", type=int, default=None,
                        help="pyNewmarkDisp's cells along each side (default 100: 10^4 cells)")
    parser.add_argument("--chunk", type=int, default=CHUNK,
                        help=f"cells along each side of a chunk (default {CHUNK:,})")
    parser.add_argument("--out", default=None, help="folder of the Zarr stores (default: a temporary one)")
    args = parser.parse_args(argv)
    import dask
    import xarray as xr
    from blockdae import regional as rg

    n = args.size or (400 if args.quick else 10_000)
    chunk = min(args.chunk, n)
    n_records = 2 if args.quick else RECORDS
    suite = bd.RecordSet.fema_p695("far-field")
    records = [suite[name] for name in suite.names[:n_records]]
    out = args.out or tempfile.mkdtemp(prefix="blockdae-regional-")
    load_before = os.getloadavg()
    with dask.config.set(scheduler="threads", num_workers=THREADS):
        with Stage() as inputs:
            _terrain(n, chunk).to_zarr(os.path.join(out, "terrain.zarr"), mode="w", zarr_format=2)
        with Stage() as build:
            tables = rg.DisplacementTables.build(records, "both", atol_m=1e-6 / rg.MAX_PGA_G)
        terrain = lambda: xr.open_zarr(os.path.join(out, "terrain.zarr"), decode_coords="all")
        zone_table = {"zone": [1, 2], "cohesion_kpa": [3.0, 10.0], "friction_deg": [30.0, 36.0],
                      "unit_weight_kn_m3": [18.5, 20.5]}

        def the_map(window=None):
            stored = terrain() if window is None else terrain().isel(x=window, y=window)
            # the float32 rasters as stored: the compiled kernels take each value as float64
            dem = stored["dem"].rio.write_crs(stored.rio.crs)
            strength = rg.strength_from_zones(stored["zone"].rio.write_crs(stored.rio.crs), zone_table)
            ds = rg.displacement_map(dem, strength, None, stored["pga_g"], thickness_m=2.5,
                                     saturated_fraction=0.2, thresholds_m=(THRESHOLD_M,), regressions=False,
                                     tables=tables)
            return ds[["median_displacement_m", "exceedance"]].astype("float32"), dem

        with Stage() as warm:  # numba's compiled kernels (from its cache after the first run) on 50 x 50 cells
            float(the_map(slice(0, 50))[0]["median_displacement_m"].sum().compute())
        with Stage() as slope:  # read the DEM, Horn's slope of every cell, a sum (nothing written)
            stored = terrain()
            rg.slope_and_azimuth(stored["dem"])["slope_deg"].sum().compute()
        with Stage() as computed:  # the whole map, summed (nothing written)
            float(the_map()[0]["median_displacement_m"].sum().compute())
        with Stage() as written:  # the whole map written: the bar's
            written_map, dem = the_map()
            rg.write_map(written_map, os.path.join(out, "map.zarr"))
    peak_gb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    load_after = os.getloadavg()
    back = xr.open_zarr(os.path.join(out, "map.zarr"))
    sliding = float((back["median_displacement_m"] > 0).mean())
    cells, members = n * n, len(tables.members)
    print(f"terrain {n:,} x {n:,} = {cells:,} cells of {CELL_M:g} m (float32 DEM, zones and PGA [g] in a Zarr "
          f"store), {n_records} records x 2 polarities, chunks {chunk} x {chunk}, {THREADS} threads; tables "
          f"{int(tables.counts.sum()):,} knots ({tables.counts.min()}-{tables.counts.max()} per member)")
    print(f"machine load (1-min average over its cores, shared): {load_before[0]:.1f} before, "
          f"{load_after[0]:.1f} after; CPU: process time over all threads")
    total_wall, total_cpu = build.wall + warm.wall + written.wall, build.cpu + warm.cpu + written.cpu
    print_table(["stage", "wall [s]", "CPU [s]"], [
        ("inputs: the synthetic terrain written to Zarr (not in the bar)", f"{inputs.wall:.1f}", f"{inputs.cpu:.1f}"),
        (f"tables: exact engine, {n_records} records x 2 polarities", f"{build.wall:.1f}", f"{build.cpu:.1f}"),
        ("kernels compiled or loaded from numba's cache (a 50 x 50 map)", f"{warm.wall:.1f}", f"{warm.cpu:.1f}"),
        ("terrain: DEM read, Horn slope of every cell (summed)", f"{slope.wall:.1f}", f"{slope.cpu:.1f}"),
        ("map: read, slope, strength, FS, ky, median D, P (summed)", f"{computed.wall:.1f}", f"{computed.cpu:.1f}"),
        ("map written: the same, float32 to Zarr", f"{written.wall:.1f}", f"{written.cpu:.1f}"),
        ("the bar's total: tables + kernels + map written", f"{total_wall:.1f}", f"{total_cpu:.1f}")])
    per_cell_ns = 1e9 * written.cpu / (cells * members)
    print(f"map written: {per_cell_ns:.2f} ns of CPU per cell and record-polarity, everything included; "
          f"writing {written.cpu - computed.cpu:+.1f} s of CPU over computing alone; {written.system:.1f} s of its "
          f"CPU the system's (mostly zeroing the fresh pages of each block's arrays)")
    print(f"cells with median D > 0: {100 * sliding:.1f} %; peak memory {peak_gb:.2f} GB")
    met = {"wall": total_wall < BAR_S, "memory": peak_gb < BAR_GB}
    print(f"bar {BAR_S:g} s of wall time for the tables and the map written: {verdict(met['wall'], args.quick)} "
          f"({total_wall:.1f} s; {total_cpu / THREADS:.1f} s of CPU per core)")
    print(f"bar {BAR_GB:g} GB peak memory: {verdict(met['memory'], args.quick)} ({peak_gb:.2f} GB)")
    print()
    given_ky_ns = 1e9 * (written.cpu - slope.cpu) / (cells * members)  # pyNewmarkDisp is given ky per cell
    met["speed-up"] = _versus_pynewmarkdisp(records[0], tables, args.peer_side or (20 if args.quick else 100),
                                            per_cell_ns, given_ky_ns, args.quick)
    print()
    _rectangular_pulse()
    return 0 if args.quick or all(met.values()) else 1


def _terrain(n, chunk):
    """A Dataset of n x n cells, Dask arrays computed chunk by chunk: dem [m], zone, pga_g [g] (float32)."""
    import dask.array as da
    import rioxarray  # noqa: F401  (the .rio accessor)
    import xarray as xr

    x = 500_000.0 + CELL_M * np.arange(n)
    y = 4_100_000.0 - CELL_M * np.arange(n)

    def field(kind, block_info=None):
        (r0, r1), (c0, c1) = block_info[None]["array-location"]
        X, Y = np.meshgrid(CELL_M * np.arange(c0, c1), CELL_M * np.arange(r0, r1))
        if kind == "dem":
            z = 80 * np.sin(X / 900) * np.cos(Y / 700) + 30 * np.sin(X / 130 + Y / 170) + 0.2 * X
        elif kind == "zone":
            z = np.where(np.sin(X / 2500) * np.cos(Y / 3100) > 0, 1.0, 2.0)
        else:
            side = n * CELL_M
            z = 0.25 + 0.2 * np.exp(-((X - 0.4 * side) ** 2 + (Y - 0.6 * side) ** 2) / (0.3 * side) ** 2)
        return z.astype(np.float32)

    chunks = ((chunk,) * (n // chunk) + ((n % chunk,) if n % chunk else ()),) * 2
    units = {"dem": "m", "zone": "1", "pga_g": "g"}
    arrays = {name: (("y", "x"), da.map_blocks(field, name, chunks=chunks, dtype=np.float32,
                                               meta=np.array((), dtype=np.float32)), {"units": unit})
              for name, unit in units.items()}
    return xr.Dataset(arrays, coords={"x": x, "y": y}).rio.write_crs("EPSG:32611")


def _versus_pynewmarkdisp(record, tables, side, map_ns, given_ky_ns, quick):
    """CPU time per cell and the differences on side x side cells, one record, the normal polarity;
    pyNewmarkDisp's time per cell (the median of three calls) over blockdae's in the map
    (``map_ns`` [ns] per cell and record-polarity, everything included: the bar's; ``given_ky_ns``
    the same without the DEM's read and slope, printed beside it) against the bar: True where
    met (or not installed)."""
    try:
        from pynewmarkdisp.spatial import spatial_newmark
    except ImportError:
        print("pyNewmarkDisp is not installed (pip install pynewmarkdisp): its comparison is skipped")
        return True
    rng = np.random.default_rng(0)
    pga_g = record.peak_acceleration / bd.STANDARD_GRAVITY
    ky = pga_g * rng.uniform(0.05, 0.6, (side, side))
    time_s, accel = record.sample_times, record.acceleration_m_s2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spatial_newmark(time_s, accel, ky[:1, :1], 9.81)  # its first call compiles (numba)
    peer_cpu = []
    for _ in range(PEER_CALLS):
        with warnings.catch_warnings(), Stage() as peer:
            warnings.simplefilter("ignore")
            theirs = spatial_newmark(time_s, accel, ky * bd.STANDARD_GRAVITY / 9.81, 9.81)
        peer_cpu.append(peer.cpu)
    one = tables.select(record.name, "normal")
    one.displacement(ky, pga_g)  # compiled (or loaded from numba's cache) before the clock
    repeat = 200
    with Stage() as call:
        for _ in range(repeat):
            ours = one.displacement(ky, pga_g)[0]
    exact_to_end = np.asarray(bd.newmark(record, ky.ravel(), polarity="normal", t_end=record.duration).normal)
    cells = ky.size
    theirs_ns, call_ns = 1e9 * float(np.median(peer_cpu)) / cells, 1e9 * call.cpu / (repeat * cells)
    print(f"pyNewmarkDisp spatial_newmark vs blockdae: {cells:,} cells, {record.name} (normal polarity), "
          f"ky/PGA 0.05-0.6; CPU time (process time), one thread")
    print_table(["", "per cell [ns]", "total [s]"], [
        (f"pyNewmarkDisp: one call (a Python loop, trapezoid), median of {PEER_CALLS}", f"{theirs_ns:,.0f}",
         f"{np.median(peer_cpu):.3f}"),
        ("blockdae: the record's table, one call (mean of 200)", f"{call_ns:,.1f}", f"{call.cpu / repeat:.5f}"),
        ("blockdae: the map, per cell and record-polarity, everything included", f"{map_ns:.2f}", ""),
        ("the same without the DEM's read and slope (pyNewmarkDisp is given ky)", f"{given_ky_ns:.2f}", "")])
    print(f"pyNewmarkDisp's {PEER_CALLS} calls: {', '.join(f'{t:.3f}' for t in peer_cpu)} s of CPU; the map "
          "everything included: the DEM read, Horn's slope, strength, FS, ky, lookups, statistics, writing")
    print(f"speed-up, the same 10^4 cells in one call each: {theirs_ns / call_ns:,.0f}x")
    print(f"per-cell ratio, pyNewmarkDisp's call over blockdae's map: {theirs_ns / map_ns:,.0f}x everything "
          f"included; {theirs_ns / given_ky_ns:,.0f}x without the DEM's read and slope")
    ok = theirs_ns / map_ns >= BAR_SPEED_UP
    print(f"bar {BAR_SPEED_UP:,.0f}x per cell and record, everything included: {verdict(ok, quick)} "
          f"({theirs_ns / map_ns:,.0f}x)")
    sliding = exact_to_end.reshape(ky.shape) > 0.01
    rel_end = (theirs - exact_to_end.reshape(ky.shape))[sliding] / exact_to_end.reshape(ky.shape)[sliding]
    rel_rest = (theirs - ours)[sliding] / ours[sliding]
    print(f"pyNewmarkDisp - exact, cells with D > 1 cm ({np.count_nonzero(sliding):,}): against D at the record's end "
          f"{100 * rel_end.min():+.1f} % to {100 * rel_end.max():+.1f} % (median {100 * np.median(rel_end):+.1f} %); "
          f"against D at rest {100 * rel_rest.min():+.1f} % to {100 * rel_rest.max():+.1f} %")
    return ok


def _rectangular_pulse():
    """0.5 g for 0.3 s, ky = 0.1 g: D = (A - k) g T² / 2 + ((A - k) g T)² / (2 k g) in closed form."""
    g, amplitude, duration, ky = bd.STANDARD_GRAVITY, 0.5, 0.3, 0.1
    closed = (amplitude - ky) * g * duration**2 / 2 + ((amplitude - ky) * g * duration) ** 2 / (2 * ky * g)
    dt = 1e-4
    samples = np.r_[np.full(round(duration / dt) + 1, amplitude * g), np.zeros(round(3 / dt))]
    record = bd.Record(samples, dt, name="pulse")
    ours = bd.newmark(record, ky, polarity="normal").normal
    line = f"rectangular pulse 0.5 g for 0.3 s, ky 0.1 g: closed form {closed:.4f} m (sharp end), " \
           f"blockdae {ours:.4f} m " \
           f"(samples every {1e3 * dt:g} ms: the pulse ends over a {1e3 * dt:g} ms ramp)"
    try:
        from pynewmarkdisp.newmark import direct_newmark
        theirs = direct_newmark(record.sample_times, samples, ky * g / 9.81, 9.81)["perm_disp"]
        line += f", pyNewmarkDisp {theirs:.4f} m"
    except ImportError:
        pass
    print(line)


if __name__ == "__main__":
    raise SystemExit(main())
