"""Short reprs of results: arrays by their range and shape, long sequences by their
length, nested objects by their own short form; one line, whatever the result's size."""

import dataclasses

import numpy as np

#: the longest repr of a field shown in full; longer ones are summarised
FIELD_CHARS = 60


def compact_repr(result, summary: str = "") -> str:
    """``Name(summary; field=value, ...)``: the fields of a dataclass or named tuple, each
    at most about :data:`FIELD_CHARS` characters (see :func:`short`)."""
    if dataclasses.is_dataclass(result):
        names = [f.name for f in dataclasses.fields(result) if f.repr]
    else:
        names = list(result._fields)
    fields = ", ".join(f"{name}={short(getattr(result, name))}" for name in names)
    return f"{type(result).__name__}({summary + '; ' if summary else ''}{fields})"


def short(value) -> str:
    """A value in at most about :data:`FIELD_CHARS` characters: a number as ``%.6g``; an
    array of more than four values as ``[first .. last] shape (n,)``; anything else by its
    repr, or where that is long, a sequence by its length and type, an object by its type."""
    if isinstance(value, (float, np.floating)):
        return f"{value:.6g}"
    if isinstance(value, np.ndarray):
        flat = value.ravel()
        if value.ndim == 0:
            return _number(value[()])
        if value.ndim == 1 and value.size <= 4:
            return f"[{', '.join(_number(x) for x in flat)}]"
        return f"[{_number(flat[0])} .. {_number(flat[-1])}] shape {value.shape}" if flat.size else \
            f"[] shape {value.shape}"
    text = repr(value)
    if len(text) <= FIELD_CHARS:
        return text
    if isinstance(value, (list, tuple)) and value:
        return f"<{len(value)} {type(value[0]).__name__}>"
    return f"{type(value).__name__}(...)"


def _number(x):
    if isinstance(x, (float, np.floating)):
        return f"{x:.4g}"
    return str(int(x)) if isinstance(x, (int, np.integer)) else repr(x)
