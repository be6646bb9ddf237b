"""The free-standing rectangular block: rest, slide, rock with impacts and the Zeno rest,
overturning (Housner 1963); its model, modes and solution; overturning spectra (Zhang &
Makris 2001), the rest/slide/rock map and overturning fragility; the complete block with
slide-rock and flight (:class:`FreeStandingBlock`)."""

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
