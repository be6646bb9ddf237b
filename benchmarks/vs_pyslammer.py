"""Exact backend against pySLAMMER's rigid (Newmark) analysis on its 18 sample records.

One-way sliding: pySLAMMER's block slides "downslope" (positive) while the ground
acceleration exceeds ky g; ours is ``SlidingBlock(mu=ky, direction="negative")`` with
u = -(their displacement). Both stop at the record's last sample (pySLAMMER integrates
sample by sample to the last one; ours runs with ``t_end = record.duration``); how much a
block still sliding there adds until it comes to rest is printed apart. Accuracy:
pySLAMMER's relative difference from the exact answer at ky = fractions of each record's
PGA, its median and largest over all the analyses. Speed (one-way): a warm single run at
ky = 0.1 through ``bd.simulate``, and a 64-value ky grid (0.05-0.3) batched through
``bd.simulate``, each beside pySLAMMER and beside the limit, a bare compiled loop that
only reads the record once; every side warmed by one call, then timed alike (the median
of --repeat calls). Then, in fresh processes, a user's loop (180 analyses:
every record read from its file, scaled to a target PGA, both polarities, five ky;
compilation included), and 10^6 analyses with final numbers only (``bd.simulate(..., final_only=True)``).

    python benchmarks/vs_pyslammer.py [--quick]
"""

import argparse
import importlib.resources
import os
import subprocess
import sys
import tempfile
import time

import numba
import numpy as np
import pyslammer

import blockdae as bd
from _common import G, print_table, sample_records, timed, verdict

#: bar name -> (bound, whether the value must be at least (True) or at most the bound)
BARS = {
    "warm speed-up, aggregate [x]": (100.0, True),
    "warm speed-up, worst record [x]": (30.0, True),
    "grid speed-up per analysis, aggregate [x]": (1000.0, True),
    "first call in this process [s]": (2.0, False),
    "user loop in a fresh process [s]": (2.0, False),
    "10^6 analyses, final numbers [s]": (60.0, False),
}

_USER_LOOP = """
import pathlib, sys, time
start = time.perf_counter()
import blockdae as bd
G, read = 9.80665, 0.0
paths = sorted(pathlib.Path(sys.argv[1]).glob("*.csv"))[: int(sys.argv[2])]
n = 0
for path in paths:
    tic = time.perf_counter()
    record = bd.read_record(path, units="g", g=G)
    read += time.perf_counter() - tic
    record = record.scaled(0.3 * G / record.peak_acceleration)  # target PGA 0.3 g
    for motion in (record, record.inverted()):
        for ky in (0.05, 0.1, 0.15, 0.2, 0.25):
            u = -bd.simulate(bd.SlidingBlock(mu=ky, direction="negative", g=G), motion).displacement
            n += 1
print(n, time.perf_counter() - start, read)
"""


@numba.njit
def _read_once(a):
    """The limit: one pass over the samples that only reads them."""
    total = 0.0
    for x in a:
        total += x
    return total


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="2 short records, small grid (smoke run)")
    parser.add_argument("--ratios", type=float, nargs="+", default=(0.1, 0.3, 0.5, 0.7),
                        help="ky as fractions of each record's PGA, for accuracy [-]")
    parser.add_argument("--grid", type=int, default=64, help="ky values in the batched grid (0.05-0.3)")
    parser.add_argument("--repeat", type=int, default=20, help="warm repetitions (median) per timing")
    parser.add_argument("--analyses", type=int, default=10**6, help="analyses with final numbers only")
    args = parser.parse_args(argv)
    if args.quick:
        args.ratios, args.grid, args.repeat, args.analyses = (0.3, 0.6), 8, 2, 10**4
    records = sample_records(args.quick)
    print(f"exact backend (numba, {numba.get_num_threads()} threads) vs pySLAMMER {pyslammer.__version__} "
          f"RigidAnalysis, one-way, g = {G} m/s²; accuracy at ky = {', '.join(f'{r:g}' for r in args.ratios)} "
          f"x PGA, both to the record's last sample; speed at ky = 0.1 and on a grid of {args.grid} ky in "
          f"0.05-0.3; warm times: median of {args.repeat} calls on every side, after one\n")
    rows, summary = [], []
    for record in records:
        row, numbers = _compare(record, args)
        rows.append(row)
        summary.append(numbers)
    headers = ["record", "samples", *(f"u({r:g}PGA) [m]" for r in args.ratios),
               *(f"diff({r:g}PGA) [%]" for r in args.ratios), "pySLAMMER [ms]", "exact warm [us]",
               "speed-up [x]", "grid [us/an.]", "grid speed-up [x]", "limit [us]", "exact [ns/sample]",
               "limit [ns/sample]", "first call [s]"]
    print_table(headers, rows)
    measured = _summarize(summary)
    measured["user loop in a fresh process [s]"] = _user_loop(len(records), cold=not args.quick,
                                                             repeat=1 if args.quick else 3)
    measured["10^6 analyses, final numbers [s]"] = _final_numbers(records, args.analyses)
    met = _report_bars(measured, args)
    return 0 if met or args.quick else 1


