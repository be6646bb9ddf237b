"""Pure physics: modes, flows, guards and transition rules."""

from ._base import AbstractHybridModel, ExplicitForm
from ._block import (SlidingBlock, SlidingDAEForm, comes_to_rest, demand, never_rests_error, relative_acceleration, rest_mode,
                     slip_constant, stick_guards, stop_mode)
from .._modes import Mode, PlanarMode, UpthrowMode
from ._planar import PlanarBlock, PlanarDAEForm
from ._spring import SpringDAEForm, SpringSupportedMass
from ._support import RigidSupport, SpringSupport

__all__ = ["AbstractHybridModel", "ExplicitForm", "PlanarDAEForm", "SlidingDAEForm", "SpringDAEForm", "Mode", "PlanarBlock", "PlanarMode", "RigidSupport", "SlidingBlock", "SpringSupport", "SpringSupportedMass", "UpthrowMode", "comes_to_rest", "demand", "never_rests_error",
           "relative_acceleration", "rest_mode", "slip_constant", "stick_guards", "stop_mode"]
