"""The core: the model contract (:mod:`.contract`: :class:`AbstractHybridModel` and the
capabilities a model declares), the generic solution and event (:class:`DriverSolution`,
:class:`HybridEvent`), the hybrid driver, ``simulate``, cross-checks and derivatives
(:mod:`.derivatives`). It names no concrete model: a model declares what the core needs."""

from ._driver import InconsistentStateError, SolverError
from .contract import (SCALAR, AbstractHybridModel, BatchedModel, DifferentiableModel, EngineModel, ExplicitForm,
                       LinearModesModel, StudyBatch, StudyModel)
from ._solution import AbstractEvent, AbstractSolution, DriverSolution, HybridEvent

__all__ = ["AbstractEvent", "AbstractHybridModel", "AbstractSolution", "BatchedModel", "DifferentiableModel",
           "DriverSolution", "EngineModel", "ExplicitForm", "HybridEvent", "InconsistentStateError",
           "LinearModesModel", "SCALAR", "SolverError", "StudyBatch", "StudyModel"]
