"""The fast paths of ``bd.flexible`` (issue 22): its event search (``flexible_mass._roots``)
against the linear engine's bisection on the same forms, and a batch run in parallel
against the same batch run serially."""

import inspect
import math

import numba
import numpy as np
import pytest

import blockdae as bd
from blockdae.solvers import _linear
from blockdae.flexible_mass import _analysis, _engine, _fused, _roots
from conftest import load_sample_record

_EPS = np.finfo(float).eps


def _random_form(rng):
    """A cubic plus a damped oscillation, of the sizes of the engine's guards, positive
    at 0 (a guard that may fall through zero)."""
    q = rng.normal(size=4) * np.array([0.1, 50.0, 1e3, 1e4])
    C, D = rng.normal(size=2)
    q[0] = 0.1 * abs(q[0]) - C
    return (q[0], q[1], q[2], q[3], C, D, abs(rng.normal()) * 10.0, 5.0 + abs(rng.normal()) * 100.0)


def test_first_fall_matches_the_linear_engines_search():
    """Reference: engines/_linear's _down_crossing_search (bisection to adjacent floats of
    tau) on 300 random forms over a 5 ms step at t = 10 s: the same crossing or none,
    within one ulp of the time (the resolution _roots bisects to)."""
    rng = np.random.default_rng(22)
    origin, span, found = 10.0, 0.005, 0
    stack_linear = np.empty((_linear.STACK_DEPTH, 4))
    stack = np.empty((_linear.STACK_DEPTH, _roots.STACK_COLUMNS))
    for _ in range(300):
        f = _random_form(rng)
        f1 = _linear.form_derivative(f)
        f2 = _linear.form_derivative(f1)
        f3 = _linear.form_derivative(f2)
        expected = _linear._down_crossing_search(f, f1, f2, f3, 0.0, span, origin, stack_linear)
        trig = math.exp(-f[6] * span), math.cos(f[7] * span), math.sin(f[7] * span)
        root = _roots.first_fall(f, f1, f2, f3, span, origin, stack, *trig)
        if math.isnan(expected):
            assert math.isnan(root)
        else:
            found += 1
            assert abs(root - expected) <= 2 * _EPS * origin
            assert _linear.evaluate_form(f, root) <= 0
    assert found >= 30  # the draw has crossings to compare


@pytest.mark.parametrize("slopes", ["known", "unknown"])
def test_sign_change_brackets_the_root_to_an_ulp_of_the_time(slopes):
    """f = 2 e^{-tau} - 1 falls through zero at ln 2: the result r has f(r) <= 0 and f > 0
    one ulp of the time (origin 10 s) before it, and r is within that of ln 2; from the
    Hermite start (the ends' slopes known) and from an end (slopes nan)."""
    f = (-1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 1.0, 0.0)
    f1 = _linear.form_derivative(f)
    origin = 10.0
    d_lo, d_hi = (_linear.evaluate_form(f1, 0.0), _linear.evaluate_form(f1, 1.0)) if slopes == "known" else (math.nan, math.nan)
    r = _roots.sign_change(f, f1, 0.0, _linear.evaluate_form(f, 0.0), d_lo, 1.0, _linear.evaluate_form(f, 1.0), d_hi, origin)
    assert _linear.evaluate_form(f, r) <= 0 < _linear.evaluate_form(f, r - _EPS * origin)
    assert abs(r - math.log(2.0)) <= 2 * _EPS * origin


def test_scans_by_bit_patterns_equal_numpy():
    """The scans that compare bounds by their bit patterns (``_fused._bits``) against
    numpy on the floats: max |x[1:]| of signed values, and the first bound >= a level
    from each start, on bounds with zeros, infinities, runs longer than a chunk below the
    level and levels 0, a bound's own value and its neighbours."""
    rng = np.random.default_rng(7)
    x = rng.standard_normal(1001) * 10.0 ** rng.integers(-3, 3, 1001)
    largest = numba.njit(_fused._largest)
    assert largest(x) == np.abs(x[1:]).max()
    reach = np.abs(rng.standard_normal(700))
    reach[rng.integers(0, 700, 40)] = 0.0
    reach[[3, 411]] = np.inf
    reach[100:300] *= 1e-3  # a quiet stretch of several chunks
    bits = reach.view(np.int64)
    first = numba.njit(_fused._first_reaching)
    for level in (0.0, 0.5, reach[250], np.nextafter(reach[250], np.inf), 2.5, np.inf):
        for start in (0, 2, 4, 99, 100, 250, 650, 699, 700):
            hits = np.flatnonzero(reach[start:] >= level)
            assert first(bits, start, level) == (start + hits[0] if hits.size else reach.size), (level, start)


