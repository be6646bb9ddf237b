"""The displacement hazard λ(D > d) = ∫ P(D > d | im) |dλ/dim| dim.

Between the curve's levels λ is a power law (linear in ln x, ln λ), so on a piece
|dλ| = k λ d(ln x) with k its log-log slope; each piece is integrated in ln x by
Gauss-Legendre on sub-intervals at most :data:`STEP` wide. Above the last level the
fragility there stands for all higher intensities: + P(D > d | x_n) λ(x_n) (a lower
bound of that tail); below the first level nothing is counted.
"""

import numpy as np

from ._curve import HazardCurve

STEP = 0.05  # widest sub-interval in ln im
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)


def displacement_hazard(curve: HazardCurve, fragility, d_m):
    """λ(D > d) [1/yr] for displacements ``d_m`` [m] (shape of ``d_m``).

    Args:
        curve: the site's :class:`HazardCurve` of the fragility's intensity measure.
        fragility: a :class:`Fragility` or :class:`EmpiricalFragility` (anything with
            ``exceedance(d_m, im)``).
        d_m: displacements [m] > 0.
    """
    d = np.asarray(d_m, dtype=float)
    if np.any(~(np.isfinite(d) & (d > 0))):
        raise ValueError(f"d_m must be positive and finite [m], got {d!r}")
    u, ln_rate = np.log(curve.im), np.log(curve.rate)
    nodes, weights = [], []
    for i in range(u.size - 1):
        k = -(ln_rate[i + 1] - ln_rate[i]) / (u[i + 1] - u[i])
        edges = np.linspace(u[i], u[i + 1], int(np.ceil((u[i + 1] - u[i]) / STEP)) + 1)
        half = 0.5 * np.diff(edges)
        at = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * _GL_X
        rate = np.exp(ln_rate[i] - k * (at - u[i]))
        nodes.append(at.ravel())
        weights.append((half[:, None] * _GL_W * k * rate).ravel())
    x = np.exp(np.concatenate(nodes))
    w = np.concatenate(weights)
    p = fragility.exceedance(d[..., None], x)
    tail = fragility.exceedance(d, curve.im[-1]) * curve.rate[-1]
    return p @ w + tail
