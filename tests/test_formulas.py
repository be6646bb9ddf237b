"""Seed 002's formulas: Newmark's eqs. 1-3 against the exact sliding under one rectangular
pulse (``bd.simulate``, whose events are exact), and the adjustment factor (eq. 4) and its
least-squares refit against synthetic data made with known coefficients."""

import numpy as np
import pytest

import blockdae as bd

G = bd.STANDARD_GRAVITY
PULSES = [(0.4, 0.1, 0.5), (0.25, 0.2, 0.1), (1.0, 0.3, 0.05), (0.31, 0.3, 2.0)]  # A [g], μ, t0 [s]


def exact_pulse(pga, mu, t0):
    """The sliding block under one rectangular pulse: (max |u| [m], the time it stops [s])."""
    sol = bd.simulate(bd.SlidingBlock(mu, direction="negative"), bd.RectangularPulse(pga * G, t0))
    return sol.max_abs_displacement, sol.t_events[-1]


@pytest.mark.parametrize("pga, mu, t0", PULSES)
def test_eq1_is_the_exact_sliding_distance_of_a_rectangular_pulse(pga, mu, t0):
    """Eq. 1 with V = A g t0 equals the exact max |u| to rounding."""
    rc, _ = exact_pulse(pga, mu, t0)
    assert bd.sliding.newmark_rd(pga * G * t0, pga, mu) == pytest.approx(rc, rel=1e-13)


@pytest.mark.parametrize("pga, mu, t0", PULSES)
def test_eq2_and_eq3_are_exact_for_a_rectangular_pulse(pga, mu, t0):
    """Sd of eq. 2 is the base displacement when the exact block stops (t1 = A t0/μ), and
    eq. 3 from that Sd equals the exact max |u| to rounding."""
    rc, t_stop = exact_pulse(pga, mu, t0)
    pulse = bd.RectangularPulse(pga * G, t0)
    assert t_stop == pytest.approx(pga * t0 / mu, rel=1e-14)
    sd = pulse.displacement(t_stop)
    assert bd.sliding.pulse_sd(pga, t0, mu) == pytest.approx(sd, rel=1e-14)
    assert bd.sliding.newmark_rd_sd(sd, pga, mu) == pytest.approx(rc, rel=1e-13)


def test_no_sliding_below_the_friction_coefficient():
    """A <= μ: the block never slides, and the formulas give 0 (not a negative distance)."""
    sol = bd.simulate(bd.SlidingBlock(0.3, direction="negative"), bd.RectangularPulse(0.3 * G, 0.5))
    assert sol.events == () and sol.max_abs_displacement == 0.0
    assert bd.sliding.newmark_rd(1.0, 0.3, 0.3) == 0.0 and bd.sliding.newmark_rd_sd(1.0, 0.2, 0.3) == 0.0
    assert bd.sliding.pulse_sd(0.2, 0.5, 0.3) == pytest.approx(0.5 * 0.2 * G * 0.25, rel=1e-15)


def test_formulas_broadcast():
    mu = np.array([0.1, 0.2, 0.3])
    rd = bd.sliding.newmark_rd(0.5, 0.4, mu)
    assert rd.shape == (3,)
    np.testing.assert_allclose(rd, [bd.sliding.newmark_rd(0.5, 0.4, m) for m in mu], rtol=1e-15)
    np.testing.assert_allclose(bd.sliding.newmark_rd_sd(0.2, [[0.2], [0.4]], mu).shape, (2, 3))


def test_adjustment_factor_seed_values():
    """Adj = 0.19 √A / (μ + 0.06): 0.19/0.16 at A = 1, μ = 0.1; 0.19·0.5/0.36 at A = 0.25, μ = 0.3."""
    adj = bd.sliding.AdjustmentFactor()
    assert (adj.scale, adj.offset) == (0.19, 0.06)
    assert adj(1.0, 0.1) == pytest.approx(0.19 / 0.16, rel=1e-15)
    np.testing.assert_allclose(adj([1.0, 0.25], [0.1, 0.3]), [0.19 / 0.16, 0.095 / 0.36], rtol=1e-15)


