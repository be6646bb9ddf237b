"""The seed-002 study grid: 18 records × 3 μ × 20 PGA × (ground + 5 floors × 3 frames) =
17,280 analyses, frame responses included; local vs a 2-worker Dask LocalCluster.

    python benchmarks/study.py [--quick] [--repeat N]
"""

import argparse
import time
import tracemalloc

import numpy as np

import blockdae as bd
from _common import print_table, sample_records, timed, verdict

BAR_S = 5.0  # the full grid, warm, on this 2-core machine


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="2 short records, a small grid (smoke run)")
    parser.add_argument("--repeat", type=int, default=3, help="warm repetitions (median) per timing")
    parser.add_argument("--no-dask", action="store_true", help="local runs only")
    args = parser.parse_args(argv)
    records = sample_records(quick=args.quick)
    periods = (0.3,) if args.quick else (0.2, 0.3, 0.5)
    mu = [0.1, 0.3] if args.quick else [0.1, 0.2, 0.3]
    pga = np.linspace(0.05, 1.0, 3 if args.quick else 20)
    where = ["ground"] + [bd.ShearFrame(5, T, 0.05).floor(i) for T in periods for i in range(1, 6)]
    repeat = 1 if args.quick else args.repeat
    run = lambda **kw: bd.study(records, mu=mu, pga=pga, where=where, direction="negative", progress=False, **kw)
    n = len(records) * len(where) * len(mu) * len(pga)
    print(f"{len(records)} records × {len(mu)} mu × {len(pga)} PGA × {len(where)} locations = {n} analyses "
          f"(one-way block, until rest; floors refined 4x; warm: median of {repeat})")

    table, first, warm = timed(run, repeat)
    rows = [("local (numba, all cores)", f"{first:.2f}", f"{warm:.2f}", f"{n / warm:,.0f}",
             verdict(warm < BAR_S, args.quick, "FAIL"))]
    if not args.no_dask:
        rows.append(_dask_row(run, table, n, repeat, args.quick))
    print_table(["engine", "first call [s]", "warm [s]", "analyses/s", f"bar < {BAR_S:g} s"], rows)

    samples = sum(r.acceleration_samples.size for r in records)
    tracemalloc.start()
    run()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    largest = max(r.acceleration_samples.size for r in records)
    copies = n * 4 * samples / len(records) * 8  # one scaled (floor: 4x refined) copy per analysis
    print(f"\nmemory (tracemalloc, numpy arrays): peak {peak / 2**20:.0f} MiB, set by the largest task "
          f"(the longest record has {largest:,} samples, {len(where)} locations, floors 4x refined; "
          f"all {samples:,} ground samples: {samples * 8 / 2**20:.1f} MiB); a scaled copy per analysis "
          f"would need ~{copies / 2**30:.1f} GiB")
    s = bd.studies.summary(table)
    ground = s[(s["floor"] == 0) & (s["pga_g"] == pga[-1])]
    print(f"\nsummary, ground, PGA {pga[-1]:g} g (means over {len(records)} records):")
    print_table(["mu [-]", "R_c [m]", "Sd [m]", "R_d eq.3 [m]", "adjusted R_d [m]"],
                [(f"{r.mu:g}", f"{r.rc_m:.4f}", f"{r.sd_m:.4f}", f"{r.rd_m:.4f}", f"{r.rd_adjusted_m:.4f}")
                 for r in ground.itertuples()])
    return 0 if warm < BAR_S or args.quick else 1


def _dask_row(run, table, n, repeat, quick):
    from distributed import Client, LocalCluster

    start = time.perf_counter()
    with LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        up = time.perf_counter() - start
        on_dask, first, warm = timed(lambda: run(executor=client), repeat)
    same = on_dask.equals(table)
    return (f"Dask LocalCluster 2x1 (start {up:.1f} s){'' if same else ' DIFFERS'}", f"{first:.2f}",
            f"{warm:.2f}", f"{n / warm:,.0f}", verdict(warm < BAR_S, quick, "FAIL"))


if __name__ == "__main__":
    raise SystemExit(main())
