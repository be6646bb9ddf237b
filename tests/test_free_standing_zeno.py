"""The Zeno tail of the complete free-standing block: the accumulation time of its
sticking impacts against an independent computation, and what limits the arc below which
the tail is summed (zeno_arc).

Reference: free rocking on a fixed base after a located impact with theta'+ = w: each
arc lasts T(w) = 2 ∫_0^theta_max dtheta / sqrt(w² - 2 p² (cos(alpha - theta) - cos alpha))
(the energy integral, mpmath's tanh-sinh quadrature at 30 digits), every impact sticks
with Housner's w -> r w, and the accumulation time is t + Σ_j T(r^j w) (summed to w < 1e-9
rad/s, where T(w) = 2 w / (p² sin alpha) to 1e-18 relative, the rest as a geometric sum).
From the run's 6th or 11th impact it gives the same time within 2e-11 s.
"""

import math

import mpmath
import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import FreeStandingBlock

QUIET = bd.Record(np.zeros(3), 0.01, name="no shaking", units="m/s2")


def accumulation_time(block, t, w):
    """The free rocking block's Zeno accumulation time [s] after an impact at ``t`` [s]
    that left theta' = ``w`` [rad/s] (the module's reference)."""
    with mpmath.workdps(30):
        p2 = mpmath.mpf(0.75) * mpmath.mpf(block.g) / mpmath.hypot(block.b, block.h)
        alpha = mpmath.atan2(block.b, block.h)
        r = 1 - mpmath.mpf(1.5) * mpmath.sin(alpha) ** 2
        t, w = mpmath.mpf(t), abs(mpmath.mpf(w))
        while w > 1e-9:
            top = alpha - mpmath.acos(mpmath.cos(alpha) + w * w / (2 * p2))
            slowness = lambda th, w=w: 1 / mpmath.sqrt(abs(w * w - 2 * p2 * (mpmath.cos(alpha - th) - mpmath.cos(alpha))))
            t += 2 * mpmath.quad(slowness, [0, top])
            w *= r
        return float(t + 2 * w / (p2 * mpmath.sin(alpha)) / (1 - r))


@pytest.mark.parametrize("backend, zeno_arc, bar", [("cvode", 1e-4, 3e-9), ("cvode", 1e-5, 3e-8),
                                                     ("ida", 1e-4, 3e-8), ("ida", 1e-5, 3e-7)])
def test_the_zeno_rest_is_at_the_accumulation_time_of_the_impacts(backend, zeno_arc, bar):
    """b/h = 1/2 (r = 0.7) released from 0.2 rad, mu = 1 (every impact sticks): the rest is
    at the accumulation time of its impacts. The error is that of the located impacts
    below the arc summed: the integrator holds theta to atol = 1e-14 rad, an arc a rises
    only p² sin(alpha) a²/8 (3.7e-11 rad at 1e-5 s) and its impact, a root of theta with
    |theta'| = p² sin(alpha) a/2, is located to about atol/|theta'| (7e-10 s at 1e-5 s),
    so the error grows as the arcs summed shrink: measured on CVODE 9e-10 s at zeno_arc =
    1e-4 s, 8.4e-9 s at 1e-5 s (7e-8 s at 1e-6 s, 5e-7 s at 1e-7 s; below 3e-8 s the arcs
    are lower than atol and their impacts are not located at all), on IDA 9.6e-9 s and
    1.1e-7 s."""
    block = FreeStandingBlock(b=0.5, h=1.0, mu=1.0, theta0=0.2, zeno_arc=zeno_arc)
    sol = bd.simulate(block, QUIET, t_end=4.0, backend=backend, rtol=1e-12)
    impact = sol.impacts[5]
    assert abs(sol.rest_time - accumulation_time(block, impact.t, impact.state_after[5])) <= bar
    zeno = sol.events_of("zeno")[0]
    assert 2 * abs(zeno.state_after[5]) / (block.frequency**2 * math.sin(block.alpha)) < zeno_arc