def synthetic(scale, offset, noise=0.0, seed=0):
    """R_c = scale √A R_d / (μ + offset) × lognormal noise on a seed-002 grid (3 μ × 20 A)."""
    mu, pga = np.meshgrid([0.1, 0.2, 0.3], np.linspace(0.05, 1.0, 20), indexing="ij")
    rd = bd.sliding.newmark_rd_sd(0.15, pga, mu)
    rng = np.random.default_rng(seed)
    rc = scale * np.sqrt(pga) * rd / (mu + offset) * np.exp(noise * rng.standard_normal(mu.shape))
    return rc, rd, pga, mu


@pytest.mark.parametrize("space", ["log", "linear"])
@pytest.mark.parametrize("scale, offset", [(0.19, 0.06), (0.4, -0.05), (0.05, 0.5)])
def test_refit_recovers_known_coefficients(space, scale, offset):
    """Exact synthetic data: the fit returns the coefficients that made it (cases with
    A <= μ have R_d = 0 and drop out of the log fit; they fit exactly in the linear one)."""
    fit = bd.sliding.fit_adjustment_factor(*synthetic(scale, offset), space=space)
    assert fit.scale == pytest.approx(scale, rel=1e-7)
    assert fit.offset == pytest.approx(offset, rel=1e-7, abs=1e-9)


def test_refit_with_scatter_is_close_and_beats_the_true_coefficients():
    """With 10 % lognormal scatter the fit is near the truth and, being the least-squares
    minimum, has a log residual no larger than the true coefficients'."""
    rc, rd, pga, mu = synthetic(0.19, 0.06, noise=0.1, seed=1)
    fit = bd.sliding.fit_adjustment_factor(rc, rd, pga, mu)
    assert fit.scale == pytest.approx(0.19, rel=0.15) and fit.offset == pytest.approx(0.06, abs=0.03)
    keep = rd > 0

    def cost(adj):
        return np.sum(np.log(rc[keep] / (adj(pga, mu)[keep] * rd[keep])) ** 2)

    assert cost(fit) <= cost(bd.sliding.AdjustmentFactor(0.19, 0.06))


@pytest.mark.parametrize("call, message", [
    (lambda: bd.sliding.newmark_rd(0.5, 0.4, 0.0), r"mu=0\.0 must be positive and finite \[-\]"),
    (lambda: bd.sliding.newmark_rd(-1.0, 0.4, 0.1), r"pgv=-1\.0 must be >= 0"),
    (lambda: bd.sliding.newmark_rd_sd(0.1, [0.4, np.nan], 0.1), r"pga=nan must be positive"),
    (lambda: bd.sliding.pulse_sd(0.4, 0.0, 0.1), r"duration=0\.0 must be positive and finite \[s\]"),
    (lambda: bd.sliding.AdjustmentFactor(scale=-1.0), r"scale=-1\.0 must be positive"),
    (lambda: bd.sliding.AdjustmentFactor(offset=np.inf), r"offset must be finite"),
    (lambda: bd.sliding.AdjustmentFactor(offset=-0.2)(0.5, 0.1), r"mu \+ offset must be positive"),
    (lambda: bd.sliding.fit_adjustment_factor([1.0, 2.0], 1.0, 0.5, 0.1), r"two values of mu"),
    (lambda: bd.sliding.fit_adjustment_factor([1.0, 0.0], 1.0, 0.5, [0.1, 0.2]), r"at least 2 cases"),
    (lambda: bd.sliding.fit_adjustment_factor([1.0, 1.0], [1.0, 0.0], 0.5, [0.1, 0.2], space="linear"),
     r"at least 2 cases with R_d > 0, got 1"),
    (lambda: bd.sliding.fit_adjustment_factor(1.0, 1.0, 0.5, 0.1, space="lin"), r"space must be"),
])
def test_bad_input_names_the_field(call, message):
    with pytest.raises(ValueError, match=message):
        call()
