"""K-NET and KiK-net ASCII files (NIED): 17 header lines ``Label  value`` from ``Origin Time``
to ``Memo.``, then integer counts, 8 a line; acceleration = counts × the scale factor, in gal."""

import re

from ._header import Channel, check_peak_statement, free_values, parse_float, statement
from ._units import unit_factor

_LABELS = ("Origin Time", "Lat.", "Long.", "Depth. (km)", "Mag.", "Station Code", "Station Lat.", "Station Long.",
           "Station Height(m)", "Record Time", "Sampling Freq(Hz)", "Duration Time(s)", "Dir.", "Scale Factor",
           "Max. Acc. (gal)", "Last Correction", "Memo.")
_SCALE = re.compile(r"^\s*([0-9.eE+-]+)\s*\(\s*([^)]*?)\s*\)\s*/\s*([0-9.eE+-]+)\s*$")
_FREQUENCY = re.compile(r"^\s*([0-9.]+)\s*(?:Hz)?\s*$", re.IGNORECASE)
# the direction field: K-NET's, and KiK-net's channels 1-6 (1-3 borehole, 4-6 surface)
_DIRECTIONS = {"N-S": ("N-S", 0.0), "E-W": ("E-W", 90.0), "U-D": ("U-D", None),
               "1": ("N-S borehole", 0.0), "2": ("E-W borehole", 90.0), "3": ("U-D borehole", None),
               "4": ("N-S surface", 0.0), "5": ("E-W surface", 90.0), "6": ("U-D surface", None)}


def is_knet(text):
    """Whether ``text`` is a K-NET/KiK-net ASCII file: it starts with ``Origin Time`` and names a ``Station Code``."""
    return text.startswith("Origin Time") and "\nStation Code" in text[:1000]


def read_knet(path, text):
    """The channel of a K-NET/KiK-net ASCII file [cm/s²].

    The samples are the file's counts times its ``Scale Factor  A(gal)/B``, A/B [gal per count],
    and nothing else: they carry the recorder's offset, which NIED subtracts (the mean) before
    stating ``Max. Acc. (gal)`` and read_record subtracts by default. The step is
    1 / ``Sampling Freq(Hz)``; the count must give ``Duration Time(s)`` (whole seconds, to
    1 s), and the samples, less their mean, the header's ``Max. Acc.`` (to its 3 decimals).
    Metadata: station (``Station Code``), component (``Dir.``: N-S, E-W, U-D; KiK-net's 1-3
    borehole, 4-6 surface), event (``Origin Time``), magnitude (``Mag.``), ``Memo.``.
    """
    lines = text.split("\n")
    values = _header(path, lines)
    count_line = len(_LABELS)
    counts = free_values(path, lines, count_line)
    scale_index = _LABELS.index("Scale Factor")
    scale = _SCALE.match(values["Scale Factor"])
    if scale is None:
        raise ValueError(f"{path}, {statement(lines, scale_index)}: Scale Factor not understood, expected "
                         "e.g. '3920(gal)/6182761'")
    numerator, unit, denominator = scale.groups()
    units = _units(path, lines, scale_index, unit)
    factor = parse_float(path, lines, scale_index, numerator, "Scale Factor") / parse_float(
        path, lines, scale_index, denominator, "Scale Factor")
    dt = _step(path, lines, values, counts.size)
    samples = counts * factor
    max_index = _LABELS.index("Max. Acc. (gal)")
    stated = parse_float(path, lines, max_index, values["Max. Acc. (gal)"], "Max. Acc. (gal)")
    in_gal = (samples - samples.mean()) * unit_factor(units) * 100.0
    check_peak_statement(path, in_gal, stated, statement(lines, max_index), f"gal; {statement(lines, scale_index)}",
                         0.0005 + 1e-4 * abs(stated))
    direction = values["Dir."].strip()
    if direction not in _DIRECTIONS:
        raise ValueError(f"{path}, {statement(lines, _LABELS.index('Dir.'))}: direction {direction!r} is not "
                         f"one of {', '.join(_DIRECTIONS)}")
    component, azimuth = _DIRECTIONS[direction]
    metadata = {"format": "KiK-net" if direction.isdigit() else "K-NET", "station": values["Station Code"].strip(),
                "component": component, "azimuth_deg": azimuth, "vertical": azimuth is None,
                "event": values["Origin Time"].strip(), "magnitude": values["Mag."].strip(),
                "memo": values["Memo."].strip()}
    return [Channel(samples, units, statement(lines, scale_index), dt, metadata)]


def _header(path, lines):
    """{label: value text} of the 17 header lines, each checked to start with its label."""
    if len(lines) < len(_LABELS):
        raise ValueError(f"{path}, line {len(lines)}: the file ends inside the header of "
                         f"{len(_LABELS)} lines (a truncated file?)")
    values = {}
    for index, label in enumerate(_LABELS):
        if not lines[index].startswith(label):
            raise ValueError(f"{path}, {statement(lines, index)}: expected the K-NET header line {label!r}")
        values[label] = lines[index][len(label):].strip()
    return values


def _units(path, lines, index, unit):
    """The scale factor's units: gal, as NIED writes (other acceleration units are honoured)."""
    key = unit.strip().lower().replace("^", "")
    known = {"gal": "cm/s2", "cm/s2": "cm/s2", "m/s2": "m/s2", "g": "g"}
    if key not in known:
        raise ValueError(f"{path}, {statement(lines, index)}: Scale Factor in {unit!r}, not an acceleration "
                         "(gal, as NIED writes)")
    return known[key]


def _step(path, lines, values, count):
    """1 / the sampling frequency [s], checked against the duration the header states."""
    freq_index, duration_index = _LABELS.index("Sampling Freq(Hz)"), _LABELS.index("Duration Time(s)")
    match = _FREQUENCY.match(values["Sampling Freq(Hz)"])
    if match is None or not float(match.group(1)) > 0:
        raise ValueError(f"{path}, {statement(lines, freq_index)}: sampling frequency not understood, "
                         "expected e.g. '100Hz'")
    dt = 1.0 / float(match.group(1))
    duration = parse_float(path, lines, duration_index, values["Duration Time(s)"], "Duration Time(s)")
    if abs(count * dt - duration) > 1.0:
        raise ValueError(f"{path}, {statement(lines, duration_index)}: {count} samples at "
                         f"{values['Sampling Freq(Hz)']} ({statement(lines, freq_index)}) last {count * dt:g} s, "
                         f"not {duration:g} s: the header's sample count or step contradicts the data"
                         + (" (a truncated file?)" if count * dt < duration else ""))
    return dt
