"""SLAMMER 1.1's fixed-step flexible sliding-mass analyses, quirks included, to reproduce
its results to the printed digits (docs/flexible-mass.md, "SLAMMER's own scheme").

Newmark average acceleration (gamma = 1/2, beta = 1/4) at the record's dt from a virtual
zero sample at t = -dt; sliding detected at the samples only; one-way sliding in the
direction in which the (equivalent) acceleration exceeds +ky g.
"""

import dataclasses
import math
from typing import Optional

import numpy as np
from numba import njit

from ..core import notice_numba, set_real_fields
from ._column import MASS_PARTICIPATION, MODE_PARTICIPATION, SLIP_MASS_FRACTION, ShearColumn, equivalent_linear

METHODS = ("coupled", "decoupled")
_GAMMA, _BETA = 0.5, 0.25


@dataclasses.dataclass(frozen=True)
class SlammerFlexible:
    """One SLAMMER 1.1 flexible analysis.

    Attributes:
        displacement: one-way downslope sliding displacement at the last sample [m], as
            SLAMMER prints it: |s| (its coupled scheme keeps the whole trapezoid step of a
            slip that stops in its first step, which can leave s slightly below 0).
        kmax: max |HEA| / g at the samples of the no-sliding response [g].
        vs: shear-wave velocity after the equivalent-linear iteration [m/s].
        damping: total damping ratio after the iteration.
        passes: equivalent-linear responses computed (0: linear-elastic).
        episodes: sliding episodes (onsets).
    """

    displacement: float
    kmax: float
    vs: float
    damping: float
    passes: int
    episodes: int


def slammer_scale(acceleration_g, target_pga: float) -> float:
    """SLAMMER's factor S = target / round(max |a|, 3) on a record ``acceleration_g`` [g]
    (shape (N,)) to reach ``target_pga`` [g]: the record's peak rounded to 0.001 g, as in
    SLAMMER's database."""
    if isinstance(target_pga, bool) or not isinstance(target_pga, (int, float, np.floating, np.integer)) or \
            not math.isfinite(target_pga) or target_pga <= 0:
        raise ValueError(f"target_pga must be a finite peak acceleration > 0 [g], got {target_pga!r}")
    samples = _samples(acceleration_g)
    peak = round(float(np.max(np.abs(samples))), 3)
    if peak == 0:
        raise ValueError(f"the record's peak |a| = {float(np.max(np.abs(samples)))!r} g rounds to 0 at 0.001 g: "
                         "it cannot be scaled to a target PGA")
    return target_pga / peak


def slammer_flexible(acceleration_g, dt: float, *, scale: float, ky: float, column: ShearColumn, method: str,
                     reference_strain: Optional[float] = None, g: float = 9.80665) -> SlammerFlexible:
    """SLAMMER 1.1's decoupled or coupled analysis of a flexible sliding mass.

    Args:
        acceleration_g: the record's samples [g], shape (N,), at t_k = k dt.
        dt: the record's time step [s].
        scale: signed factor on the record: +S for SLAMMER's 'normal' polarity, -S for
            'inverse' (see :func:`slammer_scale`).
        ky: yield acceleration [g], >= 0.
        column: the sliding mass (its vs and total damping start the iteration).
        method: "coupled" or "decoupled".
        reference_strain: None: linear-elastic; a fraction > 0: equivalent-linear with
            this reference strain (SLAMMER's GUI takes percent: divide by 100).
        g: the value of one g [m/s²].

    Returns:
        A :class:`SlammerFlexible`.
    """
    samples = _samples(acceleration_g)
    checked = _Inputs(dt=dt, scale=scale, ky=ky, g=g)
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if not isinstance(column, ShearColumn):
        raise ValueError(f"column must be a ShearColumn, got {column!r}")
    ground = samples * (checked.scale * checked.g)
    notice_numba("SLAMMER's flexible analyses", 1, _stick_response,
                 _decoupled_sliding if method == "decoupled" else _coupled)
    vs, damping, passes = column.vs, column.total_damping, 0
    if reference_strain is not None:
        def peak(vs_pass, damping_pass):
            return _stick_response(ground, checked.dt, _omega(column, vs_pass), damping_pass)[1]

        properties = equivalent_linear(peak, column, reference_strain)
        vs, damping, passes = properties.vs, properties.damping, properties.passes
    omega = _omega(column, vs)
    hea, _ = _stick_response(ground, checked.dt, omega, damping)
    kyg = checked.ky * checked.g
    if method == "decoupled":
        displacement, episodes = _decoupled_sliding(hea, checked.dt, kyg)
    else:
        displacement, episodes = _coupled(ground, checked.dt, omega, damping, kyg)
    return SlammerFlexible(displacement=abs(float(displacement)), kmax=float(np.max(np.abs(hea))) / checked.g,
                           vs=float(vs), damping=float(damping), passes=passes, episodes=int(episodes))


