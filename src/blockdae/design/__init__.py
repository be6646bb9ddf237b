"""Performance-based design: slopes with uncertain properties (log-normal, normal,
uniform, truncated, correlated), the probability that their seismic displacement
exceeds a threshold over a record set (Monte Carlo, Latin hypercube or scrambled Sobol
samples, run until precise enough), and the yield acceleration a design needs."""

from ._distributions import LogNormal, Normal, Truncated, Uniform
from ._models import Flexible, Rigid
from ._result import Exceedance
from ._study import exceedance

__all__ = ["Exceedance", "Flexible", "LogNormal", "Normal", "Rigid", "Truncated", "Uniform", "exceedance"]
