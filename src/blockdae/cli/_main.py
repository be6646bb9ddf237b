"""The ``blockdae`` command: run a record (or two or three components: a block on a
plane, see ``blockdae.cli._planar``), Newmark's analysis, a mass on a spring support under a
vertical record (``blockdae.cli._upthrow``), Sawicki & Chybicki's examples, a batch over a folder.

Every error about a file or an argument ends the command with exit status 2 and one
line ``blockdae: error: ...`` on stderr naming the file (and line) or the argument. A
batch analyses every good file and lists the bad ones at the end (exit status 1).
"""

import argparse
import importlib.metadata
import itertools
import json
import os
import pathlib
import sys
import time
import warnings

import numpy as np

from .. import backends
from ._common import (UsageError, checked, clean, describe_gravity, describe_record, files_or_set, finite, folder_files,
                      in_units_out, ky_table, ky_table_row, positive, read, record_arguments, record_fields,
                      recursive_argument,
                      print_run_end, report_failures, save_figure, set_argument, units_out_argument, write_csv)
from ._planar import is_planar, read_motion_argument, run_planar, x_record
from ._app import add_app_parser
from ._back_analysis import add_back_analysis_parser
from ._design import add_design_parser
from ._flexible import add_flexible_parser
from ._hazard import add_hazard_parsers
from ._info import add_info_parser
from ._map import add_map_parser
from ._model import parameter, run_model
from ._upthrow import add_upthrow_parser
from ._rocking import add_rocking_parser
from ..sliding import SlidingBlock, example_solution, newmark, seed_examples
from ..core import CompileNotice, progress_bar, set_compilation_cache, simulate
from ..units import STANDARD_GRAVITY, length_units
from ._motions import add_spectrum_parser, add_two_point_parser
from ._study import add_study_parser
from ..excitation import PGA_ROUNDINGS, RECORD_SUFFIXES, UnitsWarning, pga_factor, unit_factor

_CSV_FIELDS = ("record", "n_samples", "dt_s", "start_time_s", "peak_acceleration_m_s2", "mu", "mu_kinetic", "bias",
               "g_m_s2", "direction", "backend", "u_end_m", "max_abs_displacement_m", "n_events",
               "t_end_s")
_EVENTS_SHOWN = 5  # events printed at each end of a long list by default


