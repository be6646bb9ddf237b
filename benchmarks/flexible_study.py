"""A study of the flexible sliding mass: pySLAMMER's 18 records × 7 ky × 20 PGA = 2,520
analyses (both polarities each), local and on a 2-worker Dask LocalCluster, beside the
same analyses as 20 ``bd.flexible`` calls (one per target PGA), and a fragility fitted
to one ky of it.

    python benchmarks/flexible_study.py [--quick] [--repeat N] [--no-dask]
"""

import argparse
import time

import numpy as np
import pandas as pd

import blockdae as bd
from _common import print_table, sample_records, timed, verdict

HEIGHT_M, VS_M_S = 20.0, 300.0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the 10 shortest records (a fragility's fewest), a "
                                                             "small grid (smoke run)")
    parser.add_argument("--repeat", type=int, default=3, help="warm repetitions (median) per timing")
    parser.add_argument("--no-dask", action="store_true", help="local runs only")
    args = parser.parse_args(argv)
    records = sample_records()
    if args.quick:
        records = sorted(records, key=lambda r: r.acceleration_samples.size)[:10]
    ky = np.linspace(0.05, 0.35, 2 if args.quick else 7)
    pga = np.linspace(0.05, 1.0, 3 if args.quick else 20)
    repeat = 1 if args.quick else args.repeat
    mass = bd.FlexibleSlidingMass(bd.ShearColumn(HEIGHT_M, VS_M_S), ky=float(ky[0]))
    run = lambda **kw: bd.study(records, ky=ky, pga=pga, block=mass, progress=False, **kw)
    n = len(records) * len(ky) * len(pga)
    print(f"{len(records)} records × {len(ky)} ky × {len(pga)} PGA = {n} analyses of a coupled flexible mass "
          f"(H = {HEIGHT_M:g} m, Vs = {VS_M_S:g} m/s), both polarities; warm: median of {repeat}")

    table, first, warm = timed(run, repeat)
    by_calls = lambda: pd.concat([bd.flexible(records, ky=ky, height=HEIGHT_M, vs=VS_M_S, pga=a)
                                  .to_dataframe() for a in pga])
    peer, peer_first, peer_warm = timed(by_calls, repeat)
    worst = _largest_difference(table, peer, records, ky, pga)
    rows = [("bd.study, local", f"{first:.2f}", f"{warm:.2f}", f"{warm / n * 1e3:.2f}"),
            (f"{len(pga)} bd.flexible calls", f"{peer_first:.2f}", f"{peer_warm:.2f}", f"{peer_warm / n * 1e3:.2f}")]
    if not args.no_dask:
        rows.append(_dask_row(run, table, n, repeat))
    print_table(["run", "first call [s]", "warm [s]", "per analysis [ms]"], rows)
    print(f"\nlargest relative difference of normal_m, inverse_m from bd.flexible's: {worst:.1e} [-] "
          f"(the study scales a record to 1 g, then by the PGA: rounding)")
    print(f"bar: the study no slower than the bd.flexible calls ({warm:.2f} s vs {peer_warm:.2f} s): "
          f"{verdict(warm <= peer_warm, args.quick)}")

    one = table[table["ky_g"] == ky[1]]
    start = time.perf_counter()
    fit = bd.hazard.fit_fragility(one, im="pga_g", displacement=("normal_m", "inverse_m"),
                                  n_boot=0 if args.quick else 200)
    fit_s = time.perf_counter() - start
    print(f"\nfragility at ky = {ky[1]:g} g ({fit.n_rows} rows, {len(fit.boot)} bootstrap refits, {fit_s:.2f} s): "
          f"P(D > 5 cm | PGA 0.5 g) = {fit.exceedance(0.05, 0.5):.2f} [-], median D at 0.5 g = "
          f"{np.exp(fit.c0 + fit.c1 * np.log(0.5)):.3f} m above 1 cm")
    return 0 if warm <= peer_warm or args.quick else 1


def _largest_difference(table, peer, records, ky, pga):
    """max |study / bd.flexible - 1| over the displacements [-], rows matched by (record, ky, PGA)."""
    order = {r.name: i for i, r in enumerate(records)}
    peer = peer.assign(pga_g=np.repeat(pga, len(records) * len(ky)))
    peer = peer.sort_values(["record", "ky_g", "pga_g"], key=lambda c: c.map(order) if c.name == "record" else c,
                            kind="stable").reset_index(drop=True)
    worst = 0.0
    for name in ("normal_m", "inverse_m"):
        a, b = table[name].to_numpy(), peer[name].to_numpy()
        slid = b > 0
        worst = max(worst, float(np.max(np.abs(a[slid] / b[slid] - 1), initial=0.0)))
        assert np.array_equal(a[~slid], b[~slid])
    return worst


def _dask_row(run, table, n, repeat):
    from distributed import Client, LocalCluster

    start = time.perf_counter()
    with LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        up = time.perf_counter() - start
        on_dask, first, warm = timed(lambda: run(executor=client), repeat)
    same = "" if on_dask.equals(table) else " DIFFERS"
    return (f"bd.study, Dask LocalCluster 2x1 (start {up:.1f} s){same}", f"{first:.2f}", f"{warm:.2f}",
            f"{warm / n * 1e3:.2f}")


if __name__ == "__main__":
    raise SystemExit(main())
