"""Validation shared by the models' settings."""

import math

import numpy as np


def set_real_fields(obj, names) -> None:
    """Set each field of ``names`` on the frozen dataclass ``obj`` to its value as a
    float; a value that is not a finite real number raises ValueError naming the field."""
    for name in names:
        value = getattr(obj, name)
        if type(value) is float and math.isfinite(value):
            continue  # already what it would be set to
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
            raise ValueError(f"{name} must be a real number, got {value!r}")
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite, got {value!r}")
        object.__setattr__(obj, name, float(value))


def set_batch_fields(obj, names) -> tuple[int, ...]:
    """Set each field of ``names`` on the frozen dataclass ``obj`` to a float, or to a
    read-only 1-D float array (a batch of parameter sets), broadcast together; returns the
    batch shape, () for one set. ValueError naming the field and the value otherwise (not
    a finite real number or a non-empty 1-D array of them, or arrays of different sizes)."""
    arrays = {}
    for name in names:
        value = getattr(obj, name)
        if np.ndim(value) == 0:
            set_real_fields(obj, (name,))
            continue
        try:
            array = np.array(value, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be a real number or a 1-D array of them, got {value!r}") from None
        if isinstance(value, bool) or array.ndim != 1 or array.size == 0:
            raise ValueError(f"{name} must be a real number or a non-empty 1-D array of them, got shape {array.shape}")
        bad = np.flatnonzero(~np.isfinite(array))
        if bad.size:
            raise ValueError(f"{name}[{bad[0]}] must be finite, got {array[bad[0]]!r}")
        arrays[name] = array
    if not arrays:
        return ()
    sizes = {array.size for array in arrays.values()}
    if len(sizes) > 1:
        raise ValueError(f"the batch's arrays differ in size: {', '.join(f'{n} {a.size}' for n, a in arrays.items())}")
    for name, array in arrays.items():
        array.setflags(write=False)
        object.__setattr__(obj, name, array)
    return (sizes.pop(),)
