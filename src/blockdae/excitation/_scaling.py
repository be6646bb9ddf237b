"""Scaling a motion to a target peak ground acceleration [g]: the factor, how the motion's
own peak is taken, and the deprecated keyword of the target."""

import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ._plausibility import check_pga


#: how :func:`pga_factor` takes a motion's own peak: "exact", or "slammer" (rounded to 0.001 g)
PGA_ROUNDINGS = ("exact", "slammer")


def pga_keyword(function: str, pga, target_pga):
    """The target peak ground acceleration(s) [g] a call to ``function`` gave: ``pga``, or
    ``target_pga``, its deprecated name, with a DeprecationWarning naming ``pga``; a
    ValueError where both are given."""
    if target_pga is None:
        return pga
    if pga is not None:
        raise ValueError(f"{function}: pga={pga!r} and target_pga={target_pga!r} name the same target peak [g]; "
                         "give pga only (target_pga is its deprecated name)")
    warnings.warn(f"{function}(..., target_pga=...) is deprecated; use {function}(..., pga=...), the same target "
                  "peak ground acceleration [g]", DeprecationWarning, stacklevel=3)
    return target_pga


def check_pga_rounding(rounding):
    """ValueError unless ``rounding`` is one of :data:`PGA_ROUNDINGS`."""
    if rounding not in PGA_ROUNDINGS:
        raise ValueError(f"pga_rounding must be one of {PGA_ROUNDINGS}, got {rounding!r}")


def pga_factor(peak, pga, g: float = STANDARD_GRAVITY, rounding: str = "exact", name: str = "pga",
               check_peak: bool = True):
    """Factor(s) [-] on a motion of peak |a| ``peak`` [m/s²] that scale it to ``pga`` [g]
    (a number or 1-D sequence; one g is ``g`` [m/s²]): ``pga g / peak``.

    ``rounding``: "exact" (default) or "slammer", SLAMMER's convention for reproducing its
    tables: the record's own peak in g rounded to 0.001 g, ``pga / round(peak / g, 3)``.
    ``check_peak``: False accepts a ``pga`` above :data:`~._plausibility.MAX_PGA_G` (see :func:`check_pga`).
    Returns an array shaped like ``pga`` (a float for a number).
    """
    check_pga_rounding(rounding)
    targets = check_pga(pga, name, check_peak)
    own = round(float(peak) / g, 3) if rounding == "slammer" else float(peak)
    if not own > 0:
        raise ValueError(f"{name} needs a motion with a nonzero peak; this one's is {float(peak):.4g} m/s² "
                         f"(= {float(peak) / g:.4g} g{', 0 to 0.001 g' if rounding == 'slammer' else ''})")
    factors = targets / own if rounding == "slammer" else targets * g / own
    return float(factors[0]) if np.ndim(pga) == 0 else factors
