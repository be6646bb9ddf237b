"""Newmark's rigid-block analysis in the conventions of slope-stability practice.

Practitioners (Newmark 1965; Jibson 1993; SLAMMER) state a sliding mass by its yield
acceleration k_y [g] and report the *downslope* displacement as a positive number, for
the record as given ("normal" polarity) and for the record inverted ("inverse"). Here
that is the signed 1-D block of seed 000 with ``mu = k_y`` sliding one way only
(``direction="negative"``): it slides while the ground acceleration exceeds k_y g, and
the downslope displacement is D = -u(t_end).
"""

import dataclasses
import warnings

import numpy as np

from ..core._simulate import simulate
from ..core._units import STANDARD_GRAVITY
from ..excitation import AbstractExcitation, UnitsWarning, pga_factor
from ._model import SlidingBlock

_POLARITIES = ("both", "normal", "inverse")


def yield_acceleration(factor_of_safety, thrust_angle):
    """Yield acceleration k_y [g] of a slide from its static factor of safety [-] and
    thrust angle [degrees] (Newmark 1965; Jibson 1993, eq. 2): k_y = (FS - 1) sin(alpha).

    The thrust angle is the direction of the slide's movement when it first yields (the
    slope angle for a planar slide). Array arguments broadcast.
    """
    fs = np.asarray(factor_of_safety, dtype=float)
    alpha = np.asarray(thrust_angle, dtype=float)
    _require(np.isfinite(fs) & (fs >= 1), "factor_of_safety", fs, "must be >= 1 (a slope that stands)")
    _require(np.isfinite(alpha) & (alpha > 0) & (alpha < 90), "thrust_angle", alpha,
             "must lie in (0, 90) degrees")
    ky = (fs - 1.0) * np.sin(np.radians(alpha))
    return float(ky) if ky.ndim == 0 else ky


@dataclasses.dataclass(frozen=True, eq=False)
class NewmarkResult:
    """Downslope displacements of a rigid block, one value per yield acceleration.

    Attributes:
        ky: yield accelerations [g], scalar or shape (n,).
        normal: downslope displacement D >= 0 for the record as given [m] (None if not run).
        inverse: D for the record inverted [m] (None if not run).
        g: the value of one g used [m/s²].
    """

    ky: float | np.ndarray
    normal: float | np.ndarray | None
    inverse: float | np.ndarray | None
    g: float

    @property
    def maximum(self):
        """The larger D of the polarities run [m] (the conservative value)."""
        return _combine(np.maximum, self.normal, self.inverse)

    @property
    def mean(self):
        """The mean D of the polarities run [m] (SLAMMER's "average")."""
        return _combine(lambda a, b: 0.5 * (a + b), self.normal, self.inverse)

    def to_dataframe(self):
        """One row per k_y: ky_g, normal_m, inverse_m, mean_m, max_m (pandas)."""
        import pandas as pd

        columns = {"ky_g": self.ky, "normal_m": self.normal, "inverse_m": self.inverse,
                   "mean_m": self.mean, "max_m": self.maximum}
        return pd.DataFrame({k: np.atleast_1d(v) for k, v in columns.items() if v is not None})


def newmark(motion: AbstractExcitation, ky, polarity: str = "both", g: float = STANDARD_GRAVITY,
            t_end: float | None = None, backend: str = "exact", *, pga: float | None = None,
            pga_rounding: str = "exact", **options) -> NewmarkResult:
    """Newmark's rigid-block (one-way) downslope displacement, positive downslope.

    Args:
        motion: ground acceleration along the slope [m/s²] (e.g. a :class:`Record`).
        ky: yield acceleration [g], scalar or 1-D array (a batch, one compiled call);
            see :func:`yield_acceleration` and :meth:`SlidingBlock.on_incline`. A ky at
            or above the motion's peak [g] slides nowhere (D = 0): a :class:`UnitsWarning`
            says so; one also above 1 g is refused (likely m/s², e.g. ``ky=9.81``).
        polarity: "both" (default, as SLAMMER reports), "normal" (the record as given:
            sliding while a(t) > ky g) or "inverse" (the record inverted).
        g: the value of one g [m/s²]; standard gravity by default.
        t_end: final time [s]; None: until the block rests after the record.
        backend, **options: as for :func:`blockdae.simulate`.
        pga: target peak ground acceleration [g]: the motion is scaled so that its peak
            |a| is ``pga`` g (see :func:`blockdae.pga_factor`); None: as given.
        pga_rounding: "exact" (default) or "slammer": the motion's own peak rounded to
            0.001 g before scaling, as SLAMMER scales (to reproduce its tables).

    Returns:
        A :class:`NewmarkResult`; ``D = -u(t_end)`` of ``SlidingBlock(mu=ky,
        direction="negative", g=g)`` for each polarity run.
    """
    if polarity not in _POLARITIES:
        raise ValueError(f"polarity must be one of {_POLARITIES}, got {polarity!r}")
    if "target_pga" in options:
        raise TypeError(f"newmark: target_pga={options['target_pga']!r} is called pga here: the target peak "
                        "ground acceleration [g], newmark(motion, ky, pga=...)")
    ky_array = np.asarray(ky, dtype=float)
    _require(np.isfinite(ky_array) & (ky_array > 0), "ky", ky_array, "must be a positive yield acceleration [g]")
    if pga is not None:
        if np.ndim(pga) != 0:
            raise ValueError(f"pga must be one target peak [g], got {pga!r}; run newmark once per target")
        motion = motion.scaled(pga_factor(motion.peak_acceleration, pga, g, pga_rounding))
    _check_ky(ky_array, motion.peak_acceleration / g)
    block = SlidingBlock(mu=ky, direction="negative", g=g)

    def downslope(excitation):
        u = simulate(block, excitation, t_end=t_end, backend=backend, **options).displacement
        return 0.0 - u  # downslope positive; no -0.0 for a block that never slid

    normal = downslope(motion) if polarity in ("both", "normal") else None
    inverse = downslope(motion.inverted()) if polarity in ("both", "inverse") else None
    return NewmarkResult(ky=block.mu, normal=normal, inverse=inverse, g=block.g)


#: a yield acceleration [g] above this that no motion exceeds is refused: likely m/s²
MAX_KY_G = 1.0


def _check_ky(ky, pga):
    """Refuse a ky [g] above :data:`MAX_KY_G` and at or above the motion's peak ``pga`` [g]
    (it reads as m/s²); warn of one below 1 g at or above ``pga``: no sliding, D = 0."""
    still = np.atleast_1d(ky)[np.atleast_1d(ky) >= pga]
    if still.size == 0:
        return
    high = still[still > MAX_KY_G]
    if high.size:
        k = float(high[0])
        raise ValueError(f"ky={k:g} g is above {MAX_KY_G:g} g and the motion's peak ({pga:.4g} g): it looks "
                         f"like m/s² ({k:g} m/s² = {k / STANDARD_GRAVITY:.4g} g); give ky in g")
    shown = ", ".join(f"{k:g}" for k in still)
    warnings.warn(f"ky={shown} g >= PGA = {pga:.4g} g: the block does not slide, D = 0 m", UnitsWarning,
                  stacklevel=3)


def _combine(op, normal, inverse):
    if normal is None or inverse is None:
        return inverse if normal is None else normal
    return op(normal, inverse)


def _require(ok, name, values, message):
    if not np.all(ok):
        raise ValueError(f"{name}={float(np.asarray(values)[~np.asarray(ok)].flat[0])!r} {message}")
