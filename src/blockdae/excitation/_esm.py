"""ESM ASCII files (the Engineering Strong-Motion database): header lines ``KEY: value``
(``NDATA``, ``SAMPLING_INTERVAL_S``, ``UNITS``, ``STREAM``, ...), then one value a line."""

import re

from ._header import Channel, check_count, check_peak_statement, free_values, parse_float, statement

_KEY = re.compile(r"^([A-Z0-9_/^.()-]+):\s?(.*)$")
_UNITS = {"cm/s^2": "cm/s2", "cm/s2": "cm/s2", "m/s^2": "m/s2", "m/s2": "m/s2", "g": "g", "gal": "cm/s2"}
_AZIMUTHS = {"N": 0.0, "E": 90.0}


def is_esm(text):
    """Whether ``text`` is an ESM ASCII file: ``KEY: value`` lines naming ``NDATA`` and ``SAMPLING_INTERVAL_S``."""
    head = text[:6000]
    return _KEY.match(text.split("\n", 1)[0]) is not None and "\nNDATA:" in head and "\nSAMPLING_INTERVAL_S:" in head


def read_esm(path, text):
    """The channel of an ESM ASCII file, in its header's ``UNITS`` (cm/s^2, m/s^2 or g).

    The step is ``SAMPLING_INTERVAL_S``; the values must number ``NDATA``, and last
    ``DURATION_S`` (to one step, either convention) where it is given; ``PGA_CM/S^2``, where
    given, must be the data's peak (in cm/s²; it catches a wrong ``UNITS``); ``DATA_TYPE``
    must be ACCELERATION. Metadata: station (``NETWORK.STATION_CODE``), component (``STREAM``),
    event (``EVENT_ID``), magnitude (``MAGNITUDE_W``, else ``MAGNITUDE_L``), epicentral
    distance [km], Vs30 [m/s].
    """
    lines = text.split("\n")
    header, start = _header(path, lines)
    where = {key: statement(lines, index) for key, (index, _) in header.items()}

    def value(key, required=True):
        if key not in header:
            if required:
                raise ValueError(f"{path}: the ESM header has no {key} line (lines 1-{start})")
            return None
        return header[key][1].strip() or None

    kind = value("DATA_TYPE", required=False)
    if kind is not None and kind.upper() != "ACCELERATION":
        raise ValueError(f"{path}, {where['DATA_TYPE']}: {kind.lower()}, not acceleration; blockdae reads "
                         "accelerations")
    units_text = value("UNITS")
    if units_text.lower() not in _UNITS:
        raise ValueError(f"{path}, {where['UNITS']}: units {units_text!r} are not an acceleration (cm/s^2, m/s^2, g)")
    units = _UNITS[units_text.lower()]
    samples = free_values(path, lines, start)
    check_count(path, int(_number(path, lines, header, "NDATA")), samples.size, where["NDATA"])
    dt = _number(path, lines, header, "SAMPLING_INTERVAL_S")
    if not dt > 0:
        raise ValueError(f"{path}, {where['SAMPLING_INTERVAL_S']}: the sample step must be > 0 s")
    if value("DURATION_S", required=False) is not None:
        duration = _number(path, lines, header, "DURATION_S")
        if min(abs(samples.size * dt - duration), abs((samples.size - 1) * dt - duration)) > dt:
            raise ValueError(f"{path}, {where['DURATION_S']}: {samples.size} samples at {dt:g} s "
                             f"({where['SAMPLING_INTERVAL_S']}) last {samples.size * dt:g} s, not {duration:g} s: "
                             "the header's step contradicts the data")
    if value("PGA_CM/S^2", required=False) is not None:
        to_cm = {"cm/s2": 1.0, "m/s2": 100.0, "g": 980.665}[units]
        stated = _number(path, lines, header, "PGA_CM/S^2")
        check_peak_statement(path, samples * to_cm, stated, where["PGA_CM/S^2"], f"cm/s²; {where['UNITS']}",
                             5e-4 * abs(stated) + 1e-6)
    stream = value("STREAM", required=False) or ""
    orientation = stream[-1:].upper()
    station = ".".join(v for v in (value("NETWORK", False), value("STATION_CODE", False)) if v)
    metadata = {"format": "ESM", "station": station, "component": stream,
                "azimuth_deg": _AZIMUTHS.get(orientation), "vertical": orientation == "Z",
                "event": value("EVENT_ID", False) or value("EVENT_NAME", False) or "",
                "magnitude": value("MAGNITUDE_W", False) or value("MAGNITUDE_L", False),
                "epicentral_distance_km": value("EPICENTRAL_DISTANCE_KM", False),
                "vs30_m_s": value("VS30_M/S", False)}
    return [Channel(samples, units, where["UNITS"], dt, metadata)]


def _header(path, lines):
    """({KEY: (line index, value text)}, index of the first data line)."""
    header = {}
    for index, line in enumerate(lines):
        match = _KEY.match(line.strip())
        if match is None:
            if line.strip() and _is_number(line):
                return header, index
            if line.strip():
                raise ValueError(f"{path}, {statement(lines, index)}: neither a 'KEY: value' header line nor a number")
            continue
        header[match.group(1)] = (index, match.group(2))
    raise ValueError(f"{path}, line {len(lines)}: the file ends before its data (a truncated file?)")


def _is_number(text):
    try:
        float(text)
    except ValueError:
        return False
    return True


def _number(path, lines, header, key):
    index, text = header[key]
    return parse_float(path, lines, index, text.strip(), key)