def main(argv=None) -> int:
    """Entry point of the ``blockdae`` console script; returns the exit status."""
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:
        return int(exit_.code or 0)
    try:
        _compilation_cache(args)
        with warnings.catch_warnings():
            warnings.showwarning = _one_line_notices(warnings.showwarning)
            return args.command(args)
    except UsageError as err:
        print(f"blockdae: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader of the output stopped early (e.g. `| head`)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error at exit
        return 0


def _one_line_notices(show):
    """``warnings.showwarning`` that prints a :class:`CompileNotice` as its one line on
    stderr (not the caller's file and line) and leaves other warnings to ``show``."""
    def showwarning(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, CompileNotice):
            print(message, file=sys.stderr, flush=True)
        else:
            show(message, category, filename, lineno, file, line)
    return showwarning


def _prefixed(show, where):
    """``warnings.showwarning`` that prints a warning as ``blockdae: warning: <where>:
    ...`` on stderr, and leaves a :class:`CompileNotice` to ``show``."""
    def showwarning(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, CompileNotice):
            show(message, category, filename, lineno, file, line)
        else:
            print(f"blockdae: warning: {where + ': ' if where else ''}{message}", file=sys.stderr)
    return showwarning


def _parser():
    parser = argparse.ArgumentParser(
        prog="blockdae", description="Seismic sliding of blocks and masses: exact event times.")
    parser.add_argument("--version", action="version", version=f"blockdae {_version()}")
    parser.add_argument("--cache-dir", type=pathlib.Path, default=None,
                        help="JAX compilation cache, so that later runs skip compiling "
                             "(default: $BLOCKDAE_CACHE_DIR or ~/.cache/blockdae/jax)")
    parser.add_argument("--no-cache", action="store_true", help="compile afresh, keep no cache")
    sub = parser.add_subparsers(required=True,
                                metavar="{run,newmark,flexible,spectrum,two-point,upthrow,rocking,examples,batch,study,"
                                        "design,back-analysis,fragility,hazard,map,info,app}")

    run = sub.add_parser("run", help="slide a block under one accelerogram file (signed u), a block on a "
                                     "plane under two or three components (u_x, u_y), or any model (--model)")
    run.add_argument("record", type=pathlib.Path,
                     help="accelerogram (CSV t,a / one column / .AT2), the x component; or a table of "
                          "time [s], a_x, a_y[, a_z] (a block on a plane)")
    run.add_argument("--y", type=pathlib.Path, default=None, metavar="FILE",
                     help="second horizontal component (a block on a plane)")
    run.add_argument("--z", type=pathlib.Path, default=None, metavar="FILE",
                     help="vertical component, upward positive (a block on a plane)")
    _block_arguments(run, nargs=None, planar=True)
    run.add_argument("--model", default=None, metavar="MODULE:CLASS",
                     help="run any model of the contract instead of the block: package.module:Class (or "
                          "path/to/file.py:Class), built from --param; its default backend unless --backend")
    run.add_argument("--param", type=checked_parameter, action="append", default=None, metavar="NAME=VALUE",
                     help="a keyword of --model's class (a number, or text), repeated for each")
    run.add_argument("--bias-y", type=finite("--bias-y"), default=0.0,
                     help="on a plane: constant force / weight in +y [-] (--bias is the one in +x)")
    record_arguments(run)
    run.add_argument("--resample", type=positive("--resample"), default=None, metavar="DT",
                     help="resample every component to the step DT [s] first (linear a(t), exact at the "
                          "new samples; see blockdae.excitation.resample): files of mixed steps make one motion")
    run.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG", help="save a figure")
    run.add_argument("--history", type=pathlib.Path, default=None, metavar="CSV",
                     help="write the history as CSV: t, base acceleration, u, v (signed) and mode at the record's "
                          "samples and every event")
    run.add_argument("--json", action="store_true", help="print the results as JSON")
    run.add_argument("--events", choices=("summary", "all", "none"), default="summary",
                     help=f"events to print: the first and last {_EVENTS_SHOWN} (default), all or none")
    run.add_argument("--quiet", action="store_true", help="print only u(t_end) [m]")
    run.set_defaults(command=_run)

    newmark_ = sub.add_parser("newmark", help="Newmark's one-way analysis: downslope displacement "
                                              "(positive) for both polarities, over records x ky x PGA")
    newmark_.add_argument("records", type=pathlib.Path, nargs="*", metavar="RECORD",
                          help="accelerogram files or folders of them "
                               f"({', '.join(RECORD_SUFFIXES)}, each also .gz; sorted by name); or --set NAME")
    ky = newmark_.add_mutually_exclusive_group(required=True)
    ky.add_argument("--ky", type=positive("--ky"), nargs="+",
                    help="yield acceleration(s) [g]; 0.05 g is 0.49 m/s²: a ky typed in m/s² is read "
                         "9.8 times too large and gives millimetres")
    ky.add_argument("--ky-table", type=ky_table_row, nargs="+", metavar="D_M:KY_G",
                    help="ky [g] against the sliding displacement D [m] instead, linear between the rows "
                         "(e.g. 0:0.15 0.5:0.05, a slide that softens as it moves)")
    newmark_.add_argument("--pga", type=positive("--pga"), nargs="+", default=None, metavar="PGA_G",
                          help="scale each record so that its peak |a| is PGA_G [g], each value in turn "
                               "(default: as read; above 2 g, likely m/s², refused unless --accept-peak)")
    newmark_.add_argument("--pga-rounding", choices=PGA_ROUNDINGS, default="exact",
                          help="with --pga: 'slammer' rounds the record's own peak to 0.001 g before "
                               "scaling, as SLAMMER does (default exact)")
    newmark_.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                          help="gravitational acceleration [m/s²], also the unit 'g' (default 9.80665)")
    record_arguments(newmark_)
    recursive_argument(newmark_)
    set_argument(newmark_)
    newmark_.add_argument("--csv", type=pathlib.Path, default=None, metavar="PATH",
                          help="write the table (one row per record, PGA and ky) as CSV")
    newmark_.add_argument("--plot", type=pathlib.Path, default=None, metavar="PATH",
                          help="save a figure: D against ky per record; for one record and one ky, the "
                               "history of the polarity with the larger D")
    newmark_.add_argument("--history", type=pathlib.Path, default=None, metavar="CSV",
                          help="one record, one PGA and one ky: write the history of both polarities as CSV "
                               "(t, the ground acceleration as given, D >= 0 downslope and its rate per polarity)")
    newmark_.add_argument("--derivative", action="store_true",
                          help="also dD/dky [m/g] of each polarity, exact (its first run compiles, about 10 s)")
    units_out_argument(newmark_)
    newmark_.add_argument("--json", action="store_true", help="print the results as JSON")
    newmark_.set_defaults(command=_newmark)

    add_flexible_parser(sub)
    add_spectrum_parser(sub)
    add_two_point_parser(sub)
    add_upthrow_parser(sub)
    add_rocking_parser(sub)

    examples = sub.add_parser("examples", help="Sawicki & Chybicki's (2005) Examples 1-6: exact vs the paper")
    examples.set_defaults(command=_examples)

    batch = sub.add_parser("batch", help="every record in a folder, over a parameter grid")
    batch.add_argument("folder", type=pathlib.Path, nargs="?",
                       help=f"folder of records ({', '.join(RECORD_SUFFIXES)}, each also gzip-compressed: .gz); "
                            "or --set NAME")
    _block_arguments(batch, nargs="+")
    record_arguments(batch)
    recursive_argument(batch)
    set_argument(batch)
    batch.add_argument("--csv", type=pathlib.Path, default=None, help="write the results as CSV")
    batch.add_argument("--json", action="store_true", help="print the results as JSON")
    batch.add_argument("--strict", action="store_true", help="stop at the first bad file")
    batch.set_defaults(command=_batch)

    add_study_parser(sub)
    add_hazard_parsers(sub)
    add_design_parser(sub)
    add_back_analysis_parser(sub)
    add_map_parser(sub)
    add_info_parser(sub)
    add_app_parser(sub)
    return parser


