"""The complete free-standing block's modes and event kinds (what its model and its
solution share).

A mode's sign is its side: + for the pivot (or the corner struck) at +b, - at -b. REST,
the slides and the rocking modes keep :class:`~blockdae.rocking.RockingMode`'s values, so
that the rocking rules (:mod:`._rules`) run on them unchanged; SLIDE_ROCK (s, sigma) is
7 s where the pivot slips toward its own side (sigma = s) and 8 s where it slips back
(sigma = -s).
"""

import enum

from ._modes import BEYOND, IN, OUT, OVERTURNED, SETTLE


class FreeMode(enum.IntEnum):
    """Mode of a :class:`~blockdae.rocking.FreeStandingBlock`."""

    REST = 0  # both corners down, no slip
    SLIDE_POS = 1  # sliding flat, x' > 0
    SLIDE_NEG = -1
    ROCK_POS_OUT = 2  # rocking on the sticking corner +b, rotating away from the base, theta < alpha
    ROCK_NEG_OUT = -2
    ROCK_POS_IN = 3  # rocking on +b, falling back toward the base
    ROCK_NEG_IN = -3
    ROCK_POS_BEYOND = 4  # rocking on +b beyond the slenderness (theta > alpha), rotating away
    ROCK_NEG_BEYOND = -4
    SETTLE_POS = 5  # the Zeno tail of sticking impacts summed; theta' is its envelope
    SETTLE_NEG = -5
    OVERTURNED_POS = 6  # lying on its side: terminal
    OVERTURNED_NEG = -6
    SLIDE_ROCK_POS_POS = 7  # rocking on +b while that corner slips toward +x
    SLIDE_ROCK_NEG_NEG = -7  # on -b, slipping toward -x
    SLIDE_ROCK_POS_NEG = 8  # on +b, slipping toward -x
    SLIDE_ROCK_NEG_POS = -8  # on -b, slipping toward +x
    FLIGHT_POS = 9  # no corner touches the base; the state's position is the corner +b's (the one that lifted)
    FLIGHT_NEG = -9  # the same, the state's position the corner -b's
    IMPACT_POS_STICK = 10  # instant: the corner +b strikes and sticks
    IMPACT_NEG_STICK = -10
    IMPACT_POS_SLIP = 11  # instant: the corner +b strikes and slips through the impact
    IMPACT_NEG_SLIP = -11
    LANDING_FLAT = 12  # instant: the whole face lands
    RELEASE = 13  # instant: t = 0 of a block released from a tilt

    def __str__(self):
        return self.name


SLIDE_ROCK_KINDS = (7, 8)
IMPACT_KINDS = (10, 11, 12)
#: the instant modes: an impact's or a landing's velocity jump, the release from a tilt
INSTANT = tuple(m for m in FreeMode if abs(int(m)) in (*IMPACT_KINDS, 13))


def kind_of(mode) -> int:
    """|mode|: 0 rest, 1 slide, 2-4 rock (out, in, beyond), 5 settle, 6 overturned,
    7-8 slide-rock, 9 flight, 10-12 impacts, 13 release."""
    return abs(int(mode))


def side(mode) -> int:
    """The pivot's side (+1: +b, -1: -b) of a rocking, settling, slide-rocking,
    overturned or impact mode; a flight's reference corner; a slide's direction; 0 for
    REST, the flat landing and the release."""
    value = int(mode)
    if kind_of(mode) in (0, 12, 13):
        return 0
    return 1 if value > 0 else -1


def slip_direction(mode) -> int:
    """sigma of a slide-rocking mode (+1: the pivot slips toward +x), of a slide; 0 otherwise."""
    kind, s = kind_of(mode), side(mode)
    if kind == 1:
        return s
    if kind == 7:
        return s
    if kind == 8:
        return -s
    return 0


def slide_rock_mode(s: int, sigma: int) -> FreeMode:
    """SLIDE_ROCK on pivot ``s`` slipping toward ``sigma`` (both +1 or -1)."""
    return FreeMode((7 if s == sigma else 8) * s)


def rock_mode(kind: int, s: int) -> FreeMode:
    """The rocking mode of ``kind`` (2 out, 3 in, 4 beyond, 5 settle, 6 overturned) on side ``s``."""
    return FreeMode(kind * s)


def _ends_kind(before, after):
    """The kind that the ends of a mode change ``before`` -> ``after`` decide alone, an
    impact's instant between them or not: "release", "overturn", "land" from FLIGHT,
    "zeno" into SETTLE; None otherwise."""
    if before == FreeMode.RELEASE:
        return "release"
    if kind_of(after) == OVERTURNED:
        return "overturn"
    if kind_of(before) == 9:
        return "land"
    if kind_of(after) == SETTLE:
        return "zeno"
    return None


def event_kind(before, after) -> str:
    """The kind of the mode change ``before`` -> ``after`` (an impact's two changes
    through its instant mode merged: ``before`` the mode that struck, ``after`` the one
    after it): "release", "uplift", "slide", "stick", "reverse", "slip", "lift",
    "apex", "return", "beyond_alpha", "impact", "land", "zeno", "chatter", "rest",
    "overturn"."""
    shared = _ends_kind(before, after)
    if shared is not None:
        return shared
    b, a = kind_of(before), kind_of(after)
    if b == SETTLE:
        return "rest" if a == 0 else ("lift" if a == 9 else "uplift")
    if a == 9:
        return "lift"
    if b == 0:
        return "slide" if a == 1 else "uplift"
    if b == 1:
        if a == 0:
            return "stick"
        return "reverse" if a == 1 else "uplift"
    if b in SLIDE_ROCK_KINDS and a in SLIDE_ROCK_KINDS and side(before) == side(after):
        return "reverse"
    if b in (OUT, IN, BEYOND) and a in SLIDE_ROCK_KINDS and side(before) == side(after):
        return "slip"
    if b in SLIDE_ROCK_KINDS and a in (OUT, IN, BEYOND) and side(before) == side(after):
        return "stick"
    if b in (OUT, IN, BEYOND) and a in (OUT, IN, BEYOND) and side(before) == side(after):
        if a == BEYOND and b == OUT:
            return "beyond_alpha"
        return "apex" if a == IN else "return"
    return "impact"


def impact_kind(before, instant, after) -> str:
    """The kind of an impact from ``before`` through the ``instant`` mode (the jump) to
    ``after``: "land" from FLIGHT or where the face lands flat, "zeno" where the rest of
    the impacts is summed, "chatter" where a slide-rock's shrinking arcs end with the face
    down (sliding, or at rest), "overturn", else "impact"."""
    shared = _ends_kind(before, after)
    if shared is not None:
        return shared
    if instant == FreeMode.LANDING_FLAT:
        return "land"
    return "chatter" if kind_of(after) in (0, 1) else "impact"
