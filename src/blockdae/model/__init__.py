"""Pure physics: modes, flows, guards and transition rules."""

from ._base import AbstractHybridModel
from ._block import (SlidingBlock, comes_to_rest, demand, never_rests_error, relative_acceleration, rest_mode,
                     slip_constant, stick_guards, stop_mode)
from ._modes import Mode
from ._planar import PlanarBlock, PlanarMode
from ._spring import SpringSupportedMass, UpthrowMode
from ._support import RigidSupport, SpringSupport

__all__ = ["AbstractHybridModel", "Mode", "PlanarBlock", "PlanarMode", "RigidSupport", "SlidingBlock", "SpringSupport", "SpringSupportedMass", "UpthrowMode", "comes_to_rest", "demand", "never_rests_error",
           "relative_acceleration", "rest_mode", "slip_constant", "stick_guards", "stop_mode"]
