"""Error of the refined-grid floor motions (ShearFrame.floor_motions) on the sliding of a block.

A floor's absolute acceleration is exact at the samples of the grid dt/m and joined by
straight lines in between. This script measures what that costs on the largest relative
displacement max |u| of a two-way block: every record, floors 1 and n of the seed-002
frames, each floor motion scaled to a peak of A g (the scale taken once, from the
reference grid, so that only the representation changes with m), against m = 64. The bars,
at m = 4 (the default refine), a decade above the measured median 7.9e-5 and largest
3.2e-3 (docs/verification.md); the script exits with 1 where one is not met.

    python benchmarks/floor_refinement.py [--quick]
"""

import argparse

import numpy as np

import blockdae as bd
from _common import G, print_table, sample_records, verdict

REFERENCE = 64
BAR_M, BAR_MEDIAN, BAR_MAX = 4, 7.9e-4, 3.2e-2  # refine [-], relative errors of max |u| [-]


def errors(records, frames, mus, pga, refines):
    """Relative errors of max |u| for every case, shape (len(refines), n_cases)."""
    out = []
    for record in records:
        for frame in frames:
            reference = frame.floor_motions(record, refine=REFERENCE)
            for level in (1, frame.storeys):
                scale = pga * G / reference[level - 1].peak_acceleration
                block = bd.SlidingBlock(mu=np.asarray(mus), g=G)
                exact = bd.simulate(block, reference[level - 1].scaled(scale)).max_abs_displacement
                rows = []
                for m in refines:
                    floor = frame.floor(level).motion(record, refine=m).scaled(scale)
                    rows.append(np.abs(bd.simulate(block, floor).max_abs_displacement / exact - 1.0))
                out.append(np.array(rows))
    return np.concatenate(out, axis=1)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the 2 shortest records, one frame")
    args = parser.parse_args(argv)
    records = sample_records(quick=args.quick)
    periods = (0.3,) if args.quick else (0.2, 0.3, 0.5)
    frames = [bd.ShearFrame(storeys=5, period=T, damping=0.05) for T in periods]
    mus, pga, refines = (0.1, 0.2, 0.3), 1.0, (1, 2, 4, 8, 16)
    err = errors(records, frames, mus, pga, refines)
    print(f"{len(records)} records x frames T1 = {periods} s (floors 1 and 5) x mu = {mus}, "
          f"floor peak {pga} g; reference m = {REFERENCE}\n")
    rows = []
    for i, m in enumerate(refines):
        order = "" if i == 0 else f"{np.log2(np.median(err[i - 1]) / np.median(err[i])):.2f}"
        rows.append((str(m), f"{np.median(err[i]):.2e}", f"{np.percentile(err[i], 90):.2e}",
                     f"{np.max(err[i]):.2e}", order))
    print_table(["m (samples per dt)", "median rel. error", "90th percentile", "max", "observed order"], rows)
    at = err[refines.index(BAR_M)]
    met = np.median(at) <= BAR_MEDIAN and np.max(at) <= BAR_MAX
    print(f"\nat m = {BAR_M}: median {np.median(at):.1e} (bar {BAR_MEDIAN:g}), largest {np.max(at):.1e} "
          f"(bar {BAR_MAX:g}): {verdict(met, args.quick)}")
    return 0 if met or args.quick else 1


if __name__ == "__main__":
    raise SystemExit(main())
