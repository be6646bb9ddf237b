"""The core: the model contract (:mod:`.contract`: :class:`AbstractHybridModel` and the
capabilities a model declares), the generic solution and event (:class:`DriverSolution`,
:class:`HybridEvent`), the hybrid driver, ``simulate``, cross-checks and derivatives
(:mod:`.derivatives`). It names no concrete model: a model declares what the core needs."""

from ._driver import InconsistentStateError, ModelContractError, SolverError
from .contract import (SCALAR, AbstractHybridModel, BatchedModel, DifferentiableModel, EngineModel, ExplicitForm,
                       LinearModesModel, StudyBatch, StudyModel)
from ._solution import AbstractEvent, AbstractSolution, DriverSolution, HybridEvent
from ._sensitivity_result import Sensitivities
from ._ensemble import Ensemble

__all__ = ["AbstractEvent", "AbstractHybridModel", "AbstractSolution", "BatchSolution", "BatchedModel", "CrossCheck",
           "DifferentiableModel", "DriverSolution", "EngineModel", "Ensemble", "ExplicitForm", "HybridEvent",
           "InconsistentStateError", "LinearModesModel", "ModelContractError", "SCALAR", "Sensitivities",
           "SolverError", "StudyBatch", "StudyModel"]

# what the other packages of blockdae use
from ._atomic import atomic_path
from ._backend import AbstractBackend, cached_per_excitation, check_window
from ._cases import cases, labelled_motions
from ._checks import set_batch_fields, set_real_fields
from ._compile_notice import CompileNotice, notice_numba
from ._crosscheck import CrossCheck, crosscheck
from ._driver import AbstractIntegrator, EventRun, HermiteDense, drive
from ._engines import LazyEngine
from .events import falls, first_nonpositive, one_sign, sign_change, too_short
from ._file_hashes import FILES, record_file, recorded, write_manifest
from ._figures import BASE, BLOCK, EVENTS, curve, time_grid
from ._jax_config import jax_context, set_compilation_cache
from ._progress import progress_bar, show_progress
from ._registry import BUILT_IN, Horizon, available, backend_class, backend_name, make_backend, register_backend
from ._repr import compact_repr
from ._sensitivities import sensitivities
from ._simulate import simulate
from ._solution import BatchSolution, SolveItem
from ._states import state_columns, state_labels, unit_suffix
from ._threads import run_items