@dataclasses.dataclass(frozen=True)
class _Inputs:
    dt: float
    scale: float
    ky: float
    g: float

    def __post_init__(self):
        set_real_fields(self, ("dt", "scale", "ky", "g"))
        for name, unit, low in (("dt", "s", "> 0"), ("ky", "g", ">= 0"), ("g", "m/s²", "> 0")):
            value = getattr(self, name)
            if value < 0 or (value == 0 and low == "> 0"):
                raise ValueError(f"{name} must be {low} [{unit}], got {value!r}")


def _samples(acceleration_g) -> np.ndarray:
    samples = np.asarray(acceleration_g, dtype=float)
    if samples.ndim != 1 or samples.size == 0:
        raise ValueError(f"acceleration_g must be a 1-D array of samples [g], got shape {samples.shape}")
    bad = np.flatnonzero(~np.isfinite(samples))
    if bad.size:
        raise ValueError(f"acceleration_g must be finite, got {float(samples[bad[0]])!r} at sample {bad[0]}")
    return samples


def _omega(column: ShearColumn, vs: float) -> float:
    return math.pi * vs / (2.0 * column.height)


@njit(cache=True)
def _stick_response(ground, dt, omega, xi):
    """The column's response without sliding (note, section 6): incremental Newmark from
    rest at t = -dt (a = 0 there). Returns HEA at the samples [m/s²], shape (N,), and
    max |u| [m]."""
    c, k = 2.0 * xi * omega, omega * omega
    khat = k + _GAMMA / (_BETA * dt) * c + 1.0 / (_BETA * dt * dt)
    a_coef = 1.0 / (_BETA * dt) + _GAMMA / _BETA * c
    b_coef = 1.0 / (2.0 * _BETA) + dt * (_GAMMA / (2.0 * _BETA) - 1.0) * c
    hea = np.empty(ground.size)
    u = ud = udd = previous = peak = 0.0
    for j in range(ground.size):
        du = (-MODE_PARTICIPATION * (ground[j] - previous) + a_coef * ud + b_coef * udd) / khat
        dud = _GAMMA / (_BETA * dt) * du - _GAMMA / _BETA * ud + dt * (1.0 - _GAMMA / (2.0 * _BETA)) * udd
        dudd = du / (_BETA * dt * dt) - ud / (_BETA * dt) - udd / (2.0 * _BETA)
        u, ud, udd, previous = u + du, ud + dud, udd + dudd, ground[j]
        hea[j] = ground[j] + MASS_PARTICIPATION * udd
        peak = max(peak, abs(u))
    return hea, peak


@njit(cache=True)
def _decoupled_sliding(hea, dt, kyg):
    """Rigid one-way sliding under ``hea`` [m/s²] taken linear between samples; a stop
    discards its whole last step (note, section 4). Returns (displacement [m], episodes)."""
    s = v = 0.0
    sliding, episodes = False, 0
    for j in range(hea.size):
        if sliding:
            excess, change = hea[j - 1] - kyg, hea[j] - hea[j - 1]
            v_new = v + excess * dt + change * dt / 2.0
            if v_new <= 0.0:
                sliding, v = False, 0.0
            else:
                s += v * dt + excess * dt * dt / 2.0 + change * dt * dt / 6.0
                v = v_new
        elif hea[j] > kyg:
            sliding, episodes = True, episodes + 1
    return s, episodes


