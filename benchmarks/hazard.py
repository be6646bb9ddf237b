"""Issue 26: a 10^5-analysis study (18 records x 8 ky x 700 PGA, the compiled 1-D engine)
with its fragilities (one per ky, 200 bootstrap refits each) and displacement hazard
curves from a power-law PGA hazard curve, in one run; the bar: under 60 s on 2 cores.

    python benchmarks/hazard.py [--quick]
"""

import argparse
import time

import numpy as np

import blockdae as bd
from _common import print_table, sample_records, verdict

BAR_S = 60.0  # study + fragilities, on the 2-core machine
D_M = 0.05  # the displacement of the printed fragility [m]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="2 short records, a small grid (smoke run)")
    args = parser.parse_args(argv)
    records = sample_records(quick=args.quick)
    ky = np.linspace(0.05, 0.3, 2 if args.quick else 8)
    pga = np.geomspace(0.02, 1.5, 12 if args.quick else 700)
    bd.study(records[:1], ky[:1], pga=pga[:2], progress=False)  # compile (or load) the engine first
    start = time.perf_counter()
    table = bd.study(records, ky, pga=pga, progress=False)
    t_study = time.perf_counter() - start
    if args.quick:  # 2 records: too few to fit; repeat them under other names
        table = _renamed(table, 5)
    start = time.perf_counter()
    fits = {k: bd.hazard.fit_fragility(table[table.mu == k], "pga_g", d0_m=0.01, n_boot=200, seed=0) for k in ky}
    t_fit = time.perf_counter() - start
    x = np.geomspace(0.01, 3.0, 60)
    curve = bd.hazard.HazardCurve(x, 1e-4 * x**-2.5)  # a power-law PGA hazard curve [1/yr]
    d = np.geomspace(0.005, 1.0, 30)
    start = time.perf_counter()
    rates = {k: bd.hazard.displacement_hazard(curve, f, d) for k, f in fits.items()}
    t_hazard = time.perf_counter() - start
    rows = []
    for k, f in fits.items():
        jibson = bd.hazard.EmpiricalFragility(bd.empirical.jibson_2007, "pga_g", {"ky_g": k})
        low, high = f.band(D_M, 0.5)
        rows.append((f"{k:.3f}", f"{f.exceedance(D_M, 0.5):.3f}", f"{low:.3f}-{high:.3f}",
                     f"{jibson.exceedance(D_M, 0.5):.3f}", f"{rates[k][np.searchsorted(d, D_M)]:.2e}",
                     f"{bd.hazard.displacement_hazard(curve, jibson, D_M):.2e}"))
    print_table(("ky [g]", "P(D>5cm|0.5g) fit", "90% band", "Jibson 2007", "rate D>5cm fit [1/yr]",
                 "rate Jibson [1/yr]"), rows)
    total = t_study + t_fit
    print(f"\nstudy: {len(table):,} analyses ({len(records)} records x {ky.size} ky x {pga.size} PGA) in "
          f"{t_study:.2f} s; fragilities ({ky.size} fits x 200 bootstrap refits) in {t_fit:.2f} s; "
          f"hazard curves ({ky.size} x {d.size} displacements) in {t_hazard:.3f} s")
    print(f"study + fragilities {total:.1f} s (bar {BAR_S:g} s): {verdict(total <= BAR_S, args.quick)}")
    return 0 if total <= BAR_S or args.quick else 1


def _renamed(table, copies):
    import pandas as pd

    return pd.concat([table.assign(record=table.record + f"#{i}") for i in range(copies)], ignore_index=True)


if __name__ == "__main__":
    raise SystemExit(main())
