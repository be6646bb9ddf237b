"""The flexible sliding mass (Bray & Rathje; Rathje & Bray): the first mode of a shear
column above the slip surface, sliding when its average acceleration reaches ky g,
decoupled or coupled.

Its entry point is the function :func:`~._analysis.flexible`, exported at the top level as
``bd.flexible(motion, ky, height, vs, ...)`` (the package's own name, ``flexible_mass``, leaves
that name to the function); the classes are exported there too.
"""

from ._analysis import Analysis, FlexibleResult, analyse_exact, flexible
from ._column import EquivalentLinear, ShearColumn, equivalent_linear, impedance_damping
from ._ky_table import KyTable
from ._model import FlexibleSlidingMass
from ._modes import FlexibleMode
from ._sensitivities import displacement_sensitivities
from ._solution import Episode, FlexibleEvent, FlexibleSolution
from ._study import study_batch, study_sweep

#: bd.study's hooks on the mass; attached here as its rows (._analysis) import the model
FlexibleSlidingMass.study_batch = study_batch
FlexibleSlidingMass.study_sweep = study_sweep

__all__ = ["Analysis", "EquivalentLinear", "Episode", "FlexibleEvent", "FlexibleMode", "FlexibleResult",
           "FlexibleSlidingMass", "FlexibleSolution", "KyTable", "ShearColumn", "analyse_exact",
           "displacement_sensitivities", "equivalent_linear", "flexible", "impedance_damping"]

# what the other packages of blockdae use
from ._analysis import INTEGRATIONS, POLARITIES, as_ky_table, with_zero_sample
from ._column import prechecked_column
from ._model import METHODS
from ._rigid_ky_table import downslope_with_table
