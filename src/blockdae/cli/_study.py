"""``blockdae study``: the command function for the CLI.

``blockdae.cli`` adds it with ``add_study_parser(sub)``; it sets ``command`` to
:func:`run_study` (errors: :class:`UsageError`, one ``blockdae: error: ...`` line, exit
status 2; no Dask worker alive for ``--no-worker-timeout`` [s]: such a line, exit status
1). Every file is read, and checked, before any analysis.
"""

import argparse
import pathlib
import sys
import time

import numpy as np

from ._common import (UsageError, files_or_set, ky_table_row, number, positive, read, record_arguments,
                           recursive_argument, set_argument)
from ._flexible import add_flexible_study_arguments, flexible_study_block
from ..units import STANDARD_GRAVITY
from ..excitation import RECORD_SUFFIXES, record_files
from ..structures import ShearFrame
from ..studies import NoWorkerError, save_study, study, summary


def _grid(text):
    """"START:STOP:N" (N values, linearly spaced, ends included) or one number."""
    try:
        if ":" in text:
            start, stop, n = text.split(":")
            return list(np.linspace(float(start), float(stop), int(n)))
        return [float(text)]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number or START:STOP:N, got {text!r}") from None


def _seconds_or_none(text):
    """--no-worker-timeout: a positive number of seconds [s], or "none" (wait forever)."""
    return None if text.strip().lower() == "none" else positive("--no-worker-timeout")(text)


def add_study_parser(subparsers):
    """The ``study`` sub-command on an argparse ``subparsers`` object."""
    p = subparsers.add_parser("study", help="every record of a folder × mu (or ky) × PGA × ground and floors "
                                            "(--ky with --height and --vs: the flexible sliding mass)")
    p.add_argument("folder", type=pathlib.Path, nargs="?",
                   help=f"folder of records ({', '.join(RECORD_SUFFIXES)}, each also gzip-compressed: .gz); "
                        "or --set NAME")
    swept = p.add_mutually_exclusive_group(required=True)
    swept.add_argument("--mu", type=positive("--mu"), nargs="+", help="friction coefficients [-] (the 1-D block)")
    swept.add_argument("--ky", type=positive("--ky"), nargs="+",
                       help="yield accelerations [g]: of Newmark's rigid block (column ky_g), or with --height "
                            "and --vs of the flexible sliding mass")
    swept.add_argument("--ky-table", type=ky_table_row, nargs="+", metavar="D_M:KY_G",
                       help="the flexible sliding mass with ky [g] against the sliding displacement D [m], rows D:ky "
                            "(bd.KyTable; the column ky_g: ky at D = 0)")
    size = p.add_mutually_exclusive_group(required=True)
    size.add_argument("--pga", type=_grid, nargs="+", help="target peak accelerations [g]: values or START:STOP:N")
    size.add_argument("--scale", type=_grid, nargs="+", help="factors on the motions [-]: values or START:STOP:N")
    p.add_argument("--frame", type=positive("--frame"), nargs="*", default=[], metavar="T1",
                   help="fundamental periods [s] of shear frames: every floor of each is a location")
    p.add_argument("--storeys", type=int, default=5, help="storeys of the frames (default 5)")
    p.add_argument("--damping", type=number("--damping", lambda x: 0 <= x < 1, "in [0, 1)"), default=0.05, help="modal damping ratio of the frames [-] (default 0.05)")
    p.add_argument("--no-ground", action="store_true", help="floors only")
    p.add_argument("--direction", choices=("negative", "positive", "both"), default=None,
                   help="the 1-D block: default both polarities of the one-way block, as newmark (columns "
                        "polarity, D_m >= 0 [m]); negative: the records as given only; positive or both: signed u "
                        "(u_end_m); the flexible mass runs both polarities")
    record_arguments(p)
    recursive_argument(p)
    p.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                   help="the unit 'g' [m/s²] of the files and the PGA grid (default 9.80665)")
    set_argument(p)
    p.add_argument("--out", type=pathlib.Path, required=True, help="results table (.csv or .parquet)")
    p.add_argument("--summary", type=pathlib.Path, default=None, help="also the paper's summaries (.csv)")
    p.add_argument("--checkpoint", type=pathlib.Path, default=None, metavar="FOLDER",
                   help="save each finished task in FOLDER (new, empty, or this study's checkpoint): a rerun "
                        "with the same arguments runs only the tasks not saved yet")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="a Dask scheduler (e.g. tcp://host:8786) to run the tasks on")
    p.add_argument("--no-worker-timeout", type=_seconds_or_none, default=60.0, metavar="SECONDS",
                   help="with --scheduler: fail (exit status 1) after this long [s] with no worker alive; "
                        "'none': wait forever (default 60)")
    add_flexible_study_arguments(p)
    p.set_defaults(command=run_study)
    return p


