"""Performance-based design: slopes (and blocks on a plane) with uncertain properties
(log-normal, normal, uniform, truncated, correlated), the probability that their seismic
displacement exceeds a threshold over a record set (Monte Carlo, Latin hypercube or
scrambled Sobol samples, run until precise enough), the yield acceleration (the
friction coefficient, on a plane) a design needs, and the back-analysis of a parameter
(the rigid block's or the flexible mass's ky, the plane's mu, ...) from observed
displacements (its posterior, by NUTS or a Laplace approximation)."""

from ._back_analysis import BackAnalysis, ConvergenceWarning, Observation, back_analysis, log_posterior
from ._figures import exceedance_figure
from ._infinite_slope_model import InfiniteSlope, Slope, SlopesBackAnalysis
from ._distributions import LogNormal, Normal, Truncated, Uniform
from ._inverse import MeanKyDesign, ky_for_displacement, ky_for_percentile, mean_ky_for_probability
from ._models import DesignModel, Flexible, Planar, Rigid, Simulated
from ._result import Exceedance
from ._study import exceedance

__all__ = ["BackAnalysis", "ConvergenceWarning", "DesignModel", "Exceedance", "Flexible", "InfiniteSlope", "LogNormal",
           "MeanKyDesign", "Normal", "Observation", "Planar", "Rigid", "Simulated", "Slope", "SlopesBackAnalysis",
           "Truncated", "Uniform", "back_analysis", "exceedance", "exceedance_figure", "ky_for_displacement",
           "ky_for_percentile", "log_posterior", "mean_ky_for_probability"]
