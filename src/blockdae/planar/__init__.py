"""The block on a plane with vertical shaking and flight (Elms 2000): its model, modes
and solution; Elms's set-up."""

from ._model import PlanarBlock, PlanarDAEForm
from ._modes import PlanarMode
from ._solution import PlanarEvent, PlanarSolution

__all__ = ["PlanarBlock", "PlanarDAEForm", "PlanarEvent", "PlanarMode", "PlanarSolution"]
