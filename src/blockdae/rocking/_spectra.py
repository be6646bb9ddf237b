"""What users run with a free-standing block: overturning spectra under one-sine and
one-cosine pulses (Zhang & Makris 2001), the rest/slide/rock map, overturning fragility
over a record set; for the complete block (:class:`FreeStandingBlock`, whose pivot may
slip and lift) or Housner's (``contact="housner"``: its pivot holds, as the literature's
spectra assume)."""

import dataclasses
import math

import numpy as np

from ..core import Horizon, available, make_backend, progress_bar
from ..excitation import Record
from ._modes import side

#: samples per pulse period of a sampled pulse: linear interpolation keeps its peak and
#: shape to (pi / 400)² / 8 = 8e-6 of the amplitude
PULSE_SAMPLES = 400
SHAPES = ("sine", "cosine")


def pulse(shape: str, amplitude: float, period: float) -> Record:
    """One full cycle of a_x = amplitude sin(2 pi t / period) ("sine") or cos ("cosine")
    [m/s², s], sampled at period / 400."""
    if shape not in SHAPES:
        raise ValueError(f"shape must be one of {SHAPES}, got {shape!r}")
    t = np.linspace(0.0, period, PULSE_SAMPLES + 1)
    wave = np.sin if shape == "sine" else np.cos
    return Record(amplitude * wave(2 * np.pi * t / period), period / PULSE_SAMPLES,
                  name=f"one-{shape} pulse {amplitude:g} m/s², {period:g} s", units="m/s2", check_peak=False)


def overturns_freely(block, mode, theta, rate) -> bool:
    """Whether a block left without excitation in ``mode`` at (theta [rad], theta'
    [rad/s]) overturns: it passes theta = s alpha moving out (energy above the top of its
    potential), or is beyond it and not carried back over it; or, falling back, the
    impact at theta = 0 (theta' times r) leaves it energy above the top on the other side
    (later impacts only take energy)."""
    s = side(mode)
    if abs(int(mode)) == 6:
        return True
    if s == 0 or abs(int(mode)) not in (2, 3, 4):
        return False
    p2, alpha = block.frequency ** 2, block.alpha
    if block.linearised:
        energy = 0.5 * rate ** 2 - 0.5 * p2 * (theta - s * alpha) ** 2  # top of the potential: 0
        barrier = 0.5 * p2 * alpha ** 2  # the energy from the top down to theta = 0
    else:
        energy = 0.5 * rate ** 2 + p2 * (math.cos(alpha - s * theta) - 1.0)
        barrier = p2 * (1.0 - math.cos(alpha))
    outward = s * rate > 0
    if s * theta >= alpha and (outward or energy < 0):
        return True
    if s * theta < alpha and outward and energy > 0:
        return True
    return 0.5 * block.r ** 2 * 2.0 * (energy + barrier) > barrier  # after the impact, on the other side


def overturns(block, motion, backend=None, **options) -> bool:
    """Whether ``motion`` overturns ``block``.

    Housner's block (``contact="housner"``) runs to the motion's end, then is decided by
    the free block's energy (no impact can follow a rotation past alpha). Its pivot holds:
    the contact-force limits are not located (``strict`` still stops at them), as the
    literature's spectra assume. The complete block runs until it
    rests or overturns after the motion (its pivot may slip or lift on the way)."""
    block.check_motion(motion)
    solver = make_backend(block.default_backend if backend is None else backend, **options)
    if not solver.runs(block):
        raise ValueError(f"backend={solver.name!r} does not run this {type(block).__name__}; choose one of "
                         f"{list(available(block))}")
    if block.contact == "complete":
        return solver.solve(block, motion, Horizon.resolve(motion, None)).overturned
    solution = solver.solve(block, motion, Horizon.resolve(motion, motion.duration))
    if solution.overturned:
        return True
    return overturns_freely(block, solution.mode[-1], *solution.state[-1])


def rocking_threshold(block) -> float:
    """|a_x| / g that tips ``block`` from rest where its pivot holds [-]: b/h (alpha for the
    linearised block)."""
    return block.rocking_threshold if block.contact == "housner" else block.slenderness_ratio


def overturning_amplitude(block, shape, frequency_ratio, *, max_factor=30.0, steps=30, rtol=1e-4, backend=None,
                          **options) -> float:
    """The smallest amplitude of a one-``shape`` pulse of angular frequency
    ``frequency_ratio`` p that overturns ``block``, in units of its rocking threshold g
    tan(alpha) (g alpha linearised) [-] (a pulse below 1 does not lift it); found on a
    geometric grid of ``steps`` from 1 to ``max_factor`` and bisected to ``rtol``. inf
    where none on the grid overturns."""
    if not frequency_ratio > 0:
        raise ValueError(f"frequency_ratio={frequency_ratio!r} must be > 0")
    unit = block.g * rocking_threshold(block)
    period = 2 * math.pi / (frequency_ratio * block.frequency)
    tips = lambda factor: overturns(block, pulse(shape, factor * unit, period), backend, **options)
    grid = np.geomspace(1.0, max_factor, steps)
    above = next((k for k, factor in enumerate(grid) if tips(factor)), None)
    if above is None:
        return math.inf
    if above == 0:
        return float(grid[0])
    low, high = float(grid[above - 1]), float(grid[above])
    while high - low > rtol * high:
        mid = 0.5 * (low + high)
        low, high = (low, mid) if tips(mid) else (mid, high)
    return high


