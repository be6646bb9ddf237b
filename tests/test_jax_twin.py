"""The JAX twin (backend "jax", diffrax) against the exact closed-form backend."""

import numpy as np
import pytest
from conftest import assert_same_events, load_sample_record

import blockdae as bd
from blockdae.backends import make_backend

G = 9.81  # the seed paper's g [m/s²]

# seed 000: Examples 1-3 (harmonic, run 3 s: one compiled shape) and 4-6 (pulses, to rest)
SEED_EXAMPLES = {
    "ex1": (bd.SlidingBlock(0.6, g=G), bd.Harmonic(9.0, 1.0), 3.0),
    "ex2": (bd.SlidingBlock(0.6, 0.3, g=G), bd.Harmonic(9.0, 1.0), 3.0),
    "ex3a": (bd.SlidingBlock(0.6, 0.6, bias=0.3, g=G), bd.Harmonic(7.0, 1.0), 3.0),
    "ex3b": (bd.SlidingBlock(0.6, 0.4, bias=0.3, g=G), bd.Harmonic(7.0, 1.0), 3.0),
    "ex4": (bd.SlidingBlock(0.6, g=G), bd.RectangularPulse(9.0, 0.5), None),
    "ex5": (bd.SlidingBlock(0.6, g=G), bd.TriangularPulse(9.0, 0.5), None),
    "ex6": (bd.SlidingBlock(0.6, g=G), bd.SinePulse(9.0, 0.5), None),
}


def assert_twins(exact, twin):
    """Same event sequence; event times within 1e-9 s; u(t_end) within 1e-7 relative."""
    assert_same_events(twin, exact, 1e-9)
    np.testing.assert_allclose(twin.displacement, exact.displacement, rtol=1e-7, atol=0)
    np.testing.assert_allclose(twin.t_end, exact.t_end, rtol=0, atol=1e-9)


@pytest.mark.parametrize("name", SEED_EXAMPLES)
def test_seed_examples_agree_with_exact(name):
    """Reference: the exact backend (closed forms, verified against seed 000)."""
    block, motion, t_end = SEED_EXAMPLES[name]
    assert_twins(bd.simulate(block, motion, t_end), bd.simulate(block, motion, t_end, backend="jax"))


def test_example1_event_times_from_seed():
    """Reference: seed 000, Example 1 (onset 0.1125 s, stop 0.535 s, onset 0.614 s, stop 1.035 s)."""
    block, motion, t_end = SEED_EXAMPLES["ex1"]
    t = bd.simulate(block, motion, t_end, backend="jax").t_events
    np.testing.assert_allclose(t[:4], [0.113455, 0.535036, 0.613455, 1.035036], atol=1e-6)


@pytest.mark.parametrize("stem, block", [
    ("Kobe_1995_TAK-090", bd.SlidingBlock(0.3, 0.22, bias=0.05)),
    ("Kobe_1995_TAK-090", bd.SlidingBlock(0.15)),  # many reversals, f = mu
    ("Northridge_1994_PAC-175", bd.SlidingBlock(0.25, 0.2, bias=-0.05)),
    ("Northridge_1994_PAC-175", bd.SlidingBlock(0.1, direction="negative")),
])
def test_real_records_agree_with_exact(stem, block):
    """Reference: the exact backend on pySLAMMER's sample records (m/s²)."""
    record = load_sample_record(stem)
    assert_twins(bd.simulate(block, record), bd.simulate(block, record, backend="jax"))


def test_batch_is_vectorised_and_matches_single_runs():
    """One vmapped call equals the exact batch and the twin's own single runs."""
    record = load_sample_record("Northridge_1994_PAC-175")
    block = bd.SlidingBlock(np.array([0.1, 0.25, 0.4]), np.array([0.08, 0.2, 0.3]), bias=0.02)
    twin = bd.simulate(block, record, backend="jax")
    exact = bd.simulate(block, record)
    assert isinstance(twin, bd.core.BatchSolution) and twin.backend == "jax"
    np.testing.assert_allclose(twin.displacement, exact.displacement, rtol=1e-7)
    np.testing.assert_array_equal(twin.n_events, exact.n_events)
    np.testing.assert_allclose(twin.displacement[1], twin[1].displacement, rtol=1e-12)


def test_other_solver_agrees():
    """Dopri8 on the sine pulse (Example 6): reference the exact backend."""
    block, motion, _ = SEED_EXAMPLES["ex6"]
    assert_twins(bd.simulate(block, motion), bd.simulate(block, motion, backend="jax", solver="dopri8"))


def test_segment_bound_is_reported():
    """Example 1 needs three segments in a half period (stick, slip to the turning
    point of v, slip to the stop); a bound of two must raise, not truncate."""
    block, motion, t_end = SEED_EXAMPLES["ex1"]
    with pytest.raises(RuntimeError, match="max_segments=2"):
        bd.simulate(block, motion, t_end, backend="jax", max_segments=2)


@pytest.mark.parametrize("options, field", [
    (dict(rtol=0.0), "rtol"), (dict(atol=-1e-9), "atol"), (dict(solver="euler"), "solver"),
    (dict(max_segments=1), "max_segments"), (dict(max_steps=2.5), "max_steps"),
])
def test_bad_settings_name_the_field(options, field):
    with pytest.raises(ValueError, match=field):
        make_backend("jax", **options)


def test_registered_by_name():
    assert "jax" in bd.backends.available()
