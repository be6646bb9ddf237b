"""Derivatives of a free-standing block's largest rotation, max |theta| / alpha, by b, h,
the restitution and the motion's amplitude, through the impacts (the JAX twin's located
trajectory, ``bd.sensitivities(..., of="max_theta_over_alpha")``).

References: central finite differences of CVODE runs at rtol 1e-12, their own error
measured by the step (each bar is above that estimate and above the agreement measured,
written beside it); the linearised block under a one-sine pulse in closed form (the
rocking arc cosh/sinh plus the forced sine, its apex found and differentiated in 40-digit
mpmath); an overturned block's max |theta| / alpha = (pi/2) / alpha in closed form.
"""

import functools
import math

import mpmath
import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import RockingBlock
from conftest import load_sample_record

G = bd.STANDARD_GRAVITY
OF = "max_theta_over_alpha"
mpmath.mp.dps = 40


def kobe_first_6_s() -> bd.Record:
    kobe = load_sample_record("Kobe_1995_TAK-090")
    return bd.Record(kobe.acceleration_samples[:600], kobe.dt, name="Kobe TAK-090, 0-6 s", units="m/s2")


def largest_rotation(block, motion, t_end):
    """max |theta| / alpha [-] of a CVODE run at rtol 1e-12."""
    return bd.simulate(block, motion, t_end=t_end, backend="cvode", rtol=1e-12, atol=1e-14).max_theta_over_alpha


def central_difference(block, motion, t_end, name, step):
    """d(max |theta| / alpha)/d ``name`` [-/unit] by central differences, relative ``step``
    ("A": the motion scaled by 1 +- step, per g of its peak)."""
    if name == "A":
        peak = motion.peak_acceleration / G
        up, down = largest_rotation(block, motion.scaled(1 + step), t_end), \
            largest_rotation(block, motion.scaled(1 - step), t_end)
        return (up - down) / (2 * step * peak)
    value = block.parameters()[name]
    move = step * value
    up, down = largest_rotation(block.replace_parameter(name, value + move), motion, t_end), \
        largest_rotation(block.replace_parameter(name, value - move), motion, t_end)
    return (up - down) / (2 * move)


def richardson(block, motion, t_end, name, step):
    """(the central differences at ``step`` and 2 ``step`` extrapolated, (4 D(h) - D(2h))
    / 3, its error estimate |R(h) - R(2h)|) [-/unit]."""
    d1, d2, d4 = (central_difference(block, motion, t_end, name, k * step) for k in (1, 2, 4))
    fine, coarse = (4 * d1 - d2) / 3, (4 * d2 - d4) / 3
    return fine, abs(fine - coarse)


@functools.cache
def twin(block, motion, t_end, wrt):
    return bd.sensitivities(block, motion, t_end=t_end, wrt=wrt, of=OF)


def test_under_a_pulse_against_finite_differences():
    """A half-sine pulse rocks the block (b = 0.2 m, h = 0.8 m; Housner's r from b and
    h): d/db, d/dh and d/dA of its largest rotation (the first apex) agree with central
    differences extrapolated from the relative steps 1e-4, 2e-4 and 4e-4 to 1e-8
    (measured 2.7e-10; the extrapolation's own error estimate 3e-10 at most)."""
    block, pulse = RockingBlock(b=0.2, h=0.8, mu=0.6), bd.SinePulse(-0.4 * G, 0.5)
    found = twin(block, pulse, 2.0, ("b", "h", "A"))
    assert found.quantities == (OF,) and found.units[0] == ("1/m", "1/m", "1/g")
    for name in ("b", "h", "A"):
        reference, error = richardson(block, pulse, 2.0, name, 1e-4)
        assert error < 1e-8 * abs(reference), name
        assert abs(found[name] - reference) < 1e-8 * abs(reference), (name, found[name], reference)


