"""The sliding mass as a uniform shear column: its first mode, its damping and the
equivalent-linear iteration, as SLAMMER 1.1 defines them (Rathje & Bray 2000; docs/flexible-mass.md, "The model")."""

import contextvars
import dataclasses
import math
from typing import Callable, Optional

from ..core import set_real_fields
from ..excitation import check_column

#: L/M: the first mode's participation factor, phi(z) = sin(pi z / 2H)
MODE_PARTICIPATION = 4.0 / math.pi
#: L/Mtot: the share of the modal acceleration in the column's average acceleration (HEA)
MASS_PARTICIPATION = 2.0 / math.pi
#: d1 = 1 - L²/(M Mtot): the mass fraction the frictional base does not carry in slip
SLIP_MASS_FRACTION = 1.0 - 8.0 / math.pi**2
#: impedance damping min(0.55016 (vr/vs)^-0.9904, 0.20) (SLAMMER's fit, a ratio)
IMPEDANCE_COEFFICIENT, IMPEDANCE_EXPONENT, IMPEDANCE_CAP = 0.55016, -0.9904, 0.20
#: effective strain = 0.65 x 1.57 x peak u / H (SLAMMER writes 1.57 for pi/2)
STRAIN_PER_DRIFT = 0.65 * 1.57
#: the equivalent-linear iteration stops when modulus and damping change by <= 5 %
CONVERGENCE_CHANGE = 0.05
#: passes before the iteration is reported as not converging
MAX_PASSES = 100


def impedance_damping(vr: float, vs: float) -> float:
    """Radiation damping ratio of the column on a base of shear-wave velocity ``vr``
    [m/s] (its own ``vs`` [m/s]), capped at 0.20."""
    return min(IMPEDANCE_COEFFICIENT * (vr / vs) ** IMPEDANCE_EXPONENT, IMPEDANCE_CAP)


@dataclasses.dataclass(frozen=True)
class ShearColumn:
    """A uniform shear column of the sliding mass, first mode only.

    Attributes:
        height: H [m], from the slip surface up.
        vs: shear-wave velocity of the column [m/s].
        vr: shear-wave velocity below the slip surface [m/s]; None: ``vs``.
        damping: the soil's damping ratio; the impedance damping from vr/vs is added to
            it as SLAMMER does (``impedance=False`` leaves it out). May be negative
            (SLAMMER's way to offset the impedance damping) while the total stays in (0, 1).
        impedance: add the impedance damping.

    A height, vs or vr out of the range of slopes, or a damping ratio above 0.3, is warned
    about (a :class:`~blockdae.excitation.UnitsWarning` naming the likely unit); a damping
    ratio of 1 or more (a percentage) is refused.
    """

    height: float
    vs: float
    vr: Optional[float] = None
    damping: float = 0.05
    impedance: bool = True

    def __post_init__(self):
        given_vr = self.vr
        if self.vr is None:
            object.__setattr__(self, "vr", self.vs)
        set_real_fields(self, ("height", "vs", "vr", "damping"))
        for name, unit in (("height", "m"), ("vs", "m/s"), ("vr", "m/s")):
            if getattr(self, name) <= 0:
                raise ValueError(f"{name} must be > 0 {unit}, got {getattr(self, name)!r}")
        if not _PRECHECKED.get():
            check_column(self.height, self.vs, None if given_vr is None else self.vr, self.damping)
        total = self.total_damping
        if not 0 < total < 1:
            raise ValueError(f"damping={self.damping!r} gives a total damping ratio of {total!r} "
                             f"(impedance {self.impedance_damping!r} added): it must stay in (0, 1)")

    @property
    def impedance_damping(self) -> float:
        """The impedance damping ratio added to ``damping`` (0 without ``impedance``)."""
        return impedance_damping(self.vr, self.vs) if self.impedance else 0.0

    @property
    def total_damping(self) -> float:
        """xi: the soil's and the impedance damping ratios together."""
        return self.damping + self.impedance_damping

    @property
    def omega(self) -> float:
        """First-mode circular frequency pi vs / 2H [rad/s]."""
        return math.pi * self.vs / (2.0 * self.height)

    @property
    def period(self) -> float:
        """First-mode period 4 H / vs [s]."""
        return 4.0 * self.height / self.vs


#: set while :func:`prechecked_column` builds a column (per thread: a context variable)
_PRECHECKED = contextvars.ContextVar("prechecked_column", default=False)


