"""Reading cost of the 18 sample CSVs: bd.read_record against numpy's own text parsing.

    python benchmarks/readers.py [--quick]
"""

import argparse
import importlib.resources
import time

import numpy as np

import blockdae as bd
from _common import print_table


def best(action, repeat):
    """Shortest of ``repeat`` wall times of ``action()`` [s]."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return min(times)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="3 files, 2 repetitions")
    args = parser.parse_args(argv)
    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    paths = sorted(p for p in folder.iterdir() if p.name.endswith(".csv"))
    repeat = 2 if args.quick else 7
    paths = paths[:3] if args.quick else paths
    rows, ours, numpy = [], 0.0, 0.0
    for path in paths:
        t_ours = best(lambda: bd.read_record(path), repeat)
        t_numpy = best(lambda: np.loadtxt(path, delimiter=",", comments="#", encoding="utf-8-sig"), repeat)
        ours, numpy = ours + t_ours, numpy + t_numpy
        rows.append((path.stem, f"{1e3 * t_ours:.2f}", f"{1e3 * t_numpy:.2f}", f"{t_ours / t_numpy:.2f}"))
    rows.append(("all", f"{1e3 * ours:.2f}", f"{1e3 * numpy:.2f}", f"{ours / numpy:.2f}"))
    print_table(["record", "read_record [ms]", "np.loadtxt [ms]", "ratio [-]"], rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