def _block_arguments(parser, nargs, planar=False):
    grid = " (several: a grid over every combination)" if nargs else ""
    parser.add_argument("--mu", type=finite("--mu"), required=not planar, nargs=nargs,
                        help="static friction coefficient [-]" + grid + (" (required without --model)"
                                                                          if planar else ""))
    parser.add_argument("--mu-kinetic", type=finite("--mu-kinetic"), default=None, nargs=nargs,
                        help="kinetic friction f [-] (default mu)" + grid)
    parser.add_argument("--bias", type=finite("--bias"), default=[0.0] if nargs else 0.0, nargs=nargs,
                        help="R/Q, constant force / weight in +x [-]" + grid)
    parser.add_argument("--direction", choices=("both", "positive", "negative"), default="both",
                        help="allowed sliding direction (negative + bias 0: one-way Newmark, u < 0; "
                             "see `blockdae newmark` for positive downslope displacements)")
    parser.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                        help="gravitational acceleration [m/s²], also the unit 'g' (default 9.80665)")
    parser.add_argument("--backend", default=None if planar else "exact",
                        help=f"solver backend, one of {backends.available()} (default: exact"
                             + ("; on a plane: ida)" if planar else ")"))
    parser.add_argument("--t-end", type=positive("--t-end"), default=None,
                        help="final time [s] (default: until the block rests after the record)")


# ---- commands ---------------------------------------------------------------

