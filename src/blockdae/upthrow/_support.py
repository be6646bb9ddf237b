"""What a block stands on: the vertical physics of its contact (Newmark 1969, upthrow).

A support gives the normal force per unit mass n [m/s², compression positive] from
the vertical state (w [m], w' [m/s]) and the rule that ends a flight. w is the
block's height relative to the ground, measured from its rest on the support
(upward positive); in contact Newton's law reads w'' = n - g - a_z, in flight
(n = 0) w'' = -g - a_z, where a_z [m/s²] is the vertical ground acceleration.

* :class:`RigidSupport` (the default): w = 0 in contact, so n = g + a_z; the block
  flies when n reaches zero and lands where w returns to zero.
* :class:`SpringSupport`: a unilateral spring-dashpot of natural frequency f and
  damping ratio zeta, the clamped Kelvin-Voigt law of
  :class:`~blockdae.SpringSupportedMass`: with omega = 2 pi f and the static
  deflection u0 = g / omega²,

      n = omega² (u0 - w) - 2 zeta omega w'     while the block is on it,

  liftoff where n reaches zero from above, landing where the block is at or below
  the unloaded length (w <= u0) and the law pushes (n >= 0).

Every rule works on floats, NumPy and JAX arrays (``xp``: the array namespace).
"""

import dataclasses
import math

from ..core import set_real_fields


@dataclasses.dataclass(frozen=True)
class RigidSupport:
    """A rigid support: the block is either on it (w = 0) or above it."""

    #: whether the vertical state moves in contact
    compliant = False

    def static_deflection(self, g):
        """u0 = 0 [m]: nothing deflects."""
        return 0.0

    def parameters(self) -> dict:
        """None."""
        return {}

    def with_parameters(self, values: dict) -> "RigidSupport":
        return self


@dataclasses.dataclass(frozen=True)
class SpringSupport:
    """A unilateral spring-dashpot support (Newmark 1969).

    Args:
        frequency: natural frequency f of the block on the support [Hz], > 0.
        damping: damping ratio zeta [-], in [0, 1).
    """

    frequency: float
    damping: float = 0.0

    compliant = True

    def __post_init__(self):
        set_real_fields(self, ("frequency", "damping"))
        if self.frequency <= 0:
            raise ValueError(f"frequency={self.frequency!r} must be > 0 [Hz]")
        if not 0 < self.omega * self.omega < math.inf:
            raise ValueError(f"frequency={self.frequency!r} Hz is out of range: omega² = (2 pi f)² [1/s²] "
                             "must be a finite number > 0")
        if not 0 <= self.damping < 1:
            raise ValueError(f"damping={self.damping!r} must lie in [0, 1)")

    @classmethod
    def unchecked(cls, frequency, damping) -> "SpringSupport":
        """The support with traced (JAX) parameters, not validated: for compiled rules."""
        support = object.__new__(cls)
        object.__setattr__(support, "frequency", frequency)
        object.__setattr__(support, "damping", damping)
        return support

    def replace(self, **changes) -> "SpringSupport":
        """A copy with some parameters changed (validated again)."""
        return dataclasses.replace(self, **changes)

    @property
    def omega(self):
        """Natural circular frequency omega = 2 pi f [rad/s]."""
        return 2 * math.pi * self.frequency

    def static_deflection(self, g):
        """u0 = g / omega² [m] under gravity ``g`` [m/s²] (seed eq. 5)."""
        return g / self.omega**2

    def stiffness(self):
        """(k [1/s²], c [1/s]) of the contact flow w'' + c w' + k w = -a_z."""
        return self.omega**2, 2 * self.damping * self.omega

    def law(self, g, w, w_rate):
        """n = omega² (u0 - w) - 2 zeta omega w' [m/s²], the law on the block."""
        return self.omega**2 * (self.static_deflection(g) - w) - 2 * self.damping * self.omega * w_rate

    def law_rows(self, g):
        """The guards on the law as rows (alpha, beta, gamma) of alpha w + beta w' + gamma
        [m]: (n / omega² -> liftoff, -n / omega² -> landing while rising, w - u0 ->
        landing while falling)."""
        u0, ratio = self.static_deflection(g), 2 * self.damping / self.omega
        return (-1.0, -ratio, u0), (1.0, ratio, -u0), (1.0, 0.0, -u0)

    def landing_gap(self, g, w, w_rate, xp):
        """w - u0 + (2 zeta / omega) max(w', 0) [m]: positive while the block is in the
        air (above u0, or below it while the law pulls), zero where it lands (the
        falling and the rising landing rows of :meth:`law_rows` in one function)."""
        ratio = 2 * self.damping / self.omega
        return w - self.static_deflection(g) + ratio * xp.where(w_rate > 0, w_rate, 0.0 * w_rate)

    def parameters(self) -> dict:
        """support_frequency [Hz], support_damping [-]."""
        return {"support_frequency": self.frequency, "support_damping": self.damping}

    def with_parameters(self, values: dict) -> "SpringSupport":
        return SpringSupport.unchecked(values["support_frequency"], values["support_damping"])


def parse_support(support):
    """``support`` checked: a RigidSupport or a SpringSupport."""
    if not isinstance(support, (RigidSupport, SpringSupport)):
        raise ValueError(f"support must be a RigidSupport or a SpringSupport, got {support!r}")
    return support
