"""Elms's set-up (Elms 2000) in one place, for the notebook, tests and benchmarks.

Dimensionless as in the paper: g = 1 m/s², so accelerations are coefficients of g and
displacements are in units of g (T*/2)² with T* the wave's period; t [s] is his T.
The base moves with one sine wave C_x = A sin(pi t) on 0 <= t <= 2 (A = 1), C_y = R C_x,
and the bias P = mu - N (his eq. 2) pushes the block in -x.
"""

import numpy as np

from ..core import simulate
from ..excitation import BaseMotion, Harmonic
from ._model import PlanarBlock
from ..sliding import SlidingBlock

#: Elms's table wave: C_x = sin(pi t) for one period (A = 1, T* = 2 s) [m/s² with g = 1]
WAVE = Harmonic(1.0, 2.0, cycles=1)

# What the paper says in its text (its figures are not in the text; "almost", "about",
# "nearly" and "roughly" are its words, so every comparison is approximate): percent
# increase of the final x displacement over R = 0
SEED_FIG7_MAX_PERCENT = 60.0  # "reaching almost 60 %" (mu = 0.8, largest N/A)
SEED_FIG8_MAX_PERCENT = 60.0  # "a maximum of about 60 % for high values of R" (N/A = 0.5)
SEED_EXTREME_PERCENT = 700.0  # "nearly 700 %" for R = 1, mu = 1, N/A = 0.9
SEED_FIG6_PLATEAU = -0.707 * 0.8 - 0.3  # his estimate of the passive k_x plateau, "roughly" [-]


def elms_block(n_over_a: float, mu: float) -> PlanarBlock:
    """The block of N/A = ``n_over_a`` [-] and friction ``mu`` [-] (A = 1, g = 1 m/s²)."""
    return PlanarBlock(mu=mu, bias=(-(mu - n_over_a), 0.0), g=1.0)


def elms_one_d(n_over_a: float, mu: float) -> SlidingBlock:
    """The 1-D block of the same N/A and mu (the R = 0 case, solved in closed form)."""
    return SlidingBlock(mu=mu, bias=-(mu - n_over_a), g=1.0)


def elms_motion(ratio: float, z=None) -> BaseMotion:
    """C_x = sin(pi t), C_y = ``ratio`` C_x, vertical ``z`` (upward; None: none)."""
    return BaseMotion(WAVE, WAVE.scaled(ratio) if ratio else None, z)


def elms_run(n_over_a: float, mu: float, ratio: float, z=None, **options):
    """The PlanarSolution of one case (the default backend, IDA, unless ``options`` say)."""
    return simulate(elms_block(n_over_a, mu), elms_motion(ratio, z), **options)


def percent_increase(n_over_a: float, mu: float, ratios, **options) -> np.ndarray:
    """100 (d_x(R) / d_x(0) - 1) [%] for each R of ``ratios``, shape (len(ratios),); d_x(0)
    from the 1-D block in closed form (the exact backend)."""
    base = simulate(elms_one_d(n_over_a, mu), WAVE).displacement
    d_x = np.array([elms_run(n_over_a, mu, r, **options).displacement[0] if r else base for r in ratios])
    return 100.0 * (d_x / base - 1.0)
