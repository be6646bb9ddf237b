"""Readers for accelerogram files: two-column, one-column and PEER NGA .AT2 text, each
plain or gzip-compressed (what :func:`~._read_record.read_record` reads itself; the formats
with a header are ``_formats``'), and the file helpers those formats share."""

import gzip
import io
import pathlib
import re
import typing
import warnings
import zlib

import numpy as np

from ..units import STANDARD_GRAVITY  # noqa: F401 (imported from here by blockdae.excitation)
from . import _record_checks
from ._plausibility import check_peak_acceleration, unstated_units_error
from ._units import _SYMBOLS, canonical_units, time_units_named, unit_factor, units_named

# an AT2 header's "IN UNITS OF ..." text, squeezed by _squeeze_units
_HEADER_UNITS = {"G": "g", "M/S2": "m/s2", "CM/S2": "cm/s2", "GAL": "cm/s2", "GALS": "cm/s2"}
_NPTS = re.compile(r"\bNPTS\s*=\s*(\d+)", re.IGNORECASE)
_DT = re.compile(r"\bDT\s*=\s*([0-9.eE+-]+)", re.IGNORECASE)
_OLD_HEADER = re.compile(r"^\s*(\d+)\s+([0-9.eE+-]+)\s+NPTS", re.IGNORECASE)
_UNITS_OF = re.compile(r"UNITS\s+OF\s+(.*?)[\s.]*$", re.IGNORECASE)
_HEADER_LINES = 10  # where the NPTS/DT line of an AT2 file is looked for
_GZIP_MAGIC = b"\x1f\x8b"  # the first bytes of a gzip file
#: the table read_record reads: (most columns, their description for errors)
ONE_COMPONENT = (2, "1 or 2 columns (time [s], acceleration)")


#: format suffixes of the record files found in a folder (each also gzip-compressed: .gz): tables,
#: PEER AT2, COSMOS V1/V2 (CESMD's .V1C/.V2C too), K-NET (.NS/.EW/.UD) and KiK-net (1: borehole,
#: 2: surface), ESM ASCII, SAC and miniSEED; the format itself is found by content
RECORD_SUFFIXES = (".csv", ".txt", ".dat", ".at2", ".v1", ".v2", ".v1c", ".v2c",
                   ".ns", ".ew", ".ud", ".ns1", ".ew1", ".ud1", ".ns2", ".ew2", ".ud2",
                   ".asc", ".sac", ".mseed", ".miniseed")


def record_files(folder, recursive=False) -> list[pathlib.Path]:
    """The record files in ``folder`` (suffixes :data:`RECORD_SUFFIXES`, each also ``.gz``),
    and in its subfolders if ``recursive``, sorted by their path in it.

    Every file left out is named, with why, in one UserWarning: a file of another suffix,
    or (not ``recursive``) record files in subfolders. Hidden files and folders (a name
    starting with '.') are not looked at. A ValueError names the folder if it is none or
    holds no record file.
    """
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        raise ValueError(f"{folder}: not a folder")
    files = sorted(p for p in folder.rglob("*") if p.is_file()
                   and not any(part.startswith(".") for part in p.relative_to(folder).parts))
    is_record = [record_suffix(p) in RECORD_SUFFIXES for p in files]
    below = [p.parent != folder for p in files]
    paths = [p for p, record, deep in zip(files, is_record, below) if record and (recursive or not deep)]
    other = [p for p, record, deep in zip(files, is_record, below) if not record and (recursive or not deep)]
    unsearched = [p for p, record, deep in zip(files, is_record, below) if record and deep and not recursive]
    notes = [f"{p.relative_to(folder)} (not a record file: suffix {record_suffix(p) or 'none'})" for p in other]
    if unsearched:
        subfolders = sorted({p.relative_to(folder).parts[0] for p in unsearched})
        notes.append(f"{_count(len(unsearched), 'record file')} in subfolders ({', '.join(subfolders)}): "
                     "not searched, recursive=True (--recursive) reads them")
    if notes:
        warnings.warn(f"{folder}: {_count(len(other) + len(unsearched), 'file')} left out: {'; '.join(notes)}",
                      UserWarning, stacklevel=2)
    if not paths:
        raise ValueError(f"{folder}: no record files ({', '.join(RECORD_SUFFIXES)}, each also .gz)")
    return paths


