"""The 1-D rigid block on an accelerating base (Sawicki & Chybicki 2005): its model, modes and
solution; Newmark's conventions, the SMiRT paper's formulas, final numbers and sweeps."""

from ._model import SlidingBlock, SlidingDAEForm
from ._modes import Mode
from ..core._solution import BatchSolution
from ._solution import Event, EventLog, Solution

__all__ = ["BatchSolution", "Event", "EventLog", "Mode", "SlidingBlock", "SlidingDAEForm", "Solution"]
