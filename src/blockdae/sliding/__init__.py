"""The 1-D rigid block on an accelerating base (Sawicki & Chybicki 2005): its model, modes and
solution; Newmark's conventions, the SMiRT paper's formulas, final numbers and sweeps."""

from ._model import SlidingBlock, SlidingDAEForm
from ._modes import Mode
from ..core import BatchSolution
from ._sensitivities import block_differences, kernel_sensitivities
from ._solution import Event, EventLog, Solution

#: the block's own derivatives (its DifferentiableModel hooks), attached here: the compiled
#: kernels they differentiate import the model's module
SlidingBlock.sensitivities = kernel_sensitivities
SlidingBlock.finite_differences = block_differences

from ._examples import SeedExample, seed_examples
from ._final import FinalNumbers, simulate_final
from ._formulas import AdjustmentFactor, fit_adjustment_factor, newmark_rd, newmark_rd_sd, pulse_sd
from ._newmark import NewmarkResult, NewmarkSweep, newmark, yield_acceleration
from ._sweep import SweepSolution, simulate_many

__all__ = ["AdjustmentFactor", "BatchSolution", "Event", "EventLog", "FinalNumbers", "Mode", "NewmarkResult",
           "NewmarkSweep", "SeedExample", "SlidingBlock", "SlidingDAEForm", "Solution", "SweepSolution",
           "fit_adjustment_factor", "newmark", "newmark_rd", "newmark_rd_sd", "pulse_sd", "seed_examples",
           "simulate_final", "simulate_many", "yield_acceleration"]

# what the other packages of blockdae use
from ._downslope import downslope
from ._examples import example_solution
from ._figures import newmark_history_figure
from ._model import relative_acceleration, rest_mode, slip_constant, stop_mode