def _compare(record, args):
    """One table row (strings) and the numbers of the summary: a dict of per-analysis
    arrays (pySLAMMER's |diff| [%], the block's further slide after the last sample [%]) and
    per-record times (pySLAMMER s, single s, grid s per analysis, limit s, samples, first call s)."""
    ground = pyslammer.GroundMotion(record.acceleration_samples / G, record.dt, record.name)
    t_end = record.duration  # pySLAMMER's last sample, on both sides
    exact, diffs, further, first = [], [], [], None
    for k in np.asarray(args.ratios) * record.peak_acceleration / G:
        block = bd.SlidingBlock(mu=k, direction="negative", g=G)
        ours, first_k, _ = timed(lambda: bd.simulate(block, record, t_end), 0)
        first = first_k if first is None else first
        theirs = pyslammer.RigidAnalysis(k, ground).max_sliding_disp
        u = -ours.displacement
        at_rest = -bd.simulate(block, record).displacement
        exact.append(u)
        diffs.append(100 * (theirs - u) / u if abs(u) > 1e-9 else np.nan)
        further.append(100 * (at_rest - u) / u if abs(u) > 1e-9 else np.nan)
    block = bd.SlidingBlock(mu=0.1, direction="negative", g=G)
    _, _, t_single = timed(lambda: bd.simulate(block, record, t_end), args.repeat)
    _, _, t_theirs = timed(lambda: pyslammer.RigidAnalysis(0.1, ground).max_sliding_disp, args.repeat)
    grid = bd.SlidingBlock(mu=np.linspace(0.05, 0.3, args.grid), direction="negative", g=G)
    _, _, t_grid = timed(lambda: bd.simulate(grid, record, t_end), args.repeat)
    samples = record.acceleration_samples
    _, _, t_limit = timed(lambda: _read_once(samples), args.repeat)
    per_analysis, n = t_grid / args.grid, samples.size
    row = (record.name, str(n), *(f"{u:.4f}" for u in exact), *(_percent(d) for d in diffs),
           f"{1e3 * t_theirs:.2f}", f"{1e6 * t_single:.1f}", f"{t_theirs / t_single:.0f}",
           f"{1e6 * per_analysis:.2f}", f"{t_theirs / per_analysis:.0f}", f"{1e6 * t_limit:.2f}",
           f"{1e9 * t_single / n:.1f}", f"{1e9 * t_limit / n:.2f}", f"{first:.2f}")
    return row, {"diff": np.array(diffs), "further": np.array(further),
                 "times": (t_theirs, t_single, per_analysis, t_limit, n, first)}


def _percent(d):
    return "no slip" if np.isnan(d) else f"{d:+.2f}"


