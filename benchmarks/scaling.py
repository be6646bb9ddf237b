"""Cost of the exact backend against record length and parameter-grid size (should be linear).

    python benchmarks/scaling.py [--quick] [--cache-dir DIR]
"""

import argparse
import sys

import numpy as np

import blockdae as bd
from _common import G, enable_compilation_cache, print_table, synthetic_record, timed


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes (smoke run)")
    parser.add_argument("--repeat", type=int, default=5, help="warm repetitions (median) per timing")
    parser.add_argument("--cache-dir", default=None, help="JAX persistent compilation cache folder")
    args = parser.parse_args(argv)
    lengths = (250, 500) if args.quick else (1000, 2000, 4000, 8000, 16000, 32000)
    grids = (2, 4) if args.quick else (4, 16, 64, 256)
    repeat = 1 if args.quick else args.repeat
    enable_compilation_cache(args.cache_dir)
    block = bd.SlidingBlock(mu=0.15, g=G)  # two-way; synthetic records peak at 0.5 g, dt = 0.01 s

    print(f"record length (mu = 0.15, two-way, warm: median of {repeat})")
    rows, warm = [], []
    for n in lengths:
        record = synthetic_record(n)
        solution, first, t = timed(lambda: bd.simulate(block, record), repeat)
        warm.append(t)
        rows.append((str(n), str(len(solution.events)), f"{first:.2f}", f"{1e3 * t:.2f}", f"{1e6 * t / n:.3f}"))
    print_table(["samples", "events", "first call [s]", "warm [ms]", "warm per sample [us]"], rows)
    print(f"log-log slope of warm time against length: {_slope(lengths, warm):.2f} (1 = linear)\n")

    record = synthetic_record(lengths[-1] // 2)
    print(f"grid size on {record.acceleration_samples.size} samples (mu from 0.05 to 0.45, batched)")
    rows, warm = [], []
    for n in grids:
        grid = bd.SlidingBlock(mu=np.linspace(0.05, 0.45, n), g=G)
        _, first, t = timed(lambda: bd.simulate(grid, record), repeat)
        warm.append(t)
        rows.append((str(n), f"{first:.2f}", f"{1e3 * t:.2f}", f"{1e3 * t / n:.3f}"))
    print_table(["parameter sets", "first call [s]", "warm [ms]", "warm per analysis [ms]"], rows)
    print(f"log-log slope of warm time against grid size: {_slope(grids, warm):.2f} (1 = linear; the "
          "parameter sets run one after another in one compiled call)")
    return 0


def _slope(sizes, seconds):
    return float(np.polyfit(np.log(sizes), np.log(seconds), 1)[0])


if __name__ == "__main__":
    sys.exit(main())
