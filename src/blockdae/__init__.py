"""blockdae: seismic sliding of rigid blocks as a hybrid automaton.

Exact event times, solver backends that check each other, and derivatives of the
answer with respect to its parameters. Units are SI throughout (m, s, m/s²).
"""

from ._crosscheck import CrossCheck, crosscheck
from ._driver import InconsistentStateError, SolverError
from ._examples import SeedExample, seed_examples
from ._final import FinalNumbers, simulate_final
from ._formulas import AdjustmentFactor, fit_adjustment_factor, newmark_rd, newmark_rd_sd, pulse_sd
from ._jax_config import set_compilation_cache
from ._newmark import NewmarkResult, newmark, yield_acceleration
from ._plot import plot
from ._sensitivities import sensitivities
from ._simulate import simulate
from ._solution import BatchSolution, Event, EventLog, Solution
from ._solution_driver import DriverSolution, HybridEvent
from ._solution_planar import PlanarEvent, PlanarSolution
from ._solution_upthrow import Flight, UpthrowEvent, UpthrowSolution
from ._sweep import SweepSolution, simulate_many
from ._upthrow import UpthrowEstimate, upthrow_estimate
from ._units import STANDARD_GRAVITY
from .excitation import (AbstractExcitation, BaseMotion, Harmonic, Record, RectangularPulse, SinePulse,
                         TriangularPulse, check_peak_acceleration, read_motion, read_record)
from .model import (AbstractHybridModel, Mode, PlanarBlock, PlanarMode, RigidSupport, SlidingBlock, SpringSupport,
                    SpringSupportedMass, UpthrowMode)
from .motions import (IntensityMeasures, RelativeMotion, ResponseSpectrum, baseline_corrected,
                      cumulative_arias, fourier_amplitude, intensity_measures, motion_histories,
                      relative_motion, response_spectrum)
from .structures import Floor, ShearFrame
from .studies import load_study, save_study, study, summary as study_summary

__all__ = [
    "AbstractExcitation", "AbstractHybridModel", "BaseMotion", "BatchSolution", "Event", "EventLog", "Harmonic", "Mode",
    "Record", "RectangularPulse", "SinePulse", "SlidingBlock", "Solution", "TriangularPulse",
    "check_peak_acceleration", "read_motion", "read_record", "simulate", "InconsistentStateError", "SolverError",
    "DriverSolution", "HybridEvent",
    "PlanarBlock", "PlanarEvent", "PlanarMode", "PlanarSolution", "RigidSupport", "SpringSupport",
    "Flight", "SpringSupportedMass", "UpthrowEstimate", "UpthrowEvent", "UpthrowMode", "UpthrowSolution",
    "upthrow_estimate",
    "SweepSolution", "simulate_many",
    "FinalNumbers", "simulate_final",
    "CrossCheck", "crosscheck",
    "SeedExample", "STANDARD_GRAVITY", "plot", "seed_examples",
    "sensitivities", "set_compilation_cache",
    "NewmarkResult", "newmark", "yield_acceleration",
    "IntensityMeasures", "baseline_corrected", "cumulative_arias", "intensity_measures", "motion_histories",
    "ResponseSpectrum", "response_spectrum", "RelativeMotion", "fourier_amplitude", "relative_motion",
    "AdjustmentFactor", "fit_adjustment_factor", "newmark_rd", "newmark_rd_sd", "pulse_sd",
    "Floor", "ShearFrame",
    "load_study", "save_study", "study", "study_summary",
]
