"""``blockdae design``: a slope with uncertain properties over a record set at a target PGA:
P(D > threshold) with its interval, each record's part, and with --allowable and --target
the mean ky the design needs."""

import argparse
import pathlib
import time

from ..design import (Flexible, LogNormal, Normal, Planar, Rigid, Uniform, exceedance, mean_ky_for_probability)
from ..units import STANDARD_GRAVITY
from ._common import (UsageError, checked, folder_files, positive, read, record_arguments, recursive_argument,
                      save_figure)

#: --param kinds -> (the distribution, what its two numbers are)
KINDS = {"lognormal": (lambda a, b: LogNormal(mean=a, cov=b), "MEAN:COV"),
         "normal": (lambda a, b: Normal(a, b), "MEAN:STD"),
         "uniform": (lambda a, b: Uniform(a, b), "LOW:HIGH")}


#: samples a record of the mean-ky design (--allowable, --target)
DESIGN_RUNS = 64


def parameter(text):
    """NAME=VALUE or NAME=KIND:A:B (e.g. ky=lognormal:0.13:0.2) -> (name, number or distribution)."""
    name, _, value = text.partition("=")
    kind, *numbers = value.split(":")
    try:
        if not numbers:
            return name, float(kind)
        build, _ = KINDS[kind]
        return name, build(*(float(x) for x in numbers))
    except (KeyError, TypeError, ValueError) as err:
        kinds = ", ".join(f"{k}:{what}" for k, (_, what) in KINDS.items())
        raise argparse.ArgumentTypeError(f"--param {text!r}: expected NAME=NUMBER or NAME=KIND:A:B with KIND one of "
                                         f"{kinds} ({err})") from None


def model_arguments(p, param_help):
    """--model (the design model) and --param (``param_help`` says what a NAME=SPEC is;
    the parameters' names and units follow it)."""
    p.add_argument("--model", choices=("rigid", "flexible", "planar"), default="rigid",
                   help="rigid block (parameter ky), flexible sliding mass (ky, height, vs, vr, damping) or block on "
                        "a plane (mu, mu_kinetic, bias_x, bias_y; D its final sliding distance |u|)")
    p.add_argument("--param", type=parameter, action="append", required=True, metavar="NAME=SPEC",
                   help=f"{param_help} (ky [g], height [m], vs and vr [m/s], damping, mu, bias_x [-]); repeat it")


def add_design_parser(sub):
    """The ``design`` subcommand."""
    p = sub.add_parser("design", help="P(D > d) of a slope with uncertain ky, vs, ... over records at a target PGA "
                                      "(Monte Carlo, Latin hypercube or Sobol), and the mean ky a design needs")
    p.add_argument("records", type=pathlib.Path, nargs="+", metavar="RECORD",
                   help="accelerogram files or folders of them (ground acceleration along the slope)")
    model_arguments(p, "a parameter, a number (height=25) or a distribution: lognormal:MEAN:COV, normal:MEAN:STD, "
                       "uniform:LOW:HIGH")
    p.add_argument("--pga", type=positive("--pga"), default=None, metavar="PGA_G",
                   help="target PGA [g] every record is scaled to (default: as given)")
    p.add_argument("--threshold", type=positive("--threshold"), required=True, metavar="D_M",
                   help="the displacement of interest [m]: P(D > threshold)")
    p.add_argument("--method", choices=("coupled", "decoupled"), default="coupled", help="flexible: slip equations")
    p.add_argument("--reference-strain", type=positive("--reference-strain"), default=None, metavar="FRACTION",
                   help="flexible: the equivalent-linear iteration with this reference strain (e.g. 0.0005)")
    p.add_argument("--polarity", choices=("normal", "inverse", "larger"), default="normal",
                   help="D of the record as given (default), inverted, or the larger of the two")
    p.add_argument("--sampling", choices=("sobol", "lhs", "mc"), default="sobol",
                   help="scrambled Sobol (default), Latin hypercube or Monte Carlo")
    p.add_argument("--seed", type=int, default=0, help="the study's seed (default 0): the same seed, the same samples")
    p.add_argument("--rse", type=positive("--rse"), default=0.05,
                   help="stop once the mean D's relative standard error is at most this (default 0.05)")
    p.add_argument("--halfwidth", type=positive("--halfwidth"), default=None,
                   help="and once the 95 %% interval of P(D > threshold) is at most +- this")
    p.add_argument("--runs", type=int, default=None, help="a fixed number of runs instead (one sample a record a run)")
    p.add_argument("--allowable", type=positive("--allowable"), default=None, metavar="D_M",
                   help="with --target: the mean ky [g] (mu [-] on a plane; same cov) for which "
                        "P(D > allowable) <= target, on 64 samples a record kept for every mean")
    p.add_argument("--target", type=positive("--target"), default=None, help="the probability allowed (e.g. 0.1)")
    p.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                   help="the unit 'g' [m/s²] of the files and the PGA (default 9.80665)")
    record_arguments(p)
    recursive_argument(p)
    p.add_argument("--checkpoint", type=pathlib.Path, default=None, metavar="FOLDER",
                   help="save each finished block of runs there; rerun the same command to resume")
    p.add_argument("--csv", type=pathlib.Path, default=None, metavar="PATH", help="write every sample as CSV")
    p.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG", help="save the exceedance curve")
    p.set_defaults(command=_design)


