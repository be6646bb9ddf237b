"""``blockdae info FILE...``: what the readers understood of each file (format, units as read,
step, samples, duration, peak, component, station, event); bad files are listed at the end
and make the exit status 1."""

import pathlib

from ..core._units import STANDARD_GRAVITY
from ..excitation import read_record
from ..excitation._formats import read_channels
from ._common import UsageError, checked, report_failures


def add_info_parser(sub):
    """The ``info`` subcommand."""
    info = sub.add_parser("info", help="what the readers understood of record files (format, units, step, peak, "
                                       "component, station, event)")
    info.add_argument("files", type=pathlib.Path, nargs="+", metavar="FILE", help="record files, any format")
    info.add_argument("--units", default=None, help="units of files that do not state them (SAC, miniSEED, tables)")
    info.add_argument("--dt", type=float, default=None, help="sample step [s] of one-column files")
    info.add_argument("--gain", type=float, default=None, help="counts per unit of --units (SAC/miniSEED counts)")
    info.set_defaults(command=_info)


def _info(args):
    failed = []
    for path in args.files:
        try:
            records = _read(path, args)
        except UsageError as err:
            failed.append(str(err))
            continue
        for record in records:
            print(_describe(path, record))
    return report_failures(failed, len(args.files))


def _read(path, args):
    """Every acceleration channel of the file at ``path`` (one for most files), peaks unchecked."""
    if not path.is_file():
        raise UsageError(f"{path}: no such file")
    options = {} if args.gain is None else {"gain": args.gain}
    records, _ = checked(lambda: read_channels(path, args.units, args.dt, STANDARD_GRAVITY, False, None, options),
                         str(path))
    if records is None:
        records = [checked(lambda: read_record(path, units=args.units, dt=args.dt, check_peak=False), str(path))]
    return records


def _describe(path, record):
    """The lines printed for one file."""
    meta = record.metadata
    peak = record.peak_acceleration
    fields = [("format", meta.get("format", "")), ("units as read", meta.get("units", "")),
              ("time step [s]", f"{record.dt:g}"), ("samples", record.acceleration_samples.size),
              ("duration [s]", f"{record.duration:g}"),
              ("peak", f"{peak / STANDARD_GRAVITY:.4g} g = {peak:.4g} m/s²"),
              ("component", meta.get("component", "")), ("station", meta.get("station", "")),
              ("event", meta.get("event", ""))]
    return "\n".join([str(path)] + [f"  {label:<14} {value if value not in (None, '') else '-'}"
                                    for label, value in fields])
