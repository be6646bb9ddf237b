"""Many motions in one call: the batched paths over pySLAMMER's 18 sample records, timed.

Three workloads, each the median of warm repeats (compilation outside the timing):
Newmark's sweep (``bd.newmark``: 18 records x 2 target PGAs x 2 polarities x 50 ky), final
numbers only (18 records x 4 scales x 50 ky), and full runs of a grid over many motions
(the same cases, each a batch solution kept). The script runs on any version of the
package: where ``bd.simulate`` takes many motions it times that, else the functions it
replaced (``simulate_final``, ``simulate_many``), so one run on each version compares them.

    python benchmarks/many_motions.py [--repeat 5]
"""

import argparse
import warnings

import numpy as np

import blockdae as bd
from _common import print_table, sample_records, timed

KY = np.linspace(0.02, 0.3, 50)
SCALES = [0.5, 1.0, 1.5, 2.0]
PGA = [0.2, 0.4]


def _takes_many_motions() -> bool:
    return hasattr(bd, "Ensemble")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="warm repeats per workload (their median)")
    args = parser.parse_args()
    warnings.simplefilter("ignore", DeprecationWarning)
    warnings.simplefilter("ignore", bd.UnitsWarning)  # ky above the lower target PGA: D = 0 there, as meant
    records = sample_records()
    grid = bd.SlidingBlock(mu=KY, direction="negative")
    many = _takes_many_motions()
    if many:
        final = lambda: bd.simulate(grid, records, scale=SCALES, final_only=True)
        full = lambda: bd.simulate(grid, records, scale=SCALES)
        names = ("bd.simulate(..., final_only=True)", "bd.simulate(grid, records, scale=...)")
    else:
        final = lambda: bd.sliding.simulate_final(grid, records, scale=SCALES)
        full = lambda: bd.sliding.simulate_many(grid, records, scale=SCALES)
        names = ("bd.sliding.simulate_final", "bd.sliding.simulate_many")
    workloads = [("bd.newmark (records x PGA x polarity x ky)", len(records) * len(PGA) * 2 * KY.size,
                  lambda: bd.newmark(records, KY, pga=PGA)),
                 (f"final numbers: {names[0]}", len(records) * len(SCALES) * KY.size, final),
                 (f"full runs: {names[1]}", len(records) * len(SCALES) * KY.size, full)]
    rows = []
    for name, n, action in workloads:
        _, first, warm = timed(action, args.repeat)
        rows.append([name, f"{n}", f"{1e3 * warm:.1f}", f"{1e6 * warm / n:.2f}"])
    print(f"blockdae {bd.__file__}; {len(records)} records, {KY.size} ky; median of {args.repeat} warm runs")
    print_table(["workload", "analyses", "time [ms]", "per analysis [us]"], rows)


if __name__ == "__main__":
    main()