def _count(n, noun):
    """"1 file", "2 files"."""
    return f"{n} {noun}{'' if n == 1 else 's'}"


def record_name(path) -> str:
    """A record's default name: its file's name less ``.gz`` and the format's suffix."""
    return _uncompressed(pathlib.Path(path)).stem


def record_suffix(path) -> str:
    """The format's suffix of a record file, lower case, ``.gz`` left out (".at2" for rec.AT2.gz)."""
    return _uncompressed(pathlib.Path(path)).suffix.lower()


def _uncompressed(path):
    """``path`` less a final ``.gz``."""
    return path.with_suffix("") if path.suffix.lower() == ".gz" else path


def read_samples(path, units, dt, g, check_peak, columns, *, check_step=True, remove_mean=False):
    """(accelerations [m/s²], shape (n, k), sample step [s], start time [s]) of a file read
    as :func:`read_record` reads a table or an AT2 file; a table may hold k > 1 accelerations
    after its time column.

    ``columns``: (most columns of a table, their description for errors), e.g. :data:`ONE_COMPONENT`.
    The peak check covers all k columns at once (one file, one unit).
    """
    return read_table(path, units, dt, g, check_peak, columns, check_step=check_step, remove_mean=remove_mean)[:3]


def read_table(path, units, dt, g, check_peak, columns, text=None, *, check_step=True, remove_mean=False):
    """read_samples' result and the metadata (format, units as read, mean removed) of a table or
    AT2 file (its ``text``, read if None). Units must be stated, by ``units`` or the header; the
    step, peak and offset rules apply (:mod:`._record_checks`, :func:`check_peak_acceleration`)."""
    path = pathlib.Path(path)
    if units is not None:
        canonical_units(units)  # an unknown name fails before the file is read
    text = _text(path) if text is None else text
    layout = _scan(text, path)
    lines = text.split("\n")
    if layout.at2 is not None:
        samples, file_dt, start_time = _read_at2(lines, layout.at2, path)
        samples = samples[:, None]
        header_units, statement = _at2_units(lines[:layout.at2[0]], path)
        step_source = f"{path}, line {layout.at2[0] + 1}: DT"
    else:
        samples, file_dt, start_time = _read_columns(text, layout, path, columns)
        if file_dt is not None:  # a time column: in the units its header names (s by default)
            to_seconds = _table_time_factor(lines[:layout.start], path)
            file_dt, start_time = float(f"{file_dt * to_seconds:.12g}"), start_time * to_seconds
        header_units, statement = _table_units(lines[:layout.start], path)
        rows = _data_line_numbers(lines, layout.start)[:2]
        step_source = (f"{path}, lines {rows[0]}-{rows[-1]}: the time column" if file_dt is not None
                       else f"{path}, the dt given")
    dt = _sample_step(dt, file_dt, path)
    units = _resolve_units(units, header_units, statement, path, samples)
    _record_checks.check_step(dt, step_source, check_step, time_column=layout.at2 is None and file_dt is not None)
    mean = samples.mean(axis=0)
    samples = samples - mean if remove_mean else samples
    if check_peak:
        check_peak_acceleration(samples, units, g, str(path), statement and f"the header's {statement}")
    if not remove_mean:
        _record_checks.check_offset(samples, str(path))
    metadata = {"format": "PEER AT2" if layout.at2 is not None else "table", "units": units,
                "mean_removed": bool(remove_mean), "mean_m_s2": float(mean[0]) * unit_factor(units, g)}
    if layout.at2 is not None:
        metadata.update(_at2_component(text.split("\n", 2)[:2]))
    return samples * unit_factor(units, g), dt, start_time, metadata


class _Layout(typing.NamedTuple):
    """Where a file's data start: an AT2 header, or a table's first line and separators."""
    at2: tuple | None  # (line index, NPTS, DT [s]) of the AT2 header line
    start: int = 0  # index of the table's first data line
    delimiter: str | None = None  # loadtxt's: ",", ";" or None (blanks)
    decimal_comma: bool = False


