"""The planar block (seed 001) on every backend that runs it, against IDA.

Cases: Elms's one sine wave (g = 1, N/A = 0.5, mu = 0.8; R = 0, 0.4, 0.8) and two
pairs of pySLAMMER sample records with one sample step as (x, y) (not recorded
together: a test of the solvers, not a real two-component motion), mu = 0.5 PGA_x / g,
a bias 0.25 mu in -x, until rest. Per backend and case: wall time of a warm run [s]
(median; the first call with --quick), events, final (u_x, u_y) [m] and the largest event-time difference from IDA
[s] (where the event sequences match) and the speed-up over IDA and the JAX twin
(bars for "compiled", medians over the record pairs: >= 300x IDA, >= 30x JAX). Then the
compiled engine's cold compile (a fresh process, an empty numba cache) and a planar study
on "compiled" at the study tolerance (``STUDY_RTOL``): the 18 sample records as x with
the next one as y x mu x factors, 10^4 analyses in one batch on every core (bar: < 60 s
on 2 cores; its CPU time [s] too, summed over threads, which other jobs on the machine
change less than the wall time). "jax" is included where ``bd.simulate`` runs a PlanarBlock on it (it raises
ValueError where not).

    python benchmarks/planar.py [--quick] [--repeat N]
"""

import argparse
import importlib.resources
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import blockdae as bd
from blockdae.planar import _elms as elms
from blockdae.planar._model import STUDY_RTOL
from _common import G, print_table, timed, verdict

#: backends that may run a PlanarBlock; IDA is the reference (it follows turning slides)
CANDIDATES = ("ida", "cvode", "jax", "compiled")
#: (x, y) pairs of sample records with one sample step [file stems]
PAIRS = (("Kobe_1995_TAK-090", "Duzce_1999_375-090"), ("N_Palm_Springs_1986_WWT-180", "Nahanni_1985_NS1-280"))
RTOL = 1e-10
QUICK_SAMPLES = 1000


def cases(quick=False):
    """(label, block, motion) for every comparison."""
    ratios = (0.0, 0.4) if quick else (0.0, 0.4, 0.8)
    out = [(f"Elms R = {r:g}", elms.elms_block(0.5, 0.8), elms.elms_motion(r)) for r in ratios]
    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    for x_stem, y_stem in PAIRS[1:] if quick else PAIRS:
        x, y = (bd.read_record(folder / f"{stem}.csv", units="g", g=G) for stem in (x_stem, y_stem))
        if quick:  # the first QUICK_SAMPLES samples of each
            x, y = (bd.Record(r.acceleration_samples[:QUICK_SAMPLES], r.dt, r.name, units="m/s2", check_peak=False)
                    for r in (x, y))
        mu = 0.5 * x.peak_acceleration / G
        block = bd.PlanarBlock(mu=mu, bias=(-0.25 * mu, 0.0), g=G)
        out.append((f"{x_stem.rsplit('_', 2)[0]} x + {y_stem.rsplit('_', 2)[0]} y", block, bd.BaseMotion(x, y)))
    return out


def runs_planar(name) -> bool:
    """Whether backend ``name`` runs a PlanarBlock (bd.simulate raises ValueError if not)."""
    try:
        bd.simulate(elms.elms_block(0.5, 0.8), elms.elms_motion(0.0), t_end=0.1, backend=name)
    except ValueError:
        return False
    return True


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help=f"Elms R = 0, 0.4 and the first {QUICK_SAMPLES} samples of one record pair (smoke run)")
    parser.add_argument("--repeat", type=int, default=3, help="warm repetitions (median) per timing")
    args = parser.parse_args(argv)
    names = [name for name in CANDIDATES if runs_planar(name)]
    skipped = [name for name in CANDIDATES if name not in names]
    print(f"planar backends: {', '.join(names)}" + (f" ({', '.join(skipped)}: no PlanarBlock)" if skipped else "")
          + f"; rtol = {RTOL:g}; Elms's cases in g = 1 units (u in g (T*/2)² = m at g = 1 m/s²)")
    repeat = 0 if args.quick else args.repeat
    rows, speedups = [], {"ida": [], "jax": []}
    for label, block, motion in cases(args.quick):
        reference, times = None, {}
        for name in names:
            options = {"rtol": RTOL}
            try:
                sol, _, warm = timed(lambda: bd.simulate(block, motion, backend=name, **options), repeat)
            except RuntimeError as err:  # a solver failure is a result here, not a crash
                rows.append((label, name, "-", "failed", "-", "-", str(err).split(":")[0]))
                continue
            reference = reference or (sol if name == "ida" else None)
            times[name] = warm
            ratio = lambda other: f"{times[other] / warm:.0f}x" if other in times and other != name else "-"
            rows.append((label, name, f"{warm:.4f}", str(len(sol.events)), f"{sol.displacement[0]:+.6f}",
                         f"{sol.displacement[1]:+.6f}", _event_difference(sol, reference), ratio("ida"), ratio("jax")))
            if name == "compiled" and not label.startswith("Elms"):
                for other in speedups:
                    if other in times:
                        speedups[other].append(times[other] / warm)
    print()
    print_table(("case", "backend", "warm [s]", "events", "u_x [m]", "u_y [m]", "max |dt| vs ida [s]",
                 "ida / this", "jax / this"), rows)
    met = True
    if "compiled" in names:
        print()
        for other, bar in (("ida", 300), ("jax", 30)):
            if speedups[other]:
                median = statistics.median(speedups[other])
                met &= median >= bar
                print(f"compiled vs {other} on the record pairs (median): {median:.0f}x; bar >= {bar}x: "
                      f"{verdict(median >= bar, args.quick)}")
        if not args.quick:
            print(f"compiled engine, cold compile (fresh process, empty numba cache): {cold_compile():.1f} s")
        met &= study(100 if args.quick else 10_000, args.quick)
    return 0 if met or args.quick else 1


