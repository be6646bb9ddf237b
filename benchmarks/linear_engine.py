"""The compiled linear engine (issue 21) on the spring-supported mass, in one run.

Per case of ``benchmarks/upthrow.py`` (a 10 Hz sine train, undamped bouncing, the 18
pySLAMMER records as vertical motion at 0.6 g, 5 and 10 Hz, 5 %, first 15 s, the cases
that fly): the largest event-time difference of the compiled engine from the Python
closed-form path [s] (the bar: 4e-14 s, a decade above the 4.0e-15 s measured), and warm
wall times [s] (median of --repeat) of the compiled engine, the Python path and CVODE at
rtol 1e-10, with the ratio CVODE / compiled (the bar: >= 500x, median). Then final
numbers of records x frequencies x damping x scales (the bar: 1e5 analyses under 10 s),
and the first call in a fresh process with numba's cache cold and warm (the bar: under
3 s warm). The script exits
with 1 where a bar is not met.

    python benchmarks/linear_engine.py [--quick] [--repeat N]
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import blockdae as bd
from _common import G, print_table, sample_records, timed, verdict
from upthrow import cases, differences

BAR_DT, BAR_RATIO, BAR_BATCH, BAR_FIRST = 4e-14, 500.0, 10.0, 3.0  # [s], [-], [s], [s]
FIRST_CALL = ("import time, blockdae as bd\n"
              "rec = bd.Record([0.0, -12.0, 3.0, -12.0, 0.0] * 40, dt=0.01, units=\"m/s2\")\n"
              "start = time.perf_counter()\n"
              "bd.simulate(bd.SpringSupportedMass(5.0, 0.05), rec, t_end=1.9)\n"
              "print(time.perf_counter() - start)\n")


def per_case(quick, repeat):
    rows, ratios, worst = [], [], 0.0
    for label, mass, motion, t_end in cases(quick):
        compiled, _, t_compiled = timed(lambda: bd.simulate(mass, motion, t_end=t_end), repeat)
        python, _, t_python = timed(lambda: bd.simulate(mass, motion, t_end=t_end, linear="python"), 1)
        _, _, t_cvode = timed(lambda: bd.simulate(mass, motion, t_end=t_end, backend="cvode", rtol=1e-10), 1)
        dt, _ = differences(compiled, python)
        worst = max(worst, dt)
        ratios.append(t_cvode / t_compiled)
        rows.append((label, str(len(compiled.events)), f"{dt:.1e}", f"{t_compiled * 1e3:.2f}",
                     f"{t_python:.3f}", f"{t_cvode:.3f}", f"{t_cvode / t_compiled:.0f}x"))
    print_table(("case", "events", "max |dt| vs Python [s]", "compiled [ms]", "Python [s]", "CVODE [s]",
                 "CVODE / compiled"), rows)
    median = statistics.median(ratios)
    print(f"worst event-time difference {worst:.1e} s (bar {BAR_DT:g} s): {verdict(worst <= BAR_DT, quick)}")
    print(f"median CVODE / compiled {median:.0f}x (bar {BAR_RATIO:.0f}x): {verdict(median >= BAR_RATIO, quick)}")
    return worst <= BAR_DT and median >= BAR_RATIO


def batch(quick):
    records = sample_records(quick)
    motions = {r.name: r.scaled(G / r.peak_acceleration) for r in records}
    frequencies = np.linspace(3.0, 12.0, 4 if quick else 10)
    models = [bd.SpringSupportedMass(f, z) for f in frequencies for z in (0.02, 0.05, 0.1, 0.15, 0.2)]
    scales = np.linspace(0.2, 1.5, 3 if quick else 111)
    bd.solvers.simulate_linear_final(models, motions, 15.0, scales[:1])  # compiled (or loaded) first
    start = time.perf_counter()
    table = bd.solvers.simulate_linear_final(models, motions, 15.0, scales)
    wall = time.perf_counter() - start
    print(f"final numbers: {len(table)} analyses ({len(records)} records x {len(models)} masses x "
          f"{len(scales)} scales, first 15 s) in {wall:.2f} s "
          f"(bar: 1e5 under {BAR_BATCH:g} s: {verdict(wall <= BAR_BATCH, quick)})")
    return wall <= BAR_BATCH


def first_calls(quick):
    """The first call in a fresh process [s]: numba's cache cold, then warm."""
    times = []
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        for _ in range(2):
            out = subprocess.run([sys.executable, "-c", FIRST_CALL], env=env, capture_output=True, text=True,
                                 check=True).stdout
            times.append(float(out.split()[-1]))
    print(f"first call in a fresh process: {times[0]:.2f} s with numba's cache cold, {times[1]:.2f} s warm "
          f"(bar {BAR_FIRST:g} s warm: {verdict(times[1] <= BAR_FIRST, quick)})")
    return times[1] <= BAR_FIRST


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a smoke run: one record, few scales (not a measurement)")
    parser.add_argument("--repeat", type=int, default=5, help="warm runs per case (median) [-]")
    args = parser.parse_args(argv)
    if args.quick:
        print("smoke run (--quick): not a measurement")
    met = [per_case(args.quick, args.repeat), batch(args.quick), first_calls(args.quick)]
    return 0 if all(met) or args.quick else 1


if __name__ == "__main__":
    sys.exit(main())