def _text(path):
    """The text of the file at ``path``, gunzipped if it is gzip-compressed, every line
    end ``\\n``; ValueError naming the file for a binary file or text that is not UTF-8."""
    return decode(file_bytes(path), path)


def file_bytes(path):
    """The bytes of the file at ``path``, gunzipped if it is gzip-compressed."""
    data = pathlib.Path(path).read_bytes()
    return _gunzip(data, path) if data.startswith(_GZIP_MAGIC) else data


def decode(data, path):
    """The text of a file's bytes ``data``, every line end ``\\n``; ValueError naming the
    file at ``path`` for a binary file or text that is not UTF-8."""
    nul = data.find(b"\0")
    if nul >= 0:
        raise ValueError(f"{path}: a binary file (a NUL byte at offset {nul}), not a record: "
                         "records are text (two columns, one column or PEER AT2), plain or gzip-compressed")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        line = data[:err.start].count(b"\n") + 1
        raise ValueError(f"{path}, line {line}: byte 0x{data[err.start]:02x} is not UTF-8 text (a binary file, "
                         "or text in another encoding: save it as UTF-8)") from None
    return text.replace("\r\n", "\n").replace("\r", "\n")


def _gunzip(data, path):
    """The bytes of the gzip-compressed ``data`` of the file at ``path``."""
    try:
        return gzip.decompress(data)
    except (OSError, EOFError, zlib.error) as err:
        raise ValueError(f"{path}: a damaged gzip file ({err})") from None


def _scan(text, path):
    """The :class:`_Layout` of the file at ``path`` (its ``text``), read up to the AT2
    header line or the first data line."""
    at2 = record_suffix(path) == ".at2"
    names = []  # (index, text) of the lines before the first data line that are no numbers
    for i, line in enumerate(io.StringIO(text)):
        header = _at2_header(line, i, path) if i < _HEADER_LINES else None
        if header is not None:
            return _Layout(header)
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        if _numbers(text, False) is None:
            names.append((i, text))  # a header line of column names, or a malformed data line
            continue
        if at2:
            break
        delimiter = ";" if ";" in text else "," if "," in text else None
        decimal_comma = _decimal_comma(text, i, path)
        _check_header_lines(names, len(_numbers(text, decimal_comma)), decimal_comma, path)
        return _Layout(None, i, delimiter, decimal_comma)
    if at2:
        raise ValueError(f"{path}: no 'NPTS=..., DT=...' line in the first {_HEADER_LINES} lines (AT2 header)")
    raise ValueError(f"{path}: no data rows")


#: a field that starts as a number does ("1.5", "-0.2", "--1", ".5e-3x"): no column name
_NUMERIC_LOOKING = re.compile(r"[+-]*\.?\d")


def _check_header_lines(lines, columns, decimal_comma, path):
    """ValueError naming the first of ``lines`` (index, text), the lines above a table's
    first data line that are not all numbers, which is a malformed data line rather than a
    header: a field that starts as a number does, and as many fields as the ``columns``
    of the data lines (a header line names its columns in words)."""
    for i, text in lines:
        fields = [f for f in re.split(r"[;\s]+" if decimal_comma else r"[,;\s]+", text) if f]
        if len(fields) == columns and any(_NUMERIC_LOOKING.match(f) for f in fields):
            bad = next((f for f in fields if _numbers(f, decimal_comma) is None), text)
            raise ValueError(f"{path}, line {i + 1}: not a number, {bad!r}, in {text!r}: a data line, not a header "
                             "(a header line names the columns in words; start a comment line with '#')")


def _sample_step(dt, file_dt, path):
    """The sample step [s]: the file's, which a given ``dt`` must match, or the given one."""
    if file_dt is None:
        if dt is None:
            raise ValueError(f"{path}: one-column file needs the sample step dt [s]")
        return dt
    if dt is not None and not np.isclose(dt, file_dt):
        raise ValueError(f"{path}: dt={dt:.6g} s contradicts the file's step {file_dt:.6g} s")
    return file_dt


