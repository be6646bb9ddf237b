"""The driver's event rules (blockdae.core.events), shared by the Python driver and the
compiled engines: each against a closed form, in Python and compiled by numba alike."""

import math

import numba
import numpy as np
import pytest
from numba.extending import register_jitable

from blockdae.core import events


@register_jitable
def _falling_line(c, t):
    """c - t: > 0 before t = c, <= 0 from it on."""
    return c - t


@register_jitable
def _rising_rate(c, t):
    """(t - c, defined): a rate that turns at t = c."""
    return t - c, True


@register_jitable
def _two_guards(c, t):
    return c[0] - t, c[1] - t


@register_jitable
def _one_guard(pair, t):
    c, index = pair
    return _two_guards(c, t)[index]


@numba.njit
def _compiled(c, origin):
    return (events.first_nonpositive(_falling_line, c, 0.0, 1.0, origin),
            events.sign_change(_falling_line, c, 0.0, 1.0),
            events.turning_point(_rising_rate, c, 0.0, 1.0),
            events.static_root(_two_guards, _one_guard, (c, 0.5 * c), 0.0, math.nan, 1.0))


@pytest.mark.parametrize("c", [0.3, 1.0 / 3.0, 0.7123456789])
def test_bisections_end_where_the_closed_form_crosses(c):
    """c - t first reaches <= 0 at t = c exactly (a float), the rate t - c leaves its sign
    there, and of two guards c - t and c/2 - t the second is reached first, at c/2:
    Python and numba return the same floats. With an origin of 1e3 s the bisection stops
    at adjacent floats of 1e3 + t: within two ulps of 1e3 above c."""
    python = (events.first_nonpositive(_falling_line, c, 0.0, 1.0),
              events.sign_change(_falling_line, c, 0.0, 1.0),
              events.turning_point(_rising_rate, c, 0.0, 1.0),
              events.static_root(_two_guards, _one_guard, (c, 0.5 * c), 0.0, math.nan, 1.0))
    assert python == (c, c, c, (0.5 * c, 1))
    assert _compiled(c, 0.0) == python
    coarse = events.first_nonpositive(_falling_line, c, 0.0, 1.0, 1e3)
    assert c <= coarse <= c + 2 * np.spacing(1e3) and _compiled(c, 1e3)[0] == coarse


def test_a_graze_holds_a_fall_leaves():
    """A rate of rounding size that turns back within the resolution is a graze."""
    assert not events.falls(-1e-20, 1.0, 1e-12)
    assert events.falls(-1.0, 1.0, 1e-12) and events.falls(0.0, -1.0, 1e-12)
    assert not events.falls(0.0, 1.0, 1e-12) and not events.falls(1.0, -1.0, 1e-12)
    rates = lambda _, index: ((-1e-20, 1.0), (-1.0, 1.0))[index]
    assert events.left_at_once((0.0, 0.0), rates, None, 1e-12) == 1
    assert events.left_at_once((0.0, 1.0), rates, None, 1e-12) == -1


def test_stop_uncertainty_solves_its_quadratic():
    """|g'| d + |g''| d²/2 = e: e / |g'| without curvature, sqrt(2 e / |g''|) at a graze."""
    assert events.stop_uncertainty(-2.0, 0.0, 1e-6, 1e-12) == pytest.approx(5e-7, rel=1e-15)
    assert events.stop_uncertainty(0.0, 4.0, 1e-6, 1e-12) == pytest.approx(math.sqrt(5e-7), rel=1e-15)
    assert events.stop_uncertainty(0.0, 0.0, 1e-6, 1e-12) == 1e-12
