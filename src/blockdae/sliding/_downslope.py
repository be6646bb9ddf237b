"""Newmark's rigid block for many calls on one motion: D [m] and its exact dD/dky [m/g]
straight from the compiled exact engine, the motion's pieces prepared once (cached per
motion), without the checks and tables of :func:`blockdae.newmark`: the inner loop of a
sampler or an optimiser, where one call costs tens of microseconds.

dD/dky is exact in closed form from the located events: while the block slides downslope
from t_s, its velocity relative to the base is v(t) = ∫_{t_s}^t (a(τ) - ky g) dτ, and
v = 0 at both ends of the episode (and a = ky g at its onset), so that moving ky moves
the episode's ends without changing D to first order and

    dD/dky = -g Σ_i T_i² / 2   [m/g],

T_i [s] the length of sliding episode i (the kinetic coefficient moving with ky, as
in :func:`blockdae.newmark`, which gives the same number by differentiating the JAX
kernel).
"""

import numpy as np

from ..core import Horizon, notice_numba
from ..solvers import Exact
from . import _exact_numba as engine
from ._exact import _COMPILE_SECONDS, _engine_input

_WINDOW = Exact().window


def downslope(motion, ky, factor, g, derivative=True):
    """D [m] downslope of the one-way rigid block (``SlidingBlock(mu=ky,
    direction="negative", g=g)``, until it rests after the motion) on ``motion`` times
    ``factor`` [-] (negative: the record inverted), for each ky [g] of ``ky`` (shape (n,),
    each > 0), and with ``derivative`` also dD/dky [m/g], shape (n,).

    No input is checked here: ky must be finite and > 0 (one at or above the scaled
    peak gives D = 0 and dD/dky = 0); ValueError where the engine did not finish."""
    ky = np.asarray(ky, dtype=float).reshape(-1)
    pieces, exc = _engine_input(motion, Horizon.resolve(motion, None).integration_end(motion), _WINDOW)
    run_one = engine.kernels()[0]
    notice_numba("the exact engine", _COMPILE_SECONDS, run_one)
    flags = (True, False, True)  # slip- only (downslope), until rest
    d, slope = np.empty(ky.shape), np.empty(ky.shape)
    for i, k in enumerate(ky):
        outcome, knots = run_one(exc, _WINDOW, (k, k, 0.0, g, factor), flags, 64 if derivative else 0)
        if not (outcome[6] and outcome[7]):  # rests, finished
            raise ValueError(f"the exact engine did not finish the rigid block of ky={k!r} g (rests "
                             f"{bool(outcome[6])}, finished {bool(outcome[7])})")
        d[i] = 0.0 - outcome[0]
        if derivative:
            t, mode, before = knots[0], knots[3], knots[4]
            starts = t[(before == 0) & (mode != 0)]
            ends = t[(before != 0) & (mode == 0)]
            slope[i] = -0.5 * g * np.sum((ends - starts) ** 2)
    return (d, slope) if derivative else d
