"""Displacement fragility and hazard: P(D > d | IM) fitted to a study by maximum
likelihood (with bootstrap bands) or from an empirical regression, and the annual rate
λ(D > d) from a hazard curve of the intensity measure."""

from ._curve import HazardCurve
from ._empirical import Deaggregation, EmpiricalFragility
from ._fragility import Fragility, fit_fragility
from ._integral import displacement_hazard
from ._plots import plot_displacement_hazard, plot_fragility

__all__ = ["Deaggregation", "EmpiricalFragility", "Fragility", "HazardCurve", "displacement_hazard",
           "fit_fragility", "plot_displacement_hazard", "plot_fragility"]
