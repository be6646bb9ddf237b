"""Pure physics: modes, flows, guards and transition rules."""

from ._base import AbstractHybridModel
from ._block import (SlidingBlock, comes_to_rest, demand, relative_acceleration, rest_mode, slip_constant,
                     stick_guards, stop_mode)
from ._modes import Mode

__all__ = ["AbstractHybridModel", "Mode", "SlidingBlock", "comes_to_rest", "demand", "relative_acceleration",
           "rest_mode", "slip_constant", "stick_guards", "stop_mode"]
