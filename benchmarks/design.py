"""Performance-based design (blockdae.design) against pySLAMMER's probabilistic example:
two road segments beside slopes whose ky and Vs are log-normal, coupled
equivalent-linear analyses of nine of pySLAMMER's sample records at a target PGA of
0.44 g, P(D > 25 cm).

1. The same drawn samples on both sides (Monte Carlo, seed 42, 20 runs x 9 records x 2
   segments, one parameter set per (run, record)): pySLAMMER 0.2.2's ``Coupled`` one
   analysis at a time, blockdae one ``bd.flexible`` call per record (all its samples, record
   scaling included; the median of 3 calls; on every core, the bar's case, and on one
   thread), record by record in turn so that both sides share the machine's load; the
   per-analysis agreement, the speed ratio and P_B / P_A.
2. The whole study in blockdae: both segments, scrambled Sobol, until the relative standard
   error of the mean D is at most 5 % and the 95 % interval of P(D > 25 cm) at most
   +-0.02 wide; warm time.
3. Standard error against analyses: segment A, each sampling replicated with independent
   seeds; the standard deviation of the mean D (and of P(D > 25 cm)) over the replicates,
   and the analyses Monte Carlo would need for the same standard error (1/n scaling).

    python benchmarks/design.py [--quick]
"""

import argparse
import statistics
import time

import numba
import numpy as np
import pyslammer

import blockdae as bd
import blockdae.design as dz
from blockdae.design._study import Draws
from _common import G, print_table, sample_records, verdict

#: the anchor case: nine of pySLAMMER's sample records, each at a target PGA of 0.44 g
ANCHOR_RECORDS = ("Nisqually_2001_UNR-058", "Imperial_Valley_1979_BCR-230", "Northridge_1994_PAC-175",
                  "Cape_Mendocino_1992_PET-090", "Coalinga_1983_PVB-045", "Mammoth_Lakes-1_1980_CVK-090",
                  "Loma_Prieta_1989_HSP-000", "Coyote_Lake_1979_G02-050", "Northridge_1994_VSP-360")
PGA = 0.44  # g
HEIGHT, VS_BASE, DAMPING, REFERENCE_STRAIN = 25.0, 1500.0, 0.05, 5e-4  # m, m/s, -, fraction
#: segment -> (mean ky [g], mean Vs [m/s]); covs 0.2 (ky) and 0.15 (Vs)
SEGMENTS = {"A": (0.13, 250.0), "B": (0.15, 400.0)}
THRESHOLD = 0.25  # m
MODEL = dz.Flexible(method="coupled", equivalent_linear=True, reference_strain=REFERENCE_STRAIN)
BARS = {"speed-up per analysis [x]": (300.0, True), "whole study, warm [s]": (5.0, False)}


def parameters(segment):
    """The uncertain slope of ``segment``."""
    ky, vs = SEGMENTS[segment]
    return {"ky": dz.LogNormal(mean=ky, cov=0.2), "vs": dz.LogNormal(mean=vs, cov=0.15), "height": HEIGHT,
            "vr": VS_BASE, "damping": DAMPING}


def anchor_records(quick):
    """The anchor case's records (name -> Record [m/s²]); with ``quick`` the two shortest."""
    records = {r.name: r for r in sample_records()}
    chosen = {name: records[name] for name in ANCHOR_RECORDS}
    if quick:
        chosen = dict(sorted(chosen.items(), key=lambda item: item[1].acceleration_samples.size)[:2])
    return chosen


def _peer(record, ky, vs):
    """pySLAMMER's coupled equivalent-linear D [m] (normal polarity) at the target PGA."""
    motion = pyslammer.GroundMotion(record.acceleration_samples / G, record.dt, record.name)
    return pyslammer.Coupled(ky, motion, HEIGHT, vs, VS_BASE, DAMPING, ref_strain=REFERENCE_STRAIN, target_pga=PGA,
                             soil_model="equivalent_linear").max_sliding_disp