def prechecked_column(*args, **kwargs) -> ShearColumn:
    """``ShearColumn(*args, **kwargs)`` without the plausibility rules (check_column), for a
    column whose values were checked already (a batch's, checked as arrays once) or computed
    from such a column (the converged equivalent-linear one); its own checks still apply."""
    token = _PRECHECKED.set(True)
    try:
        return ShearColumn(*args, **kwargs)
    finally:
        _PRECHECKED.reset(token)


@dataclasses.dataclass(frozen=True)
class EquivalentLinear:
    """The column's properties after the equivalent-linear iteration.

    Attributes:
        vs: degraded shear-wave velocity [m/s].
        damping: total damping ratio (strain damping + impedance damping).
        passes: responses computed.
        strain: the last effective shear strain (a fraction).
    """

    vs: float
    damping: float
    passes: int
    strain: float


def equivalent_linear(peak_displacement: Callable[[float, float], float], column: ShearColumn,
                      reference_strain: float, max_passes: int = MAX_PASSES) -> EquivalentLinear:
    """SLAMMER's equivalent-linear iteration (the note's section 3).

    Args:
        peak_displacement: ``(vs [m/s], damping ratio) -> max |u| [m]`` of the column's
            response without sliding.
        column: the initial column (its vs and total damping start the iteration).
        reference_strain: gamma_ref of the hyperbolic modulus reduction, a fraction
            (SLAMMER's GUI takes percent).
        max_passes: responses before the iteration is reported as not converging.

    Raises:
        ValueError: a reference strain <= 0, or no convergence in ``max_passes`` passes.
    """
    steps = equivalent_linear_steps(column, reference_strain, max_passes)
    request = next(steps)
    try:
        while True:
            request = steps.send(peak_displacement(*request))
    except StopIteration as finished:
        return finished.value


def equivalent_linear_steps(column: ShearColumn, reference_strain: float, max_passes: int = MAX_PASSES):
    """:func:`equivalent_linear` as a generator, so that many iterations can run in
    step (their responses of a pass in one batch): it yields (vs [m/s], damping ratio)
    of each response it needs, is sent that response's max |u| [m], and returns the
    :class:`EquivalentLinear` (StopIteration's value). Raises as :func:`equivalent_linear`."""
    if isinstance(reference_strain, bool) or not isinstance(reference_strain, (int, float)) or \
            not math.isfinite(reference_strain) or reference_strain <= 0:
        raise ValueError(f"reference_strain must be a fraction > 0, got {reference_strain!r}")
    vs, damping, soil_damping = column.vs, column.total_damping, None
    for passes in range(1, max_passes + 1):
        strain = STRAIN_PER_DRIFT * (yield vs, damping) / column.height
        modulus_ratio = 1.0 / (1.0 + strain / reference_strain)
        degraded_vs = column.vs * math.sqrt(modulus_ratio)
        new_soil_damping = 0.62 * modulus_ratio**0.1 * _masing_damping(strain, reference_strain) + 0.01
        modulus_change = abs(vs**2 - degraded_vs**2) / vs**2
        damping_change = math.inf if soil_damping is None else abs(soil_damping - new_soil_damping) / soil_damping
        impedance = impedance_damping(column.vr, degraded_vs) if column.impedance else 0.0
        vs, soil_damping, damping = degraded_vs, new_soil_damping, new_soil_damping + impedance
        if modulus_change <= CONVERGENCE_CHANGE and damping_change <= CONVERGENCE_CHANGE:
            return EquivalentLinear(vs=vs, damping=damping, passes=passes, strain=strain)
    raise ValueError(f"the equivalent-linear iteration did not converge in {max_passes} passes "
                     f"(H={column.height!r} m, vs={column.vs!r} m/s, reference_strain={reference_strain!r}; "
                     f"last vs {vs!r} m/s, damping {damping!r})")


def _masing_damping(strain: float, reference_strain: float) -> float:
    """Masing damping ratio of the hyperbolic backbone at ``strain`` (0 at zero strain)."""
    if strain <= 0:
        return 0.0
    ratio = strain / reference_strain
    # 4 (gam - gref ln(1 + gam/gref)) / (gam²/(gam + gref)) / pi - 2/pi, in gref units
    return (4.0 * (ratio - math.log1p(ratio)) * (ratio + 1.0) / ratio**2 - 2.0) / math.pi
