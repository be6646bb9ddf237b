"""Derivatives of the complete free-standing block's largest rotation (max |theta| /
alpha), its slip at t_end and its overturning time by b, h, mu_s, mu_k and the pulse's
amplitude, along the JAX twin's located trajectory through slide-rock, impacts and the
overturn (``bd.sensitivities(..., of=...)``).

Reference: central finite differences of CVODE runs at rtol 1e-12, extrapolated from the
relative steps 1e-4, 2e-4 and 4e-4 (Richardson), their own error estimated by the
extrapolation from the steps twice as large. Measured on these runs (``python
benchmarks/free_standing_derivatives.py``): the twin agrees to 4.3e-9 relative at most
(the extrapolation's own estimate 1.4e-8 at most: the slip by b through the overturn);
the bar is 3e-8.
"""

import functools

import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import FreeStandingBlock, pulse

G = bd.STANDARD_GRAVITY
WRT = ("b", "h", "mu", "mu_kinetic", "A")
BAR = 3e-8


def quantities(block, motion, t_end):
    """(max |theta| / alpha [-], slip at t_end [m], overturning time [s]) of a CVODE run."""
    sol = bd.simulate(block, motion, t_end=t_end, backend="cvode", rtol=1e-12, atol=1e-14)
    return np.array([sol.max_theta_over_alpha, sol.final_slip, sol.overturn_time])


def central_difference(block, motion, t_end, name, step):
    """d quantities / d ``name`` by central differences, relative ``step`` ("A": the motion
    scaled by 1 +- step, per g of its peak)."""
    if name == "A":
        up, down = (quantities(block, motion.scaled(1 + s * step), t_end) for s in (1, -1))
        return (up - down) / (2 * step * motion.peak_acceleration / G)
    value = block.parameters()[name]
    up, down = (quantities(block.replace(**{name: value * (1 + s * step)}), motion, t_end) for s in (1, -1))
    return (up - down) / (2 * step * value)


def richardson(block, motion, t_end, name, step=1e-4):
    """(the central differences at ``step`` and 2 ``step`` extrapolated, their error estimate)."""
    d1, d2, d4 = (central_difference(block, motion, t_end, name, k * step) for k in (1, 2, 4))
    fine, coarse = (4 * d1 - d2) / 3, (4 * d2 - d4) / 3
    return fine, np.abs(fine - coarse)


@functools.cache
def twin(block, motion, t_end, of):
    return bd.sensitivities(block, motion, t_end=t_end, wrt=WRT, of=of)


def check(block, motion, t_end, of):
    found = twin(block, motion, t_end, of)
    assert found.quantities == of and found.parameters == WRT
    index = {"max_theta_over_alpha": 0, "slip": 1, "overturn_time": 2}
    for name in WRT:
        reference, error = richardson(block, motion, t_end, name)
        for quantity in of:
            expected, estimate = reference[index[quantity]], error[index[quantity]]
            assert estimate <= BAR * abs(expected), (quantity, name)
            assert abs(found.of(quantity)[name] - expected) <= BAR * abs(expected), \
                (quantity, name, found.of(quantity)[name], expected)


@pytest.mark.slow
def test_overturning_time_and_slip_through_slide_rock_an_impact_and_the_overturn():
    """b/h = 1/4, mu_s = 0.3, mu_k = 0.28 under a one-sine pulse of 0.5 g, 0.6 s: the pivot
    slips and sticks, the block strikes, rocks on the other corner past alpha, slips,
    reverses and overturns. d t_overturn and d slip by every parameter; the largest
    rotation is then (pi/2) / alpha, moving with b and h alone (closed form)."""
    block, motion = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, mu_kinetic=0.28), pulse("sine", 0.5 * G, 0.6)
    kinds = [e.kind for e in bd.simulate(block, motion, t_end=4.0, backend="cvode", rtol=1e-12).events]
    assert kinds == ["uplift", "slip", "stick", "apex", "impact", "beyond_alpha", "slip", "reverse", "overturn"]
    check(block, motion, 4.0, ("slip", "overturn_time"))
    largest = twin(block, motion, 4.0, ("max_theta_over_alpha",)).of("max_theta_over_alpha")
    r2 = block.b ** 2 + block.h ** 2
    assert largest["b"] == pytest.approx(-np.pi / 2 / block.alpha ** 2 * block.h / r2, rel=1e-14)
    assert largest["h"] == pytest.approx(np.pi / 2 / block.alpha ** 2 * block.b / r2, rel=1e-14)
    assert largest["mu"] == largest["mu_kinetic"] == largest["A"] == 0


