"""The planar block (seed 001) on every backend that runs it, against IDA.

Cases: Elms's one sine wave (g = 1, N/A = 0.5, mu = 0.8; R = 0, 0.4, 0.8) and two
pairs of pySLAMMER sample records with one sample step as (x, y) (not recorded
together: a test of the solvers, not a real two-component motion), mu = 0.5 PGA_x / g,
a bias 0.25 mu in -x, until rest. Per backend and case: wall time of a warm run [s]
(median; the first call with --quick), events, final (u_x, u_y) [m] and the largest event-time difference from IDA
[s] (where the event sequences match). "jax" is included where ``bd.simulate`` runs a
PlanarBlock on it (it raises ValueError where not).

    python benchmarks/planar.py [--quick] [--repeat N]
"""

import argparse
import importlib.resources

import numpy as np

import blockdae as bd
from blockdae.planar import _elms as elms
from _common import G, print_table, timed

#: backends that may run a PlanarBlock; IDA is the reference (it follows turning slides)
CANDIDATES = ("ida", "cvode", "jax")
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
    rows = []
    for label, block, motion in cases(args.quick):
        reference = None
        for name in names:
            options = {"rtol": RTOL}
            try:
                sol, _, warm = timed(lambda: bd.simulate(block, motion, backend=name, **options), repeat)
            except RuntimeError as err:  # a solver failure is a result here, not a crash
                rows.append((label, name, "-", "failed", "-", "-", str(err).split(":")[0]))
                continue
            reference = reference or (sol if name == "ida" else None)
            rows.append((label, name, f"{warm:.3f}", str(len(sol.events)), f"{sol.displacement[0]:+.6f}",
                         f"{sol.displacement[1]:+.6f}", _event_difference(sol, reference)))
    print()
    print_table(("case", "backend", "warm [s]", "events", "u_x [m]", "u_y [m]", "max |dt| vs ida [s]"), rows)
    return 0


def _event_difference(sol, reference):
    if reference is None or sol is reference:
        return "-"
    if [(e.mode_before, e.mode_after) for e in sol.events] != [(e.mode_before, e.mode_after) for e in reference.events]:
        return f"other events ({len(sol.events)} vs {len(reference.events)})"
    return f"{np.max(np.abs(sol.t_events - reference.t_events), initial=0.0):.2e}"


if __name__ == "__main__":
    raise SystemExit(main())
