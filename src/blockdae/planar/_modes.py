"""The planar block's modes and state layout (what its model and its solution share)."""

import enum

import numpy as np


class PlanarMode(enum.IntEnum):
    """Mode of the planar block relative to its base."""

    STICK = 0
    SLIP = 1  # sliding in the direction e, on the base
    FLIGHT = 2  # off the base (n <= 0): no friction

    def __str__(self):
        return self.name


#: the planar block's states: u_x, u_y [m], s [m/s], c_x, c_y [-], w [m], w' [m/s]
_UX, _UY, _S, _CX, _CY, _W, _WD = range(7)


def horizontal_velocity(mode, y):
    """(v_x, v_y) [m/s] from the state in ``mode`` (works on arrays of states)."""
    y = np.asarray(y, dtype=float)
    flying = np.asarray(mode) == PlanarMode.FLIGHT
    size = np.hypot(y[..., _CX], y[..., _CY])
    scale = np.where(flying, 1.0, y[..., _S] / np.where(size > 0, size, 1.0))
    return y[..., _CX] * scale, y[..., _CY] * scale