def _resolve_units(units, header_units, statement, path, samples):
    """The units to read ``samples`` with: ``units``, or the header's (at ``statement``); they
    must agree, and one of them must be given (else the error gives the peak in each unit)."""
    if units is None:
        if statement is None:
            raise unstated_units_error(str(path), samples)
        if header_units is None:
            raise ValueError(f"{path}, {statement}: units not understood; pass units= ('g', 'm/s2' or 'cm/s2')")
        return header_units
    given = canonical_units(units)
    if header_units and given != header_units:
        raise ValueError(f"{path}: units={units!r} ({_SYMBOLS[given]}) contradicts the header, "
                         f"{statement}, which says {_SYMBOLS[header_units]}; leave units=None to "
                         "use the header's")
    return given


# --- PEER NGA AT2 -----------------------------------------------------------------

def _at2_header(line, index, path):
    """(index, NPTS, DT [s]) if ``line`` is an AT2 header's NPTS/DT line, else None."""
    npts, dt = _NPTS.search(line), _DT.search(line)
    old = _OLD_HEADER.search(line)
    if line.lstrip().startswith("#") or not (npts and dt or old):
        return None
    count, step = (npts.group(1), dt.group(1)) if npts and dt else old.groups()
    try:
        return index, int(count), float(step)
    except ValueError:
        raise ValueError(f"{path}, line {index + 1}: cannot read NPTS and DT in {line.strip()!r}") from None


#: an AT2 header's components (the last field of its second line) that name a vertical channel
_AT2_VERTICAL = {"UP", "UD", "V", "VER", "VERT", "Z", "DWN", "DOWN"}


def _at2_component(first_lines):
    """{"component": the last field of an AT2 file's second line as written (PEER's: "UP",
    "90", "360", "DWN"), "vertical": whether it names a vertical channel}; {} where there
    is none."""
    if len(first_lines) < 2 or "," not in first_lines[1]:
        return {}
    component = first_lines[1].rsplit(",", 1)[1].strip()
    return {"component": component, "vertical": component.upper() in _AT2_VERTICAL} if component else {}


def _at2_units(header_lines, path):
    """(units or None, "line N: '...'") of the header's 'IN UNITS OF' line; (None, None) without."""
    for n, line in enumerate(header_lines, start=1):
        match = _UNITS_OF.search(line)
        if not match:
            continue
        statement = f"line {n}: {line.strip()!r}"
        if re.search(r"VELOCITY|DISPLACEMENT", line, re.IGNORECASE):
            raise ValueError(f"{path}, {statement}: not an acceleration time series")
        return _HEADER_UNITS.get(_squeeze_units(match.group(1))), statement
    return None, None


def _squeeze_units(text):
    """'CM/SEC/SEC', 'cm/s^2', 'CM/S**2' -> 'CM/S2'."""
    text = re.sub(r"\s+", "", text.upper()).replace("SEC", "S")
    return re.sub(r"(/S|\*\*2|\^2|²)$", "2", text)


def _read_at2(lines, header, path):
    """(samples, DT [s], start time 0) of an AT2 file, its values after the header line."""
    index, npts, dt = header
    body = lines[index + 1:]
    try:
        samples = np.array(" ".join(body).split(), dtype=float)
    except ValueError:
        _raise_first_bad_value(body, index + 2, path)
    if samples.size != npts:
        raise ValueError(f"{path}: header (line {index + 1}) says NPTS={npts}, found {samples.size} values")
    _check_last_value(body, index + 2, path)
    bad = np.flatnonzero(~np.isfinite(samples))
    if bad.size:
        counts = np.cumsum([len(line.split()) for line in body])
        line_no = index + 2 + int(np.searchsorted(counts, bad[0], side="right"))
        raise ValueError(f"{path}, line {line_no}: value {samples[bad[0]]} is not finite")
    return samples, dt, 0.0


#: how a value is written: its decimals, and its exponent's digits
_WRITTEN = re.compile(r"[+-]?\d*(?:\.(\d*))?(?:[eEdD][+-]?(\d*))?$")
#: values before the last that show how an AT2 file writes its values
_VALUES_COMPARED = 8


