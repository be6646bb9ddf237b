"""Structures that filter the ground motion: the floors of a uniform shear frame (seed 002)."""

from ._frame import Floor, ShearFrame

__all__ = ["Floor", "ShearFrame"]
