"""Ground motions: histories, intensity measures, baseline correction, response spectra
and the relative motion of two surface points (Christian 1973)."""

from ._baseline import baseline_corrected, polynomial_trend
from ._figures import plot_relative_motion, plot_spectrum
from ._intensity import IntensityMeasures, cumulative_arias, intensity_measures, motion_histories
from ._mean_period import MEAN_PERIOD_BAND, mean_period
from ._spectra import ResponseSpectrum, response_spectrum
from ._two_point import RelativeMotion, fourier_amplitude, relative_motion

__all__ = ["IntensityMeasures", "MEAN_PERIOD_BAND", "RelativeMotion", "ResponseSpectrum", "baseline_corrected",
           "cumulative_arias", "fourier_amplitude", "intensity_measures", "mean_period", "motion_histories",
           "plot_relative_motion", "plot_spectrum", "polynomial_trend", "relative_motion", "response_spectrum"]

# what the other packages of blockdae use
from ._baseline import METHODS
