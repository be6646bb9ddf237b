"""COSMOS V1/V2 "Volume" files (CESMD; COSMOS Strong-Motion Data Format v1.20): per channel
a text header, an integer and a real header block, comments, a data block and an
``End-of-data`` line; one file may hold several channels, and a V2 file velocity and
displacement after each acceleration."""

import re

from ._header import Channel, check_count, check_peak_statement, fixed_values, statement

_FIRST_LINE = re.compile(r"\(format\s+v\s*(\d+\.\d+)\s+with\s+(\d+)\s+text\s+lines\)", re.IGNORECASE)
_BLOCK = re.compile(r"^\s*(\d+)\s+{}.*?follow\s+on\s+(\d+)\s+lines.*?format\s*=\s*\(([^)]*)\)", re.IGNORECASE)
_INTEGERS, _REALS = (re.compile(_BLOCK.pattern.format(kind), re.IGNORECASE)
                     for kind in ("integer-header\\s+values", "real-header\\s+values"))
_COMMENTS = re.compile(r"^\s*(\d+)\s+comment\s+line", re.IGNORECASE)
_DATA = re.compile(r"^\s*(\d+)\s+(\w+)\s+pts,\s*approx\s+([0-9.]+)\s+secs?,\s*units\s*=\s*(.*?)\s*\(\s*(\d+)\s*\)"
                   r"\s*,\s*format\s*=\s*\(([^)]*)\)", re.IGNORECASE)
_UNKNOWN = re.compile(r"unknown.*?:\s*(-?\d+)", re.IGNORECASE)
_CODE = re.compile(r"code:\s*([A-Za-z0-9_]*)-\s*(\S+)", re.IGNORECASE)
# COSMOS Table 2, units codes of acceleration: canonical units, or why not
_UNITS = {2: "g", 4: "cm/s2", 10: "cm/s2"}
_UNITS_TEXT = {"CM/S2": "cm/s2", "CM/SEC2": "cm/s2", "CM/S/S": "cm/s2", "GAL": "cm/s2", "G": "g"}
# COSMOS Table 1, physical parameter codes; Table 3, orientations that are not azimuths
_PARAMETERS = {1: "acceleration", 2: "velocity", 3: "displacement"}
_VERTICAL = {400: "Up", 401: "Down", 402: "Vertical"}
_OTHER_ORIENTATIONS = {500: "Radial", 501: "Transverse", 600: "Longitudinal", 601: "Tangential", 700: "H1",
                       701: "H2"}
# 0-based places in the integer header (physical parameter, units, orientation) and the real one
_I_PARAMETER, _I_UNITS, _I_ORIENTATION = 1, 2, 53
_R_DT_MS, _R_MAX = 61, 63


def is_cosmos(text):
    """Whether ``text`` is a COSMOS file: its first line names the format and its text lines."""
    return _FIRST_LINE.search(text[:200].split("\n", 1)[0]) is not None


def read_cosmos(path, text):
    """The acceleration channels of a COSMOS V1/V2 file, in the units its header states.

    Per channel: the step is the real header's (its value 62, in ms); the units the integer
    header's units code (value 3: 2 g, 4 or 10 cm/s²), which must agree with the data line's
    ``units=``; the sample count the data line's, which the data must match; the data line's
    approximate duration must be that count times the step (to 1 s), and the real header's
    peak (value 64) the data's. Velocity and displacement blocks are skipped; a file
    without acceleration is refused. Metadata: station (and network) from the text header's
    ``Code:``, the event (its line 2), the component (integer header value 54: an azimuth
    [deg], or Up, Down, ...).
    """
    lines = text.split("\n")
    channels, blocks, start = [], [], 0
    while start < len(lines) and lines[start].strip():
        channel, kind, after = _read_block(path, lines, start)
        blocks.append(f"{kind} (line {start + 1})")
        start = after
        if channel is not None:
            channels.append(channel)
        while start < len(lines) and not lines[start].strip():
            start += 1
    if not channels:
        raise ValueError(f"{path}: a COSMOS file without acceleration ({', '.join(blocks) or 'no data'}); "
                         "blockdae reads acceleration only: take the file's corrected or uncorrected acceleration")
    return channels


