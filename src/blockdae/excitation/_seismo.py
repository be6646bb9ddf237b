"""SAC and miniSEED files, read by ObsPy (the optional extra ``blockdae[seismo]``)."""

import io
import struct

import numpy as np

from ._header import Channel

_SAC_HEADER_BYTES = 632  # SAC's binary header
_SAC_VERSION_AT = 304  # byte offset of NVHDR, 6 (or 7) in a SAC file
_SAC_NOT_ACCELERATION = {6: "displacement", 7: "velocity", 50: "volts"}  # SAC's IDEP codes
_AZIMUTHS = {"N": 0.0, "E": 90.0}


def seismo_format(data):
    """"SAC" or "MSEED" if the bytes ``data`` are one of these files, else None."""
    if data[:3] == b"MS\x03" or (len(data) >= 48 and data[6:7] in (b"D", b"R", b"Q", b"M")
                                  and data[7:8] in (b" ", b"\0") and data[:6].strip(b" 0123456789\0") == b""):
        return "MSEED"
    if len(data) >= _SAC_HEADER_BYTES:
        for order in "<>":
            if struct.unpack_from(f"{order}i", data, _SAC_VERSION_AT)[0] in (6, 7):
                return "SAC"
    return None


def read_seismo(path, data, units, gain=None):
    """The traces of a SAC or miniSEED file (its bytes ``data``) as channels in ``units``.

    These files do not state the units of their samples: ``units`` ("g", "m/s2", "cm/s2")
    is required. Samples stored as integers are counts: they are refused unless ``gain``
    [counts per unit of ``units``] is given; samples / ``gain`` are then in ``units`` (a
    gain applies to float samples too). A SAC file whose IDEP says displacement, velocity
    or volts is refused. Metadata: station (``NET.STA``), component (the channel code),
    event (SAC's KEVNM), start time.
    """
    fmt = seismo_format(data)
    try:
        import obspy
    except ImportError:
        raise ValueError(f"{path}: a {fmt} file; reading it needs ObsPy: pip install 'blockdae[seismo]'") from None
    if units is None:
        raise ValueError(f"{path}: a {fmt} file does not state the units of its samples; pass units= "
                         "('g', 'm/s2' or 'cm/s2'), and gain= [counts per unit] for counts")
    if gain is not None and not (np.isfinite(gain) and gain > 0):
        raise ValueError(f"{path}: gain={gain!r} must be a positive finite number [counts per unit of {units}]")
    try:
        stream = obspy.read(io.BytesIO(data), format=fmt)
    except Exception as err:  # ObsPy's readers raise many kinds on a damaged file
        raise ValueError(f"{path}: ObsPy cannot read this {fmt} file ({type(err).__name__}: {err})") from None
    return [_channel(path, trace, fmt, gain) for trace in stream]


def _channel(path, trace, fmt, gain):
    """The Channel of one ObsPy trace."""
    stats = trace.stats
    samples = np.asarray(trace.data)
    label = f"{stats.network}.{stats.station}.{stats.location}.{stats.channel}"
    if np.issubdtype(samples.dtype, np.integer) and gain is None:
        raise ValueError(f"{path}: trace {label} holds counts (integers); pass gain= [counts per unit of units=] "
                         "to convert them")
    sac = stats.get("sac") or {}
    idep = int(sac.get("idep", -12345))
    if idep in _SAC_NOT_ACCELERATION:
        raise ValueError(f"{path}: SAC header IDEP = {idep}: {_SAC_NOT_ACCELERATION[idep]}, not acceleration")
    samples = samples.astype(float) / (1.0 if gain is None else float(gain))
    orientation = stats.channel[-1:].upper()
    event = str(sac.get("kevnm", "")).strip()
    metadata = {"format": "SAC" if fmt == "SAC" else "miniSEED", "station": f"{stats.network}.{stats.station}",
                "component": stats.channel, "location": stats.location, "azimuth_deg": _AZIMUTHS.get(orientation),
                "vertical": orientation == "Z", "event": event, "start": str(stats.starttime),
                "gain": gain}
    return Channel(samples, None, None, float(stats.delta), metadata)
