"""Base excitations a(t), v(t), x(t), their breakpoints and file readers."""

from ._analytic import Harmonic, RectangularPulse, SinePulse, TriangularPulse
from ._base import AbstractExcitation
from ._motion import BaseMotion
from ._pieces import Pieces
from ._read_motion import read_motion
from ._readers import PLAUSIBLE_PEAK_G, STANDARD_GRAVITY, check_peak_acceleration, read_record
from ._record import Record

__all__ = ["AbstractExcitation", "BaseMotion", "Harmonic", "Pieces", "Record", "RectangularPulse",
           "PLAUSIBLE_PEAK_G", "STANDARD_GRAVITY", "SinePulse", "TriangularPulse", "check_peak_acceleration",
           "read_motion", "read_record"]
