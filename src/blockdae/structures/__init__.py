"""Structures that filter the ground motion: the floors of a uniform shear frame (as in the SMiRT
paper on Newmark's formula)."""

from ._frame import Floor, ShearFrame

__all__ = ["Floor", "ShearFrame"]
