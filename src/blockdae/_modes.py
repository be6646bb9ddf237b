"""The modes of every model, and the planar block's state layout: what models and
their solutions share (no model class here, so that a solution needs none)."""

import enum

import numpy as np


class Mode(enum.IntEnum):
    """Mode of the block relative to its base.

    The value is the sign of the relative velocity v = d(x_block - x_base)/dt.
    """

    STICK = 0
    SLIP_POS = 1  # block slides in +x relative to the base (v > 0)
    SLIP_NEG = -1  # block slides in -x relative to the base (v < 0)

    def __str__(self):
        return self.name


class PlanarMode(enum.IntEnum):
    """Mode of the planar block relative to its base."""

    STICK = 0
    SLIP = 1  # sliding in the direction e, on the base
    FLIGHT = 2  # off the base (n <= 0): no friction

    def __str__(self):
        return self.name


class UpthrowMode(enum.IntEnum):
    """Mode of a spring-supported mass."""

    CONTACT = 0  # on the support: a damped oscillator
    FLIGHT_UP = 1  # off the support, rising relative to the ground (u' > 0)
    FLIGHT_DOWN = 2  # off the support, falling relative to the ground (u' <= 0)

    def __str__(self):
        return self.name


#: event kind of each mode change (before, after)
EVENT_KINDS = {(UpthrowMode.CONTACT, UpthrowMode.FLIGHT_UP): "liftoff",
               (UpthrowMode.FLIGHT_UP, UpthrowMode.FLIGHT_DOWN): "top",
               (UpthrowMode.FLIGHT_DOWN, UpthrowMode.FLIGHT_UP): "bottom",
               (UpthrowMode.FLIGHT_UP, UpthrowMode.CONTACT): "landing",
               (UpthrowMode.FLIGHT_DOWN, UpthrowMode.CONTACT): "landing"}


#: the planar block's states: u_x, u_y [m], s [m/s], c_x, c_y [-], w [m], w' [m/s]
_UX, _UY, _S, _CX, _CY, _W, _WD = range(7)


def horizontal_velocity(mode, y):
    """(v_x, v_y) [m/s] from the state in ``mode`` (works on arrays of states)."""
    y = np.asarray(y, dtype=float)
    flying = np.asarray(mode) == PlanarMode.FLIGHT
    size = np.hypot(y[..., _CX], y[..., _CY])
    scale = np.where(flying, 1.0, y[..., _S] / np.where(size > 0, size, 1.0))
    return y[..., _CX] * scale, y[..., _CY] * scale
