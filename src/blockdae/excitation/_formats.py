"""Record formats with a header (COSMOS, K-NET/KiK-net, ESM, SAC, miniSEED): found by content,
each read by its module into :class:`~._header.Channel` s, made Records here with the caller's options."""

from . import _cosmos, _esm, _knet, _record_checks, _seismo
from ._readers import _resolve_units, _sample_step, decode, file_bytes, record_name
from ._record import Record
from ._plausibility import check_peak_acceleration
from ._units import unit_factor

#: (name, test of a file's text, reader) of the text formats, tried in this order
_TEXT_FORMATS = (("COSMOS", _cosmos.is_cosmos, _cosmos.read_cosmos),
                 ("K-NET", _knet.is_knet, _knet.read_knet),
                 ("ESM", _esm.is_esm, _esm.read_esm))
#: the options of read_record that one format takes: {option: format}
FORMAT_OPTIONS = {"gain": "SAC/miniSEED"}
#: the formats whose samples carry an offset by definition: read_record removes their mean by default
OFFSET_FORMATS = ("K-NET", "KiK-net")


def read_channels(path, units, dt, g, check_peak, name, options, *, check_step=True, remove_mean=None):
    """(Records of every acceleration channel, None) of a file in a format with a header, or
    (None, its text) for the tables and AT2 files that :func:`read_record` reads itself.
    ``remove_mean``: subtract each channel's mean; None: for :data:`OFFSET_FORMATS` only."""
    data = file_bytes(path)
    if _seismo.seismo_format(data) is not None:
        channels = _seismo.read_seismo(path, data, units, **_options(options, path, "SAC/miniSEED"))
    else:
        text = decode(data, path)
        found = next(((fmt, read) for fmt, test, read in _TEXT_FORMATS if test(text)), None)
        if found is None:
            _options(options, path, "a table or AT2")
            return None, text
        fmt, read = found
        channels = read(path, text, **_options(options, path, fmt))
    label = record_name(path) if name is None else name
    many = len(channels) > 1
    return [_record(c, path, units, dt, g, check_peak, check_step, remove_mean,
                    f"{label} {c.metadata['component']}" if many else label) for c in channels], None


def _options(options, path, fmt):
    """``options`` (name: value), refused naming the first that format ``fmt`` does not take."""
    for option in options:
        if FORMAT_OPTIONS[option] != fmt:
            raise ValueError(f"{path}: {option}= is an option for {FORMAT_OPTIONS[option]} files; this one is {fmt}")
    return options


def _record(channel, path, units, dt, g, check_peak, check_step, remove_mean, name):
    """The Record [m/s²] of ``channel`` read with the caller's ``units`` (checked against the
    header's), ``dt`` (checked against the file's), mean removal and the peak, step and offset rules."""
    units = _resolve_units(units, channel.units, channel.statement, path, channel.samples)
    step = _sample_step(dt, channel.dt, path)
    _record_checks.check_step(step, str(path), check_step)
    if remove_mean is None:
        remove_mean = channel.metadata["format"] in OFFSET_FORMATS
    mean = float(channel.samples.mean())
    samples = channel.samples - mean if remove_mean else channel.samples
    if check_peak:
        check_peak_acceleration(samples, units, g, str(path), channel.statement and f"the header's {channel.statement}")
    if not remove_mean:
        _record_checks.check_offset(samples, str(path))
    metadata = {**channel.metadata, "units": units, "mean_removed": bool(remove_mean),
                "mean_m_s2": mean * unit_factor(units, g)}
    return Record(samples * unit_factor(units, g), step, name, units="m/s2", check_peak=False, metadata=metadata)
