"""The flexible sliding mass (Bray & Rathje; Rathje & Bray): the first mode of a shear
column above the slip surface, sliding when its average acceleration reaches ky g,
decoupled or coupled (../shared/flexible_formulation.md)."""

from ._analysis import Analysis, FlexibleResult, analyse_exact, flexible
from ._column import EquivalentLinear, ShearColumn, equivalent_linear, impedance_damping
from ._model import FlexibleSlidingMass
from ._modes import FlexibleMode
from ._sensitivities import displacement_sensitivities
from ._solution import Episode, FlexibleEvent, FlexibleSolution

__all__ = ["Analysis", "EquivalentLinear", "Episode", "FlexibleEvent", "FlexibleMode", "FlexibleResult",
           "FlexibleSlidingMass", "FlexibleSolution", "ShearColumn", "analyse_exact", "displacement_sensitivities",
           "equivalent_linear", "flexible", "impedance_damping"]
