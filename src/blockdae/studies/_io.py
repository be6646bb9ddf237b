"""Saving and reloading a study's table (CSV, or Parquet when pyarrow is installed)."""

import pathlib


def save_study(table, path) -> pathlib.Path:
    """Write a study's table to ``path``: ``.csv`` (floats to the last bit), or
    ``.parquet`` (needs pyarrow or fastparquet). Returns the path."""
    path = pathlib.Path(path)
    kind = _kind(path)
    if kind == "parquet":
        _parquet_engine()
        table.to_parquet(path, index=False)
    else:
        table.to_csv(path, index=False)
    return path


def load_study(path):
    """Read a table written by :func:`save_study`; equal to the one saved (same
    columns, dtypes and values)."""
    path = pathlib.Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file")
    import pandas as pd

    if _kind(path) == "parquet":
        _parquet_engine()
        return pd.read_parquet(path)
    return pd.read_csv(path)


def _kind(path):
    suffix = path.suffix.lower()
    if suffix not in (".csv", ".parquet"):
        raise ValueError(f"{path}: a study is saved as .csv or .parquet, got {suffix or 'no suffix'!r}")
    return suffix[1:]


def _parquet_engine():
    import importlib.util

    if not any(importlib.util.find_spec(m) for m in ("pyarrow", "fastparquet")):
        raise ImportError("saving a study as .parquet needs pyarrow (pip install pyarrow); or use .csv")