def _run(args):
    _check_units_and_backend(args)
    if args.model is not None:
        if args.mu is not None:
            raise UsageError("argument --mu: the built-in block's; with --model give --param mu=VALUE")
        return run_model(args, _print_events)
    if args.param is not None:
        raise UsageError("argument --param: takes --model MODULE:CLASS")
    if args.mu is None:
        raise UsageError("the following arguments are required: --mu (or --model MODULE:CLASS)")
    motion = read_motion_argument(args)
    if is_planar(motion) or args.y is not None or args.z is not None:
        return run_planar(args, motion, _print_events)
    if args.bias_y:
        raise UsageError("argument --bias-y: needs a second horizontal component (--y, or a table of "
                         "time, a_x, a_y)")
    block = _block(args, args.mu, args.mu_kinetic, args.bias)
    record = x_record(motion, args.record)
    start = time.perf_counter()
    solution = checked(lambda: simulate(block, record, t_end=args.t_end, backend=args.backend or "exact"),
                        f"{args.record}")
    wall = time.perf_counter() - start
    if args.plot is not None:
        _save_plot(args, solution, record, block)
    if args.history is not None:
        history = solution.history()  # in g s² where --g is 1, a dimensionless set-up
        write_csv(args.history, history.to_dict(orient="records"), list(history.columns))
    if args.json:
        print(json.dumps(_run_json(record, block, solution, wall), indent=2))
        return 0
    length = length_units(block.g)[0]  # g s² where --g is 1, a dimensionless set-up
    if args.quiet:
        print(f"{solution.displacement:+.6f} {length}")
        return 0
    print(f"record: {describe_record(record, block.g)}")
    print(f"block: {_describe_block(block)}; backend {solution.backend}")
    print(f"final time t_end = {solution.t_end:.4f} s"
          + (" (block at rest after the record)" if args.t_end is None else ""))
    print(f"permanent displacement u(t_end) = {solution.displacement:+.6f} {length}")
    print(f"max |u| = {solution.max_abs_displacement:.6f} {length}")
    print_run_end(solution, args, wall, _print_events)
    return 0


def _newmark(args):
    if args.ky_table is not None and (args.history is not None or args.plot is not None or args.derivative):
        raise UsageError("--ky-table: --history, --plot and --derivative take a constant --ky")
    table = ky_table(args)
    ky = np.asarray(args.ky, dtype=float) if table is None else table
    record_set = files_or_set(args, args.records)
    paths = [] if record_set is not None else \
        [p for arg in args.records for p in (folder_files(arg, args) if arg.is_dir() else [arg])]
    records = list(record_set) if record_set is not None else [read(path, args) for path in paths]
    pga = None if args.pga is None else args.pga[0] if len(args.pga) == 1 else args.pga
    one = len(paths) == 1 and np.ndim(pga) == 0  # one record file at one PGA: a NewmarkResult
    where = f"{paths[0]}" if len(paths) == 1 else ""
    motions = records[0] if one else records if record_set is None else record_set
    with warnings.catch_warnings():
        warnings.simplefilter("always", UnitsWarning)
        warnings.showwarning = _prefixed(warnings.showwarning, where)
        result = checked(lambda: newmark(motions, ky, g=args.g, pga=pga,
                                         pga_rounding=args.pga_rounding, derivative=args.derivative,
                                         check_peak=not args.accept_peak), where)
    table = result.to_dataframe()
    if one:
        table.insert(0, "pga_g", records[0].peak_acceleration / args.g if pga is None else pga)
        table.insert(0, "record", records[0].name)
    rows = [in_units_out(row, args.units_out) for row in table.to_dict(orient="records")]
    if args.csv is not None:
        write_csv(args.csv, rows)
    if args.plot is not None:
        _newmark_plot(args, records, pga, result)
    if args.history is not None:
        _newmark_history(args, records, pga, one)
    _print_newmark(args, records, pga, one, rows)
    saved = [f"{what}: {path}" for what, path in (("results", args.csv), ("figure", args.plot),
                                                  ("history", args.history)) if path is not None]
    for line in saved:
        print(line, file=sys.stderr if args.json else sys.stdout)
    return 0


