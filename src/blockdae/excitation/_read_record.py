"""read_record: one accelerogram file, in any format blockdae reads, found by content."""

import pathlib

from ..units import STANDARD_GRAVITY
from ._formats import read_channels
from ._readers import ONE_COMPONENT, read_table, record_name
from ._record import Record
from ._units import canonical_units


def read_record(path, units=None, dt=None, g=STANDARD_GRAVITY, name=None, check_peak=True, *,
                check_step=True, remove_mean=None, gain=None) -> Record:
    """Read an accelerogram file into a :class:`Record` [m/s²].

    Formats, found by content whatever the file's name:
      * two columns (time [s], acceleration), separated by commas, blanks or semicolons
        (semicolons with decimal commas, ``0,01;0,5``, too), '#' comments, optional
        header line and UTF-8 BOM; the time column [s] must be uniform and increasing, and
        its first value is kept as ``Record.start_time``; the units its header lines
        (column names or '#' comments) name are read: ``time (s), acceleration (m/s2)``,
        ``# time (s), acceleration (m/s2)`` (numpy's savetxt), ``Acceleration in m/s2``,
        ``acc [cm/sec2]``, ``m/s**2``, ``(gal)``, ``(g)``, ``(g's)``, ``in g``;
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
            says. Units are never assumed: a file whose header does not state them (a
            table without units in its header lines, SAC, miniSEED) needs ``units``, and the
            error gives the peak the file would have in each unit. Contradicting the header
            raises, naming the line and both units.
        dt: sample step [s]; required for one-column files only, checked against the
            file's step otherwise.
        g: the value of one "g" [m/s²].
        name: record name; by default the file's, less its suffix (:func:`~._readers.record_name`).
        check_peak: raise if the peak acceleration is implausible (outside
            :data:`PLAUSIBLE_PEAK_G`, 1e-4 g to 4 g), a sign of wrong units, naming the
            likely units; False accepts any peak.
        check_step: raise if the sample step is above 0.1 s (times in milliseconds, or a
            column of sample numbers); False accepts it. A step above 0.025 s (fewer than
            4 samples per 0.1 s period) gives a :class:`~._record_checks.RecordWarning`.
        remove_mean: subtract the samples' mean; None (default): for K-NET/KiK-net files only,
            whose samples carry the recorder's offset (NIED's practice); False keeps it.
            ``Record.metadata`` says whether it was removed (``mean_removed``) and the mean
            [m/s²] (``mean_m_s2``). A record that keeps a mean above 5 % of its peak gives a
            :class:`~._record_checks.RecordWarning` naming the fix.
        gain: SAC/miniSEED only: counts per unit of ``units`` [counts/(units)].

    Errors are ValueErrors naming the file and, where there is one, its 1-based line
    (also for a binary file, a damaged gzip file or text that is not UTF-8).
    """
    path = pathlib.Path(path)
    return only_record(read_file_records(path, units, dt, g, check_peak, name, check_step=check_step,
                                         remove_mean=remove_mean, gain=gain), path)


def read_file_records(path, units=None, dt=None, g=STANDARD_GRAVITY, check_peak=True, name=None, *,
                      check_step=True, remove_mean=None, gain=None) -> list[Record]:
    """Every acceleration channel of the file at ``path`` as a Record [m/s²] (one for a table or
    AT2 file; a COSMOS or miniSEED file may hold several, named "<name> <component>");
    the arguments as for :func:`read_record`."""
    path = pathlib.Path(path)
    if units is not None:
        canonical_units(units)  # an unknown name fails before the file is read
    options = {} if gain is None else {"gain": gain}
    records, text = read_channels(path, units, dt, g, check_peak, name, options, check_step=check_step,
                                  remove_mean=remove_mean)
    if records is not None:
        return records
    samples, dt, start_time, metadata = read_table(path, units, dt, g, check_peak, ONE_COMPONENT, text,
                                                   check_step=check_step, remove_mean=bool(remove_mean))
    return [Record(samples[:, 0], dt, record_name(path) if name is None else name, start_time, units="m/s2",
                   check_peak=False, metadata=metadata)]  # _read_table checked the peak in the file's units


def only_record(records, path):
    """The one Record of ``records`` read from ``path``; ValueError naming the channels if several."""
    if len(records) > 1:
        names = ", ".join(repr(r.metadata.get("component", r.name)) for r in records)
        raise ValueError(f"{path}: {len(records)} acceleration channels ({names}); read_record reads one: "
                         "bd.read_motion(path) groups them into a BaseMotion")
    return records[0]
