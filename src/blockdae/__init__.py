"""blockdae: seismic sliding of rigid blocks as a hybrid automaton.

Exact event times, solver backends that check each other, and derivatives of the
answer with respect to its parameters. Units are SI throughout (m, s, m/s²).

The top level holds what an analysis uses every day: the models, ``simulate``,
``sensitivities``, ``crosscheck``, ``newmark``, ``flexible``, ``study``, ``plot``, the
motions and record readers, the backends, the errors and warnings. The rest lives in
the subpackages named for what they hold: ``blockdae.motions`` (spectra, intensity
measures, baseline correction, relative motion), ``blockdae.hazard``,
``blockdae.empirical``, ``blockdae.backends`` (the registry), ``blockdae.excitation``
(resampling and unit checks), ``blockdae.core.contract`` (a model's capabilities) and each
system's package (``blockdae.sliding``, ``blockdae.planar``, ``blockdae.upthrow``,
``blockdae.rocking``: events,
solutions, modes, the papers' formulas).
"""

import importlib as _importlib
import warnings as _warnings

from . import backends, design, empirical, hazard, motions
from ._plot import plot
from .core import AbstractHybridModel, CompileNotice, InconsistentStateError, SolverError
from .core import Ensemble, Sensitivities, crosscheck, sensitivities, simulate
from .units import STANDARD_GRAVITY
from .excitation import (BaseMotion, Harmonic, Record, RecordSet, RecordWarning, RectangularPulse, SinePulse,
                         TriangularPulse, UnitsWarning, read_motion, read_record, read_records)
from .flexible_mass import (EquivalentLinear, FlexibleEvent, FlexibleMode, FlexibleResult, FlexibleSlidingMass,
                            FlexibleSolution, KyTable, ShearColumn, flexible)
from .planar import PlanarBlock
from .rocking import FreeStandingBlock, RockingBlock
from .sliding import SlidingBlock, newmark
from .structures import ShearFrame
from .studies import load_study, save_study, study
from .upthrow import RigidSupport, SpringSupport, SpringSupportedMass

__all__ = [
    # the models (and what builds them)
    "AbstractHybridModel", "SlidingBlock", "PlanarBlock", "SpringSupportedMass", "SpringSupport", "RigidSupport",
    "FlexibleSlidingMass", "ShearFrame", "FreeStandingBlock", "RockingBlock",
    # the analyses
    "simulate", "Ensemble", "sensitivities", "Sensitivities", "crosscheck", "newmark", "flexible", "study", "load_study",
    "save_study", "plot",
    # the flexible mass's inputs and results, and ky against D
    "FlexibleResult", "FlexibleSolution", "FlexibleEvent", "FlexibleMode", "EquivalentLinear", "ShearColumn",
    "KyTable",
    # the motions and the records
    "BaseMotion", "Harmonic", "SinePulse", "RectangularPulse", "TriangularPulse", "Record", "RecordSet",
    "read_record", "read_records", "read_motion", "STANDARD_GRAVITY",
    # the backends
    "Exact", "ExactJax", "CVODE", "IDA", "JaxTwin", "Compiled",
    # the errors and warnings
    "InconsistentStateError", "SolverError", "UnitsWarning", "RecordWarning", "CompileNotice",
]

#: the backend classes by public name -> their registered name; imported on first use,
#: so that ``import blockdae`` loads neither JAX nor scikit-sundae
_BACKEND_CLASSES = {"Exact": "exact", "ExactJax": "exact-jax", "CVODE": "cvode", "IDA": "ida", "JaxTwin": "jax",
                    "Compiled": "compiled"}


def _homes(module, *names):
    return {name: (module, name) for name in names}


#: the names that left the top level -> (their module, their name there); the old name
#: works with a DeprecationWarning until the next release
_MOVED = {
    **_homes("blockdae.motions", "IntensityMeasures", "RelativeMotion", "ResponseSpectrum", "baseline_corrected",
             "cumulative_arias", "fourier_amplitude", "intensity_measures", "mean_period", "motion_histories",
             "relative_motion", "response_spectrum"),
    **_homes("blockdae.excitation", "AbstractExcitation", "check_peak_acceleration", "pga_factor", "resample"),
    **_homes("blockdae.core.contract", "BatchedModel", "DifferentiableModel", "EngineModel", "LinearModesModel",
             "StudyBatch", "StudyModel"),
    **_homes("blockdae.core", "AbstractEvent", "AbstractSolution", "BatchSolution", "CrossCheck", "DriverSolution",
             "HybridEvent"),
    **_homes("blockdae.backends", "AbstractBackend", "register_backend", "set_compilation_cache"),
    **_homes("blockdae.sliding", "Event", "EventLog", "Mode", "Solution", "FinalNumbers", "simulate_final",
             "SweepSolution", "simulate_many", "NewmarkResult", "NewmarkSweep", "yield_acceleration",
             "AdjustmentFactor", "fit_adjustment_factor", "newmark_rd", "newmark_rd_sd", "pulse_sd", "SeedExample",
             "seed_examples"),
    **_homes("blockdae.planar", "PlanarEvent", "PlanarMode", "PlanarSolution"),
    **_homes("blockdae.upthrow", "Flight", "UpthrowEvent", "UpthrowMode", "UpthrowSolution", "UpthrowEstimate",
             "upthrow_estimate"),
    **_homes("blockdae.structures", "Floor"),
    **_homes("blockdae.solvers", "simulate_linear_final"),
    "study_summary": ("blockdae.studies", "summary"),
}


def __getattr__(name):
    if name in _BACKEND_CLASSES:
        from .backends import backend_class

        cls = globals()[name] = backend_class(_BACKEND_CLASSES[name])
        return cls
    if name in _MOVED:
        module, new_name = _MOVED[name]
        _warnings.warn(f"bd.{name} is {module}.{new_name}; the top-level name goes in the next release",
                      DeprecationWarning, stacklevel=2)
        return getattr(_importlib.import_module(module), new_name)
    raise AttributeError(f"module 'blockdae' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_BACKEND_CLASSES))
