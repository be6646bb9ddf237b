"""The flexible sliding mass (Bray & Rathje; Rathje & Bray): the first mode of a shear
column above the slip surface, sliding when its average acceleration reaches ky g,
decoupled or coupled (../shared/flexible_formulation.md)."""

from ._column import EquivalentLinear, ShearColumn, equivalent_linear, impedance_damping

__all__ = ["EquivalentLinear", "ShearColumn", "equivalent_linear", "impedance_damping"]