def _read_block(path, lines, start):
    """(Channel or None for velocity or displacement, the data's kind, index of the line after the block)
    of the block whose text header starts on 0-based line ``start``."""
    first = _FIRST_LINE.search(lines[start])
    if first is None:
        raise ValueError(f"{path}, {statement(lines, start)}: expected a COSMOS text header's first line, "
                         "'... (Format v01.20 with 13 text lines) ...'")
    version, text_lines = first.group(1), int(first.group(2))
    header = lines[start:start + text_lines]
    index = start + text_lines
    int_index = index
    integers, index = _numbers_block(path, lines, index, _INTEGERS, "integer-header", int, _I_ORIENTATION)
    real_index = index
    reals, index = _numbers_block(path, lines, index, _REALS, "real-header", float, _R_MAX)
    comments = _match(path, lines, index, _COMMENTS, "'N Comment line(s) follow ...'")
    index += 1 + int(comments.group(1))
    data_index = index
    data = _match(path, lines, index, _DATA, "the data line, 'N acceleration pts, approx T secs, units=...'")
    count, kind, approx, units_text, units_code, fortran = data.groups()
    samples, index = fixed_values(path, lines, index + 1, int(count), fortran)
    if index < len(lines) and lines[index].strip().lower().startswith("end-of-data"):
        index += 1
    elif index < len(lines) and lines[index].strip():
        check_count(path, int(count), int(count) + len(lines[index].split()), statement(lines, data_index))
    kind = kind.lower()
    parameter = _PARAMETERS.get(integers[_I_PARAMETER])
    if parameter is not None and parameter != kind:
        raise ValueError(f"{path}, {statement(lines, data_index)}: {kind} data, but the integer header's "
                         f"physical parameter code {integers[_I_PARAMETER]} says {parameter}")
    if kind != "acceleration":
        return None, kind, index
    unknown = _unknown(header)
    units, units_where = _units(path, lines, data_index, int_index, integers, units_text, units_code)
    dt = _step(path, lines, real_index, reals, unknown, int(count), float(approx), data_index)
    if reals[_R_MAX] != unknown:
        check_peak_statement(path, samples, reals[_R_MAX], _value_line(lines, real_index, _R_MAX), units_where,
                             _resolution(fortran, reals[_R_MAX]))
    return Channel(samples, units, units_where, dt, {
        "format": f"COSMOS V{integers[0]} (v{version})", "station": _station(header), "event": _event(header),
        **_orientation(integers[_I_ORIENTATION], unknown), "units_code": int(units_code),
        "data_type": header[0][:25].strip()}), kind, index


def _numbers_block(path, lines, index, pattern, what, kind, last):
    """(values, index of the next line) of the integer or real header block starting on line
    ``index``, which must hold value ``last`` (0-based)."""
    match = _match(path, lines, index, pattern, f"the {what} line, 'N {what.capitalize()} values follow on M "
                                                "lines, Format= (...)'")
    count, rows, fortran = int(match.group(1)), int(match.group(2)), match.group(3)
    values, after = fixed_values(path, lines, index + 1, count, fortran, kind)
    if after != index + 1 + rows:
        raise ValueError(f"{path}, {statement(lines, index)}: {count} values in format ({fortran}) take "
                         f"{after - index - 1} lines, not {rows}")
    if count <= last:
        raise ValueError(f"{path}, {statement(lines, index)}: {count} {what} values, too few for value "
                         f"{last + 1}; COSMOS v1.20 has 100")
    return values, after


def _match(path, lines, index, pattern, expected):
    """The match of ``pattern`` on line ``index``, or ValueError naming the line and what was expected."""
    if index >= len(lines):
        raise ValueError(f"{path}, line {len(lines)}: the file ends where {expected} should come (a truncated file?)")
    match = pattern.match(lines[index])
    if match is None:
        raise ValueError(f"{path}, {statement(lines, index)}: expected {expected}")
    return match


