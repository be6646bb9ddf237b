"""The 1-D rigid block on an accelerating base (Sawicki & Chybicki 2005): its model, modes and
solution; Newmark's conventions, the SMiRT paper's formulas, final numbers and sweeps."""

from ._model import SlidingBlock, SlidingDAEForm
from ._modes import Mode
from ..core._solution import BatchSolution
from ._sensitivities import block_differences, kernel_sensitivities
from ._solution import Event, EventLog, Solution

#: the block's own derivatives (its DifferentiableModel hooks), attached here: the compiled
#: kernels they differentiate import the model's module
SlidingBlock.sensitivities = kernel_sensitivities
SlidingBlock.finite_differences = block_differences

__all__ = ["BatchSolution", "Event", "EventLog", "Mode", "SlidingBlock", "SlidingDAEForm", "Solution"]
