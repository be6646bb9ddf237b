"""blockdae: seismic sliding of rigid blocks as a hybrid automaton.

Exact event times, solver backends that check each other, and derivatives of the
answer with respect to its parameters. Units are SI throughout (m, s, m/s²).
"""

from ._crosscheck import CrossCheck, crosscheck
from ._examples import SeedExample, seed_examples
from ._final import FinalNumbers, simulate_final
from ._plot import plot
from ._sensitivities import sensitivities
from ._simulate import simulate
from ._solution import BatchSolution, Event, EventLog, Solution
from .excitation import (AbstractExcitation, Harmonic, Record, RectangularPulse, SinePulse,
                         TriangularPulse, read_record)
from .model import AbstractHybridModel, Mode, SlidingBlock

__all__ = [
    "AbstractExcitation", "AbstractHybridModel", "BatchSolution", "Event", "EventLog", "Harmonic", "Mode",
    "Record", "RectangularPulse", "SinePulse", "SlidingBlock", "Solution", "TriangularPulse",
    "read_record", "simulate",
    "FinalNumbers", "simulate_final",
    "CrossCheck", "crosscheck",
    "SeedExample", "plot", "seed_examples",
    "sensitivities",
]
