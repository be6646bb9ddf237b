"""The free-standing block's modes and event kinds (what its model and its solution share).

A mode's sign is its side: + for the pivot at the corner x = +b (the block leans toward
+x, theta > 0), - for the corner at -b. REST and the slides keep the 1-D sliding block's
values (0, +1, -1), whose rules they run.
"""

import enum
import functools


class RockingMode(enum.IntEnum):
    """Mode of a free-standing block."""

    REST = 0  # both corners down, no slip
    SLIDE_POS = 1  # sliding, u' > 0 (the 1-D sliding block's rules with g + a_z)
    SLIDE_NEG = -1
    ROCK_POS_OUT = 2  # rocking about +b, rotating away from the base (theta' > 0), theta < alpha
    ROCK_NEG_OUT = -2
    ROCK_POS_IN = 3  # rocking about +b, falling back toward the base (theta' <= 0)
    ROCK_NEG_IN = -3
    ROCK_POS_BEYOND = 4  # rocking about +b beyond the slenderness (theta > alpha), rotating away
    ROCK_NEG_BEYOND = -4
    SETTLE_POS = 5  # the Zeno tail of impacts summed in closed form; theta' is its envelope
    SETTLE_NEG = -5
    OVERTURNED_POS = 6  # lying on its side (theta = pi/2): terminal
    OVERTURNED_NEG = -6
    RELEASE = 7  # the instant t = 0 of a block released from a tilt

    def __str__(self):
        return self.name


#: |mode| of rocking away from the base, falling back, beyond alpha, the Zeno tail and
#: overturned: the same numbers in both blocks' modes (and :class:`~._free_modes.FreeMode`)
OUT, IN, BEYOND, SETTLE, OVERTURNED = 2, 3, 4, 5, 6
SLIDES = (RockingMode.SLIDE_POS, RockingMode.SLIDE_NEG)


def side(mode) -> int:
    """+1 for the pivot at +b, -1 at -b, 0 for REST, RELEASE and the slides."""
    value = int(mode)
    return 0 if abs(value) <= 1 or value == RockingMode.RELEASE else (1 if value > 0 else -1)


def rock_mode(kind: int, s: int) -> RockingMode:
    """The rocking mode of ``kind`` (2 out, 3 in, 4 beyond, 5 settle, 6 overturned) on side ``s``."""
    return RockingMode(kind * s)


@functools.cache
def event_kind(before, after) -> str:
    """The kind of the mode change ``before`` -> ``after``: "release", "uplift", "slide",
    "stick", "apex", "return", "beyond_alpha", "impact", "zeno", "rest", "overturn"."""
    b, a = abs(int(before)), abs(int(after))
    if before == RockingMode.RELEASE:
        return "release"
    if a == 6:
        return "overturn"
    if a == 5:
        return "zeno"
    if after == RockingMode.REST:
        return "rest" if b >= 2 else "stick"
    if a == 1:
        return "slide"
    if before == RockingMode.REST or b == 5:
        return "uplift"
    if b == 3 and side(before) != side(after):
        return "impact"
    if a == 4 and b == 2:
        return "beyond_alpha"
    if a == 3:
        return "apex"
    return "return"
