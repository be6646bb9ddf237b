"""Saving and reloading a study's table (CSV, or Parquet when pyarrow is installed).

Files are written atomically (:func:`blockdae.core._atomic.atomic_path`). A CSV table
ends with a footer line, ``# blockdae study table: N rows``, written last:
:func:`load_study` refuses a CSV file without it, or with another number of rows, so a
truncated or partly written table is never read as a shorter one. (Other readers skip
the footer with ``pandas.read_csv(path, comment="#")``.) A Parquet file carries its own
footer, which its reader checks.
"""

import io
import os
import pathlib
import re

from ..core import atomic_path

#: the last line of a CSV table written by save_study
FOOTER = "# blockdae study table: {rows} rows\n"
_FOOTER = re.compile(rb"(?:\A|(?<=\n))# blockdae study table: (\d+) rows\r?\n\Z")
_TAIL_BYTES = 128  # the end of a file where the footer is looked for


def save_study(table, path) -> pathlib.Path:
    """Write a study's table to ``path``, atomically: ``.csv`` (floats to the last bit,
    then the footer line) or ``.parquet`` (needs pyarrow or fastparquet). Returns the path."""
    path = pathlib.Path(path)
    kind = _kind(path)
    if kind == "parquet":
        _parquet_engine()
    with atomic_path(path) as temporary:
        if kind == "parquet":
            table.to_parquet(temporary, index=False)
        else:
            _write_csv(table, temporary)
    return path


def load_study(path):
    """Read a table written by :func:`save_study`; equal to the one saved (same
    columns, dtypes and values, floats to the last bit; only empty fields are NaN, so a
    record named "NA" stays a name).

    Raises ValueError naming the file if a CSV table lacks its footer line or has
    another number of rows than the footer says (a truncated or partly written file).
    """
    path = pathlib.Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file")
    import pandas as pd

    if _kind(path) == "parquet":
        _parquet_engine()
        return pd.read_parquet(path)
    rows, body_bytes = _footer(path)
    with open(path, "rb") as stream:
        body = io.BufferedReader(_Head(stream, body_bytes))
        table = pd.read_csv(body, keep_default_na=False, na_values=[""], **_exact_floats(pd))
    if len(table) != rows:
        raise ValueError(f"{path}: {len(table)} rows before the footer line, which says {rows}: "
                         "the table is incomplete; save it again")
    return table


def _exact_floats(pd):
    """read_csv's option that parses floats to the last bit (pandas 3 does by default)."""
    return {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}


def _write_csv(table, path):
    """The table as CSV at ``path``, then the footer line."""
    with open(path, "w", newline="") as stream:
        table.to_csv(stream, index=False, lineterminator="\n")
        stream.write(FOOTER.format(rows=len(table)))


def _footer(path):
    """(rows the footer line says, bytes before it) of the CSV table at ``path``."""
    with open(path, "rb") as stream:
        size = stream.seek(0, os.SEEK_END)
        stream.seek(max(0, size - _TAIL_BYTES))
        tail = stream.read()
    match = _FOOTER.search(tail)
    if match is None:
        raise ValueError(f"{path}: no footer line '# blockdae study table: N rows' at the end: the file is "
                         "truncated or partly written, or was not written by bd.save_study; save it again")
    return int(match.group(1)), size - len(tail) + match.start()


class _Head(io.RawIOBase):
    """The first ``size`` bytes of a binary stream (the table above its footer line)."""

    def __init__(self, stream, size):
        self._stream, self._left = stream, size

    def readable(self):
        return True

    def readinto(self, buffer):
        data = self._stream.read(min(len(buffer), self._left))
        buffer[:len(data)] = data
        self._left -= len(data)
        return len(data)


def _kind(path):
    suffix = path.suffix.lower()
    if suffix not in (".csv", ".parquet"):
        raise ValueError(f"{path}: a study is saved as .csv or .parquet, got {suffix or 'no suffix'!r}")
    return suffix[1:]


def _parquet_engine():
    import importlib.util

    if not any(importlib.util.find_spec(m) for m in ("pyarrow", "fastparquet")):
        raise ImportError("saving a study as .parquet needs pyarrow (pip install pyarrow); or use .csv")
