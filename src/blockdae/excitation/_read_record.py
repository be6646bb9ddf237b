"""read_record: one accelerogram file, in any format blockdae reads, found by content."""

import pathlib

from ..core._units import STANDARD_GRAVITY
from ._formats import read_channels
from ._readers import ONE_COMPONENT, read_table, record_name
from ._record import Record


def read_record(path, units=None, dt=None, g=STANDARD_GRAVITY, name=None, check_peak=True, *,
                remove_mean=False, gain=None) -> Record:
    """Read an accelerogram file into a :class:`Record` [m/s²].

    Formats, found by content whatever the file's name:
      * two columns (time [s], acceleration), separated by commas, blanks or semicolons
        (semicolons with decimal commas, ``0,01;0,5``, too), '#' comments, optional
        header line and UTF-8 BOM; the time column must be uniform and increasing, and
        its first value is kept as ``Record.start_time``; units in brackets in the header
        line (``time (s), acceleration (m/s2)``, ``acc [cm/s2]``, ``(gal)``, ``(g)``) are read;
      * one column of accelerations, with the sample step ``dt`` [s] given;
      * PEER NGA AT2 (found by its ``NPTS=..., DT=...`` header line, in
        either order, or the older ``5000  0.0050  NPTS, DT`` line); its
        ``... IN UNITS OF G`` (or ``CM/SEC/SEC``, ``M/SEC/SEC``, ``GAL``) line is read;
      * COSMOS V1/V2 (CESMD), K-NET/KiK-net ASCII (NIED), ESM ASCII: the step and units
        their headers state, checked against the data (see ``_cosmos``, ``_knet``, ``_esm``);
      * SAC and miniSEED, through ObsPy (``pip install 'blockdae[seismo]'``): ``units=``
        required, and ``gain=`` for counts (see ``_seismo``).

    Any of them gzip-compressed (found by its first bytes; ``rec.AT2.gz`` is named
    ``rec``). Text is UTF-8 (or ASCII), with or without a BOM, any line ends. A file of
    several acceleration channels (a COSMOS file of three, a miniSEED file of three
    traces) is refused here: :func:`blockdae.read_motion` groups them.
    ``Record.metadata`` says what was read: format, units, and for the formats with a
    header station, component and event.

    Args:
        path: file path.
        units: units of the values: "g", "m/s2", "cm/s2" or "gal"; None: as the header
            says, "g" for tables that do not say (SAC and miniSEED need it).
            Contradicting the header raises, naming the line and both units.
        dt: sample step [s]; required for one-column files only, checked against the
            file's step otherwise.
        g: the value of one "g" [m/s²].
        name: record name; by default the file's, less its suffix (:func:`~._readers.record_name`).
        check_peak: raise if the peak acceleration is implausible (outside
            :data:`PLAUSIBLE_PEAK_G`), a sign of wrong units; False accepts any peak.
        remove_mean: K-NET/KiK-net only: subtract the samples' mean (NIED's practice);
            off by default, the samples are the counts times the scale factor.
        gain: SAC/miniSEED only: counts per unit of ``units`` [counts/(units)].

    Errors are ValueErrors naming the file and, where there is one, its 1-based line
    (also for a binary file, a damaged gzip file or text that is not UTF-8).
    """
    path = pathlib.Path(path)
    return only_record(read_file_records(path, units, dt, g, check_peak, name, remove_mean=remove_mean, gain=gain),
                       path)


def read_file_records(path, units=None, dt=None, g=STANDARD_GRAVITY, check_peak=True, name=None, *,
                      remove_mean=False, gain=None) -> list[Record]:
    """Every acceleration channel of the file at ``path`` as a Record [m/s²] (one for a table or
    AT2 file; a COSMOS or miniSEED file may hold several, named "<name> <component>");
    the arguments as for :func:`read_record`."""
    path = pathlib.Path(path)
    options = {key: value for key, value in (("remove_mean", remove_mean), ("gain", gain)) if value not in (None, False)}
    records, text = read_channels(path, units, dt, g, check_peak, name, options)
    if records is not None:
        return records
    samples, dt, start_time, metadata = read_table(path, units, dt, g, check_peak, ONE_COMPONENT, text)
    return [Record(samples[:, 0], dt, record_name(path) if name is None else name, start_time, units="m/s2",
                   check_peak=False, metadata=metadata)]  # _read_table checked the peak in the file's units


def only_record(records, path):
    """The one Record of ``records`` read from ``path``; ValueError naming the channels if several."""
    if len(records) > 1:
        names = ", ".join(repr(r.metadata.get("component", r.name)) for r in records)
        raise ValueError(f"{path}: {len(records)} acceleration channels ({names}); read_record reads one: "
                         "bd.read_motion(path) groups them into a BaseMotion")
    return records[0]
