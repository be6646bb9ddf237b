"""``blockdae info FILE...``: what the readers understood of each file (format, units as read,
step, samples, duration, peak, offset, component, station, event); bad files are listed at the
end and make the exit status 1."""

import argparse
import pathlib
import warnings

from ..units import STANDARD_GRAVITY
from ..excitation import OFFSET_FRACTION, RecordWarning, offset_fraction, read_channels, read_record
from ._common import UsageError, checked, report_failures


def add_info_parser(sub):
    """The ``info`` subcommand."""
    info = sub.add_parser("info", help="what the readers understood of record files (format, units, step, peak, "
                                       "component, station, event)")
    info.add_argument("files", type=pathlib.Path, nargs="+", metavar="FILE", help="record files, any format")
    info.add_argument("--units", default=None, help="units of files that do not state them (SAC, miniSEED, tables)")
    info.add_argument("--dt", type=float, default=None, help="sample step [s] of one-column files")
    info.add_argument("--gain", type=float, default=None, help="counts per unit of --units (SAC/miniSEED counts)")
    info.add_argument("--remove-mean", action=argparse.BooleanOptionalAction, default=None,
                      help="subtract each record's mean (default: for K-NET/KiK-net files only)")
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
    """Every acceleration channel of the file at ``path`` (one for most files), peaks and steps
    unchecked, warnings left out (the offset is among the lines printed)."""
    if not path.is_file():
        raise UsageError(f"{path}: no such file")
    options = {} if args.gain is None else {"gain": args.gain}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordWarning)
        records, _ = checked(lambda: read_channels(path, args.units, args.dt, STANDARD_GRAVITY, False, None, options,
                                                   check_step=False, remove_mean=args.remove_mean), str(path))
        if records is None:
            records = [checked(lambda: read_record(path, units=args.units, dt=args.dt, check_peak=False,
                                                   check_step=False, remove_mean=args.remove_mean), str(path))]
    return records


def _describe(path, record):
    """The lines printed for one file."""
    meta = record.metadata
    peak = record.peak_acceleration
    fields = [("format", meta.get("format", "")), ("units as read", meta.get("units", "")),
              ("time step [s]", f"{record.dt:g}"), ("samples", record.acceleration_samples.size),
              ("duration [s]", f"{record.duration:g}"),
              ("peak", f"{peak / STANDARD_GRAVITY:.4g} g = {peak:.4g} m/s²"), ("offset", _offset(record)),
              ("component", meta.get("component", "")), ("station", meta.get("station", "")),
              ("event", meta.get("event", ""))]
    return "\n".join([str(path)] + [f"  {label:<14} {value if value not in (None, '') else '-'}"
                                    for label, value in fields])


def _offset(record) -> str:
    """The record's mean as a fraction of its peak, flagged above :data:`OFFSET_FRACTION`; or
    the mean removed on reading."""
    meta = record.metadata
    if meta.get("mean_removed"):
        return f"mean {meta['mean_m_s2']:.4g} m/s² removed on reading"
    fraction = offset_fraction(record.acceleration_samples)
    mean = float(record.acceleration_samples.mean())
    flag = (f": an offset (above {100 * OFFSET_FRACTION:g} %), --remove-mean or --baseline removes it"
            if fraction > OFFSET_FRACTION else "")
    return f"mean {mean:.4g} m/s² = {100 * fraction:.3g} % of the peak{flag}"
