"""The flexible sliding mass's modes (what its model, engine and solution share)."""

import enum


class FlexibleMode(enum.IntEnum):
    """Mode of a flexible sliding mass: its base stuck to the ground, or sliding downslope."""

    STICK = 0  # the base of the sliding mass moves with the ground
    SLIP = 1  # the base slides downslope (the +ky direction), w = s' > 0

    def __str__(self):
        return self.name


#: event kind of each mode change (before, after); SLIP to SLIP: a ky-table breakpoint crossed
EVENT_KINDS = {(FlexibleMode.STICK, FlexibleMode.SLIP): "onset", (FlexibleMode.SLIP, FlexibleMode.STICK): "stop",
               (FlexibleMode.SLIP, FlexibleMode.SLIP): "breakpoint"}
