"""``blockdae back-analysis``: what displacements seen under records say about a slope's
ky (or a flexible mass's vs, a plane's mu, ...): the posterior by NUTS or the Laplace
approximation, each observation beside its posterior predictive D, and with --predict the
D under a design motion."""

import argparse
import pathlib
import time
import warnings

import numpy as np

from ..design import ConvergenceWarning, Observation, back_analysis
from ..units import STANDARD_GRAVITY
from ._common import UsageError, checked, positive, read, record_arguments, save_figure, warning_line
from ._design import design_model, model_arguments

#: the kinds of --seen: the prefix -> Observation's keyword
SEEN_KINDS = {"more:": "more_than_m", "less:": "less_than_m"}


def seen(text):
    """D_M, more:D_M or less:D_M -> (Observation's keyword, the displacement [m])."""
    for prefix, keyword in SEEN_KINDS.items():
        if text.startswith(prefix):
            value = text[len(prefix):]
            break
    else:
        keyword, value = "displacement_m", text
    try:
        number = float(value)
    except ValueError:
        number = float("nan")
    if not (np.isfinite(number) and number > 0):
        raise argparse.ArgumentTypeError(f"--seen {text!r}: expected D_M (a displacement measured [m]), more:D_M (it "
                                         "moved more than this) or less:D_M (it moved less), D_M a positive number")
    return keyword, number


def add_back_analysis_parser(sub):
    """The ``back-analysis`` subcommand."""
    p = sub.add_parser("back-analysis", help="the posterior of a slope's ky (a flexible mass's vs, a plane's mu, ...) "
                                             "from the displacements seen under records, and its D under a design "
                                             "motion")
    p.add_argument("records", type=pathlib.Path, nargs="+", metavar="RECORD",
                   help="the accelerogram files the slope was seen under (ground acceleration along the slope), "
                        "one observation each")
    p.add_argument("--seen", type=seen, action="append", required=True, metavar="D_M",
                   help="what was seen under each record, in their order: D_M (a displacement measured [m]), "
                        "more:D_M (it moved more than D_M) or less:D_M (it moved less); repeat it per record")
    p.add_argument("--sigma-ln", type=positive("--sigma-ln"), required=True, metavar="SIGMA",
                   help="the standard deviation of the log of each measurement [-] (0.2: about +- 20 %%)")
    p.add_argument("--pga", type=positive("--pga"), action="append", default=None, metavar="PGA_G",
                   help="the PGA [g] each record is scaled to: once for all, or once per record in their order "
                        "(default: as recorded)")
    model_arguments(p, "the prior of a parameter inferred (lognormal:MEAN:COV, normal:MEAN:STD, uniform:LOW:HIGH) "
                       "or the value of one held (height=25)")
    p.add_argument("--polarity", choices=("normal", "inverse", "larger"), default="normal",
                   help="D of each record as given (default: downslope is the record's positive direction), "
                        "inverted, or the larger of the two")
    p.add_argument("--method", choices=("nuts", "laplace"), default="nuts",
                   help="NUTS (default: NumPyro's No-U-Turn sampler on the model's exact dD/dp) or the Laplace "
                        "approximation at the maximum a posteriori (fast)")
    p.add_argument("--flexible-method", choices=("coupled", "decoupled"), default="coupled",
                   help="flexible: slip equations")
    p.add_argument("--chains", type=int, default=4, help="chains (default 4)")
    p.add_argument("--draws", type=int, default=500, help="draws per chain (default 500)")
    p.add_argument("--warmup", type=int, default=500, help="NUTS's warm-up iterations per chain (default 500)")
    p.add_argument("--seed", type=int, default=0, help="the random seed (default 0)")
    p.add_argument("--predict", type=pathlib.Path, default=None, metavar="RECORD",
                   help="a design motion: the slope's D under it, with its 90 %% interval")
    p.add_argument("--predict-pga", type=positive("--predict-pga"), default=None, metavar="PGA_G",
                   help="the PGA [g] the design motion is scaled to (default: as recorded)")
    p.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                   help="the unit 'g' [m/s²] of the files and the PGA (default 9.80665)")
    record_arguments(p)
    p.add_argument("--csv", type=pathlib.Path, default=None, metavar="PATH", help="write the posterior draws as CSV")
    p.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG",
                   help="save the observations beside the predicted D (and the design motion's)")
    p.set_defaults(command=_back_analysis)