def _check_last_value(body, first_line, path):
    """ValueError naming the line if an AT2 file ends inside a line (no line end after its
    last value) whose last value is written shorter (fewer decimals or exponent digits) than
    the values before it, which are all written alike: a file cut inside its last value
    ('-3.5901855E-0' where the others read '-1.2345678E-02')."""
    if not body or not body[-1].strip():
        return  # the last line is complete
    lines = [(n, line.split()) for n, line in enumerate(body, start=first_line) if line.strip()]
    fields = [field for _, line in lines[-3:] for field in line]
    if len(fields) < 2:
        return
    before = fields[-1 - _VALUES_COMPARED:-1]
    forms = {_form(field) for field in before}
    last = _form(fields[-1])
    if len(forms) == 1 and (shown := forms.pop()) != last and all(a < b for a, b in zip(last, shown) if a != b):
        raise ValueError(f"{path}, line {lines[-1][0]}: the last value, {fields[-1]!r}, is written shorter than "
                         f"the values before it ({before[-1]!r}): the file is cut short; get it again")


def _form(field):
    """(decimals, exponent digits) of a number as written, each -1 where it has no decimal
    point or no exponent."""
    match = _WRITTEN.match(field)
    decimals, exponent = match.groups() if match else (None, None)
    return (-1 if decimals is None else len(decimals)), (-1 if exponent is None else len(exponent))


def _raise_first_bad_value(body, first_line, path):
    """Raise the error for the first field of ``body`` (from file line ``first_line``) that is not a number."""
    for line_no, line in enumerate(body, start=first_line):
        for field in line.split():
            try:
                float(field)
            except ValueError:
                raise ValueError(f"{path}, line {line_no}: not a number, {field!r}, in {line.strip()!r}") from None


# --- tables: one column, or time and accelerations ---------------------------------

def _table_units(header_lines, path):
    """(units or None, "line N: '...'") that a table's header lines (column names and '#'
    comments, e.g. numpy's ``# time (s), acceleration (m/s2)``) name (see
    :func:`~._units.units_named`); (None, None) if they name none. A bracketed ratio that is
    no acceleration unit (a velocity, "(m/s)") is refused, as are two different units."""
    found = {}
    for n, line in enumerate(header_lines, start=1):
        text = line.strip()
        named, others = units_named(text)
        if others:
            raise ValueError(f"{path}, line {n}: {text!r}: the header names units {others[0]!r}, not an "
                             "acceleration in g, m/s2, cm/s2 or gal; convert the file")
        for units in named:
            found.setdefault(units, f"line {n}: {text!r}")
    if len(found) > 1:
        raise ValueError(f"{path}: the header names different units, {', '.join(_SYMBOLS[u] for u in found)} "
                         f"({'; '.join(found.values())}); one file holds one unit")
    return next(iter(found.items()), (None, None))


def _table_time_factor(header_lines, path):
    """The factor to seconds of the time column's unit that a table's header lines name
    (:func:`~._units.time_units_named`: "time (ms)" gives 0.001), 1 where they name none;
    a ValueError naming the line for an unknown unit or two different ones."""
    found = {}
    for n, line in enumerate(header_lines, start=1):
        try:
            named = time_units_named(line)
        except ValueError as err:
            raise ValueError(f"{path}, line {n}: {line.strip()!r}: {err}") from None
        if named is not None:
            found.setdefault(named[1], f"line {n}: {line.strip()!r}")
    if len(found) > 1:
        raise ValueError(f"{path}: the header names different units of time ({'; '.join(found.values())})")
    return next(iter(found), 1.0)


def _read_columns(text, layout, path, columns):
    """(samples, shape (n, k), step [s] or None for one column, start time [s]) of a table of one
    column of accelerations or a time column [s] and k accelerations (the file at ``path``, its
    ``text``); ``columns`` as for read_samples."""
    source = io.StringIO(text)
    if layout.decimal_comma:
        source = "\n".join(text.split("\n")[layout.start:]).replace(",", ".").split("\n")
    try:
        rows = np.loadtxt(source, delimiter=layout.delimiter, comments="#", ndmin=2,
                          skiprows=0 if layout.decimal_comma else layout.start)
    except ValueError:  # the line-by-line parser locates the error, or reads what loadtxt cannot
        rows = _parse_rows(text.split("\n"), layout, path)
    return _check_rows(rows, text, layout.start, path, columns)


