"""A regional map: a 10,000 x 10,000 synthetic terrain (10^8 cells, 10 m cells, two
geological zones, a PGA field), 10 records of the FEMA P695 far-field set in both
polarities, median D and P(D > 0.05 m) written to a Zarr store chunk by chunk on 2 threads;
the bar: under 60 s and under 4 GB of peak memory. Then pyNewmarkDisp's spatial_newmark
against the tables on the same 10^4 cells and one record (time per cell and the differences),
and the rectangular pulse against its closed form.

    python benchmarks/regional.py [--quick] [--size N] [--out FOLDER]
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
RECORDS = 10
THRESHOLD_M = 0.05
CELL_M = 10.0
CHUNK = 2000


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a 400 x 400 terrain and 2 records (smoke run)")
    parser.add_argument("--size", type=int, default=None, help="cells along each side (default 10,000)")
    parser.add_argument("--peer-side", type=int, default=None,
                        help="pyNewmarkDisp's cells along each side (default 100: 10^4 cells)")
    parser.add_argument("--out", default=None, help="folder of the Zarr store (default: a temporary one)")
    args = parser.parse_args(argv)
    import dask
    import xarray as xr
    from blockdae import regional as rg

    n = args.size or (400 if args.quick else 10_000)
    n_records = 2 if args.quick else RECORDS
    suite = bd.RecordSet.fema_p695("far-field")
    records = [suite[name] for name in suite.names[:n_records]]
    load_before = os.getloadavg()
    start, cpu_start = time.perf_counter(), time.process_time()
    tables = rg.DisplacementTables.build(records, "both", atol_m=1e-6 / rg.MAX_PGA_G)
    t_tables, cpu_tables = time.perf_counter() - start, time.process_time() - cpu_start
    dem, zones, pga = _terrain(n, min(CHUNK, n))
    strength = rg.strength_from_zones(zones, {"zone": [1, 2], "cohesion_kpa": [3.0, 10.0],
                                              "friction_deg": [30.0, 36.0], "unit_weight_kn_m3": [18.5, 20.5]})
    out = args.out or tempfile.mkdtemp(prefix="blockdae-regional-")
    with dask.config.set(scheduler="threads", num_workers=2):
        start, cpu_start = time.perf_counter(), time.process_time()
        ds = rg.displacement_map(dem, strength, None, pga, thickness_m=2.5, saturated_fraction=0.2,
                                 thresholds_m=(THRESHOLD_M,), regressions=False, tables=tables)
        written = ds[["median_displacement_m", "exceedance"]].astype("float32")
        rg.write_map(written, os.path.join(out, "map.zarr"))
        t_map, cpu_map = time.perf_counter() - start, time.process_time() - cpu_start
    peak_gb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    load_after = os.getloadavg()
    back = xr.open_zarr(os.path.join(out, "map.zarr"))
    median = back["median_displacement_m"]
    sliding = float((median > 0).mean())
    print(f"terrain {n:,} x {n:,} = {n * n:,} cells of {CELL_M:g} m, {n_records} records x 2 polarities, "
          f"chunks {min(CHUNK, n)} x {min(CHUNK, n)}, 2 threads; tables {int(tables.counts.sum()):,} knots "
          f"({tables.counts.min()}-{tables.counts.max()} per member)")
    print(f"machine load (1-min average over its 2 cores, shared): {load_before[0]:.1f} before, "
          f"{load_after[0]:.1f} after")
    print_table(["step", "wall [s]", "CPU [s]"],
                [("tables (exact engine + exact dD/dky, JAX compile incl.)", f"{t_tables:.1f}", f"{cpu_tables:.1f}"),
                 ("map: slope, FS, ky, median D, P(D > 0.05 m) -> Zarr, 2 threads", f"{t_map:.1f}", f"{cpu_map:.1f}"),
                 ("total", f"{t_tables + t_map:.1f}", f"{cpu_tables + cpu_map:.1f}")])
    print(f"map: {1e9 * cpu_map / (n * n * len(tables.members)):.1f} ns of CPU per cell and record-polarity, "
          "everything included")
    print(f"cells with median D > 0: {100 * sliding:.1f} %; peak memory {peak_gb:.2f} GB")
    print(f"bar {BAR_S:g} s for the map written: {verdict(t_map < BAR_S, args.quick)} ({t_map:.1f} s)")
    print(f"bar {BAR_S:g} s with the tables built in the same run: "
          f"{verdict(t_tables + t_map < BAR_S, args.quick)} ({t_tables + t_map:.1f} s)")
    print(f"bar {BAR_GB:g} GB peak memory: {verdict(peak_gb < BAR_GB, args.quick)} ({peak_gb:.2f} GB)")
    print()
    _versus_pynewmarkdisp(records[0], tables, args.peer_side or (20 if args.quick else 100))
    print()
    _rectangular_pulse()
    return 0


def _terrain(n, chunk):
    """(DEM [m], zones, PGA [g]) of n x n cells, Dask arrays computed chunk by chunk."""
    import dask.array as da
    import rioxarray  # noqa: F401  (the .rio accessor)
    import xarray as xr

    x = 500_000.0 + CELL_M * np.arange(n)
    y = 4_100_000.0 - CELL_M * np.arange(n)

    def field(kind, block_info=None):
        (r0, r1), (c0, c1) = block_info[None]["array-location"]
        X, Y = np.meshgrid(CELL_M * np.arange(c0, c1), CELL_M * np.arange(r0, r1))
        if kind == "dem":
            return 80 * np.sin(X / 900) * np.cos(Y / 700) + 30 * np.sin(X / 130 + Y / 170) + 0.2 * X
        if kind == "zones":
            return np.where(np.sin(X / 2500) * np.cos(Y / 3100) > 0, 1.0, 2.0)
        side = n * CELL_M
        return 0.25 + 0.2 * np.exp(-((X - 0.4 * side) ** 2 + (Y - 0.6 * side) ** 2) / (0.3 * side) ** 2)

    arrays = []
    for kind in ("dem", "zones", "pga"):
        data = da.map_blocks(field, kind, chunks=((chunk,) * (n // chunk) + ((n % chunk,) if n % chunk else ()),) * 2,
                             dtype=float, meta=np.array((), dtype=float))
        arrays.append(xr.DataArray(data, dims=("y", "x"), coords={"x": x, "y": y}).rio.write_crs("EPSG:32611"))
    return arrays


def _versus_pynewmarkdisp(record, tables, side):
    """Time per cell and the differences on side x side cells, one record, the normal polarity."""
    try:
        from pynewmarkdisp.spatial import spatial_newmark
    except ImportError:
        print("pyNewmarkDisp is not installed (pip install pynewmarkdisp): its comparison is skipped")
        return
    rng = np.random.default_rng(0)
    pga_g = record.peak_acceleration / bd.STANDARD_GRAVITY
    ky = pga_g * rng.uniform(0.05, 0.6, (side, side))
    time_s, accel = record.sample_times, record.acceleration_m_s2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spatial_newmark(time_s, accel, ky[:1, :1], 9.81)  # its first call compiles (numba)
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        theirs = spatial_newmark(time_s, accel, ky * bd.STANDARD_GRAVITY / 9.81, 9.81)
    t_theirs = time.perf_counter() - start
    one = tables.select(record.name, "normal")
    repeat = 200
    start = time.perf_counter()
    for _ in range(repeat):
        ours = one.displacement(ky, pga_g)[0]
    t_ours = (time.perf_counter() - start) / repeat
    exact_to_end = np.asarray(bd.newmark(record, ky.ravel(), polarity="normal", t_end=record.duration).normal)
    cells = ky.size
    print(f"pyNewmarkDisp spatial_newmark vs the tables: {cells:,} cells, {record.name} (normal polarity), "
          f"ky/PGA 0.05-0.6")
    print_table(["", "per cell [ms]", "total [s]"],
                [("pyNewmarkDisp (a Python loop, trapezoid, D at the record's end)",
                  f"{1e3 * t_theirs / cells:.4f}", f"{t_theirs:.3f}"),
                 ("blockdae: the record's table (mean of 200 calls)", f"{1e3 * t_ours / cells:.6f}", f"{t_ours:.5f}")])
    print(f"per-cell speed-up: {t_theirs / t_ours:,.0f}x")
    sliding = exact_to_end.reshape(ky.shape) > 0.01
    rel_end = (theirs - exact_to_end.reshape(ky.shape))[sliding] / exact_to_end.reshape(ky.shape)[sliding]
    rel_rest = (theirs - ours)[sliding] / ours[sliding]
    print(f"pyNewmarkDisp - exact, cells with D > 1 cm ({np.count_nonzero(sliding):,}): against D at the record's end "
          f"{100 * rel_end.min():+.1f} % to {100 * rel_end.max():+.1f} % (median {100 * np.median(rel_end):+.1f} %); "
          f"against D at rest {100 * rel_rest.min():+.1f} % to {100 * rel_rest.max():+.1f} %")


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
