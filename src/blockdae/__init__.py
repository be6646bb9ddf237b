"""blockdae: seismic sliding of rigid blocks as a hybrid automaton.

Exact event times, solver backends that check each other, and derivatives of the
answer with respect to its parameters. Units are SI throughout (m, s, m/s²).
"""

from . import backends, empirical, hazard
from ._plot import plot
from .backends import AbstractBackend, register_backend
from .core import (AbstractEvent, AbstractHybridModel, AbstractSolution, BatchedModel, DifferentiableModel,
                   DriverSolution, EngineModel, HybridEvent, InconsistentStateError, LinearModesModel, SolverError,
                   StudyBatch, StudyModel)
from .core import CrossCheck, crosscheck
from .core import CompileNotice
from .core import set_compilation_cache
from .core import Sensitivities, sensitivities
from .core import simulate
from .units import STANDARD_GRAVITY
from .solvers import simulate_linear_final
from .excitation import (AbstractExcitation, BaseMotion, Harmonic, Record, RecordSet, RecordWarning, RectangularPulse,
                         SinePulse, TriangularPulse, UnitsWarning, check_peak_acceleration, pga_factor, read_motion,
                         read_record, read_records, resample)
from .flexible_mass import (EquivalentLinear, FlexibleEvent, FlexibleMode, FlexibleResult, FlexibleSlidingMass,
                            FlexibleSolution, KyTable, ShearColumn, flexible)
from .motions import (IntensityMeasures, RelativeMotion, ResponseSpectrum, baseline_corrected,
                      cumulative_arias, fourier_amplitude, intensity_measures, mean_period, motion_histories,
                      relative_motion, response_spectrum)
from .planar import PlanarBlock, PlanarEvent, PlanarMode, PlanarSolution
from .sliding import BatchSolution, Event, EventLog, Mode, SlidingBlock, Solution
from .sliding import SeedExample, seed_examples
from .sliding import FinalNumbers, simulate_final
from .sliding import AdjustmentFactor, fit_adjustment_factor, newmark_rd, newmark_rd_sd, pulse_sd
from .sliding import NewmarkResult, NewmarkSweep, newmark, yield_acceleration
from .sliding import SweepSolution, simulate_many
from .structures import Floor, ShearFrame
from .studies import load_study, save_study, study, summary as study_summary
from .upthrow import (Flight, RigidSupport, SpringSupport, SpringSupportedMass, UpthrowEvent, UpthrowMode,
                      UpthrowSolution)
from .upthrow import UpthrowEstimate, upthrow_estimate

__all__ = [
    "AbstractExcitation", "AbstractHybridModel", "BaseMotion", "BatchSolution", "Event", "EventLog", "Harmonic", "Mode",
    "Record", "RectangularPulse", "SinePulse", "SlidingBlock", "Solution", "TriangularPulse",
    "check_peak_acceleration", "read_motion", "read_record", "read_records", "RecordSet", "simulate",
    "InconsistentStateError", "SolverError",
    "RecordWarning", "UnitsWarning", "pga_factor", "resample",
    "AbstractEvent", "AbstractSolution", "DriverSolution", "HybridEvent",
    "BatchedModel", "DifferentiableModel", "EngineModel", "LinearModesModel", "StudyBatch", "StudyModel",
    "PlanarBlock", "PlanarEvent", "PlanarMode", "PlanarSolution", "RigidSupport", "SpringSupport",
    "Flight", "SpringSupportedMass", "UpthrowEstimate", "UpthrowEvent", "UpthrowMode", "UpthrowSolution",
    "upthrow_estimate",
    "SweepSolution", "simulate_many",
    "FinalNumbers", "simulate_final", "simulate_linear_final",
    "CrossCheck", "crosscheck",
    "SeedExample", "STANDARD_GRAVITY", "plot", "seed_examples",
    "Sensitivities", "sensitivities", "set_compilation_cache", "CompileNotice",
    "NewmarkResult", "NewmarkSweep", "newmark", "yield_acceleration",
    "EquivalentLinear", "FlexibleEvent", "FlexibleMode", "FlexibleResult", "FlexibleSlidingMass", "FlexibleSolution", "KyTable",
    "ShearColumn", "flexible",
    "IntensityMeasures", "baseline_corrected", "cumulative_arias", "intensity_measures", "mean_period",
    "motion_histories",
    "ResponseSpectrum", "response_spectrum", "RelativeMotion", "fourier_amplitude", "relative_motion",
    "AdjustmentFactor", "fit_adjustment_factor", "newmark_rd", "newmark_rd_sd", "pulse_sd",
    "Floor", "ShearFrame",
    "load_study", "save_study", "study", "study_summary",
    "empirical", "hazard",
    "AbstractBackend", "register_backend", "CVODE", "IDA", "JaxTwin", "Exact", "ExactJax", "Compiled",
]

#: the backend classes by public name -> their registered name; imported on first use,
#: so that ``import blockdae`` loads neither JAX nor scikit-sundae
_BACKEND_CLASSES = {"Exact": "exact", "ExactJax": "exact-jax", "CVODE": "cvode", "IDA": "ida", "JaxTwin": "jax",
                    "Compiled": "compiled"}


def __getattr__(name):
    if name in _BACKEND_CLASSES:
        from .backends import backend_class

        cls = globals()[name] = backend_class(_BACKEND_CLASSES[name])
        return cls
    raise AttributeError(f"module 'blockdae' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_BACKEND_CLASSES))