def _print_newmark(args, records, pga, one, rows):
    """The Newmark table (JSON with --json): one row per (record, PGA, ky), displacements in --units-out."""
    scale = {} if pga is None else {"pga_g": pga, "pga_rounding": args.pga_rounding}
    if args.json:
        fields = record_fields(records[0]) if one else {"records": [record_fields(r) for r in records]}
        print(json.dumps({**fields, **scale, "g_m_s2": args.g, "results": rows}, indent=2, default=float))
        return
    if one:
        print(f"record: {describe_record(records[0])}")
    else:
        print(f"{len(records)} records; PGA [g]: " + ("each record's own peak" if pga is None else "the target"))
    if pga is not None:
        print(f"scaled to a peak of {', '.join(f'{p:g}' for p in np.atleast_1d(pga))} g "
              f"(pga rounding: {args.pga_rounding})")
    u = args.units_out
    print(f"Newmark rigid block, one-way; downslope displacement D >= 0 [{u}]; g = {args.g:g} m/s²")
    if args.ky_table is not None:
        print(f"ky against the sliding displacement: {ky_table(args)} (the column ky [g]: at D = 0)")
    width = 0 if one else max(len("record"), *(len(r.name) for r in records))
    head = "" if one else f"{'record':<{width}} {'PGA [g]':>8} "
    columns = [f"{name}_{u}" for name in ("normal", "inverse", "mean", "max")]
    columns += [f"dD_dky_{name}_{u}_per_g" for name in ("normal", "inverse")] if args.derivative else []
    titles = [f"{name} [{u}]" for name in ("normal", "inverse", "mean", "max")]
    titles += [f"dD/dky {name} [{u}/g]" for name in ("normal", "inverse")] if args.derivative else []
    widths = [max(12, len(title)) for title in titles]
    print(f"{head}{'ky [g]':>8} " + " ".join(f"{t:>{w}}" for t, w in zip(titles, widths)))
    for row in rows:
        head = "" if one else f"{row['record']:<{width}} {row['pga_g']:8.4f} "
        cells = [f"{row[c]:{w}.6f}" if c.startswith(("normal", "inverse", "mean", "max")) else f"{row[c]:{w}.6g}"
                 for c, w in zip(columns, widths)]
        print(f"{head}{row['ky_g']:8.4f} " + " ".join(cells))


def _newmark_history(args, records, pga, one):
    """--history: t, the ground acceleration [g] and, per polarity, D >= 0 downslope [m] and
    its rate [m/s] at the record's samples and every event of either polarity."""
    if not one or len(args.ky) > 1:
        raise UsageError("--history takes one record, one --pga (or none) and one --ky")
    record = records[0]
    if pga is not None:
        record = record.scaled(pga_factor(record.peak_acceleration, pga, args.g, args.pga_rounding))
    block = SlidingBlock(mu=args.ky[0], direction="negative", g=args.g)
    runs = {name: simulate(block, motion) for name, motion in (("normal", record), ("inverse", record.inverted()))}
    t_end = max(run.t_end for run in runs.values())
    t = np.union1d(record.times[record.times <= t_end], np.concatenate([[t_end], *(r.t_events for r in runs.values())]))
    columns = {"t_s": t, "ground_acceleration_g": record.acceleration(t) / args.g}
    for name, run in runs.items():
        u, v = run(np.minimum(t, run.t_end))
        columns[f"{name}_D_m"], columns[f"{name}_sliding_rate_m_s"] = 0.0 - u, 0.0 - v
    write_csv(args.history, [dict(zip(columns, row)) for row in zip(*columns.values())], list(columns))


