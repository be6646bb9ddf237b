"""The numba engine of ``backend="exact"`` against the JAX kernel of ``"exact-jax"``.

Both compile the same closed forms and rules (``backends/_closed_form.py``, the model);
the loops and the bisection are written twice. Reference: the JAX kernel, validated by
the seed-000 and record tests. Bounds: every event within 1e-12 s, the same mode
sequence, displacements within 1e-12 relative to max |u| (and 1e-15 m, for a u that
cancels to ~0 from terms of 0.1 m, where XLA's and libm's sine differ by an ulp).
"""

import math
import subprocess
import sys

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from conftest import assert_same_events, load_sample_record, sample_record_paths

import blockdae as bd
from blockdae.sliding import Mode
from blockdae.sliding import _exact_kernel, _exact_numba
from blockdae.core import run_items
from blockdae.sliding._exact import prepare


#: the deprecated many-motion functions keep their tests for the release they stay
pytestmark = [pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_many is deprecated:DeprecationWarning"),
              pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_final is deprecated:DeprecationWarning")]


G = 9.80665
STEMS = [p.name[:-4] for p in sample_record_paths()]
QUICK_STEMS = ("Northridge_1994_PAC-175", "Cape_Mendocino_1992_PET-090", "Kobe_1995_TAK-090")


def assert_engines_agree(block, motion, t_end=None, min_events=0):
    """numba and JAX give the same events (<= 1e-12 s), knots and displacement (1e-12 rel.)."""
    nb = bd.simulate(block, motion, t_end=t_end)
    jx = bd.simulate(block, motion, t_end=t_end, backend="exact-jax")
    assert len(nb.events) >= min_events
    assert_same_events(nb, jx, 1e-12)
    tol = 1e-12 * jx.max_abs_displacement + 1e-15
    assert abs(nb.displacement - jx.displacement) <= tol
    assert abs(nb.max_abs_displacement - jx.max_abs_displacement) <= tol
    np.testing.assert_allclose([e.u for e in nb.events], [e.u for e in jx.events], rtol=0, atol=tol)
    assert nb.t_end == pytest.approx(jx.t_end, rel=1e-14)
    assert nb.stats["max_events_at_one_instant"] == jx.stats["max_events_at_one_instant"]
    np.testing.assert_array_equal(nb.mode, jx.mode)
    return nb


def record_variants(record):
    """One-way Newmark (ky = 0.1 and half the PGA), two-way, f < mu and a bias."""
    mu = 0.5 * record.peak_acceleration / G
    return {"one-way 0.1": bd.SlidingBlock(0.1, direction="negative", g=G),
            "one-way": bd.SlidingBlock(mu, direction="negative", g=G),
            "positive": bd.SlidingBlock(mu, direction="positive", g=G),
            "two-way": bd.SlidingBlock(mu, g=G),
            "f<mu": bd.SlidingBlock(mu, mu_kinetic=0.75 * mu, g=G),
            "bias": bd.SlidingBlock(mu, mu_kinetic=0.8 * mu, bias=0.25 * mu, g=G)}


@pytest.mark.parametrize("example", bd.sliding.seed_examples(), ids=lambda e: e.name)
def test_seed_examples(example):
    """Examples 1-6: harmonic (sine pieces, grazing at f = mu in 3a), pulses until rest."""
    assert_engines_agree(example.block, example.motion, example.t_end, min_events=2)


@pytest.mark.parametrize("example", bd.sliding.seed_examples(), ids=lambda e: e.name)
def test_seed_examples_uncompiled(example):
    """``blockdae examples`` runs the engine's source uncompiled (no compile wait): the same
    events (<= 1e-15 s: only libm's and LLVM's sine may differ, by an ulp), modes, knots
    and displacements (1e-15 relative) as the compiled engine, on the same kind of
    solution."""
    compiled = bd.simulate(example.block, example.motion, t_end=example.t_end)
    uncompiled = bd.sliding.example_solution(example)
    assert type(uncompiled) is type(compiled) and uncompiled.backend == compiled.backend == "exact"
    assert len(compiled.events) >= 2
    assert_same_events(uncompiled, compiled, 1e-15)
    tol = 1e-15 * compiled.max_abs_displacement
    np.testing.assert_allclose([e.u for e in uncompiled.events], [e.u for e in compiled.events], rtol=0, atol=tol)
    assert abs(uncompiled.displacement - compiled.displacement) <= tol
    assert uncompiled.t_end == compiled.t_end
    np.testing.assert_array_equal(uncompiled.mode, compiled.mode)


@pytest.mark.parametrize("stem", QUICK_STEMS)
def test_records_quick(stem):
    record = load_sample_record(stem)
    for block in record_variants(record).values():
        assert_engines_agree(block, record)


@pytest.mark.slow
@pytest.mark.parametrize("stem", [s for s in STEMS if s not in QUICK_STEMS])
def test_records_all(stem):
    """The other 15 of pySLAMMER's 18 sample records, every variant."""
    record = load_sample_record(stem)
    for block in record_variants(record).values():
        assert_engines_agree(block, record)


def _lobes(depth):
    """a - mu g = 0, +1, 0, -depth, 0, +1, 0 m/s² at t = 0..6 s, mu g = 5 m/s² exactly."""
    return bd.Record(5.0 + np.array([0.0, 1.0, 0.0, -depth, 0.0, 1.0, 0.0]), dt=1.0)


RULE_CASES = {  # (block, motion, t_end): the cases of test_rules.py and test_sundials.py
    "threshold": (bd.SlidingBlock(mu=0.5, g=10.0), bd.RectangularPulse(5.0, 1.0), None),
    "above threshold": (bd.SlidingBlock(mu=0.5, g=10.0), bd.RectangularPulse(5.0 * (1 + 1e-9), 1.0), None),
    "bias held": (bd.SlidingBlock(mu=0.5, bias=0.3, g=10.0), bd.RectangularPulse(-1.9, 1.0), None),
    "bias slides": (bd.SlidingBlock(mu=0.5, bias=0.3, g=10.0), bd.RectangularPulse(-2.1, 1.0), None),
    "kinetic and bias": (bd.SlidingBlock(mu=0.5, mu_kinetic=0.3, bias=0.1, g=10.0),
                         bd.RectangularPulse(8.0, 1.0), None),
    "reversal": (bd.SlidingBlock(mu=0.5, g=10.0), bd.Record([8.0, 8.0, -8.0, -8.0, -8.0], dt=1.0), 2.5),
    "onset at 0": (bd.SlidingBlock(mu=0.5, g=10.0), bd.RectangularPulse(7.0, 0.2), None),
    "graze": (bd.SlidingBlock(mu=0.5, g=10.0), _lobes(1.0), None),
    "stop before threshold": (bd.SlidingBlock(mu=0.5, g=10.0), _lobes(1.01), None),
    "cut in slip": (bd.SlidingBlock(mu=0.5, g=10.0), bd.RectangularPulse(8.0, 1.0), 0.5),
    "past the end": (bd.SlidingBlock(mu=0.5, g=10.0), bd.RectangularPulse(8.0, 1.0), 3.0),
    "onset at start wins": (bd.SlidingBlock(mu=0.0625, mu_kinetic=0.0),
                            bd.Record([-1.0] + [1.0] * 47, dt=0.02, units="m/s2"), 1.5),
    "harmonic negative": (bd.SlidingBlock(mu=0.5, g=10.0, direction="negative"), bd.Harmonic(9.0, 1.0), 3.0),
    "harmonic positive": (bd.SlidingBlock(mu=0.5, g=10.0, direction="positive"), bd.Harmonic(9.0, 1.0), 3.0),
    "harmonic f<mu bias": (bd.SlidingBlock(mu=0.3, mu_kinetic=0.2, bias=0.05, g=10.0), bd.Harmonic(5.0, 0.7), 3.0),
    "long harmonic": (bd.SlidingBlock(mu=0.6, mu_kinetic=0.4, bias=0.3), bd.Harmonic(7.0, 1.0), 40.0),
    "barely crossing": (bd.SlidingBlock(mu=0.6), bd.Harmonic(1.0001 * 0.6 * 9.81, 1.0), 2.0),
    "reversal at threshold": (bd.SlidingBlock(mu=0.6), bd.Harmonic(0.6 * 9.81 * math.sqrt(1 + math.pi**2 / 4), 1.0),
                              3.0),
    "demand at threshold": (bd.SlidingBlock(mu=0.5), bd.RectangularPulse(0.5 * 9.81, 0.5), 1.0),
    "ramp onset before a sample": (bd.SlidingBlock(mu=0.2), bd.Record(
        np.where(np.arange(41) <= 20, 1.0, -1.0) * np.minimum(np.arange(41), 40 - np.arange(41))
        * 0.01 * 0.2 * 9.81 / (0.1 - 1e-12), 0.01), None),
    "sine pulse until rest": (bd.SlidingBlock(mu=0.3, mu_kinetic=0.2, bias=-0.1), bd.SinePulse(6.0, 0.8), None),
}


@pytest.mark.parametrize("case", sorted(RULE_CASES))
def test_rule_cases(case):
    assert_engines_agree(*RULE_CASES[case])


def test_grazing_is_one_slide():
    """f = mu: v touches zero at t = 4 s where a reaches mu g and rises on; both engines
    slide on without an event (test_rules.py has the closed forms)."""
    sol = assert_engines_agree(*RULE_CASES["graze"])
    assert [e.mode_after for e in sol.events] == [Mode.SLIP_NEG, Mode.STICK]


def test_never_resting_block_raises():
    block = bd.SlidingBlock(mu=0.5, mu_kinetic=0.2, bias=0.3, g=10.0)
    for backend in ("exact", "exact-jax"):
        with pytest.raises(ValueError, match="never comes to rest"):
            bd.simulate(block, bd.RectangularPulse(-9.0, 1.0), backend=backend)
    grid = bd.SlidingBlock(mu=np.array([0.5, 0.6]), mu_kinetic=np.array([0.45, 0.2]), bias=0.3, g=10.0)
    with pytest.raises(ValueError, match=r"never comes to rest.*\(parameter set 1\)"):
        bd.simulate(grid, bd.RectangularPulse(-9.0, 1.0))


def test_batch_equals_one_by_one(kobe):
    """A batch runs the very loop of a single run, shared among threads or on the calling
    thread (small batches): identical numbers."""
    mu = np.linspace(0.05, 0.3, 16)
    block = bd.SlidingBlock(mu=mu, mu_kinetic=0.9 * mu, bias=0.01, g=G)
    batch = bd.simulate(block, kobe)
    for i in range(len(mu)):
        one = bd.simulate(block.item(i), kobe)
        assert batch.displacement[i] == one.displacement
        assert batch.max_abs_displacement[i] == one.max_abs_displacement
        assert batch.n_events[i] == len(one.events) and batch.t_end[i] == one.t_end
    exc = prepare(kobe.pieces(kobe.duration), 64)
    offsets = np.array([[0, len(exc[0]), 0, len(exc[9])]])
    params = np.stack([block.mu, block.mu_kinetic, np.full(16, 0.01), np.full(16, G), np.ones(16)], axis=1)
    run = _exact_numba.kernels()[1]
    flags = (True, True, np.array([True]))
    shared, alone = np.empty((1, 16, 9)), np.empty((1, 16, 9))
    items = np.arange(16, dtype=np.int64)
    run_items(lambda part: run(exc, offsets, 64, params, flags, part, shared), items, 1.0, 0.0)  # among threads
    run_items(lambda part: run(exc, offsets, 64, params, flags, part, alone), items, 1.0, 2.0)  # on this thread
    np.testing.assert_array_equal(shared, alone)
    jax_batch = bd.simulate(block, kobe, backend="exact-jax")
    np.testing.assert_allclose(batch.displacement, jax_batch.displacement, rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(batch.n_events, jax_batch.n_events)


def test_final_numbers_over_records_and_sets(sample_records):
    """``simulate_final`` over several records (linear and sine pieces) equals the batch of
    each record; a finite t_end applies to every motion."""
    motions = sample_records[:3] + [bd.SinePulse(6.0, 0.8)]
    block = bd.SlidingBlock(mu=np.array([0.05, 0.1, 0.2]), g=G)
    final = bd.sliding.simulate_final(block, motions)
    assert final.displacement.shape == (4, 3)
    for i, motion in enumerate(motions):
        batch = bd.simulate(block, motion)
        np.testing.assert_array_equal(final.displacement[i], batch.displacement)
        np.testing.assert_array_equal(final.n_events[i], batch.n_events)
        np.testing.assert_array_equal(final.t_end[i], batch.t_end)
    cut = bd.sliding.simulate_final(block.item(1), motions, t_end=5.0)
    assert cut.displacement.shape == (4,) and np.allclose(cut.t_end, 5.0, rtol=1e-15)
    assert cut.displacement[0] == bd.simulate(block.item(1), motions[0], t_end=5.0).displacement


def test_bisections_are_twins():
    """The one rule written twice, the bisection, finds the same root in both engines."""
    cf = (0.3, 0.0, 2.0, 5.0, 0.4)
    with jax.enable_x64(True):
        run_jax = _exact_kernel._bisect(lambda d: _exact_kernel.onset_gap(cf, d, 1.1, jnp), jnp.float64(0.0),
                                        jnp.float64(0.3))
    run_numba = _exact_numba._bisect(_exact_kernel.onset_gap, cf, 0.0, 0.3, 1.1, np)
    assert float(run_jax) == pytest.approx(run_numba, abs=1e-15)
    assert math.isclose(0.3 + 2.0 * math.sin(5.0 * run_numba + 0.4), 1.1, abs_tol=1e-14)


def test_event_log_reads_like_a_tuple(kobe):
    sol = bd.simulate(bd.SlidingBlock(mu=0.1, direction="negative", g=G), kobe)
    events = sol.events
    assert isinstance(events, bd.sliding.EventLog) and len(events) == len(tuple(events)) > 2
    assert events == tuple(events) and tuple(events) == events and events[1:] == tuple(events)[1:]
    assert events[-1] is events[len(events) - 1] and events[0].mode_after == Mode.SLIP_NEG
    np.testing.assert_array_equal(sol.t_events, [e.t for e in events])
    with pytest.raises(AttributeError):
        events.t = None
    with pytest.raises(ValueError):
        events.t[0] = 1.0


def test_compiled_once_then_loaded_from_disk():
    """A fresh process loads the compiled engine from numba's on-disk cache (this
    process has filled it) and does not import JAX."""
    code = ("import sys, blockdae as bd\n"
            "bd.simulate(bd.SlidingBlock(0.2), bd.Record([0.0, 3.0, -3.0, 0.0], 0.1))\n"
            "from blockdae.sliding import _exact_numba\n"
            "stats = _exact_numba.kernels()[0].stats\n"
            "print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()), 'jax' in sys.modules)")
    bd.simulate(bd.SlidingBlock(0.2), bd.Record([0.0, 3.0, -3.0, 0.0], 0.1))
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout
    assert out.split() == ["1", "0", "False"]


def test_a_fresh_run_imports_no_scipy_module_that_it_does_not_use():
    """``import blockdae`` and a first run of the rigid block leave scipy.stats,
    scipy.special and scipy.optimize unimported (together about 1.5 s of a fresh process
    on 2 cores): the regressions, the fragilities and the closed-form linear steps import
    them on use."""
    code = ("import sys, blockdae as bd\n"
            "bd.simulate(bd.SlidingBlock(0.2), bd.Record([0.0, 3.0, -3.0, 0.0], 0.1))\n"
            "print(*(name in sys.modules for name in ('scipy.stats', 'scipy.special', 'scipy.optimize')))")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout
    assert out.split() == ["False", "False", "False"]


def test_a_run_without_events_has_dense_output():
    """A block that never slides (mu g above the peak of a(t)) has no event; its dense
    output is u = v = 0 at every time, where the mode lookup once indexed an empty log."""
    sol = bd.simulate(bd.SlidingBlock(mu=0.5), bd.Harmonic(amplitude=1.0, period=1.0), t_end=2.0)
    assert len(sol.events) == 0
    u, v = sol(np.array([0.0, 0.7, 2.0]))
    assert np.array_equal(u, np.zeros(3)) and np.array_equal(v, np.zeros(3))
