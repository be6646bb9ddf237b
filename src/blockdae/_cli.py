"""The ``blockdae`` command: run a record, print the seed-000 examples, batch a folder.

Every error about a file or an argument ends the command with exit status 2 and one
line ``blockdae: error: ...`` on stderr naming the file (and line) or the argument.
"""

import argparse
import csv
import json
import os
import pathlib
import sys
import time

import numpy as np

from . import backends
from ._examples import seed_examples
from ._simulate import simulate
from .excitation import STANDARD_GRAVITY, read_record
from .excitation._readers import unit_factor
from .model import SlidingBlock

_RECORD_SUFFIXES = (".csv", ".txt", ".dat", ".at2")
_CSV_FIELDS = ("record", "n_samples", "dt_s", "peak_acceleration_m_s2", "mu", "mu_kinetic", "bias",
               "direction", "backend", "displacement_m", "max_abs_displacement_m", "n_events",
               "t_end_s", "wall_time_s")


class _UsageError(Exception):
    """A bad file or argument, reported as ``blockdae: error: ...`` with exit status 2."""


def main(argv=None) -> int:
    """Entry point of the ``blockdae`` console script; returns the exit status."""
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:
        return int(exit_.code or 0)
    try:
        _compilation_cache(args)
        return args.command(args)
    except _UsageError as err:
        print(f"blockdae: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader of the output stopped early (e.g. `| head`)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error at exit
        return 0


def _parser():
    parser = argparse.ArgumentParser(
        prog="blockdae", description="Seismic sliding of a rigid block: exact event times.")
    parser.add_argument("--cache-dir", type=pathlib.Path, default=None,
                        help="JAX compilation cache, so that later runs skip compiling "
                             "(default: $BLOCKDAE_CACHE_DIR or ~/.cache/blockdae/jax)")
    parser.add_argument("--no-cache", action="store_true", help="compile afresh, keep no cache")
    sub = parser.add_subparsers(required=True, metavar="{run,examples,batch}")

    run = sub.add_parser("run", help="slide a block under one accelerogram file")
    run.add_argument("record", type=pathlib.Path, help="accelerogram (CSV t,a / one column / .AT2)")
    _block_arguments(run, mu_nargs=None)
    _record_arguments(run)
    run.add_argument("--t-end", type=float, default=None,
                     help="final time [s] (default: until the block rests after the record)")
    run.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG", help="save a figure")
    run.add_argument("--json", action="store_true", help="print the results as JSON")
    run.set_defaults(command=_run)

    examples = sub.add_parser("examples", help="seed-000 Examples 1-6: exact vs the paper")
    examples.set_defaults(command=_examples)

    batch = sub.add_parser("batch", help="every record in a folder, for one or more mu")
    batch.add_argument("folder", type=pathlib.Path, help=f"folder of records ({', '.join(_RECORD_SUFFIXES)})")
    _block_arguments(batch, mu_nargs="+")
    _record_arguments(batch)
    batch.add_argument("--csv", type=pathlib.Path, default=None, help="write the results as CSV")
    batch.set_defaults(command=_batch)
    return parser


def _block_arguments(parser, mu_nargs):
    parser.add_argument("--mu", type=float, required=True, nargs=mu_nargs,
                        help="static friction coefficient [-]" + (" (several: a grid)" if mu_nargs else ""))
    parser.add_argument("--mu-kinetic", type=float, default=None, help="kinetic friction f [-] (default mu)")
    parser.add_argument("--bias", type=float, default=0.0, help="R/Q, constant force / weight in +x [-]")
    parser.add_argument("--direction", choices=("both", "positive", "negative"), default="both",
                        help="allowed sliding direction (negative + bias 0: one-way Newmark)")
    parser.add_argument("--g", type=float, default=STANDARD_GRAVITY,
                        help="gravitational acceleration [m/s²], also the unit 'g' (default 9.80665)")
    parser.add_argument("--backend", default="exact", help=f"solver backend, one of {backends.available()}")


def _record_arguments(parser):
    parser.add_argument("--units", default="g", help="acceleration units: g, m/s2, cm/s2 or gal")
    parser.add_argument("--dt", type=float, default=None, help="sample step [s], for one-column files")


# ---- commands ---------------------------------------------------------------

def _run(args):
    block = _block(args, args.mu)
    record = _read(args.record, args)
    start = time.perf_counter()
    solution = _checked(lambda: simulate(block, record, t_end=args.t_end, backend=args.backend),
                        f"{args.record}")
    wall = time.perf_counter() - start
    if args.plot is not None:
        import matplotlib.pyplot as plt

        from ._plot import plot

        figure = plot(solution, record, block, title=f"{record.name}: mu = {args.mu}")
        try:
            _checked(lambda: figure.savefig(args.plot, dpi=120), f"--plot {args.plot}")
        finally:
            plt.close(figure)
    if args.json:
        print(json.dumps(_run_json(record, block, solution, wall), indent=2))
        return 0
    print(f"record: {_describe(record)}")
    print(f"block: {_describe_block(block)}; backend {solution.backend}")
    print(f"final time t_end = {solution.t_end:.4f} s"
          + (" (block at rest after the record)" if args.t_end is None else ""))
    print(f"permanent displacement u(t_end) = {solution.displacement:+.6f} m")
    print(f"max |u| = {solution.max_abs_displacement:.6f} m")
    print(f"events: {len(solution.events)}")
    if solution.events:
        print(solution.event_table())
    print(f"time: {wall:.3f} s (wall clock, including compilation on a first call)")
    if args.plot is not None:
        print(f"figure: {args.plot}")
    return 0


def _examples(args):
    print("Seed 000, Examples 1-6: exact event times [s] and displacements [m] (g = 9.81 m/s²)")
    for example in seed_examples():
        solution = simulate(example.block, example.motion, t_end=example.t_end)
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
    block = _block(args, np.asarray(args.mu, dtype=float))
    if not args.folder.is_dir():
        raise _UsageError(f"{args.folder}: not a folder")
    paths = sorted(p for p in args.folder.iterdir() if p.suffix.lower() in _RECORD_SUFFIXES)
    if not paths:
        raise _UsageError(f"{args.folder}: no record files ({', '.join(_RECORD_SUFFIXES)})")
    records = [_read(path, args) for path in paths]
    rows = []
    for k, record in enumerate(records):
        _progress(k, len(records), record.name)
        start = time.perf_counter()
        result = _checked(lambda: simulate(block, record, backend=args.backend), f"{paths[k]}")
        wall = time.perf_counter() - start
        rows += _batch_rows(record, block, result, wall)
    _progress(len(records), len(records), "done")
    print(file=sys.stderr)
    print(f"{'record':<32} {'mu [-]':>7} {'u [m]':>11} {'max|u| [m]':>11} {'events':>7}")
    for row in rows:
        print(f"{row['record']:<32} {row['mu']:7.4f} {row['displacement_m']:+11.6f} "
              f"{row['max_abs_displacement_m']:11.6f} {row['n_events']:7d}")
    total = sum(row["wall_time_s"] for row in rows)
    print(f"{len(rows)} analyses of {len(records)} records in {total:.2f} s (wall clock)")
    if args.csv is not None:
        _checked(lambda: _write_csv(args.csv, rows), f"--csv {args.csv}")
        print(f"results: {args.csv}")
    return 0


# ---- helpers ------------------------------------------------------------------

def _compilation_cache(args):
    """Point JAX's persistent compilation cache at a folder (this process only)."""
    if args.no_cache:
        return
    folder = args.cache_dir or os.environ.get("BLOCKDAE_CACHE_DIR") or (
        pathlib.Path(os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache") / "blockdae" / "jax")
    import jax

    jax.config.update("jax_compilation_cache_dir", str(folder))


def _block(args, mu):
    try:
        unit_factor(args.units)
        if args.backend not in backends.available():
            raise ValueError(f"--backend {args.backend!r} is unknown; choose one of {backends.available()}")
        return SlidingBlock(mu=mu, mu_kinetic=args.mu_kinetic, bias=args.bias, g=args.g,
                            direction=args.direction)
    except ValueError as err:
        raise _UsageError(str(err)) from None


def _read(path, args):
    if not path.is_file():
        raise _UsageError(f"{path}: no such file")
    return _checked(lambda: read_record(path, units=args.units, dt=args.dt, g=args.g), "")


def _checked(action, where):
    """Run ``action``; a ValueError/OSError becomes a usage error naming ``where``."""
    try:
        return action()
    except (ValueError, OSError) as err:
        message = str(err)
        raise _UsageError(message if not where or where in message else f"{where}: {message}") from None


def _describe(record):
    return (f"{record.name} ({record.acceleration_samples.size} samples, dt = {record.dt:g} s, "
            f"duration {record.duration:.2f} s, peak {record.peak_acceleration:.4g} m/s²)")


def _describe_block(block):
    return (f"mu = {block.mu:g}, f = {block.friction_kinetic:g}, R/Q = {block.bias:g}, "
            f"direction {block.direction}, g = {block.g:g} m/s²")


def _record_fields(record):
    return {"record": record.name, "n_samples": int(record.acceleration_samples.size), "dt_s": record.dt,
            "peak_acceleration_m_s2": record.peak_acceleration}


def _run_json(record, block, solution, wall):
    return {
        **_record_fields(record),
        "mu": block.mu, "mu_kinetic": block.friction_kinetic, "bias": block.bias, "g_m_s2": block.g,
        "direction": block.direction, "backend": solution.backend,
        "displacement_m": solution.displacement, "max_abs_displacement_m": solution.max_abs_displacement,
        "t_end_s": solution.t_end, "wall_time_s": wall,
        "events": [{"t_s": e.t, "from": e.mode_before.name, "to": e.mode_after.name, "u_m": e.u, "v_m_s": e.v}
                   for e in solution.events],
    }


def _batch_rows(record, block, result, wall):
    n = block.batch_shape[0]
    return [{
        **_record_fields(record),
        "mu": float(np.broadcast_to(block.mu, (n,))[i]),
        "mu_kinetic": float(np.broadcast_to(block.friction_kinetic, (n,))[i]), "bias": block.bias,
        "direction": block.direction, "backend": result.backend,
        "displacement_m": float(result.displacement[i]),
        "max_abs_displacement_m": float(result.max_abs_displacement[i]),
        "n_events": int(result.n_events[i]), "t_end_s": float(result.t_end[i]), "wall_time_s": wall / n,
    } for i in range(n)]


def _write_csv(path, rows):
    with open(path, "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=_CSV_FIELDS)
        writer.writeheader()
        writer.writerows(rows)


def _progress(done, total, label, width=30):
    filled = width * done // total
    print(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} {label[:40]:<40}",
          end="", file=sys.stderr, flush=True)


if __name__ == "__main__":
    sys.exit(main())