def _decimal_comma(text, index, path):
    """Whether a line's numbers have decimal commas (then with ';' separators)."""
    if ";" not in text or "," not in text:
        return False
    if "." in text:
        raise ValueError(f"{path}, line {index + 1}: both '.' and ',' in {text!r} with ';' separators: "
                         "use '.' for decimals (or ',' with ';' separators), not both")
    return True


def _numbers(text, decimal_comma):
    """The numbers of one data line, or None if a field is not a number."""
    if decimal_comma:
        text = text.replace(",", ".")
    fields = re.split(r"[;\s]+" if decimal_comma else r"[,;\s]+", text)
    try:
        return [float(f) for f in fields if f]
    except ValueError:
        return None


def _parse_rows(lines, layout, path):
    """The table from its first data line on, parsed line by line; errors name the line."""
    rows, first = [], layout.start + 1
    for line_no, line in enumerate(lines[layout.start:], start=first):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        row = _numbers(text, layout.decimal_comma)
        if row is None:
            raise ValueError(f"{path}, line {line_no}: not a number in {text!r}")
        if rows and len(row) != len(rows[0]):
            raise ValueError(f"{path}, line {line_no}: {len(row)} columns, expected {len(rows[0])} "
                             f"as on line {first}{_comma_hint(text)}")
        rows.append(row)
    return np.array(rows)


def _comma_hint(text):
    """A hint for a line whose column count may come from decimal commas."""
    return "; decimal commas? Use '.' for decimals, or ';' between columns" if "," in text and "." not in text else ""


def _data_line_numbers(lines, start):
    """1-based file line numbers of the table's data rows, from line ``start`` on."""
    return [n for n, line in enumerate(lines[start:], start=start + 1) if line.split("#", 1)[0].strip()]


def _check_rows(rows, text, start, path, columns):
    """(samples, step [s] or None, start time [s]) of the checked rows of the table at line index
    ``start`` of the file's ``text``."""
    def line_of(k):  # file line of data row k, counted only for an error
        return _data_line_numbers(text.split("\n"), start)[k]

    most, described = columns
    if rows.shape[1] > most:
        hint = _comma_hint(text.split("\n")[start])
        raise ValueError(f"{path}, line {start + 1}: expected {described}, found {rows.shape[1]}{hint}")
    if not np.isfinite(rows).all():
        bad = np.flatnonzero(~np.all(np.isfinite(rows), axis=1))
        row = rows[bad[0]]
        raise ValueError(f"{path}, line {line_of(bad[0])}: value {row[~np.isfinite(row)][0]} is not finite")
    if rows.shape[1] == 1:
        return rows, None, 0.0
    return rows[:, 1:], *_time_step(rows[:, 0], line_of, path)


def _time_step(time, line_of, path):
    """(step [s], start time [s]) of a uniform increasing time column."""
    if time.size < 2:
        raise ValueError(f"{path}: needs at least 2 samples")
    step = np.diff(time)
    bad = np.flatnonzero(step <= 0)
    if bad.size:
        k = bad[0] + 1
        raise ValueError(f"{path}, line {line_of(k)}: time column is not increasing "
                         f"(t = {time[k]:.6g} s after {time[k - 1]:.6g} s)")
    middle = (step.size - 1) // 2
    usual = np.partition(step, middle)[middle]  # the lower median step
    bad = np.flatnonzero(np.abs(step - usual) > 1e-6 * usual + 1e-9)
    if bad.size:
        k = bad[0] + 1
        shown, others = _distinct(step[bad[0]], usual)
        raise ValueError(f"{path}, line {line_of(k)}: time column is not uniform "
                         f"(step {shown} s to t = {time[k]:.9g} s, where the others are {others} s)")
    return float(f"{(time[-1] - time[0]) / step.size:.12g}"), float(time[0])


def _distinct(a, b):
    """``a`` and ``b`` printed to the fewest significant digits (6, 9 or 12) that tell them apart."""
    for digits in (6, 9, 12):
        if f"{a:.{digits}g}" != f"{b:.{digits}g}":
            break
    return f"{a:.{digits}g}", f"{b:.{digits}g}"
