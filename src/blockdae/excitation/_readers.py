"""Readers for accelerogram files."""

import io
import pathlib
import re

import numpy as np

from .._units import STANDARD_GRAVITY
from ._record import Record

_UNIT_FACTORS = {"g": None, "m/s2": 1.0, "m/s^2": 1.0, "m/s²": 1.0, "cm/s2": 0.01, "cm/s^2": 0.01,
                 "cm/s²": 0.01, "gal": 0.01}
_AT2_HEADER = re.compile(r"NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*([0-9.eE+-]+)", re.IGNORECASE)
_AT2_OLD_HEADER = re.compile(r"^\s*(\d+)\s+([0-9.eE+-]+)\s+NPTS", re.IGNORECASE)


def unit_factor(units: str, g: float = STANDARD_GRAVITY) -> float:
    """Factor converting ``units`` to m/s² ("g", "m/s2", "cm/s2" or "gal")."""
    key = str(units).strip().lower()
    if key not in _UNIT_FACTORS:
        raise ValueError(f"units={units!r} is unknown; use one of {sorted(_UNIT_FACTORS)}")
    return g if _UNIT_FACTORS[key] is None else _UNIT_FACTORS[key]


def read_record(path, units="g", dt=None, g=STANDARD_GRAVITY, name=None) -> Record:
    """Read an accelerogram file into a :class:`Record` [m/s²].

    Formats:
      * two columns (time [s], acceleration), comma- or space-separated, '#' comments,
        optional UTF-8 BOM; the time column must be uniform and increasing, and time
        is counted from its first value;
      * one column of accelerations, with the sample step ``dt`` [s] given;
      * PEER NGA ``.AT2`` (NPTS and DT read from the header).

    Args:
        path: file path.
        units: units of the acceleration values: "g", "m/s2", "cm/s2" or "gal".
        dt: sample step [s], required for one-column files only.
        g: the value of one "g" [m/s²] when ``units="g"``.
        name: record name; the file stem by default.
    """
    path = pathlib.Path(path)
    factor = unit_factor(units, g)
    text = path.read_text(encoding="utf-8-sig")
    name = path.stem if name is None else name
    if path.suffix.lower() == ".at2":
        samples, file_dt = _parse_at2(text, path)
        if dt is not None and not np.isclose(dt, file_dt):
            raise ValueError(f"{path}: dt={dt} s contradicts the header's DT={file_dt} s")
        return Record(samples * factor, file_dt, name)
    rows = _parse_columns(text, path)
    try:
        return _from_columns(rows, path, factor, dt, name)
    except ValueError as err:
        if str(path) in str(err):
            raise
        raise ValueError(f"{path}: {err}") from None


def _from_columns(rows, path, factor, dt, name):
    if rows.shape[1] == 1:
        if dt is None:
            raise ValueError(f"{path}: one-column file needs the sample step dt [s]")
        return Record(rows[:, 0] * factor, dt, name)
    if rows.shape[1] != 2:
        raise ValueError(f"{path}: expected 1 or 2 columns, found {rows.shape[1]}")
    time = rows[:, 0]
    step = np.diff(time)
    if step.size == 0:
        raise ValueError(f"{path}: needs at least 2 samples")
    bad = np.flatnonzero(step <= 0)
    if bad.size:
        raise ValueError(f"{path}: time column is not increasing at data row {bad[0] + 2} "
                         f"(t={float(time[bad[0] + 1])} s after {float(time[bad[0]])} s)")
    bad = np.flatnonzero(np.abs(step - step[0]) > 1e-6 * step[0] + 1e-9)
    if bad.size:
        raise ValueError(f"{path}: time column is not uniform at data row {bad[0] + 2} "
                         f"(step {float(step[bad[0]])} s after steps of {float(step[0])} s)")
    file_dt = (time[-1] - time[0]) / step.size
    if dt is not None and not np.isclose(dt, file_dt):
        raise ValueError(f"{path}: dt={dt} s contradicts the time column's step {file_dt} s")
    return Record(rows[:, 1] * factor, file_dt, name)


def _parse_columns(text, path):
    rows = []
    for line_no, line in enumerate(io.StringIO(text), start=1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        fields = [f for f in re.split(r"[,\s;]+", line) if f]
        try:
            rows.append([float(f) for f in fields])
        except ValueError:
            if not rows:  # a header line of column names before the data
                continue
            raise ValueError(f"{path}, line {line_no}: not a number in {line!r}") from None
        if len(rows[-1]) != len(rows[0]):
            raise ValueError(f"{path}, line {line_no}: {len(rows[-1])} columns, expected {len(rows[0])}")
    if not rows:
        raise ValueError(f"{path}: no data rows")
    return np.array(rows)


def _parse_at2(text, path):
    lines = text.splitlines()
    for header_end, line in enumerate(lines[:10]):
        match = _AT2_HEADER.search(line) or _AT2_OLD_HEADER.search(line)
        if match:
            break
    else:
        raise ValueError(f"{path}: no 'NPTS=..., DT=...' line in the AT2 header")
    npts, dt = int(match.group(1)), float(match.group(2))
    values = []
    for line_no, line in enumerate(lines[header_end + 1:], start=header_end + 2):
        try:
            values.extend(float(v) for v in line.split())
        except ValueError:
            raise ValueError(f"{path}, line {line_no}: not a number in {line.strip()!r}") from None
    if len(values) != npts:
        raise ValueError(f"{path}: header says NPTS={npts}, found {len(values)} values")
    return np.array(values), dt
