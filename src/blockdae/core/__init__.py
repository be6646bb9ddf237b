"""The core: the hybrid-model contract (:class:`AbstractHybridModel`), the generic
solution and event (:class:`DriverSolution`, :class:`HybridEvent`), the hybrid driver,
``simulate``, cross-checks and derivatives. It names no concrete model: a model
declares what the core needs."""

from ._driver import InconsistentStateError, SolverError
from ._model import SCALAR, AbstractHybridModel, ExplicitForm
from ._solution import AbstractEvent, AbstractSolution, DriverSolution, HybridEvent

__all__ = ["AbstractEvent", "AbstractHybridModel", "AbstractSolution", "DriverSolution", "ExplicitForm", "HybridEvent",
           "InconsistentStateError", "SCALAR", "SolverError"]