def _newmark_plot(args, records, pga, result):
    """--plot: D against ky per record; one record at one PGA and one ky: the history (ground
    acceleration with ky, downslope velocity and displacement D >= 0) of the polarity with
    the larger D."""
    from .._plot import plot
    from ..sliding import newmark_history_figure

    if len(records) > 1 or np.ndim(pga) != 0 or len(args.ky) > 1:
        save_figure(plot(result), args.plot)
        return
    record = records[0]
    if pga is not None:
        record = record.scaled(pga_factor(record.peak_acceleration, pga, args.g, args.pga_rounding,
                                          check_peak=not args.accept_peak))
    normal, inverse = (float(np.ravel(d)[0]) for d in (result.normal, result.inverse))
    inverse, d = inverse > normal, max(normal, inverse)
    motion = record.inverted() if inverse else record
    block = SlidingBlock(mu=args.ky[0], direction="negative", g=args.g)
    solution = simulate(block, motion, t_end=None)
    polarity = "inverse" if inverse else "normal"
    title = f"{record.name}, {polarity} polarity: ky = {args.ky[0]:g} g, D = {d:.4g} m"
    save_figure(newmark_history_figure(solution, motion, args.ky[0], args.g, polarity=polarity, n_points=4000,
                                       title=title), args.plot)


def _examples(args):
    print("Sawicki & Chybicki 2005, Examples 1-6: exact event times [s] and displacements [m] (g = 9.81 m/s², "
          "as in the paper)")
    for example in seed_examples():
        solution = example_solution(example)
        print(f"\n{example.name}: {example.description}; "
              + (f"t_end = {example.t_end:g} s" if example.t_end else "until rest"))
        print(f"  {'#':>2}  {'t exact [s]':>12}  {'t paper [s]':>11}  {'from':>8} -> {'to':<8}  {'u [m]':>10}")
        for i, event in enumerate(solution.events):
            paper = example.paper_event_times[i] if i < len(example.paper_event_times) else None
            paper = f"{paper:11.4f}" if paper is not None else f"{'-':>11}"
            print(f"  {i + 1:2d}  {event.t:12.6f}  {paper}  {event.mode_before.name:>8} -> "
                  f"{event.mode_after.name:<8}  {event.u:+10.6f}")
        paper_u = "" if example.paper_displacement is None else f" (paper: {example.paper_displacement:+.4f} m)"
        print(f"  u(t_end) = {solution.displacement:+.6f} m{paper_u}; "
              f"max |u| = {solution.max_abs_displacement:.6f} m; t_end = {solution.t_end:.6f} s")
        if example.note:
            print(f"  note: {example.note}")
    return 0


def _batch(args):
    grid = list(itertools.product(args.mu, args.mu_kinetic or [None], args.bias))
    mu, f, bias = (np.array([np.nan if x is None else x for x in column]) for column in zip(*grid))
    block = _block(args, mu, None if args.mu_kinetic is None else f, bias)
    record_set = files_or_set(args, args.folder)
    sources = [(name, lambda name=name: record_set[name]) for name in record_set.names] if record_set is not None \
        else [(path, lambda path=path: read(path, args)) for path in folder_files(args.folder, args)]
    metadata = {} if record_set is None else record_set.metadata.to_dict("index")
    rows, failed = [], []
    start = time.perf_counter()
    with progress_bar(len(sources), "batch", "record") as bar:
        for label, source in sources:
            bar.set_postfix_str(getattr(label, "name", label), refresh=False)
            try:
                record = source()
                result = checked(lambda: simulate(block, record, t_end=args.t_end, backend=args.backend), f"{label}")
            except UsageError as err:
                if args.strict:
                    raise
                failed.append(str(err))
            else:
                rows += [{**row, **metadata.get(record.name, {})} for row in _batch_rows(record, block, result)]
            bar.update()
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps({"rows": rows, "failed": failed}, indent=2))
    else:
        print(f"{'record':<32} {'mu [-]':>7} {'f [-]':>7} {'bias [-]':>8} {'u end [m]':>11} {'max|u| [m]':>11} "
              f"{'events':>7}")
        for row in rows:
            print(f"{row['record']:<32} {row['mu']:7.4f} {row['mu_kinetic']:7.4f} {row['bias']:+8.4f} "
                  f"{row['u_end_m']:+11.6f} {row['max_abs_displacement_m']:11.6f} {row['n_events']:7d}")
        print(f"{len(rows)} analyses of {len(sources) - len(failed)} records in {wall:.2f} s (wall clock)")
    if args.csv is not None:
        fields = [*_CSV_FIELDS[:1], *next(iter(metadata.values()), {}), *_CSV_FIELDS[1:]]
        checked(lambda: write_csv(args.csv, rows, fields), f"--csv {args.csv}")
        print(f"results: {args.csv}", file=sys.stderr if args.json else sys.stdout)
    return report_failures(failed, len(sources))