def test_the_serial_kernel_is_a_function_of_its_own():
    """numba's cache key omits ``parallel``: compiled from one function, the serial and
    the parallel kernel would share one cache entry, and the serial one could load the
    parallel one (a parallel region per call, an OpenMP worker left spinning). They come
    from two functions, the serial one without prange."""
    parallel, serial = _fused.kernels()
    assert parallel.py_func is not serial.py_func
    assert "prange" in inspect.getsource(parallel.py_func)
    assert "prange" not in inspect.getsource(serial.py_func)


@pytest.mark.parametrize("method", ["coupled", "decoupled"])
def test_a_parallel_batch_equals_the_serial_one(method, monkeypatch):
    """Two records x four parameter sets, both polarities: the rows of the batch run in
    parallel over cores equal those run serially, to the last bit."""
    records = {stem: bd.Record(load_sample_record(stem).acceleration_samples[:301],
                               load_sample_record(stem).dt, name=stem, units="m/s2")
               for stem in ("Northridge_1994_PAC-175", "Cape_Mendocino_1992_PET-090")}
    args = dict(ky=[0.05, 0.1, 0.1, 0.2], height=[5.0, 10.0, 20.0, 10.0], vs=250.0, method=method)
    tables = []
    for work in (0.0, math.inf):
        monkeypatch.setattr(_analysis, "PARALLEL_WORK", work)
        tables.append(bd.flexible(records, **args).to_dataframe())
    for column in ("normal_m", "inverse_m", "kmax_g", "kmax_sup_g", "episodes_normal", "episodes_inverse"):
        np.testing.assert_array_equal(tables[0][column].to_numpy(float), tables[1][column].to_numpy(float))
    assert (tables[0]["episodes_normal"] > 0).any()


@pytest.mark.parametrize("count", [1, 2, 3, 7, 64, 999])
def test_free_steps_at_once_equal_the_steps_one_by_one(count):
    """Reference: the free STICK oscillation stepped one step at a time by its step map
    (the path the jump replaces, xi = 0.25 as PAC-175's column): the jump by powers of the
    map gives du, du' within 1e-13 of the largest it reached (the products' rounding over
    up to 999 steps), and a bound of its |HEA| no smaller than the one stepped."""
    omega, xi, step = 47.12388980384689, 0.25, 0.02
    damped = _engine._damped(omega, xi, True)
    maps, table = _engine._step_tables(omega, xi, True, 0.98, damped, step)
    m, row = maps[_engine.STICK], table[_engine.STICK]
    powers = _fused._free_powers(m, row, step, 1000, np.empty(64 * 5))
    du, dv, bound = 1e-3, -0.02, 2.5
    ref_u, ref_v, ref_bound, largest = du, dv, bound, max(abs(du), abs(dv))
    for _ in range(count):
        ref_u, ref_v = m[0] * ref_u + m[1] * ref_v, m[2] * ref_u + m[3] * ref_v
        ref_bound *= powers[0, 4]
        largest = max(largest, abs(ref_u), abs(ref_v))
    jump_u, jump_v, jump_bound = _fused._free_steps(powers, count, du, dv, bound)
    assert abs(jump_u - ref_u) <= 1e-13 * largest and abs(jump_v - ref_v) <= 1e-13 * largest
    assert jump_bound >= ref_bound >= bound * math.exp(-xi * omega * step * count)


def test_a_warm_call_checks_every_call_and_returns_rows_of_its_own():
    """A repeated call (its analyses and compiled input kept) still warns on every call
    about an implausible height, gives the same numbers, and rows that the caller may
    change without changing the next call's."""
    record = bd.Record(load_sample_record("Northridge_1994_PAC-175").acceleration_samples[:301], 0.02,
                       name="PAC-175", units="m/s2")
    results = []
    for _ in range(3):
        with pytest.warns(bd.UnitsWarning, match="height=0.3 m is implausible"):
            results.append(bd.flexible(record, ky=0.1, height=0.3, vs=300.0, polarity="normal"))
    results[0].rows[0]["normal_m"] = -1.0
    assert results[1].rows == results[2].rows and results[1].rows[0]["normal_m"] > 0
    assert results[1].rows[0] is not results[2].rows[0]
    with pytest.warns(bd.UnitsWarning):  # planned afresh: nothing kept
        analyses = _analysis._plan(record, 0.1, 0.3, 300.0, None, 0.05, "coupled", False, None, None, "normal",
                                   "exact", bd.STANDARD_GRAVITY, None, True)
    fresh = _analysis.exact_rows(analyses)
    assert fresh == results[2].rows
