"""Two horizontal components projected on each cell's dip azimuth: the Northridge 1994
Beverly Hills - Mulholland pair of the FEMA P695 far-field set (MUL009 and MUL279,
azimuths 9 and 279 deg), both polarities, on the stable cells of a synthetic terrain whose
every cell has its own dip azimuth; exact engine per cell. Prints cells per second (wall
and CPU) beside the same cells under one component alone (its table and the exact engine).

    python benchmarks/regional_pairs.py [--quick] [--size N]
"""

import argparse
import os
import time

import numpy as np

import blockdae as bd
from _common import print_table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a 30 x 30 terrain (smoke run)")
    parser.add_argument("--size", type=int, default=None, help="cells along each side (default 100)")
    args = parser.parse_args(argv)
    import rioxarray  # noqa: F401  (the .rio accessor)
    import xarray as xr
    from blockdae import regional as rg

    n = args.size or (30 if args.quick else 100)
    suite = bd.RecordSet.fema_p695("far-field")
    first, second = suite["NORTHR/MUL009"], suite["NORTHR/MUL279"]
    pair = rg.RecordPair(first, second, azimuths_deg=(9, 279))
    x, y = 500_000 + 10.0 * np.arange(n + 2), 4_100_000 - 10.0 * np.arange(n + 2)
    X, Y = np.meshgrid(x - x[0], y - y[0])
    dem = xr.DataArray(40 * np.sin(X / 90) * np.cos(Y / 70) + 0.3 * X, dims=("y", "x"),
                       coords={"x": x, "y": y}).rio.write_crs("EPSG:32611")
    strength = {"cohesion_kpa": 4.0, "friction_deg": 32.0, "unit_weight_kn_m3": 19.0}
    kwargs = dict(thickness_m=2.0, thresholds_m=(0.05,), per_record=True, regressions=False)
    rg.displacement_map(dem.isel(x=slice(0, 6), y=slice(0, 6)), strength, pair, 0.4, **kwargs)  # compile
    load = os.getloadavg()[0]
    start = time.perf_counter()
    tables = rg.DisplacementTables.build(first, "both", atol_m=1e-6 / rg.MAX_PGA_G)
    print(f"MUL009's tables of D(ky/PGA) built in {time.perf_counter() - start:.1f} s (not in the table below)")
    rows, maps = [], {}
    for label, motion, method in [("pair projected on each cell's dip azimuth", pair, "exact"),
                                  ("MUL009 alone", None, "exact"), ("MUL009 alone", None, "table")]:
        start, cpu = time.perf_counter(), time.process_time()
        ds = rg.displacement_map(dem, strength, motion, 0.4, method=method,
                                 tables=None if motion is pair else tables, **kwargs)
        wall, cpu = time.perf_counter() - start, time.process_time() - cpu
        stable = int((ds["category"] == 1).sum())
        maps[(label, method)] = ds
        rows.append((label, method, f"{stable:,}", f"{wall:.2f}", f"{cpu:.2f}", f"{stable / wall:,.0f}",
                     f"{stable / cpu:,.0f}"))
    azimuths = maps[(rows[0][0], "exact")]["dip_azimuth_deg"].where(maps[(rows[0][0], "exact")]["category"] == 1)
    distinct = np.unique(azimuths.values[np.isfinite(azimuths.values)]).size
    print(f"terrain {n + 2} x {n + 2} cells of 10 m, PGA 0.4 g (the larger component's peak), both polarities; "
          f"{distinct:,} distinct dip azimuths among the stable cells; machine load {load:.1f} on its 2 cores")
    print_table(["motion", "method", "stable cells", "wall [s]", "CPU [s]", "cells/s (wall)", "cells/s (CPU)"], rows)
    d_pair = maps[(rows[0][0], "exact")]["median_displacement_m"].values
    d_one = maps[("MUL009 alone", "exact")]["median_displacement_m"].values
    ok = np.isfinite(d_pair) & (d_one > 0.001)
    print(f"median D of the pair over that of MUL009 alone at the stable cells with D > 1 mm: "
          f"{np.min(d_pair[ok] / d_one[ok]):.3f} to {np.max(d_pair[ok] / d_one[ok]):.3f} (median "
          f"{np.median(d_pair[ok] / d_one[ok]):.3f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
