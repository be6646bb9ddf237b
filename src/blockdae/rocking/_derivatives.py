"""The derivatives of a free-standing block's largest rotation, max |theta| / alpha [-],
through its impacts (what overturning spectra and fragility read).

The largest |theta| is reached where theta' = 0 (an apex, or the release from a tilt), at
the overturn (|theta| = pi/2, fixed), or at t_end while the block still turns out; at
each of these d|theta|/dp is the located state's derivative (theta' = 0 at an apex, so
the event time's own derivative adds nothing), and

    d(m / alpha)/dp = sign(theta) (d theta/dp) / alpha - m / alpha² d alpha/dp,

alpha = atan(b/h): d alpha/db = h / R², d alpha/dh = -b / R². An overturned block has
m / alpha = (pi/2) / alpha, which moves with b and h alone.
"""

import numpy as np

from ..core.contract import parameter_names

#: the events at which |theta| may be largest: theta' = 0 there, or theta = pi/2
EXTREMES = ("release", "apex", "overturn")


def max_theta_jacobian(block, solution, final, events) -> np.ndarray:
    """d(max |theta| / alpha)/dp [-], shape (n_p,), by the names of
    :func:`~blockdae.core.contract.parameter_names` (see the module's docstring);
    ``final`` is d(theta, theta')(t_end)/dp (2, n_p), ``events`` one derivative per event
    of ``solution`` (its ``dy_dp_after``: the located state's after the event's maps)."""
    names = parameter_names(block)
    if block.slides:
        return np.zeros(len(names))
    candidates = [(float(solution.state[-1, 0]), np.asarray(final[0]))]
    candidates += [(event.q, np.asarray(derivative.dy_dp_after[0]))
                   for event, derivative in zip(solution.events, events) if event.kind in EXTREMES]
    theta, d_theta = max(candidates, key=lambda candidate: abs(candidate[0]))
    alpha, r2 = block.alpha, block.b ** 2 + block.h ** 2
    d_alpha = np.array([{"b": block.h / r2, "h": -block.b / r2}.get(name, 0.0) for name in names])
    return np.sign(theta) * d_theta / alpha - abs(theta) / alpha ** 2 * d_alpha
