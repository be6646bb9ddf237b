"""The uniform shear frame of the SMiRT paper on Newmark's formula (Fig. 3) and the absolute
accelerations of its floors.

n storeys of equal floor mass m and storey stiffness k, floor 1 the lowest and floor n
the roof; u (shape (n,)) the floor displacements relative to the ground:

    M u'' + C u' + K u = -M 1 a_g(t),   M = m I,   K = k tridiag(-1, 2, -1) with K[n-1, n-1] = k,

and C gives the damping ratio ζ on every mode (classical damping). The modes are
u = Σ_j φ_j Γ_j D_j with Γ_j = φ_jᵀ 1 / φ_jᵀ φ_j and D_j the response of the oscillator
D'' + 2ζω_j D' + ω_j² D = -a_g. As Σ_j φ_j Γ_j = 1, the absolute acceleration of the
floors is

    a(t) = u'' + 1 a_g = Σ_j φ_j Γ_j (-2ζω_j D_j' - ω_j² D_j),

the absolute accelerations of the modal oscillators: a C¹ function of time (a_g is only
continuous), no a_g term left.
"""

import dataclasses
import functools
import operator

import numpy as np

from ..core import notice_numba
from ..excitation import Record


@dataclasses.dataclass(frozen=True)
class ShearFrame:
    """A uniform shear frame: equal floor masses and storey stiffnesses (the SMiRT paper on Newmark's formula, Fig. 3).

    Args:
        storeys: number of storeys (= floors above the ground) n >= 1.
        period: fundamental period T_1 > 0 [s]; the ratio k/m is set to give it.
        damping: modal damping ratio 0 <= ζ < 1 [-], the same on every mode.

    The mass itself does not enter the floor accelerations; only k/m does.
    ``bd.motions.response_spectrum([record, *frame.floor_motions(record)], periods)`` gives the
    spectra of the ground and of every floor in one call.
    """

    storeys: int = 5
    period: float = 0.3
    damping: float = 0.05

    def __post_init__(self):
        n = self.storeys
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError(f"storeys must be an integer >= 1, got {n!r}")
        object.__setattr__(self, "storeys", int(n))
        period = float(self.period)
        if not (np.isfinite(period) and period > 0):
            raise ValueError(f"period must be a positive finite number [s], got {period!r}")
        object.__setattr__(self, "period", period)
        zeta = float(self.damping)
        if not (np.isfinite(zeta) and 0 <= zeta < 1):
            raise ValueError(f"damping must lie in [0, 1) [-] (a fraction of critical), got {zeta!r}")
        object.__setattr__(self, "damping", zeta)

    @functools.cached_property
    def _modes(self):
        """Eigenpairs of K/k (ascending) with unit-norm shapes, roof entry positive."""
        n = self.storeys
        k_hat = 2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
        k_hat[-1, -1] = 1.0
        lam, phi = np.linalg.eigh(k_hat)
        return lam, phi * np.sign(phi[-1])

    @property
    def stiffness_ratio(self) -> float:
        """k/m [1/s²], set so that the first period is ``period``."""
        return float((2 * np.pi / self.period) ** 2 / self._modes[0][0])

    @property
    def omegas(self) -> np.ndarray:
        """Natural circular frequencies ω_j [rad/s], ascending, shape (n,)."""
        lam = self._modes[0]
        return 2 * np.pi / self.period * np.sqrt(lam / lam[0])

    @property
    def periods(self) -> np.ndarray:
        """Natural periods T_j = 2π/ω_j [s], descending, shape (n,)."""
        return 2 * np.pi / self.omegas

    @property
    def mode_shapes(self) -> np.ndarray:
        """φ [-], shape (n floors, n modes): column j is mode j, unit norm, roof entry > 0."""
        return self._modes[1].copy()

    @property
    def participation(self) -> np.ndarray:
        """Participation factors Γ_j = φ_jᵀ 1 / φ_jᵀ φ_j [-], shape (n,)."""
        phi = self._modes[1]
        return phi.sum(axis=0) / np.einsum("ij,ij->j", phi, phi)

    def floor(self, level: int) -> "Floor":
        """Floor ``level`` (1 = the lowest, ``storeys`` = the roof) of this frame."""
        return Floor(self, level)

    def floor_motions(self, record: Record, *, refine: int = 4, t_end: float | None = None) -> list[Record]:
        """Absolute accelerations of the floors under the ground record, as Records.

        Args:
            record: ground acceleration [m/s²] (a :class:`bd.Record`, linear between samples).
            refine: m >= 1; the floor motions are sampled at dt/m [s].
            t_end: end of the floor motions [s] (default: the record's duration; later
                adds the free vibration of the frame after the record, rounded up to a
                whole step dt/m).

        Returns:
            n Records [m/s²], floor 1 (lowest) to n (roof), step dt/m, on the ground
            record's time axis (same ``start_time``), named "<record name> floor <i>".

        The modal responses D_j, D_j' at every point of the grid dt/m are exact (the
        Nigam-Jennings recurrence of the response spectra, on the same piecewise-linear
        ground motion split into m equal pieces), so the samples are the exact floor
        accelerations. Between samples a floor acceleration is smooth (C¹; on each piece a
        line plus a damped sinusoid per mode), and the Record joins the samples by
        straight lines: an error of at most (dt/m)²/8 · max|a''| in acceleration (so
        ``peak_acceleration`` of a floor Record is the largest sample, short of the true
        peak by as much). Measured on the largest relative
        displacement of a two-way block (benchmarks/floor_refinement.py: the 18 pySLAMMER
        records, frames T_1 = 0.2, 0.3, 0.5 s, floors 1 and 5, μ = 0.1, 0.2, 0.3, floor
        peak 1 g), the error against m = 64 falls as m⁻²:

        ====  ======================  ==========
        m     median relative error   worst
        ====  ======================  ==========
        1     1.3e-3                  5.1e-2
        2     3.2e-4                  1.3e-2
        4     7.9e-5                  3.2e-3
        8     2.0e-5                  8.0e-4
        16    4.7e-6                  1.9e-4
        ====  ======================  ==========

        The worst cases are the coarsest records (dt = 0.02 s) on the stiffest frame,
        whose highest mode (0.03 s) is then barely sampled: raise ``refine`` there.
        """
        from ..motions import kernels as _kernels

        if not isinstance(record, Record):
            raise TypeError(f"record must be a bd.Record (samples joined by straight lines), "
                            f"got {type(record).__name__}")
        if isinstance(refine, bool) or not isinstance(refine, (int, np.integer)) or refine < 1:
            raise ValueError(f"refine must be an integer >= 1 (samples per record step), got {refine!r}")
        dt = record.dt / refine
        samples = record.acceleration_samples
        n_in = (samples.size - 1) * refine  # fine steps inside the record
        if t_end is None:
            n_steps = n_in
        else:
            t_end = float(t_end)
            if not (np.isfinite(t_end) and t_end > 0):
                raise ValueError(f"t_end must be a positive finite time [s], got {t_end!r}")
            n_steps = max(1, int(np.ceil(t_end / dt * (1 - 1e-12))))
        a = np.interp(np.arange(min(n_steps, n_in) + 1) / refine, np.arange(samples.size), samples)
        p0 = np.zeros(n_steps)
        p1 = np.zeros(n_steps)
        p0[:a.size - 1] = a[:-1]
        p1[:a.size - 1] = np.diff(a) / dt  # zero after the record: a_g jumps to 0 there
        h = np.full(n_steps, dt)
        zero = np.zeros(n_steps)
        us = np.empty(n_steps + 1)
        vs = np.empty(n_steps + 1)
        modal = np.empty((self.storeys, n_steps + 1))
        notice_numba("the response kernels", 10, _kernels.history)
        for j, om in enumerate(self.omegas):
            _kernels.history(h, p0, p1, zero, zero, zero, om, self.damping, us, vs)
            modal[j] = -2.0 * self.damping * om * vs - om * om * us
        floors = (self._modes[1] * self.participation) @ modal
        return [Record(f, dt, name=f"{record.name} floor {i + 1}", start_time=record.start_time,
                       units="m/s2", check_peak=False)
                for i, f in enumerate(floors)]


@dataclasses.dataclass(frozen=True)
class Floor:
    """One floor of a :class:`ShearFrame`, as a place to put a block.

    Args:
        frame: the frame.
        level: 1 (the lowest floor) to ``frame.storeys`` (the roof).
    """

    frame: ShearFrame
    level: int

    def __post_init__(self):
        if not isinstance(self.frame, ShearFrame):
            raise TypeError(f"frame must be a bd.ShearFrame, got {type(self.frame).__name__}")
        try:
            level = operator.index(self.level)
        except TypeError:
            raise ValueError(f"level must be an integer floor number, got {self.level!r}") from None
        if isinstance(self.level, bool) or not 1 <= level <= self.frame.storeys:
            raise ValueError(f"level must lie in 1..{self.frame.storeys} (the storeys of the frame), "
                             f"got {self.level!r}")
        object.__setattr__(self, "level", level)

    def motion(self, record: Record, *, refine: int = 4, t_end: float | None = None) -> Record:
        """The absolute acceleration of this floor [m/s²]; see :meth:`ShearFrame.floor_motions`."""
        return self.frame.floor_motions(record, refine=refine, t_end=t_end)[self.level - 1]