def same_samples(records, runs):
    """Part 1: (rows of the agreement table, measured numbers)."""
    samples = {}  # (segment, record) -> name -> values
    for segment in SEGMENTS:
        draws = Draws(MODEL, parameters(segment), len(records), "mc", 42, None, runs)
        for i, name in enumerate(records):
            samples[segment, name] = draws.block(i, runs)
    batched = {name: {p: np.concatenate([samples[s, name][p] for s in SEGMENTS]) for p in ("ky", "vs")} | {
        "height": HEIGHT, "vr": VS_BASE, "damping": DAMPING} for name in records}

    for name, record in records.items():  # compiled (or loaded from numba's cache) before timing
        MODEL.displacements(record, PGA, batched[name])
    mine, theirs, peer_s = {}, {}, 0.0
    cores = numba.get_num_threads()
    seconds = dict.fromkeys((cores, 1), 0.0)  # blockdae's time [s] by thread count (one entry on one core)
    for name, record in records.items():  # record by record, both sides in turn: they share the machine's load
        for threads in seconds:
            numba.set_num_threads(threads)
            times = []
            for _ in range(3):
                start = time.perf_counter()
                mine[name] = MODEL.displacements(record, PGA, batched[name])
                times.append(time.perf_counter() - start)
            seconds[threads] += statistics.median(times)
        numba.set_num_threads(cores)
        start = time.perf_counter()
        theirs[name] = np.array([_peer(record, k, v) for k, v in zip(batched[name]["ky"], batched[name]["vs"])])
        peer_s += time.perf_counter() - start
    n = sum(v.size for v in mine.values())
    ours_each, peer_each = seconds[cores] / n, peer_s / n
    one_at_a_time = _one_at_a_time(records, batched)
    d_ours, d_peer = (np.concatenate(list(x.values())) for x in (mine, theirs))
    moving = d_ours > 0.01
    relative = np.abs(d_peer[moving] / d_ours[moving] - 1) * 100
    probability = {}
    for k, segment in enumerate(SEGMENTS):
        part = np.concatenate([np.arange(k * runs, (k + 1) * runs) + j * 2 * runs for j in range(len(records))])
        probability[segment] = (np.mean(d_ours[part] > THRESHOLD), np.mean(d_peer[part] > THRESHOLD))
    numbers = {"analyses": n, "moving": int(moving.sum()), "median [%]": np.median(relative),
               "p90 [%]": np.percentile(relative, 90), "max [%]": relative.max(), "ours [ms]": ours_each * 1e3,
               "one at a time [ms]": one_at_a_time * 1e3, "peer [ms]": peer_each * 1e3,
               "one thread [ms]": seconds[1] / n * 1e3, "cores": cores,
               "speed-up": peer_each / ours_each, "probability": probability}
    return numbers


def _one_at_a_time(records, batched, limit=40):
    """blockdae's time per analysis [s] called one analysis at a time (the first ``limit``)."""
    calls = [(record, k, v) for name, record in records.items()
             for k, v in zip(batched[name]["ky"], batched[name]["vs"])][:limit]
    run = lambda: [bd.flexible(r, ky=k, height=HEIGHT, vs=v, vr=VS_BASE, damping=DAMPING, equivalent_linear=True,
                               reference_strain=REFERENCE_STRAIN, pga=PGA, polarity="normal") for r, k, v in calls]
    run()
    start = time.perf_counter()
    run()
    return (time.perf_counter() - start) / len(calls)


def whole_study(records, quick):
    """Part 2: (results by segment, warm seconds of both segments)."""
    def run():
        return {s: dz.exceedance(records, MODEL, parameters(s), pga=PGA, threshold=THRESHOLD, sampling="sobol",
                                 seed=42, rse=0.05, halfwidth=0.05 if quick else 0.02) for s in SEGMENTS}

    run()
    start = time.perf_counter()
    results = run()
    return results, time.perf_counter() - start


def standard_errors(records, replicates, sizes):
    """Part 3: rows (sampling, runs, analyses, SE of mean D [%], SE of P [-], Monte Carlo
    analyses for the same SE of the mean)."""
    spread = {}
    for sampling in ("mc", "lhs", "sobol"):
        for runs in sizes:
            means, probabilities = [], []
            for seed in range(replicates):
                result = dz.exceedance(records, MODEL, parameters("A"), pga=PGA, threshold=THRESHOLD,
                                       sampling=sampling, seed=1000 + seed, runs=runs, runs_per_block=runs)
                means.append(result.mean_m)
                probabilities.append(result.probability)
            spread[sampling, runs] = (np.std(means, ddof=1) / np.mean(means), np.std(probabilities, ddof=1))
    rows = []
    for (sampling, runs), (se_mean, se_p) in spread.items():
        n = runs * len(records)
        mc_needed = n * (spread["mc", runs][0] / se_mean) ** 2
        rows.append((sampling, str(runs), str(n), f"{se_mean * 100:.2f}", f"{se_p:.4f}", f"{mc_needed:.0f}"))
    return rows, spread


