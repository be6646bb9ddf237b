"""bd.sensitivities: d u(t_end) / d (mu, mu_kinetic, bias, A) of both differentiable backends."""

import numpy as np
import pytest
from conftest import load_sample_record

import blockdae as bd

BACKENDS = ("exact", "jax")
G = 9.81


@pytest.mark.parametrize("backend", BACKENDS)
def test_rectangular_pulse_closed_form(backend):
    """Reference: seed 000 Eq. 14, u = A g t0²/2 (1 - A/mu) (f = mu, no bias), so
    du/dmu = A² g t0²/(2 mu²) and du/dA = g t0²/2 (1 - 2A/mu) [m/g]."""
    A, mu, t0 = 0.9, 0.6, 0.5
    s = bd.sensitivities(bd.SlidingBlock(mu, g=G), bd.RectangularPulse(A * G, t0), wrt=("mu", "A"),
                         backend=backend)
    np.testing.assert_allclose(s["mu"], A**2 * G * t0**2 / (2 * mu**2), rtol=1e-12)
    np.testing.assert_allclose(s["A"], G * t0**2 / 2 * (1 - 2 * A / mu), rtol=1e-12)


@pytest.mark.parametrize("backend", BACKENDS)
def test_rectangular_pulse_with_kinetic_friction_and_bias(backend):
    """Reference: Eq. 14 with the slip deceleration (f + R/Q) g = k g in place of mu g:
    the onset is the jump at t = 0 whatever mu, and u = -(A - k) A g t0²/(2k), so
    du/dmu = 0, du/df = du/dbias = A² g t0²/(2k²), du/dA = -(2A - k) g t0²/(2k)."""
    A, mu, f, bias, t0 = 0.9, 0.6, 0.45, 0.05, 0.5
    k = f + bias
    s = bd.sensitivities(bd.SlidingBlock(mu, f, bias=bias, g=G), bd.RectangularPulse(A * G, t0), backend=backend)
    assert s["mu"] == 0.0
    np.testing.assert_allclose(s["mu_kinetic"], A**2 * G * t0**2 / (2 * k**2), rtol=1e-12)
    np.testing.assert_allclose(s["bias"], A**2 * G * t0**2 / (2 * k**2), rtol=1e-12)
    np.testing.assert_allclose(s["A"], -(2 * A - k) * G * t0**2 / (2 * k), rtol=1e-12)


def central_differences(block, record, t_end, rel_step=1e-5, **backend):
    """Independent reference: central differences of u(t_end) [m] (exact backend unless
    ``backend`` says otherwise)."""
    A = record.peak_acceleration / block.g
    points = {"mu": block.mu, "mu_kinetic": block.mu_kinetic, "bias": block.bias, "A": A}

    def u(name, value):
        if name == "A":
            return bd.simulate(block, record.scaled(value / A), t_end, **backend).displacement
        return bd.simulate(block.replace(**{name: value}), record, t_end, **backend).displacement

    return {name: (u(name, x + rel_step * abs(x)) - u(name, x - rel_step * abs(x))) / (2 * rel_step * abs(x))
            for name, x in points.items()}


# u at t_end [s] (Kobe: first 10 s, while it slides): both runs have 950-1000 pieces,
# so they share compiled kernels
@pytest.mark.parametrize("stem, block, t_end", [
    ("Kobe_1995_TAK-090", bd.SlidingBlock(0.3, 0.22, bias=0.05), 10.0),
    ("Northridge_1994_PAC-175", bd.SlidingBlock(0.25, 0.2, bias=-0.05), 19.0),
])
def test_real_records_match_finite_differences(stem, block, t_end):
    """f < mu, a bias, two-way sliding: both backends within 6.5e-9 of central differences
    of the exact backend (relative step 1e-5: truncation and rounding errors both ~1e-10
    relative); measured: at most 6.5e-10 (Northridge, d u / d mu), the bar a decade above."""
    record = load_sample_record(stem)
    reference = central_differences(block, record, t_end)
    for backend in BACKENDS:
        s = bd.sensitivities(block, record, t_end, backend=backend)
        for name, value in reference.items():
            np.testing.assert_allclose(s[name], value, rtol=6.5e-9, err_msg=f"{backend}: d u / d {name}")