@pytest.mark.slow
def test_largest_rotation_and_slip_through_slide_rock_and_impacts():
    """The same block under 0.6 g, 0.4 s: the pivot slips and sticks, and the largest
    rotation comes after an impact (at an apex); the slip at 1.5 s after two impacts."""
    block, motion = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, mu_kinetic=0.28), pulse("sine", 0.6 * G, 0.4)
    sol = bd.simulate(block, motion, t_end=1.5, backend="cvode", rtol=1e-12)
    assert [e.kind for e in sol.events] == ["uplift", "slip", "stick", "apex", "impact", "apex", "impact", "apex"]
    assert sol.impact_times[0] < sol.t[np.argmax(np.abs(sol.state[:, 2]))]
    check(block, motion, 1.5, ("max_theta_over_alpha", "slip"))


@pytest.mark.slow
def test_quantities_that_do_not_exist_are_refused_by_name():
    block, motion = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, mu_kinetic=0.28), pulse("sine", 0.6 * G, 0.4)
    with pytest.raises(ValueError, match=r"did not overturn by t_end = 1\.5 s"):
        bd.sensitivities(block, motion, t_end=1.5, wrt=("b",), of="overturn_time")
    with pytest.raises(ValueError, match="choose among"):
        bd.sensitivities(block, motion, t_end=1.5, wrt=("b",), of="theta")


def largest_in_slide_rock(block, motion):
    """max |theta| / alpha [-] of a CVODE run whose largest rotation is at an apex inside a
    slide-rock: the apex located by bisection on theta' of the run's dense output next to
    its largest knot, then the run again to that time, and theta there moved to theta' = 0
    along the parabola of its theta' and theta'' (the dense time's error squared)."""
    sol = bd.simulate(block, motion, t_end=1.0, backend="cvode", rtol=1e-12, atol=1e-14)
    k = int(np.argmax(np.abs(sol.state[:, 2])))
    sign = np.sign(sol.state[k, 2])
    lo, hi = sol.t[k - 1], sol.t[k + 1]
    while lo < 0.5 * (lo + hi) < hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if sign * sol.dense(np.array([mid]))[5][0] > 0 else (lo, mid)
    apex = bd.simulate(block, motion, t_end=hi, backend="cvode", rtol=1e-12, atol=1e-14)
    theta, rate = apex.state[-1, 2], apex.state[-1, 5]
    turning = (rate - apex.dense(np.array([hi - 1e-4]))[5][0]) / 1e-4  # theta'' [rad/s²]
    return abs(theta - rate**2 / (2 * turning)) / block.alpha  # theta at theta' = 0, from the dense apex's time


@pytest.mark.slow
def test_largest_rotation_at_an_apex_inside_a_slide_rock():
    """mu_k = 0.24 <= b/h = 1/4 < mu_s = 0.3 under 0.6 g, 0.4 s: the block slide-rocks
    through its impacts and its largest rotation is at an apex inside a slide-rock (theta'
    = 0 there, no event): d(max |theta| / alpha) by every parameter against central
    differences of that apex's rotation (:func:`largest_in_slide_rock`), extrapolated twice
    (Richardson, O(h^6)) from the relative steps 5e-5, 1e-4 and 2e-4, its error estimated
    by the same from 1e-4, 2e-4 and 4e-4: the rotation is so curved in the parameters that
    one extrapolation from 1e-4 is 1e-5 off. Measured: the twin within 8.5e-9 relative by b,
    h, mu, mu_k (the estimate at most 9.5e-9), 2.7e-8 by A (the estimate 1.6e-8)."""
    block, motion = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, mu_kinetic=0.24), pulse("sine", 0.6 * G, 0.4)
    sol = bd.simulate(block, motion, t_end=1.0, backend="cvode", rtol=1e-12)
    assert abs(sol.mode[np.argmax(np.abs(sol.state[:, 2]))]) in (7, 8)  # a slide-rock's knot
    found = bd.sensitivities(block, motion, t_end=1.0, wrt=WRT, of=("slip", "max_theta_over_alpha"))
    assert found.quantities == ("slip", "max_theta_over_alpha")
    for name in WRT:
        value = motion.peak_acceleration / G if name == "A" else block.parameters()[name]
        differences = []
        for k in (0.5, 1, 2, 4):
            step = k * 1e-4
            if name == "A":
                up, down = (largest_in_slide_rock(block, motion.scaled(1 + s * step)) for s in (1, -1))
            else:
                up, down = (largest_in_slide_rock(block.replace(**{name: value * (1 + s * step)}), motion)
                            for s in (1, -1))
            differences.append((up - down) / (2 * step * value))
        once = [(4 * fine - coarse) / 3 for fine, coarse in zip(differences, differences[1:])]
        fine, coarse = [(16 * a - b) / 15 for a, b in zip(once, once[1:])]
        assert abs(fine - coarse) <= BAR * abs(fine), (name, fine, coarse)
        assert abs(found.of("max_theta_over_alpha")[name] - fine) <= BAR * abs(fine), \
            (name, found.of("max_theta_over_alpha")[name], fine)
