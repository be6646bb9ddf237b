"""Newmark's estimates of upthrow (Newmark 1969, eqs. 5, 8, 12, 13) from the linear response."""

import dataclasses
import math
from numbers import Real

from ._model import SpringSupportedMass
from ..core import compact_repr


@dataclasses.dataclass(frozen=True)
class UpthrowEstimate:
    """The paper's estimates for a mass on a spring support.

    Attributes:
        static_deflection: u0 = g / omega² [m] (eq. 5).
        response_acceleration: A, the largest absolute acceleration of the linear
            (tension-capable) oscillator, in g [-].
        liftoff_velocity: u'0 = g sqrt(A² - 1) / omega [m/s] (eq. 12); 0 if A <= 1.
        height: z = u0 (A² - 1) / 2 [m] (eq. 13), the rise above the ground's position
            at liftoff if the ground kept its velocity; 0 if A <= 1.
        time_to_top: Delta t = u'0 / g [s] (eq. 8); the flight lasts about 2 Delta t.
    """

    def __repr__(self):
        return compact_repr(self)

    static_deflection: float
    response_acceleration: float
    liftoff_velocity: float
    height: float
    time_to_top: float

    @property
    def flight_duration(self) -> float:
        """2 Delta t [s]."""
        return 2 * self.time_to_top

    @property
    def lifts_off(self) -> bool:
        """A > 1: the linear response acceleration exceeds g."""
        return self.response_acceleration > 1


def upthrow_estimate(block: SpringSupportedMass, motion=None, *, response_acceleration=None,
                     t_end=None) -> UpthrowEstimate:
    """Newmark's estimates of liftoff velocity, height and time to the top (Newmark 1969).

    Args:
        block: the mass on its support (frequency, damping, g).
        motion: the vertical ground acceleration; A is then the largest absolute
            acceleration of the linear oscillator of the block's frequency and damping
            under it (:func:`blockdae.motions.response_spectrum`), in g.
        response_acceleration: A [-] directly (instead of ``motion``).
        t_end: end of the response window [s] (default: the motion's duration).
    """
    if not isinstance(block, SpringSupportedMass):
        raise TypeError(f"block must be a SpringSupportedMass, got {type(block).__name__}")
    if (motion is None) == (response_acceleration is None):
        raise ValueError("give exactly one of motion and response_acceleration")
    if motion is not None:
        from ..motions import response_spectrum

        spectrum = response_spectrum(motion, 1 / block.frequency, block.damping, t_end=t_end)
        response_acceleration = float(spectrum.sa) / block.g
    if isinstance(response_acceleration, bool) or not isinstance(response_acceleration, Real) \
            or not math.isfinite(response_acceleration) or response_acceleration < 0:
        raise ValueError(f"response_acceleration={response_acceleration!r} must be a finite number >= 0 [g]")
    response_acceleration = float(response_acceleration)
    excess = max(response_acceleration**2 - 1, 0.0)
    u0 = block.static_deflection
    velocity = block.g * math.sqrt(excess) / block.omega
    return UpthrowEstimate(u0, response_acceleration, velocity, u0 * excess / 2, velocity / block.g)