@dataclasses.dataclass(frozen=True)
class OverturningSpectrum:
    """The smallest overturning amplitude of a pulse against its frequency.

    Attributes:
        frequency_ratio: omega_p / p of the pulses [-], shape (n,).
        amplitude: the smallest amplitude that overturns, in units of the block's rocking
            threshold g tan(alpha) (g alpha linearised) [-] (inf: none up to the search's
            largest), shape (n,).
        shape: "sine" or "cosine".
        block: the block.
    """

    frequency_ratio: np.ndarray
    amplitude: np.ndarray
    shape: str
    block: object

    def to_dataframe(self):
        """frequency_ratio [-], amplitude_over_threshold [-], amplitude_g [g]."""
        import pandas as pd

        return pd.DataFrame({"frequency_ratio": self.frequency_ratio, "amplitude_over_threshold": self.amplitude,
                             "amplitude_g": self.amplitude * rocking_threshold(self.block)})

    def figure(self, ax=None):
        """a_p over the rocking threshold against omega_p / p; a matplotlib Figure."""
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(6, 4), constrained_layout=True) if ax is None else ax.figure
        ax = ax or fig.add_subplot()
        ax.plot(self.frequency_ratio, self.amplitude, marker="o", ms=3, label=f"one-{self.shape} pulse")
        ax.set(xlabel="omega_p / p [-]", ylabel="a_p / (g tan alpha) [-] (g alpha linearised)",
               title="overturning spectrum")
        ax.legend(fontsize="small")
        return fig


def overturning_spectrum(block, frequency_ratios, shape="sine", **search) -> OverturningSpectrum:
    """:func:`overturning_amplitude` at each of ``frequency_ratios`` (omega_p / p [-]) for
    ``block``: the complete one (:class:`FreeStandingBlock`: its pivot may slip and lift,
    its impacts are plastic with friction) or Housner's (``contact="housner"``)."""
    ratios = np.asarray(frequency_ratios, dtype=float)
    amplitudes = np.array([overturning_amplitude(block, shape, ratio, **search) for ratio in ratios])
    return OverturningSpectrum(ratios, amplitudes, shape, block)


def motion_regime(mu, b_over_h, demand):
    """What a block at rest does first under a horizontal demand |a_x| / g_e = ``demand``
    [-], by friction ``mu`` [-] and aspect ratio ``b_over_h`` = b/h [-] (arrays broadcast):
    "rest" below min(mu, b/h), else "slide" where mu < b/h and "rock" where not (the exact
    block's rules; the linearised block's threshold is atan(b/h))."""
    mu, b_over_h, demand = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (mu, b_over_h, demand)))
    moving = np.where(mu < b_over_h, "slide", "rock")
    return np.where(demand <= np.minimum(mu, b_over_h), "rest", moving)


@dataclasses.dataclass(frozen=True)
class OverturningFragility:
    """P(overturn) over a record set at each target peak ground acceleration.

    Attributes:
        pga: target peaks [g], shape (m,).
        probability: the fraction of the records that overturn the block, scaled to each
            peak [-], shape (m,).
        overturned: which record overturns at which peak, shape (n_records, m) of bool.
        records: the records' names.
    """

    pga: np.ndarray
    probability: np.ndarray
    overturned: np.ndarray
    records: tuple

    def to_dataframe(self):
        """pga_g [g], p_overturn [-], n_overturned, n_records."""
        import pandas as pd

        return pd.DataFrame({"pga_g": self.pga, "p_overturn": self.probability,
                             "n_overturned": self.overturned.sum(axis=0), "n_records": len(self.records)})

    def figure(self, ax=None):
        """P(overturn) against the peak ground acceleration; a matplotlib Figure."""
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(6, 4), constrained_layout=True) if ax is None else ax.figure
        ax = ax or fig.add_subplot()
        ax.plot(self.pga, self.probability, marker="o", ms=4)
        ax.set(xlabel="PGA [g]", ylabel="P(overturn) [-]", ylim=(-0.02, 1.02), title="overturning fragility")
        return fig


def overturning_fragility(block, records, pga, backend=None, *, progress=None, **options) -> OverturningFragility:
    """Which of ``records`` overturn ``block`` (a :class:`FreeStandingBlock`, complete or
    Housner's: see :func:`overturns`) when each is scaled to a peak of each
    ``pga`` [g]; the fraction at each peak. ``progress``: a tqdm bar over the records on
    stderr; None: only when stderr is a terminal."""
    pga = np.atleast_1d(np.asarray(pga, dtype=float))
    if np.any(pga <= 0):
        raise ValueError(f"pga must be > 0 [g], got {pga.tolist()}")
    records = list(records)
    tipped = np.zeros((len(records), pga.size), dtype=bool)
    with progress_bar(len(records), "overturning fragility", "record", progress) as bar:
        for i, record in enumerate(records):
            for j, target in enumerate(pga):
                motion = record.scaled(target * block.g / record.peak_acceleration)
                tipped[i, j] = overturns(block, motion, backend, **options)
            bar.update()
    return OverturningFragility(pga, tipped.mean(axis=0), tipped, tuple(r.name for r in records))