def design_model(kind, method, reference_strain, args):
    """The design model of --model ``kind`` ("rigid", "flexible" or "planar"), with the
    command's --polarity (where it has one) and --g; a flexible mass's slip equations
    ``method`` and equivalent-linear ``reference_strain`` (None: none)."""
    options = {"polarity": getattr(args, "polarity", "normal"), "g": args.g}
    if kind == "rigid":
        return checked(lambda: Rigid(**options), "")
    if kind == "planar":
        return checked(lambda: Planar(**options), "")
    return checked(lambda: Flexible(method=method, equivalent_linear=reference_strain is not None,
                                    reference_strain=reference_strain, **options), "")


def _design(args) -> int:
    paths = [p for arg in args.records for p in (folder_files(arg, args) if arg.is_dir() else [arg])]
    stems = [path.stem for path in paths]
    if len(set(stems)) != len(stems):
        raise UsageError(f"two record files share a name: {sorted({s for s in stems if stems.count(s) > 1})}; "
                         "each record is labelled by its file name")
    records = {path.stem: read(path, args) for path in paths}
    parameters = dict(args.param)
    model = design_model(args.model, args.method, args.reference_strain, args)
    start = time.perf_counter()
    result = checked(lambda: exceedance(records, model, parameters, pga=args.pga, threshold=args.threshold,
                                        sampling=args.sampling, seed=args.seed, rse=args.rse,
                                        halfwidth=args.halfwidth, runs=args.runs, checkpoint=args.checkpoint), "")
    wall = time.perf_counter() - start
    low, high = result.probability_interval
    runs = result.history["runs"].iloc[-1]
    state = "" if result.converged else " (the stopping rule NOT met: more runs needed)"
    print(f"{len(result.table)} analyses ({runs} runs x {len(records)} records, {args.sampling}, seed {args.seed}) in "
          f"{wall:.1f} s{state}")
    print(f"mean D = {result.mean_m:.4g} m (relative standard error {result.rse * 100:.2f} %)")
    print(f"P(D > {args.threshold:g} m) = {result.probability:.4f} (95 % interval [{low:.4f}, {high:.4f}])\n")
    parts = result.contributions()
    print(f"{'record':>32} {'mean D [m]':>12} {'P(D > d) [-]':>14} {'share [-]':>10}")
    for row in parts.itertuples():
        print(f"{row.record[-32:]:>32} {row.mean_D_m:12.4g} {row.P_exceed:14.4f} {row.share:10.4f}")
    if (args.allowable is None) != (args.target is None):
        raise UsageError("--allowable and --target go together")
    if args.allowable is not None:
        design = checked(lambda: mean_ky_for_probability(records, model, parameters, args.allowable, args.target,
                                                         pga=args.pga, runs=DESIGN_RUNS, sampling=args.sampling,
                                                         seed=args.seed), "")
        unit = "g" if design.parameter == "ky" else "[-]"
        print(f"\nmean {design.parameter} for P(D > {args.allowable:g} m) <= {args.target:g}: {design.mean:.4f} {unit} "
              f"({len(design.table)} samples, common random numbers)")
    if args.csv is not None:
        checked(lambda: result.table.to_csv(args.csv, index=False), f"--csv {args.csv}")
        print(f"samples: {args.csv}")
    if args.plot is not None:
        save_figure(result.figure(), args.plot)
        print(f"figure: {args.plot}")
    return 0
