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
# each case's bars (event times and t_end [s], u(t_end) relative [-]), a decade above the
# agreement measured (written beside): the twin steps through a harmonic (its tolerances
# show), while pulses and records are linear between breakpoints (closed forms, to rounding)
SEED_BARS = {
    "ex1": (6.4e-12, 8.8e-9),  # measured 6.42e-13 s, 8.83e-10
    "ex2": (1.8e-11, 4.1e-10),  # measured 1.78e-12 s, 4.12e-11
    "ex3a": (2.6e-11, 1.5e-10),  # measured 2.58e-12 s, 1.52e-11
    "ex3b": (4.3e-11, 1.3e-10),  # measured 4.32e-12 s, 1.32e-11
    "ex4": (4.4e-15, 3.2e-13),  # measured 4.44e-16 s, 3.24e-14
    "ex5": (2.8e-15, 1.8e-14),  # measured 2.78e-16 s, 1.78e-15
    "ex6": (2.4e-12, 1.5e-10),  # measured 2.42e-13 s, 1.50e-11
}


def assert_twins(exact, twin, dt_max, du_max):
    """Same event sequence; event times and t_end within ``dt_max`` [s]; u(t_end) within
    ``du_max`` relative."""
    assert_same_events(twin, exact, dt_max)
    np.testing.assert_allclose(twin.displacement, exact.displacement, rtol=du_max, atol=0)
    np.testing.assert_allclose(twin.t_end, exact.t_end, rtol=0, atol=dt_max)


@pytest.mark.parametrize("name", SEED_EXAMPLES)
def test_seed_examples_agree_with_exact(name):
    """Reference: the exact backend (closed forms, verified against seed 000), the
    package's own other path."""
    block, motion, t_end = SEED_EXAMPLES[name]
    assert_twins(bd.simulate(block, motion, t_end), bd.simulate(block, motion, t_end, backend="jax"),
                 *SEED_BARS[name])


def test_example1_event_times_from_the_closed_form():
    """Reference: the closed form of Sawicki & Chybicki's (2005) Example 1 (onset where
    9 sin(2 pi t) = 0.6 g, stop where the slip velocity returns to zero), to the six
    digits written here (the paper prints 0.1125 or 0.113 s, 0.535 s, 0.614 s and 1.035 s)."""
    block, motion, t_end = SEED_EXAMPLES["ex1"]
    t = bd.simulate(block, motion, t_end, backend="jax").t_events
    np.testing.assert_allclose(t[:4], [0.113455, 0.535036, 0.613455, 1.035036], atol=1e-6)


# the bars a decade above the measured agreement (event times [s], u relative [-]); on
# all 18 sample records benchmarks/jax_twin.py measures 3.6e-15 s and 1.2e-14 and asserts
# a decade above (run by tests/test_benchmarks_slow.py)
@pytest.mark.parametrize("stem, block, bars", [
    ("Kobe_1995_TAK-090", bd.SlidingBlock(0.3, 0.22, bias=0.05), (8.9e-15, 2.2e-15)),  # 8.88e-16 s, 2.22e-16
    ("Kobe_1995_TAK-090", bd.SlidingBlock(0.15), (2.2e-15, 4.7e-14)),  # many reversals, f = mu: 0 s, 4.66e-15
    ("Northridge_1994_PAC-175", bd.SlidingBlock(0.25, 0.2, bias=-0.05), (2.2e-15, 3.3e-15)),  # 0 s, 3.33e-16
    ("Northridge_1994_PAC-175", bd.SlidingBlock(0.1, direction="negative"), (2.2e-15, 7.8e-15)),  # 0 s, 7.77e-16
])
def test_real_records_agree_with_exact(stem, block, bars):
    """Reference: the exact backend on pySLAMMER's sample records (m/s²), the package's
    own other path (closed forms on each piece; the twin integrates the same rules with
    diffrax). Where the measured difference is 0, the bar is 10 ulps of the times."""
    record = load_sample_record(stem)
    assert_twins(bd.simulate(block, record), bd.simulate(block, record, backend="jax"), *bars)


def test_batch_is_vectorised_and_matches_single_runs():
    """One vmapped call equals the exact batch and the twin's own single runs."""
    record = load_sample_record("Northridge_1994_PAC-175")
    block = bd.SlidingBlock(np.array([0.1, 0.25, 0.4]), np.array([0.08, 0.2, 0.3]), bias=0.02)
    twin = bd.simulate(block, record, backend="jax")
    exact = bd.simulate(block, record)
    assert isinstance(twin, bd.core.BatchSolution) and twin.backend == "jax"
    np.testing.assert_allclose(twin.displacement, exact.displacement, rtol=1.8e-14)  # measured 1.78e-15
    np.testing.assert_array_equal(twin.n_events, exact.n_events)
    np.testing.assert_allclose(twin.displacement[1], twin[1].displacement, rtol=1.1e-15)  # measured 1.1e-16


def test_other_solver_agrees():
    """Dopri8 on the sine pulse (Example 6): reference the exact backend. Measured
    5.55e-16 s and 3.18e-14 relative; the bars a decade above."""
    block, motion, _ = SEED_EXAMPLES["ex6"]
    assert_twins(bd.simulate(block, motion), bd.simulate(block, motion, backend="jax", solver="dopri8"),
                 5.6e-15, 3.2e-13)


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
