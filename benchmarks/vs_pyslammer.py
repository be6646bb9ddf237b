"""Exact backend against pySLAMMER's rigid (Newmark) analysis on its 18 sample records.

One-way sliding: pySLAMMER's block slides "downslope" (positive) while the ground
acceleration exceeds ky g; ours is ``SlidingBlock(mu=ky, direction="negative")`` with
u = -(their displacement). Accuracy is pySLAMMER's relative difference from the exact
answer; speed is per analysis, warm (compiled), single and batched over a ky grid.

    python benchmarks/vs_pyslammer.py [--quick] [--cache-dir DIR]
"""

import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
import pyslammer

import blockdae as bd
from _common import G, enable_compilation_cache, print_table, sample_records, timed

BARS = {"warm speed-up (single)": 30.0, "speed-up per analysis (grid)": 1000.0, "first call [s]": 2.0}

_FIRST_CALL = """
import time, importlib.resources, blockdae as bd
p = importlib.resources.files("pyslammer") / "sample_ground_motions" / "Kobe_1995_TAK-090.csv"
rec = bd.read_record(p, units="g", g=9.80665)
start = time.perf_counter()
bd.simulate(bd.SlidingBlock(mu=0.1, direction="negative", g=9.80665), rec)
print(time.perf_counter() - start)
"""


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="2 short records, small grid (smoke run)")
    parser.add_argument("--ratios", type=float, nargs="+", default=(0.1, 0.3, 0.5, 0.7),
                        help="ky as fractions of each record's PGA [-]")
    parser.add_argument("--grid", type=int, default=64, help="ky values in the batched grid")
    parser.add_argument("--repeat", type=int, default=5, help="warm repetitions (median) per timing")
    parser.add_argument("--cache-dir", default=None, help="JAX persistent compilation cache folder")
    args = parser.parse_args(argv)
    if args.quick:
        args.ratios, args.grid, args.repeat = (0.3, 0.6), 8, 1
    enable_compilation_cache(args.cache_dir)

    records = sample_records(args.quick)
    print(f"exact backend vs pySLAMMER {pyslammer.__version__} RigidAnalysis, one-way, g = {G} m/s²; "
          f"ky = {', '.join(f'{r:g}' for r in args.ratios)} x PGA; grid of {args.grid} ky; "
          f"warm times: median of {args.repeat}\n")
    rows, summary = [], []
    for record in records:
        row, numbers = _compare(record, args)
        rows.append(row)
        summary.append(numbers)
    headers = ["record", "samples", *(f"u({r:g}PGA) [m]" for r in args.ratios),
               *(f"diff({r:g}PGA) [%]" for r in args.ratios),
               "pySLAMMER [ms]", "exact warm [ms]", "speed-up [x]", "grid [ms/an.]", "grid speed-up [x]",
               "first call [s]"]
    print_table(headers, rows)
    _summarize(np.array(summary), args)
    if not args.quick:
        _fresh_process_first_call()
    return 0


def _compare(record, args):
    """One table row (strings) and (max |diff| %, speed-up, grid speed-up, first call s)."""
    ground = pyslammer.GroundMotion(record.acceleration_samples / G, record.dt, record.name)
    ky = np.asarray(args.ratios) * record.peak_acceleration / G
    exact, diffs, t_theirs, t_ours, first = [], [], [], [], None
    for k in ky:
        block = bd.SlidingBlock(mu=k, direction="negative", g=G)
        ours, first_k, warm = timed(lambda: bd.simulate(block, record), args.repeat)
        first = first_k if first is None else first
        theirs, _, t_slammer = timed(lambda: pyslammer.RigidAnalysis(k, ground).max_sliding_disp, args.repeat)
        u = -ours.displacement
        exact.append(u)
        diffs.append(100 * (theirs - u) / u if abs(u) > 1e-9 else np.nan)
        t_theirs.append(t_slammer)
        t_ours.append(warm)
    grid = bd.SlidingBlock(mu=np.linspace(0.05, 0.95, args.grid) * record.peak_acceleration / G,
                           direction="negative", g=G)
    _, _, t_grid = timed(lambda: bd.simulate(grid, record), args.repeat)
    per_analysis = t_grid / args.grid
    speed, grid_speed = np.median(t_theirs) / np.median(t_ours), np.median(t_theirs) / per_analysis
    row = (record.name, str(record.acceleration_samples.size), *(f"{u:.4f}" for u in exact),
           *(_percent(d) for d in diffs), f"{1e3 * np.median(t_theirs):.1f}",
           f"{1e3 * np.median(t_ours):.2f}", f"{speed:.1f}", f"{1e3 * per_analysis:.3f}",
           f"{grid_speed:.0f}", f"{first:.2f}")
    return row, (np.nanmax(np.abs(diffs), initial=0.0), speed, grid_speed, first)


def _percent(d):
    return "no slip" if np.isnan(d) else f"{d:+.2f}"


def _summarize(summary, args):
    diff, speed, grid_speed, first = summary.T
    print(f"\npySLAMMER vs exact: largest |difference| {np.max(diff):.1f} % (median over records "
          f"{np.median(diff):.2f} %)")
    measured = {"warm speed-up (single)": np.min(speed), "speed-up per analysis (grid)": np.min(grid_speed),
                "first call [s]": np.max(first)}
    print("bars (worst record):")
    for name, bar in BARS.items():
        value = measured[name]
        ok = value <= bar if name.startswith("first") else value >= bar
        print(f"  {name:<30} {value:10.2f}  bar {'<=' if name.startswith('first') else '>='} {bar:g}: "
              f"{'met' if ok else 'NOT met'}")
    print("  (first call in this process: includes compiling each new kernel shape)")


def _fresh_process_first_call():
    """First call in a new interpreter (Kobe, ky = 0.1 g): cold, then with a filled cache."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, JAX_COMPILATION_CACHE_DIR=cache)
        times = [float(subprocess.run([sys.executable, "-c", _FIRST_CALL], env=env, check=True,
                                      capture_output=True, text=True).stdout) for _ in range(2)]
    print(f"first call in a fresh process (Kobe, ky = 0.1 g): {times[0]:.2f} s without a compilation "
          f"cache, {times[1]:.2f} s with JAX's persistent cache filled")


if __name__ == "__main__":
    sys.exit(main())