def test_under_a_record_through_impacts_against_finite_differences():
    """Kobe TAK-090 (first 6 s) rocks a 0.8 m x 2.4 m block through three impacts before
    its largest rotation (max |theta| / alpha = 1.05: past alpha and back): d/db, d/dh and
    d/dA (Housner's r moving with b and h) agree with central differences extrapolated
    from the relative steps 5e-5, 1e-4 and 2e-4 to 3e-7 (measured 2.6e-8 at most; the
    extrapolation's own error estimate 3.1e-8 at most). Plain central differences at
    1e-4 are off by 5e-7 here, and far more where a return grazes the base."""
    block, record = RockingBlock(b=0.4, h=1.2, mu=0.8), kobe_first_6_s()
    solution = bd.simulate(block, record, t_end=6.0, backend="cvode", rtol=1e-12, atol=1e-14)
    peak_time = solution.t[np.argmax(np.abs(solution.state[:, 0]))]
    assert np.sum(solution.impact_times < peak_time) >= 3 and solution.max_theta_over_alpha > 1
    found = twin(block, record, 6.0, ("b", "h", "A"))
    for name in ("b", "h", "A"):
        reference, error = richardson(block, record, 6.0, name, 5e-5)
        assert error < 3e-7 * abs(reference), name
        assert abs(found[name] - reference) < 3e-7 * abs(reference), (name, found[name], reference)


@pytest.mark.slow
def test_by_a_given_restitution_through_impacts():
    """With the restitution given (0.85) it is a parameter of its own: d/dr of the largest
    rotation after three impacts agrees with central differences as above to 3e-7
    (measured 4.2e-9, d/db 1.2e-8; their error estimate 3.5e-8 at most), and d/db then
    holds r fixed (it differs from Housner's block's, whose r moves with b)."""
    block, record = RockingBlock(b=0.4, h=1.2, mu=0.8, restitution=0.85), kobe_first_6_s()
    found = twin(block, record, 6.0, ("b", "restitution"))
    for name in ("b", "restitution"):
        reference, error = richardson(block, record, 6.0, name, 5e-5)
        assert error < 3e-7 * abs(reference), name
        assert abs(found[name] - reference) < 3e-7 * abs(reference), (name, found[name], reference)
    housner = twin(block.replace(restitution=None), record, 6.0, ("b",))
    assert abs(housner["b"] - found["b"]) > 1e-3 * abs(found["b"])


def linearised_apex(b, h, amplitude, omega):
    """max |theta| / alpha [-] of the linearised block at rest under a_x = -amplitude
    sin(omega t) [m/s², rad/s], reached at its first apex within the pulse (closed form,
    mpmath): from the uplift at t0, amplitude sin(omega t0) = g alpha, theta = alpha + C
    sin(omega t) + c1 cosh(p (t - t0)) + c2 sinh(p (t - t0)), C = -p² amplitude / (g (p²
    + omega²)), theta(t0) = theta'(t0) = 0."""
    g = mpmath.mpf(G)
    alpha, radius = mpmath.atan(b / h), mpmath.sqrt(b * b + h * h)
    p = mpmath.sqrt(3 * g / (4 * radius))
    t0 = mpmath.asin(g * alpha / amplitude) / omega
    c = -p**2 * amplitude / (g * (p**2 + omega**2))
    c1, c2 = -(alpha + c * mpmath.sin(omega * t0)), -c * omega * mpmath.cos(omega * t0) / p
    arc = lambda t: (mpmath.cosh(p * (t - t0)), mpmath.sinh(p * (t - t0)))
    theta = lambda t: alpha + c * mpmath.sin(omega * t) + c1 * arc(t)[0] + c2 * arc(t)[1]
    rate = lambda t: c * omega * mpmath.cos(omega * t) + p * (c1 * arc(t)[1] + c2 * arc(t)[0])
    period = 2 * mpmath.pi / omega
    grid = [t0 + (period - t0) * k / 1000 for k in range(1, 1001)]
    k = next(i for i in range(len(grid) - 1) if rate(grid[i]) > 0 >= rate(grid[i + 1]))
    return theta(mpmath.findroot(rate, (grid[k], grid[k + 1]), solver="anderson")) / alpha


