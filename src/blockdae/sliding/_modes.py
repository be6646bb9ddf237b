"""The modes of the 1-D block (what its model and its solution share)."""

import enum


class Mode(enum.IntEnum):
    """Mode of the block relative to its base.

    The value is the sign of the relative velocity v = d(x_block - x_base)/dt.
    """

    STICK = 0
    SLIP_POS = 1  # block slides in +x relative to the base (v > 0)
    SLIP_NEG = -1  # block slides in -x relative to the base (v < 0)

    def __str__(self):
        return self.name
