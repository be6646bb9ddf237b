"""The spring-supported mass's modes and event kinds (what its model and its solution
share)."""

import enum


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