def test_linearised_block_under_a_one_sine_pulse_closed_form():
    """The linearised block (b = 0.2 m, h = 1 m) under one sine cycle of 3 g alpha at 3 p:
    its largest rotation (0.987 alpha, at the first apex within the pulse) and the
    derivatives by b, h and A agree with the closed form differentiated in 40 digits to
    1e-10 (measured 8e-12)."""
    block = RockingBlock(b=0.2, h=1.0, mu=0.6, linearised=True)
    b, h = mpmath.mpf("0.2"), mpmath.mpf("1.0")
    omega, amplitude = mpmath.mpf(3 * block.frequency), mpmath.mpf(3 * G * block.alpha)
    motion = bd.Harmonic(-float(amplitude), float(2 * mpmath.pi / omega), cycles=1)
    t_end = motion.duration
    assert abs(largest_rotation(block, motion, t_end) - float(linearised_apex(b, h, amplitude, omega))) < 1e-9
    closed = {"b": mpmath.diff(lambda x: linearised_apex(x, h, amplitude, omega), b),
              "h": mpmath.diff(lambda x: linearised_apex(b, x, amplitude, omega), h),
              "A": G * mpmath.diff(lambda x: linearised_apex(b, h, x, omega), amplitude)}
    found = twin(block, motion, t_end, ("b", "h", "A"))
    for name, value in closed.items():
        assert abs(found[name] - float(value)) < 1e-10 * abs(float(value)), (name, found[name], float(value))


def test_overturned_block():
    """An overturned block's largest rotation is pi/2: max |theta| / alpha = (pi/2) /
    alpha, so d/dA = 0 and d/db = -(pi/2) h / (R² alpha²), d/dh = (pi/2) b / (R² alpha²)
    (closed form, to 1e-12); central differences of CVODE runs (relative step 1e-4)
    agree to 1e-7 (measured 1e-8)."""
    block, pulse = RockingBlock(b=0.1, h=0.5, mu=0.6), bd.SinePulse(-1.0 * G, 0.6)
    assert bd.simulate(block, pulse).overturned
    found = twin(block, pulse, None, ("b", "h", "A"))
    r2, alpha = block.b ** 2 + block.h ** 2, block.alpha
    closed = {"b": -0.5 * math.pi * block.h / (r2 * alpha ** 2), "h": 0.5 * math.pi * block.b / (r2 * alpha ** 2)}
    assert found["A"] == 0.0
    for name, value in closed.items():
        assert abs(found[name] - value) < 1e-12 * abs(value), name
        assert abs(central_difference(block, pulse, None, name, 1e-4) - value) < 1e-7 * abs(value), name


def test_released_from_a_tilt():
    """Released from theta0 = alpha / 2 with no shaking, the block never rotates further:
    max |theta| / alpha = theta0 / alpha, so d/dtheta0 = 1 / alpha and d/db = -theta0 h /
    (R² alpha²) (closed form, to 1e-12)."""
    block = RockingBlock(b=0.2, h=1.0, mu=0.6)
    block = block.replace(theta0=block.alpha / 2)
    quiet = bd.Record(np.zeros(101), 0.01, name="no shaking", units="m/s2")
    found = twin(block, quiet, 1.0, ("b", "theta0"))
    r2, alpha = block.b ** 2 + block.h ** 2, block.alpha
    assert abs(found["theta0"] - 1 / alpha) < 1e-12 / alpha
    closed = -block.theta0 * block.h / (r2 * alpha ** 2)
    assert abs(found["b"] - closed) < 1e-12 * abs(closed)


def test_a_block_that_slides_or_is_asked_for_an_unknown_quantity():
    """A block that slides never rotates: its largest rotation is 0 whatever b, h or A;
    a quantity the block does not declare is refused, naming the choice."""
    block = RockingBlock(b=0.5, h=0.6, mu=0.3)
    found = twin(block, bd.SinePulse(-0.5 * G, 0.5), None, ("b", "A"))
    assert found["b"] == found["A"] == 0.0
    with pytest.raises(ValueError, match="max_theta_over_alpha"):
        bd.sensitivities(block, bd.SinePulse(-0.5 * G, 0.5), of="height")
    with pytest.raises(ValueError, match="displacement"):
        bd.sensitivities(bd.PlanarBlock(mu=0.2), bd.BaseMotion(bd.SinePulse(0.5 * G, 0.5)), of=OF)
