"""Symmetries and monotonicity of the exact solution, on random piecewise-linear records."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import blockdae as bd

# samples [m/s²] of any peak, tiny ones included: the units are stated and the peak check is off
samples = arrays(np.float64, 48, elements=st.floats(-8.0, 8.0, allow_nan=False, width=64))
mus = st.floats(0.05, 0.6)
SETTINGS = settings(max_examples=25, deadline=None)


@SETTINGS
@given(samples, mus, st.floats(0.0, 1.0))
def test_inverting_the_record_flips_u(a, mu, f_ratio):
    block = bd.SlidingBlock(mu=mu, mu_kinetic=f_ratio * mu)
    record = bd.Record(a, dt=0.02, units="m/s2", check_peak=False)
    u = bd.simulate(block, record, t_end=1.5).displacement
    u_inv = bd.simulate(block, record.inverted(), t_end=1.5).displacement
    assert abs(u + u_inv) <= 1e-12 * max(abs(u), 1e-3)


@SETTINGS
@given(samples, mus, st.floats(-0.9, 0.9), st.floats(0.2, 5.0))
def test_scaling_accelerations_scales_u(a, mu, bias_ratio, k):
    """a -> k a, mu g -> k mu g, bias g -> k bias g (i.e. g -> k g) gives u -> k u."""
    block = bd.SlidingBlock(mu=mu, mu_kinetic=0.7 * mu, bias=bias_ratio * mu)
    record = bd.Record(a, dt=0.02, units="m/s2", check_peak=False)
    u = bd.simulate(block, record, t_end=2.0).displacement
    u_k = bd.simulate(block.replace(g=block.g * k), record.scaled(k), t_end=2.0).displacement
    assert abs(u_k - k * u) <= 1e-11 * max(abs(k * u), 1e-3)


@SETTINGS
@given(samples, mus, st.floats(-0.9, 0.9))
def test_no_sliding_below_the_thresholds(a, mu, bias_ratio):
    """max |a| < (mu - |bias|) g: the block never leaves the base."""
    bias = bias_ratio * mu
    limit = (mu - abs(bias)) * bd.STANDARD_GRAVITY
    a = a / np.max(np.abs(a)) * limit * 0.999 if np.any(a) else a
    sol = bd.simulate(bd.SlidingBlock(mu=mu, bias=bias), bd.Record(a, dt=0.02, units="m/s2", check_peak=False))
    assert sol.events == () and sol.displacement == 0.0


@SETTINGS
@given(samples, mus, mus)
def test_one_way_displacement_is_monotone_in_mu(a, mu1, mu2):
    low, high = sorted((mu1, mu2))
    record = bd.Record(a, dt=0.02, units="m/s2", check_peak=False)
    u_low = bd.simulate(bd.SlidingBlock(mu=low, direction="negative"), record).displacement
    u_high = bd.simulate(bd.SlidingBlock(mu=high, direction="negative"), record).displacement
    assert u_low <= u_high + 1e-15 <= 1e-15