def _convergence_line(show):
    """``warnings.showwarning`` that prints a :class:`ConvergenceWarning` as ``blockdae:
    warning: <message>`` on stderr, and any other warning with ``show``."""
    def line(message, category, *rest, **keywords):
        (warning_line if issubclass(category, ConvergenceWarning) else show)(message, category, *rest, **keywords)
    return line


def _observations(args):
    """One :class:`Observation` per record file, each named by its file's name."""
    n = len(args.records)
    stems = [path.stem for path in args.records]
    if len(set(stems)) != n:
        raise UsageError(f"two record files share a name: {sorted({s for s in stems if stems.count(s) > 1})}; "
                         "each observation is named by its file")
    if len(args.seen) != n:
        raise UsageError(f"--seen was given {len(args.seen)} times for {n} record files: give what was seen under "
                         "each record, in their order")
    pgas = args.pga or [None]
    if len(pgas) not in (1, n):
        raise UsageError(f"--pga was given {len(pgas)} times for {n} record files: give it once for all, or once "
                         "per record")
    pgas = pgas * n if len(pgas) == 1 else pgas
    return [checked(lambda: Observation(read(path, args), sigma_ln=args.sigma_ln, pga_g=pga, name=path.stem,
                                        **{keyword: value}), str(path))
            for path, (keyword, value), pga in zip(args.records, args.seen, pgas)]


def _back_analysis(args) -> int:
    observations = _observations(args)
    model = design_model(args.model, args.flexible_method, None, args)
    for flag in ("chains", "draws", "warmup"):
        if getattr(args, flag) < 1:
            raise UsageError(f"--{flag} must be a positive whole number, got {getattr(args, flag)}")
    motion = None if args.predict is None else read(args.predict, args)
    if args.predict_pga is not None and motion is None:
        raise UsageError("--predict-pga needs --predict RECORD")
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("always", ConvergenceWarning)
        warnings.showwarning = _convergence_line(warnings.showwarning)
        result = checked(lambda: back_analysis(observations, model, dict(args.param), method=args.method,
                                               chains=args.chains, draws=args.draws, warmup=args.warmup,
                                               seed=args.seed), "")
    wall = time.perf_counter() - start
    how = (f"NUTS, {args.chains} chains x {args.draws} draws after {args.warmup} of warm-up" if args.method == "nuts"
           else f"Laplace approximation, {args.chains * args.draws} draws")
    count = f"{len(observations)} observation{'s' if len(observations) > 1 else ''}"
    print(f"{count}, {how}, in {wall:.1f} s\n")
    print(result.summary().to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    if len(result.diagnostics):
        print()
        print(result.diagnostics.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    print("\nobserved [m] beside the posterior predictive D [m] (median, 90 % interval)")
    print(result.predictive().to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    scenarios = None
    if motion is not None:
        future = result.predict(motion, args.predict_pga)
        low, mid, high = np.quantile(future.D_m, [0.05, 0.5, 0.95])
        at = "as recorded" if args.predict_pga is None else f"at {args.predict_pga:g} g"
        print(f"\nD under {args.predict.stem} {at}: median {mid:.4g} m, 90 % interval {low:.4g}-{high:.4g} m")
        scenarios = {args.predict.stem: (motion, args.predict_pga)}
    if args.csv is not None:
        checked(lambda: result.samples.to_csv(args.csv, index=False), f"--csv {args.csv}")
        print(f"draws: {args.csv}")
    if args.plot is not None:
        save_figure(result.predictive_figure(scenarios=scenarios), args.plot)
        print(f"figure: {args.plot}")
    return 0
