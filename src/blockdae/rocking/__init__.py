"""The free-standing rectangular block: rest, slide, rock with impacts and the Zeno rest,
overturning (Housner 1963); its model, modes and solution."""

from ._model import RockingBlock, housner_restitution
from ._modes import RockingMode
from ._solution import ContactWarning, RockingEvent, RockingSolution

__all__ = ["ContactWarning", "RockingBlock", "RockingEvent", "RockingMode", "RockingSolution", "housner_restitution"]