def test_real_record_matches_cvode_finite_differences():
    """Reference: central differences of the CVODE backend (an independent integrator) at
    rtol 1e-12, relative steps 2e-3 and 1e-3 combined by Richardson extrapolation (large
    steps, so CVODE's noise is small against them; the extrapolation removes the steps'
    O(h²) error). Within 1e-7 relative: the reference's error, measured as its spread over
    CVODE at rtol 1e-12 and 1e-13 against the exact kernel, is <= 1.4e-9 (the plain central
    difference at a step of 1e-4, the reference before it, was 5e-8 off at rtol 1e-12 and
    4.5e-7 at rtol 1e-13, too close to its bar of 1e-6)."""
    record, block = load_sample_record("Northridge_1994_PAC-175"), bd.SlidingBlock(0.25, 0.2, bias=-0.05)
    coarse, fine = (central_differences(block, record, 19.0, rel_step=step, backend="cvode", rtol=1e-12)
                    for step in (2e-3, 1e-3))
    reference = {name: (4 * fine[name] - coarse[name]) / 3 for name in fine}
    for backend in BACKENDS:
        s = bd.sensitivities(block, record, 19.0, backend=backend)
        for name, value in reference.items():
            np.testing.assert_allclose(s[name], value, rtol=1e-7, err_msg=f"{backend}: d u / d {name}")


# Threshold record [m/s²] with g = 8 and mu g = 2 exactly (all samples and slopes are
# binary-exact): the first peak 3.5 starts an episode inside a piece; the later peak 2
# only touches mu g and turns back. Zeros pad it to 992 pieces up to t_end = 124 s, the
# compiled shape of the runs above.
THRESHOLD_RECORD = bd.Record(np.pad([0, 1, 2.5, 3.5, 2, 1, 0, -1, -1, 0, 0, 0, 0, 0, 0, 0, 1, 2, 1], (0, 982)), 0.125)
THRESHOLD_BLOCK = bd.SlidingBlock(0.25, 0.15, g=8.0)
THRESHOLD_T_END = 124.0


@pytest.mark.parametrize("backend", BACKENDS)
def test_threshold_returns_the_derivative_of_the_branch_without_the_new_episode(backend):
    """Where a new episode appears exactly at threshold u jumps (f < mu) and is not
    differentiable. Documented answer: the touching demand does not slide, and the
    derivative is the one-sided one from that side (A below, mu above the threshold).
    Reference: one-sided differences of the exact backend on each side (step 1e-7, an
    O(h) error: measured 4.2e-8 in A and 4.4e-7 in mu, both backends)."""
    block, record, t_end = THRESHOLD_BLOCK, THRESHOLD_RECORD, THRESHOLD_T_END
    A = record.peak_acceleration / block.g
    u = lambda k=1.0, mu=block.mu: bd.simulate(block.replace(mu=mu), record.scaled(k), t_end).displacement
    h = 1e-7
    below_in_A = (u() - u(1 - h)) / (A * h)
    above_in_A = (u(1 + h) - u()) / (A * h)
    above_in_mu = (u(mu=block.mu + h) - u()) / h
    s = bd.sensitivities(block, record, t_end, wrt=("mu", "A"), backend=backend)
    np.testing.assert_allclose(s["A"], below_in_A, rtol=4.2e-7)
    np.testing.assert_allclose(s["mu"], above_in_mu, rtol=1e-6)
    assert abs(above_in_A) > 1e3 * abs(s["A"])  # the other side jumps: ~1/h
    assert bd.simulate(block, record, t_end).stats["n_events"] == 2  # the touch does not slide


@pytest.mark.parametrize("backend", BACKENDS)
def test_onset_exactly_at_a_sample_is_differentiated(backend):
    """A sample equal to mu g with a(t) crossing it (slope 8 m/s³ on both sides): u is
    differentiable, and the onset time moves with mu by 1/slope although it sits on a
    breakpoint. Reference: central differences of the exact backend's u (step 1e-6);
    measured 7.0e-12 relative on both backends, the bar a decade above."""
    block, t_end = THRESHOLD_BLOCK, THRESHOLD_T_END
    record = bd.Record(np.pad([0, 1, 2, 3, 2, 1, 0, -1, -1], (0, 992)), 0.125)
    u = lambda mu: bd.simulate(block.replace(mu=mu), record, t_end).displacement
    h = 1e-6
    reference = (u(block.mu + h) - u(block.mu - h)) / (2 * h)
    s = bd.sensitivities(block, record, t_end, wrt="mu", backend=backend)
    np.testing.assert_allclose(s["mu"], reference, rtol=7e-11)


@pytest.mark.parametrize("backend", BACKENDS)
def test_batch_is_one_vmapped_call_matching_single_sets(backend):
    """A grid of parameter sets gives arrays equal to the scalar calls."""
    record = load_sample_record("Northridge_1994_PAC-175")
    block = bd.SlidingBlock(np.array([0.2, 0.25, 0.3]), np.array([0.15, 0.2, 0.2]), bias=-0.05)
    s = bd.sensitivities(block, record, 19.0, wrt=("mu", "mu_kinetic", "bias", "A", "scale"), backend=backend)
    assert set(s) == {"mu", "mu_kinetic", "bias", "A", "scale"} and all(v.shape == (3,) for v in s.values())
    np.testing.assert_allclose(s["scale"], s["A"] * record.peak_acceleration / block.g)  # A = k peak / g
    one = bd.sensitivities(block.item(1), record, 19.0, wrt=tuple(s), backend=backend)
    for name in s:
        np.testing.assert_allclose(s[name][1], one[name], rtol=1e-12)