def _units(path, lines, data_index, int_index, integers, units_text, units_code):
    """(canonical units, where they are stated) of a channel: the integer header's units code
    and the data line's, which must agree with each other and with its units text."""
    code = integers[_I_UNITS]
    where = statement(lines, data_index)
    if code != int(units_code):
        raise ValueError(f"{path}, {where}: units code {int(units_code)}, but the integer header (line "
                         f"{int_index + 2}, value {_I_UNITS + 1}) says {code}: the header contradicts itself")
    if code not in _UNITS:
        raise ValueError(f"{path}, {where}: units code {code} ({units_text}) is not an acceleration in g or "
                         "cm/s² (COSMOS codes 2, 4, 10); counts and other units are not read")
    said = _UNITS_TEXT.get(re.sub(r"\s+", "", units_text.upper()).replace("^", "").replace("SEC", "S"))
    if said is not None and said != _UNITS[code]:
        raise ValueError(f"{path}, {where}: units={units_text} contradicts its units code {code} "
                         f"({_UNITS[code]})")
    return _UNITS[code], where


def _step(path, lines, real_index, reals, unknown, count, approx, data_index):
    """The sample step [s]: the real header's (value 62, in ms), which must give the data
    line's approximate duration (to 1 s)."""
    dt_ms = reals[_R_DT_MS]
    where = _value_line(lines, real_index, _R_DT_MS)
    if dt_ms == unknown or not dt_ms > 0:
        raise ValueError(f"{path}, {where}: sample step {dt_ms:g} ms is unknown or not positive")
    if abs(count * dt_ms / 1000.0 - approx) > 1.0:
        raise ValueError(f"{path}, {where}: a step of {dt_ms:g} ms gives {count} samples {count * dt_ms / 1000:g} s, "
                         f"not the approximately {approx:g} s of {statement(lines, data_index)}")
    return dt_ms / 1000.0


def _value_line(lines, index, k):
    """'line N, real-header value k+1': where value ``k`` (0-based) of the real-header block
    whose header line is ``index`` stands."""
    fortran = _REALS.match(lines[index]).group(3).replace(" ", "").upper()
    per_line = int(re.match(r"(?:\d*P)?(\d*)", fortran).group(1) or 1)
    return f"line {index + 2 + k // per_line}, real-header value {k + 1}"


def _resolution(fortran, value):
    """Half a unit in the last printed digit of the data format, and of the header's peak (6
    significant digits): how far a printed peak may be from the data's."""
    decimals = re.search(r"\.(\d+)", fortran)
    data = 0.5 * 10.0 ** -int(decimals.group(1)) if decimals else 0.5
    return data + 5e-6 * abs(value)


def _unknown(header):
    """The value that marks an unknown header entry (text line 13), -999 by default."""
    match = _UNKNOWN.search(header[-1]) if header else None
    return int(match.group(1)) if match else -999


def _station(header):
    """'NET.STATION' (or 'STATION') of the text header's line 5 ``Code:NET-STATION``."""
    match = _CODE.search(header[4]) if len(header) > 4 else None
    if match is None:
        return ""
    return ".".join(part for part in match.groups() if part)


def _event(header):
    """The event: the text header's line 2, spaces squeezed."""
    return " ".join(header[1].split()) if len(header) > 1 else ""


def _orientation(code, unknown):
    """component, azimuth_deg (None if not an azimuth) and vertical of an orientation code."""
    if 0 <= code <= 360 and code != unknown:
        return {"component": f"{code:03d}", "azimuth_deg": float(code % 360), "vertical": False}
    if code in _VERTICAL:
        return {"component": _VERTICAL[code], "azimuth_deg": None, "vertical": True}
    return {"component": _OTHER_ORIENTATIONS.get(code, f"orientation {code}"), "azimuth_deg": None, "vertical": False}
