"""Argument checks shared by the ground-motion functions (clear ValueErrors)."""

import numpy as np

from ..excitation import AbstractExcitation


def excitation(motion, name="motion"):
    if not isinstance(motion, AbstractExcitation):
        raise TypeError(f"{name} must be an excitation (e.g. bd.Record), got {type(motion).__name__}")
    return motion


def excitations(motion, name="motion"):
    """(list of excitations, batch shape): one excitation gives shape (), a sequence (n,)."""
    if isinstance(motion, AbstractExcitation):
        return [motion], ()
    items = list(motion) if isinstance(motion, (list, tuple)) else None
    if items is None:
        raise TypeError(f"{name} must be an excitation or a list of excitations, got {type(motion).__name__}")
    if not items:
        raise ValueError(f"{name} is an empty list; give at least one excitation")
    for i, item in enumerate(items):
        excitation(item, f"{name}[{i}]")
    return items, (len(items),)


def array(name, value, unit, *, low=None, low_open=False, high=None, high_open=True):
    """A float array of finite values within the bounds, never empty."""
    try:
        x = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numbers [{unit}], got {value!r}") from None
    if x.size == 0:
        raise ValueError(f"{name} is empty; give at least one value [{unit}]")
    flat = x.ravel()
    bad = ~np.isfinite(flat)
    if low is not None:
        bad |= (flat <= low) if low_open else (flat < low)
    if high is not None:
        bad |= (flat >= high) if high_open else (flat > high)
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        bounds = ["finite"]
        if low is not None:
            bounds.append(f"> {low:g}" if low_open else f">= {low:g}")
        if high is not None:
            bounds.append(f"< {high:g}" if high_open else f"<= {high:g}")
        where = f"{name}[{i}]" if x.ndim else name
        raise ValueError(f"{where} = {float(flat[i])!r}; {name} must be {' and '.join(bounds)} [{unit}]")
    return x


def horizon(motion, t_end, name="t_end"):
    """The end of the analysed window [s]: ``t_end`` or the excitation's duration."""
    if t_end is None:
        if not np.isfinite(motion.duration):
            raise ValueError(f"{name} is required for an excitation without end "
                             f"({type(motion).__name__}); give the end of the window [s]")
        return float(motion.duration)
    t_end = float(t_end)
    if not (np.isfinite(t_end) and t_end > 0):
        raise ValueError(f"{name} must be a positive finite time [s], got {t_end!r}")
    return t_end