@pytest.mark.parametrize("backend", BACKENDS)
def test_an_item_of_a_batch_keeps_the_kinetic_friction_following_mu(backend):
    """mu_kinetic None (f = mu): an item of a batch over mu has the single block's
    derivative by mu, the kinetic part included (with f fixed at its value, only the
    static part: ~1e-16 m against 0.139 m here)."""
    motion = bd.Harmonic(3.0, 1.0)
    item = bd.SlidingBlock(mu=np.array([0.2, 0.25])).item(0)
    assert item.mu_kinetic is None
    single = bd.sensitivities(bd.SlidingBlock(mu=0.2), motion, 3.0, wrt="mu", backend=backend)["mu"]
    assert abs(single) > 0.1
    np.testing.assert_allclose(bd.sensitivities(item, motion, 3.0, wrt="mu", backend=backend)["mu"], single,
                               rtol=1e-12)


def test_backends_agree_on_harmonic_with_kinetic_friction_and_bias():
    """Seed 000 Example 3 (f = 0.4, R/Q = 0.3), u(3 s): twin vs exact within 1e-8."""
    block, motion = bd.SlidingBlock(0.6, 0.4, bias=0.3), bd.Harmonic(7.0, 1.0)
    exact = bd.sensitivities(block, motion, t_end=3.0)
    twin = bd.sensitivities(block, motion, t_end=3.0, backend="jax")
    for name in exact:
        np.testing.assert_allclose(twin[name], exact[name], rtol=1e-8)


@pytest.mark.parametrize("kwargs, match", [
    (dict(wrt=("mu", "R")), "wrt"), (dict(wrt=()), "wrt"), (dict(backend="cvode"), "backend"),
])
def test_bad_requests_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        bd.sensitivities(bd.SlidingBlock(0.6), bd.RectangularPulse(9.0, 0.5), **kwargs)


def test_exact_derivative_of_an_onset_exactly_on_a_sample():
    """The demand reaches mu g exactly at a sample where a(t) keeps its slope, so u is
    smooth in mu: the exact kernel's derivative equals central differences (it was halved
    when the onset root sat on the bound of a clip)."""
    record = bd.Record([0, 1, 2, 3, 2, 1, 0, -1, -1, 0, 0, 0], 0.125)
    block = bd.SlidingBlock(0.25, 0.15, g=8.0)
    h = 1e-6
    central = (bd.simulate(block.replace(mu=0.25 + h), record).displacement
               - bd.simulate(block.replace(mu=0.25 - h), record).displacement) / (2 * h)
    assert bd.sensitivities(block, record, wrt=("mu",))["mu"] == pytest.approx(central, rel=1e-6)


def test_finite_differences_of_cvode_match_the_rectangular_pulse_closed_form():
    """u = A g t0²/2 (1 - A/mu) (seed Eq. 14, A in g): du/dmu = A² g t0²/(2 mu²),
    du/dA = g t0²/2 (1 - 2A/mu), here from central differences of the CVODE backend."""
    from blockdae.core._sensitivities import finite_differences

    a_g, t0, mu, g = 0.9, 0.5, 0.6, 9.81
    block = bd.SlidingBlock(mu=mu, g=g)
    fd = finite_differences(block, bd.RectangularPulse(a_g * g, t0), wrt=("mu", "A"), backend="cvode", rtol=1e-12)
    assert fd["mu"] == pytest.approx(a_g**2 * g * t0**2 / (2 * mu**2), rel=1e-6)
    assert fd["A"] == pytest.approx(g * t0**2 / 2 * (1 - 2 * a_g / mu), rel=1e-6)
    with pytest.raises(ValueError, match="step must be"):
        finite_differences(block, bd.RectangularPulse(a_g * g, t0), step=0.5)


def test_crosscheck_tabulates_sensitivities():
    """JAX twin and exact kernel derivatives agree; CVODE's central differences agree to
    their own noise at rtol 1e-11; the table names each derivative with its unit."""
    block = bd.SlidingBlock(mu=0.6, mu_kinetic=0.4, bias=0.1)
    table = bd.crosscheck(block, bd.SinePulse(9.0, 0.5), backends=("exact", "jax", "cvode"),
                          wrt=("mu", "bias", "A"), rtol=1e-11)
    assert table.row("jax")["rel_dsens"] < 1e-9
    assert table.row("cvode")["rel_dsens"] < 1e-5
    assert set(table.row("exact")["sensitivities"]) == {"mu", "bias", "A"}
    text = str(table)
    assert "du/dmu [m]" in text and "du/dA [m/g]" in text and "rel |dS| [-]" in text
