"""blockdae: seismic sliding of rigid blocks as a hybrid automaton.

Exact event times, solver backends that check each other, and derivatives of the
answer with respect to its parameters. Units are SI throughout (m, s, m/s²).
"""

from ._crosscheck import CrossCheck, crosscheck
from ._examples import SeedExample, seed_examples
from ._jax_config import set_compilation_cache
from ._newmark import NewmarkResult, newmark, yield_acceleration
from ._plot import plot
from ._sensitivities import sensitivities
from ._simulate import simulate
from ._solution import BatchSolution, Event, Solution
from ._units import STANDARD_GRAVITY
from .excitation import (AbstractExcitation, Harmonic, Record, RectangularPulse, SinePulse,
                         TriangularPulse, read_record)
from .model import AbstractHybridModel, Mode, SlidingBlock
from .motions import (IntensityMeasures, RelativeMotion, ResponseSpectrum, baseline_corrected, cumulative_arias,
                      fourier_amplitude, intensity_measures, motion_histories, relative_motion, response_spectrum)

__all__ = [
    "AbstractExcitation", "AbstractHybridModel", "BatchSolution", "Event", "Harmonic", "Mode",
    "Record", "RectangularPulse", "SinePulse", "SlidingBlock", "Solution", "TriangularPulse",
    "read_record", "simulate",
    "CrossCheck", "crosscheck",
    "SeedExample", "STANDARD_GRAVITY", "plot", "seed_examples",
    "sensitivities", "set_compilation_cache",
    "NewmarkResult", "newmark", "yield_acceleration",
    "IntensityMeasures", "baseline_corrected", "cumulative_arias", "intensity_measures", "motion_histories",
    "ResponseSpectrum", "response_spectrum", "RelativeMotion", "fourier_amplitude", "relative_motion",
]