def cold_compile() -> float:
    """Seconds [s] of the compiled engine's first run (Elms R = 0) in a fresh process
    with an empty numba cache: its compile."""
    code = ("import time, blockdae as bd; from blockdae.planar import _elms as e; s = time.perf_counter(); "
            "bd.simulate(e.elms_block(0.5, 0.8), e.elms_motion(0.0), backend='compiled'); "
            "print(time.perf_counter() - s)")
    with tempfile.TemporaryDirectory() as cache:
        result = subprocess.run([sys.executable, "-W", "ignore", "-c", code], capture_output=True, text=True,
                                check=True, env=dict(os.environ, NUMBA_CACHE_DIR=cache))
    return float(result.stdout.split()[-1])


def study(n_analyses, quick=False):
    """Time ``n_analyses`` planar analyses (record pairs x mu x factors on a(t)) in one
    batch at ``STUDY_RTOL``, and print the table; whether its bar (under 60 s per 10^4) is met."""
    from blockdae.backends import Horizon, make_backend
    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    records = [bd.read_record(p, units="g", g=G) for p in sorted(folder.iterdir()) if p.name.endswith(".csv")]
    same_dt = [(x, y) for x, y in zip(records, records[1:] + records[:1]) if x.dt == y.dt]
    motions = [bd.BaseMotion(x, y.scaled(x.peak_acceleration / y.peak_acceleration)) for x, y in same_dt]
    mu = np.array([0.05, 0.1, 0.15, 0.2, 0.3])
    n_scales = max(1, n_analyses // (len(motions) * len(mu)))
    scales = np.linspace(0.2, 2.0, n_scales)  # factors on a(t) [-]
    block = bd.PlanarBlock(mu=mu, mu_kinetic=0.8 * mu, bias=(-0.25 * mu, 0.0), g=G)
    backend = make_backend("compiled", rtol=STUDY_RTOL)
    horizons = [Horizon(None)] * len(motions)
    backend.solve_final(block, motions[:1], horizons[:1], scale=scales[:1])  # compile or load
    start, cpu_start = time.perf_counter(), time.process_time()
    out = backend.solve_final(block, motions, horizons, scale=tuple(scales))
    seconds, cpu = time.perf_counter() - start, time.process_time() - cpu_start
    n = out.shape[0] * out.shape[1]
    print()
    print_table(("study", "rtol", "analyses", "wall [s]", "cpu [s]", "per analysis [ms]", "cores", "median |u| [m]",
                 "flights", "bar < 60 s / 10^4"),
                [(f"{len(motions)} record pairs x {len(mu)} mu x {len(scales)} factors", f"{STUDY_RTOL:g}", f"{n:,}",
                  f"{seconds:.1f}", f"{cpu:.1f}", f"{1e3 * seconds / n:.2f}", str(os.cpu_count()),
                  f"{np.median(np.hypot(out[..., 0], out[..., 1])):.4f}", f"{int(out[..., 5].sum()):,}",
                  verdict(seconds * 1e4 / n < 60, quick))])
    return seconds * 1e4 / n < 60


def _event_difference(sol, reference):
    if reference is None or sol is reference:
        return "-"
    if [(e.mode_before, e.mode_after) for e in sol.events] != [(e.mode_before, e.mode_after) for e in reference.events]:
        return f"other events ({len(sol.events)} vs {len(reference.events)})"
    return f"{np.max(np.abs(sol.t_events - reference.t_events), initial=0.0):.2e}"


if __name__ == "__main__":
    raise SystemExit(main())
