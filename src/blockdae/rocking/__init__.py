"""The free-standing rectangular block (:class:`FreeStandingBlock`): the complete block
(``contact="complete"``: rest, slide, rock, slide-rock, flight and overturning, with
frictional impacts and landings) or Housner's (1963) (``contact="housner"``, a
:class:`RockingBlock`: rest, slide, rock with impacts and the Zeno rest, overturning, its
pivot held; where that breaks, :class:`ContactLimit` rows on its solution); their models,
modes and solutions; overturning spectra (Zhang & Makris 2001), the rest/slide/rock map and
overturning fragility."""

from ._figures import plot_mode_map
from ._free_model import FreeStandingBlock, PainleveWarning
from ._free_modes import FreeMode
from ._free_solution import FreeEvent, FreeStandingSolution
from ._mode_map import mode_map
from ._model import RockingBlock, housner_restitution
from ._modes import RockingMode
from ._solution import ContactLimit, RockingEvent, RockingSolution
from ._spectra import (OverturningFragility, OverturningSpectrum, motion_regime, overturning_amplitude,
                       overturning_fragility, overturning_spectrum, overturns, pulse)

__all__ = ["ContactLimit", "FreeEvent", "FreeMode", "FreeStandingBlock", "FreeStandingSolution", "PainleveWarning",
           "OverturningFragility", "OverturningSpectrum", "RockingBlock", "RockingEvent",
           "RockingMode", "RockingSolution", "housner_restitution", "motion_regime", "overturning_amplitude",
           "overturning_fragility", "overturning_spectrum", "overturns", "pulse",
           "mode_map", "plot_mode_map"]
