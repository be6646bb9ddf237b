"""Ground motions: histories, intensity measures, baseline correction, response spectra
and the relative motion of two surface points (seed 003)."""

from ._baseline import baseline_corrected, polynomial_trend
from ._two_point import RelativeMotion, fourier_amplitude, relative_motion
from ._spectra import ResponseSpectrum, response_spectrum
from ._intensity import IntensityMeasures, cumulative_arias, intensity_measures, motion_histories

__all__ = ["RelativeMotion", "fourier_amplitude", "relative_motion", "ResponseSpectrum", "response_spectrum", "baseline_corrected", "polynomial_trend", "IntensityMeasures", "cumulative_arias", "intensity_measures", "motion_histories"]