def _ratio(b, a):
    """b / a as text (\"undefined\" where a is 0)."""
    return f"{b / a:.2f}" if a else "undefined (P_A = 0)"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="two short records, few runs: a smoke run")
    args = parser.parse_args(argv)
    records = anchor_records(args.quick)
    runs = 2 if args.quick else 20
    print(f"Anchor case: {len(records)} records at a target PGA of {PGA} g; coupled equivalent-linear, reference "
          f"strain {REFERENCE_STRAIN}, damping {DAMPING}, H = {HEIGHT:g} m, base Vs {VS_BASE:g} m/s; ky and Vs "
          "log-normal (covs 0.2, 0.15), segment A mean ky 0.13 g, Vs 250 m/s; B 0.15 g, 400 m/s; normal polarity\n")
    numbers = same_samples(records, runs)
    print(f"1. The same samples (Monte Carlo, seed 42, {runs} runs x {len(records)} records x 2 segments = "
          f"{numbers['analyses']} analyses) on both sides\n")
    print_table(("analyses with D > 1 cm", "|pySLAMMER / blockdae - 1| median [%]", "90th percentile [%]",
                 "largest [%]"),
                [(str(numbers["moving"]), f"{numbers['median [%]']:.2f}", f"{numbers['p90 [%]']:.2f}",
                  f"{numbers['max [%]']:.2f}")])
    print()
    print_table(("per analysis", "time [ms]", "pySLAMMER / this [x]"),
                [("pySLAMMER Coupled, one analysis a call", f"{numbers['peer [ms]']:.1f}", "1"),
                 (f"blockdae, one bd.flexible call a record, {numbers['cores']} threads",
                  f"{numbers['ours [ms]']:.3f}", f"{numbers['speed-up']:.0f}"),
                 ("blockdae, one bd.flexible call a record, 1 thread", f"{numbers['one thread [ms]']:.3f}",
                  f"{numbers['peer [ms]'] / numbers['one thread [ms]']:.0f}"),
                 ("blockdae, one bd.flexible call an analysis", f"{numbers['one at a time [ms]']:.3f}",
                  f"{numbers['peer [ms]'] / numbers['one at a time [ms]']:.0f}")])
    print()
    p = numbers["probability"]
    print_table(("segment", f"P(D > {THRESHOLD:g} m), blockdae [-]", "pySLAMMER [-]"),
                [(s, f"{p[s][0]:.3f}", f"{p[s][1]:.3f}") for s in SEGMENTS] +
                [("B / A", _ratio(p["B"][0], p["A"][0]), _ratio(p["B"][1], p["A"][1]))])
    results, seconds = whole_study(records, args.quick)
    print(f"\n2. The whole study (both segments, scrambled Sobol, seed 42, blocks of 16 runs until the mean D's "
          f"relative standard error <= 5 % and P's 95 % interval <= +-{0.05 if args.quick else 0.02}): warm "
          f"{seconds:.2f} s\n")
    print_table(("segment", "runs", "analyses", "mean D [m]", "rse [%]", f"P(D > {THRESHOLD:g} m) [-]",
                 "95 % interval [-]"),
                [(s, str(r.history["runs"].iloc[-1]), str(len(r.table)), f"{r.mean_m:.4f}", f"{r.rse * 100:.2f}",
                  f"{r.probability:.4f}", "[{:.4f}, {:.4f}]".format(*r.probability_interval))
                 for s, r in results.items()])
    ratio = _ratio(results["B"].probability, results["A"].probability)
    print(f"P_B / P_A = {ratio} (despite B's higher mean ky, B's P(D > {THRESHOLD:g} m) is about double A's)")
    replicates, sizes = (3, (4,)) if args.quick else (20, (16, 64))
    rows, _ = standard_errors(records, replicates, sizes)
    print(f"\n3. Standard error against analyses, segment A, {replicates} replicates a sampling (independent "
          "seeds): the spread of the estimates over the replicates\n")
    print_table(("sampling", "runs", "analyses", "SE of mean D [%]", "SE of P [-]",
                 "Monte Carlo analyses for that SE of mean D"), rows)
    print()
    measured = {"speed-up per analysis [x]": numbers["speed-up"], "whole study, warm [s]": seconds}
    failed = 0
    for name, (bound, at_least) in BARS.items():
        ok = measured[name] >= bound if at_least else measured[name] <= bound
        failed += not ok
        print(f"bar {name} {'>=' if at_least else '<='} {bound:g}: {measured[name]:.3g}: {verdict(ok, args.quick)}")
    return 1 if failed and not args.quick else 0


if __name__ == "__main__":
    raise SystemExit(main())
