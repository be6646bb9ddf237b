"""What the readers of formats with a header share: the :class:`Channel` a reader returns
and the checks of a header against its data, each error naming the file and line."""

import re
import typing

import numpy as np


class Channel(typing.NamedTuple):
    """One acceleration time series a reader found, in the units its header states."""
    samples: np.ndarray  # shape (n,), in ``units``
    units: str | None  # canonical name ("g", "m/s2", "cm/s2") the header states; None: not stated
    statement: str | None  # where: "line N: '...'"
    dt: float  # sample step [s]
    metadata: dict  # format, units as read, station, component, event, azimuth_deg, vertical, ...


def statement(lines, index):
    """'line N: '...'' naming the 0-based line ``index`` of ``lines``, for errors and units' sources."""
    return f"line {index + 1}: {lines[index].strip()!r}"


def check_count(path, stated, found, where):
    """ValueError unless the ``found`` number of samples is the ``stated`` one (at ``where``)."""
    if found != stated:
        raise ValueError(f"{path}, {where}: the header says {stated} samples, the data hold {found}"
                         + (" (a truncated file?)" if found < stated else ""))


def check_peak_statement(path, samples, stated, where, units_where, tolerance):
    """ValueError unless the header's peak |a| ``stated`` (at ``where``, in the data's units,
    those of ``units_where``) is the samples' own to within ``tolerance`` (absolute, in those units)."""
    peak = float(np.max(np.abs(samples), initial=0.0))
    if abs(peak - abs(stated)) > tolerance:
        raise ValueError(f"{path}, {where}: the header's peak {abs(stated):.6g} is not the data's, {peak:.6g} "
                         f"(units: {units_where}); the header's units or scale contradict the data")


def parse_float(path, lines, index, text, field):
    """``text`` (the value of ``field`` on 0-based line ``index``) as a float, or ValueError naming the line."""
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"{path}, {statement(lines, index)}: {field} {text!r} is not a number") from None


def fixed_values(path, lines, start, count, fortran, kind=float):
    """``count`` values in fixed-width fields from 0-based line ``start`` of ``lines`` on, laid out
    as the Fortran format ``fortran`` says (e.g. "10I8", "8F10.5", "1p5E15.7"); (values, index of
    the line after them). ValueError naming the line for a field that is not a number or a file
    that ends before ``count`` values."""
    match = _FORTRAN.fullmatch(fortran.replace(" ", "").upper())
    if match is None:
        raise ValueError(f"{path}: Fortran format ({fortran}) not understood, expected e.g. (8F10.5)")
    per_line, width = int(match.group(1) or 1), int(match.group(2))
    rows = -(-count // per_line)
    if start + rows > len(lines):
        raise ValueError(f"{path}, line {len(lines)}: the file ends inside a block of {count} values that "
                         f"starts on line {start + 1} (a truncated file?)")
    values = []
    for index in range(start, start + rows):
        line = lines[index]
        for k in range(min(per_line, count - len(values))):
            field = line[k * width:(k + 1) * width]
            try:
                values.append(kind(field))
            except ValueError:
                raise ValueError(f"{path}, {statement(lines, index)}: field {k + 1} {field!r} is not a number "
                                 f"(format {fortran}: {per_line} fields of {width} characters)") from None
    last = start + rows - 1
    if lines[last][(count - (rows - 1) * per_line) * width:].strip():
        raise ValueError(f"{path}, {statement(lines, last)}: more values than the {count} that line {start} "
                         "states: the header's count contradicts the data")
    return np.array(values), start + rows


_FORTRAN = re.compile(r"(?:\d*P)?(\d*)[IFEG](\d+)(?:\.\d+)?")


def free_values(path, lines, start):
    """The numbers from 0-based line ``start`` of ``lines`` on, any number a line, as floats;
    ValueError naming the line of the first field that is not a number."""
    body = lines[start:]
    try:
        return np.array(" ".join(body).split(), dtype=float)
    except ValueError:
        for index, line in enumerate(body, start=start):
            for field in line.split():
                try:
                    float(field)
                except ValueError:
                    raise ValueError(f"{path}, {statement(lines, index)}: not a number, {field!r}") from None
        raise