def _summarize(summary):
    diff = np.abs(np.concatenate([s["diff"] for s in summary]))
    further = np.concatenate([s["further"] for s in summary])
    theirs, single, grid, limit, samples, first = np.array([s["times"] for s in summary]).T
    slid = diff[~np.isnan(diff)]
    print(f"\npySLAMMER vs exact, both to the last sample, over the {slid.size} analyses that slide (of "
          f"{diff.size}): |difference| median {np.median(slid):.2f} %, largest {np.max(slid):.1f} %")
    moving = further[~np.isnan(further)]
    print(f"the exact block's further slide from the last sample to rest: median {np.median(moving):.2g} %, "
          f"largest {np.max(moving):.2g} % of u at the last sample ({np.count_nonzero(moving > 0)} of "
          f"{moving.size} analyses still sliding there)")
    print(f"per sample, all records: exact single run {1e9 * single.sum() / samples.sum():.2f} ns, grid "
          f"{1e9 * grid.sum() / samples.sum():.2f} ns per analysis, limit (read once) "
          f"{1e9 * limit.sum() / samples.sum():.2f} ns: single run {single.sum() / limit.sum():.1f}x the "
          f"limit, grid {grid.sum() / limit.sum():.1f}x")
    return {"warm speed-up, aggregate [x]": theirs.sum() / single.sum(),
            "warm speed-up, worst record [x]": np.min(theirs / single),
            "grid speed-up per analysis, aggregate [x]": theirs.sum() / grid.sum(),
            "first call in this process [s]": np.max(first)}


def _user_loop(n_records, cold, repeat=3):
    """Seconds of the user's loop in a fresh process with numba's disk cache filled
    (median of ``repeat`` processes); with ``cold``, first in an empty cache (compiling
    the engine), which fills it."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache) if cold else None
        first = _run_user_loop(n_records, env) if cold else None
        runs = sorted(_run_user_loop(n_records, env) for _ in range(repeat))
    seconds, n, read = runs[len(runs) // 2]
    compiling = f"{first[0]:.2f} s compiling the engine, " if cold else ""
    print(f"\nuser's loop, fresh process: {n} analyses ({n_records} records read from file, scaled to PGA 0.3 g, "
          f"both polarities, 5 ky): {compiling}{seconds:.2f} s with numba's disk cache (median of {repeat} "
          f"processes: {', '.join(f'{r[0]:.2f}' for r in runs)} s; reading the files {read:.2f} s)")
    return seconds


def _run_user_loop(n_records, env):
    """(wall seconds, analyses, seconds reading files) of one fresh process."""
    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", _USER_LOOP, str(folder), str(n_records)], env=env, check=True,
                         capture_output=True, text=True).stdout.split()
    return time.perf_counter() - start, int(out[0]), float(out[2])


def _final_numbers(records, n_analyses):
    """Seconds for ``n_analyses`` (records x equal share of a ky grid), final numbers only."""
    per_record = -(-n_analyses // len(records))
    block = bd.SlidingBlock(mu=np.linspace(0.05, 0.3, per_record), direction="negative", g=G)
    # compile (or load) outside the timing the kernel that the timed call runs: the whole grid on
    # the shortest record takes the same one (two ky values alone would take the serial kernel)
    bd.simulate(block, [min(records, key=lambda r: r.acceleration_samples.size)], final_only=True)
    start = time.perf_counter()
    final = bd.simulate(block, records, final_only=True)
    seconds = time.perf_counter() - start
    print(f"{final.displacement.size} analyses ({len(records)} records x {per_record} ky), final numbers only: "
          f"{seconds:.2f} s ({1e6 * seconds / final.displacement.size:.2f} us per analysis, "
          f"{numba.get_num_threads()} threads)")
    return seconds


def _report_bars(measured, args):
    """Print every bar with its verdict; whether all are met."""
    print("\nbars:")
    met = True
    for name, (bound, at_least) in BARS.items():
        value = measured[name]
        ok = value >= bound if at_least else value <= bound
        met &= ok
        print(f"  {name:<42} {value:10.2f}  bar {'>=' if at_least else '<='} {bound:g}: "
              f"{verdict(ok, args.quick)}")
    return met


if __name__ == "__main__":
    sys.exit(main())