# ---- helpers ------------------------------------------------------------------

def _version():
    try:
        return importlib.metadata.version("blockdae")
    except importlib.metadata.PackageNotFoundError:  # run from a source tree
        return "unknown"


def _compilation_cache(args):
    """--no-cache / --cache-dir override the default JAX compilation cache (this process)."""
    if args.no_cache or args.cache_dir is not None:
        set_compilation_cache(None if args.no_cache else args.cache_dir)


#: the command-line flag of each SlidingBlock field, for errors that name the argument
_FLAGS = {"mu_kinetic": "--mu-kinetic", "mu": "--mu", "bias": "--bias", "g": "--g"}


def checked_parameter(text):
    """--param NAME=VALUE as (name, value); argparse names the flag on a bad one."""
    try:
        return parameter(text)
    except ValueError as err:
        raise argparse.ArgumentTypeError(str(err)) from None


def _check_units_and_backend(args):
    if args.units is not None:
        checked(lambda: unit_factor(args.units), "--units")
    if args.backend is not None and args.backend not in backends.available():
        raise UsageError(f"--backend {args.backend!r} is unknown; choose one of {backends.available()}")


def _block(args, mu, mu_kinetic, bias):
    _check_units_and_backend(args)
    try:
        return SlidingBlock(mu=mu, mu_kinetic=mu_kinetic, bias=bias, g=args.g, direction=args.direction)
    except ValueError as err:
        message = str(err)
        flag = next((flag for field, flag in _FLAGS.items() if message.startswith(f"{field}=")), None)
        raise UsageError(f"argument {flag}: {message}" if flag else message) from None


def _describe_block(block):
    return (f"mu = {block.mu:g}, f = {block.friction_kinetic:g}, R/Q = {block.bias:g}, "
            f"direction {block.direction}, {describe_gravity(block.g)}")


def _print_events(solution, which):
    """The event table: all events, none, or the first and last few of a long list."""
    events = solution.events
    if which == "none" or not events:
        return
    if which == "all" or len(events) <= 2 * _EVENTS_SHOWN:
        print(solution.event_table())
        return
    lines = solution.event_table(events[:_EVENTS_SHOWN]).splitlines()
    lines.append(f"{'...':>12}  ({len(events) - 2 * _EVENTS_SHOWN} more events; --events all prints them)")
    lines += solution.event_table(events[-_EVENTS_SHOWN:]).splitlines()[1:]
    print("\n".join(lines))


def _save_plot(args, solution, record, block):
    from .._plot import plot

    save_figure(plot(solution, record, block, title=f"{record.name}: mu = {args.mu}"), args.plot)


def _block_fields(block):
    return {"mu": block.mu, "mu_kinetic": block.friction_kinetic, "bias": block.bias, "g_m_s2": block.g,
            "direction": block.direction}


def _run_json(record, block, solution, wall):
    return {
        **record_fields(record), **_block_fields(block), "backend": solution.backend,
        "u_end_m": solution.displacement, "max_abs_displacement_m": solution.max_abs_displacement,
        "t_end_s": clean(solution.t_end), "wall_time_s": wall,
        "events": [{"t_s": e.t, "from": e.mode_before.name, "to": e.mode_after.name, "u_m": e.u, "v_m_s": e.v}
                   for e in solution.events],
    }


def _batch_rows(record, block, result):
    return [{
        **record_fields(record), **_block_fields(block.item(i)), "backend": result.backend,
        "u_end_m": float(result.displacement[i]),
        "max_abs_displacement_m": float(result.max_abs_displacement[i]),
        "n_events": int(result.n_events[i]), "t_end_s": clean(float(result.t_end[i])),
    } for i in range(block.batch_shape[0])]