def run_study(args) -> int:
    """Run the study that ``args`` describe; the exit status."""
    block, swept, label = _block(args)
    records = _records(args)
    frames = [ShearFrame(args.storeys, period, args.damping) for period in args.frame] if args.frame else []
    where = ([] if args.no_ground else ["ground"]) + [f.floor(i) for f in frames for i in range(1, f.storeys + 1)]
    grid = dict(pga=_flat(args.pga)) if args.pga else dict(scale=_flat(args.scale))
    client = _client(args.scheduler)
    start = time.perf_counter()
    try:
        table = study(records, where=where, direction=args.direction, executor=client, g=args.g,
                      no_worker_timeout=args.no_worker_timeout, checkpoint=args.checkpoint, block=block,
                      check_peak=not args.accept_peak, **swept, **grid)
    except (ValueError, TypeError) as err:
        raise UsageError(str(err)) from None
    except NoWorkerError as err:
        print(f"blockdae: error: {err}", file=sys.stderr)
        return 1
    finally:
        if client is not None:
            client.close()
    wall = time.perf_counter() - start
    _save(lambda: save_study(table, args.out), "--out")
    if args.summary is not None:
        _save(lambda: save_study(summary(table), args.summary), "--summary")
    values = next(iter(swept.values()))
    n_swept = len(values) if isinstance(values, list) else 1  # numbers, or one ky table
    n_polarities = table["polarity"].nunique() if "polarity" in table else 1
    polarities = f" × {n_polarities} polarities" if n_polarities > 1 else ""
    intensities = len(table) // (len(records) * len(where) * n_polarities * n_swept)
    print(f"{len(table)} analyses ({len(records)} records × {len(where)} locations{polarities} × {n_swept} {label} "
          f"× {intensities} intensities) in {wall:.2f} s; results: {args.out}")
    return 0


def _block(args):
    """(the block to study, None for the 1-D block; the swept keyword and values; their
    name): the rigid block for --mu, or --ky without --height and --vs; else the flexible
    sliding mass; its options are refused with the rigid block."""
    flexible_only = [flag for flag, value in (("--height", args.height), ("--vs", args.vs), ("--vr", args.vr),
                                              ("--soil-damping", args.soil_damping), ("--method", args.method))
                     if value is not None]
    rigid = args.mu is not None or (args.ky is not None and args.height is None and args.vs is None)
    if rigid:
        flag = "--mu" if args.mu is not None else "--ky"
        if flexible_only:
            raise UsageError(f"{flexible_only[0]} applies to the flexible sliding mass (--ky or --ky-table with "
                             f"--height and --vs), not to the rigid block of {flag}")
        return (None, dict(mu=args.mu), "mu") if args.mu is not None else (None, dict(ky=args.ky), "ky")
    if args.direction is not None:
        raise UsageError(f"--direction {args.direction}: the flexible sliding mass slides downslope in both "
                         "polarities of each record (columns normal_m, inverse_m); leave --direction out")
    if args.summary is not None:
        raise UsageError("--summary: the paper's summaries are of a block over mu; fit a fragility to the flexible "
                         "mass's table instead (bd.hazard.fit_fragility)")
    block, ky = flexible_study_block(args)
    return block, dict(ky=ky), "ky"


def _records(args):
    """The records of the folder, or the set of --set (a RecordSet: its metadata join the table)."""
    record_set = files_or_set(args, args.folder)
    if record_set is not None:
        return record_set
    try:
        paths = record_files(args.folder, args.recursive)
    except ValueError as err:
        raise UsageError(str(err)) from None
    return [read(path, args) for path in paths]


def _flat(groups):
    return [x for group in groups for x in group]


def _client(address):
    if address is None:
        return None
    try:
        from distributed import Client
    except ImportError:
        raise UsageError("--scheduler needs dask.distributed: pip install 'blockdae[study]'") from None
    try:
        return Client(address, timeout=30)
    except (OSError, TimeoutError) as err:
        raise UsageError(f"--scheduler {address}: {err}") from None


def _save(action, flag):
    try:
        action()
    except (ValueError, OSError, ImportError) as err:
        raise UsageError(f"{flag}: {err}") from None
