"""``blockdae study``: the command function for the CLI.

Hook into ``blockdae._cli._parser`` with ``add_study_parser(sub)``; it sets ``command``
to :func:`run_study` (errors: one ``blockdae: error: ...`` line, exit status 2).
"""

import argparse
import pathlib
import sys
import time

import numpy as np

from .._units import STANDARD_GRAVITY
from ..excitation import read_record
from ..structures import ShearFrame
from ._io import save_study
from ._study import study, summary

_SUFFIXES = (".csv", ".txt", ".dat", ".at2")


class _Error(Exception):
    """A bad file or argument."""


def _grid(text):
    """"START:STOP:N" (N values, linearly spaced, ends included) or one number."""
    try:
        if ":" in text:
            start, stop, n = text.split(":")
            return list(np.linspace(float(start), float(stop), int(n)))
        return [float(text)]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number or START:STOP:N, got {text!r}") from None


def add_study_parser(subparsers):
    """The ``study`` sub-command on an argparse ``subparsers`` object."""
    p = subparsers.add_parser("study", help="every record of a folder × mu × PGA × ground and floors (seed 002)")
    p.add_argument("folder", type=pathlib.Path, help=f"folder of records ({', '.join(_SUFFIXES)})")
    p.add_argument("--mu", type=float, nargs="+", required=True, help="friction coefficients [-]")
    size = p.add_mutually_exclusive_group(required=True)
    size.add_argument("--pga", type=_grid, nargs="+", help="target peak accelerations [g]: values or START:STOP:N")
    size.add_argument("--scale", type=_grid, nargs="+", help="factors on the motions [-]: values or START:STOP:N")
    p.add_argument("--frame", type=float, nargs="*", default=[], metavar="T1",
                   help="fundamental periods [s] of shear frames: every floor of each is a location")
    p.add_argument("--storeys", type=int, default=5, help="storeys of the frames (default 5)")
    p.add_argument("--damping", type=float, default=0.05, help="modal damping ratio of the frames [-] (default 0.05)")
    p.add_argument("--no-ground", action="store_true", help="floors only")
    p.add_argument("--direction", choices=("negative", "positive", "both"), default="negative",
                   help="allowed sliding direction (default negative: one-way)")
    p.add_argument("--units", default=None, help="acceleration units of the files: g, m/s2, cm/s2 or gal "
                                                 "(default: as an AT2 header says, else g)")
    p.add_argument("--dt", type=float, default=None, help="sample step [s], for one-column files")
    p.add_argument("--out", type=pathlib.Path, required=True, help="results table (.csv or .parquet)")
    p.add_argument("--summary", type=pathlib.Path, default=None, help="also the seed's summaries (.csv)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="a Dask scheduler (e.g. tcp://host:8786) to run the tasks on")
    p.set_defaults(command=run_study)
    return p


def run_study(args) -> int:
    """Run the study that ``args`` describe; the exit status."""
    try:
        return _run(args)
    except _Error as err:
        print(f"blockdae: error: {err}", file=sys.stderr)
        return 2


def _run(args):
    records = _records(args)
    frames = [ShearFrame(args.storeys, period, args.damping) for period in args.frame] if args.frame else []
    where = ([] if args.no_ground else ["ground"]) + [f.floor(i) for f in frames for i in range(1, f.storeys + 1)]
    grid = dict(pga=_flat(args.pga)) if args.pga else dict(scale=_flat(args.scale))
    client = _client(args.scheduler)
    start = time.perf_counter()
    try:
        table = study(records, mu=args.mu, where=where, direction=args.direction, executor=client, **grid)
    except (ValueError, TypeError) as err:
        raise _Error(str(err)) from None
    finally:
        if client is not None:
            client.close()
    wall = time.perf_counter() - start
    _save(lambda: save_study(table, args.out), "--out")
    if args.summary is not None:
        _save(lambda: save_study(summary(table), args.summary), "--summary")
    print(f"{len(table)} analyses ({len(records)} records × {len(where)} locations × {len(args.mu)} mu × "
          f"{len(table) // (len(records) * len(where) * len(args.mu))} intensities) in {wall:.2f} s; "
          f"results: {args.out}")
    return 0


def _records(args):
    if not args.folder.is_dir():
        raise _Error(f"{args.folder}: not a folder")
    paths = sorted(p for p in args.folder.iterdir() if p.suffix.lower() in _SUFFIXES)
    if not paths:
        raise _Error(f"{args.folder}: no record files ({', '.join(_SUFFIXES)})")
    units = {} if args.units is None else {"units": args.units}
    records = []
    for path in paths:  # every file is read (and checked) before any analysis
        try:
            records.append(read_record(path, dt=args.dt, g=STANDARD_GRAVITY, **units))
        except (ValueError, OSError) as err:
            message = str(err)
            raise _Error(message if str(path) in message else f"{path}: {message}") from None
    return records


def _flat(groups):
    return [x for group in groups for x in group]


def _client(address):
    if address is None:
        return None
    try:
        from distributed import Client
    except ImportError:
        raise _Error("--scheduler needs dask.distributed: pip install 'blockdae[study]'") from None
    try:
        return Client(address, timeout=30)
    except (OSError, TimeoutError) as err:
        raise _Error(f"--scheduler {address}: {err}") from None


def _save(action, flag):
    try:
        action()
    except (ValueError, OSError, ImportError) as err:
        raise _Error(f"{flag}: {err}") from None


def main(argv=None) -> int:
    """Stand-alone entry (``python -m blockdae.study._command``) until the hook in ``_cli``."""
    parser = argparse.ArgumentParser(prog="blockdae")
    add_study_parser(parser.add_subparsers(required=True, metavar="{study}"))
    try:
        args = parser.parse_args(["study", *(argv if argv is not None else sys.argv[1:])])
    except SystemExit as exit_:
        return int(exit_.code or 0)
    return args.command(args)


if __name__ == "__main__":
    sys.exit(main())
