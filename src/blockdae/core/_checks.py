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
