"""The flexible sliding mass (Bray & Rathje; Rathje & Bray): the first mode of a shear
column above the slip surface, sliding when its average acceleration reaches ky g,
decoupled or coupled (../shared/flexible_formulation.md)."""

from ._column import EquivalentLinear, ShearColumn, equivalent_linear, impedance_damping
from ._model import FlexibleSlidingMass
from ._modes import FlexibleMode
from ._solution import Episode, FlexibleEvent, FlexibleSolution

__all__ = ["EquivalentLinear", "Episode", "FlexibleEvent", "FlexibleMode", "FlexibleSlidingMass", "FlexibleSolution",
           "ShearColumn", "equivalent_linear", "impedance_damping"]