@njit(cache=True)
def _coupled(ground, dt, omega, xi, kyg):
    """SLAMMER's coupled stick-slip stepping (note, section 5), in its own variables:
    forcing b = -a, u of the opposite sign. Returns (displacement [m], episodes)."""
    c, k = 2.0 * xi * omega, omega * omega
    u = ud = udd = s = sd = sdd = previous = 0.0
    sliding, episodes = False, 0
    for j in range(ground.size):
        b = -ground[j]
        if sliding:
            mass, acc1, acc2 = SLIP_MASS_FRACTION, -kyg, -kyg
        else:
            mass, acc1, acc2 = 1.0, previous, b
        u2, ud2, udd2 = _newmark_step(u, ud, udd, acc1, acc2, mass, c, k, dt)
        s2, sd2, sdd2 = s, 0.0, 0.0
        if sliding:
            sdd2 = -b - kyg - MASS_PARTICIPATION * udd2
            sd2 = sd + dt * (sdd + sdd2) / 2.0
            s2 = s + dt * (sd + sd2) / 2.0
        if not sliding:
            if -b - MASS_PARTICIPATION * udd2 > kyg:
                sliding, episodes = True, episodes + 1
        elif sd2 <= 0.0:
            sliding = False
            fraction = -sd / (sd2 - sd)
            if fraction != 0.0:
                rest = fraction * dt
                sdd_stop = -(previous + fraction * (b - previous)) - kyg - MASS_PARTICIPATION * udd2
                sd_stop = sd + rest * (sdd + sdd_stop) / 2.0
                s2 = s + rest * (sd + sd_stop) / 2.0
                u2, ud2, udd2 = _stick_after_stop(u2, ud2, udd2, b, kyg, c, k, (1.0 - fraction) * dt)
            sd2 = sdd2 = 0.0
        u, ud, udd, s, sd, sdd, previous = u2, ud2, udd2, s2, sd2, sdd2, b
    return s, episodes


@njit(cache=True)
def _newmark_step(u, ud, udd, acc1, acc2, mass, c, k, dt):
    """One incremental Newmark step of ``mass u'' + c u' + k u = -(L/M) acc`` from
    ``acc1`` to ``acc2``; u'' from equilibrium at the end."""
    khat = k + c * _GAMMA / (_BETA * dt) + mass / (_BETA * dt * dt)
    a_coef = mass / (_BETA * dt) + c * _GAMMA / _BETA
    b_coef = mass / (2.0 * _BETA) + c * dt * (_GAMMA / (2.0 * _BETA) - 1.0)
    du = (-MODE_PARTICIPATION * (acc2 - acc1) + a_coef * ud + b_coef * udd) / khat
    ud2 = ud + _GAMMA / (_BETA * dt) * du - _GAMMA / _BETA * ud + dt * (1.0 - _GAMMA / (2.0 * _BETA)) * udd
    u2 = u + du
    return u2, ud2, (-MODE_PARTICIPATION * acc2 - c * ud2 - k * u2) / mass


@njit(cache=True)
def _stick_after_stop(u, ud, udd, b, kyg, c, k, step):
    """SLAMMER's stick step of length ``step`` [s] after a stop, from the slip state
    (mass fraction d1) and forcing -ky g to b (acceleration form)."""
    khat = 1.0 + c * _GAMMA * step + k * _BETA * step * step
    a_coef = SLIP_MASS_FRACTION + c * step * (_GAMMA - 1.0) + k * step * step * (_BETA - 0.5)
    udd2 = (-MODE_PARTICIPATION * (b + kyg) + a_coef * udd - k * step * ud) / khat
    ud2 = ud + step * ((1.0 - _GAMMA) * udd + _GAMMA * udd2)
    u2 = u + step * ud + step * step * ((0.5 - _BETA) * udd + _BETA * udd2)
    return u2, ud2, udd2
