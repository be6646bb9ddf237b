"""Performance-based design: slopes with uncertain properties (log-normal, normal,
uniform, truncated, correlated), the probability that their seismic displacement
exceeds a threshold over a record set (Monte Carlo, Latin hypercube or scrambled Sobol
samples, run until precise enough), and the yield acceleration a design needs."""

from ._figures import exceedance_figure
from ._distributions import LogNormal, Normal, Truncated, Uniform
from ._inverse import MeanKyDesign, ky_for_displacement, ky_for_percentile, mean_ky_for_probability
from ._models import Flexible, Rigid
from ._result import Exceedance
from ._study import exceedance

__all__ = ["Exceedance", "Flexible", "LogNormal", "MeanKyDesign", "Normal", "Rigid", "Truncated", "Uniform",
           "exceedance", "exceedance_figure", "ky_for_displacement", "ky_for_percentile", "mean_ky_for_probability"]
