"""The free-standing block (Housner 1963): closed forms of the linearised block, the
quadrature of the exact one, agreement of the backends, and the sliding regime.

References: the linearised block's free rocking in closed form (cosh; each arc 2
atanh(w / (p alpha)) / p; impact velocities times r), summed in 40-digit mpmath;
Housner's (1963) rectangular-pulse criterion a_p / (g alpha) > 1 / (1 - exp(-p t_d));
the exact block's energy integral theta'² / 2 = p² [cos(alpha - theta0) - cos(alpha -
theta)] integrated by mpmath's tanh-sinh quadrature; the 1-D SlidingBlock for mu < b/h.
"""

import math

import mpmath
import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import RockingBlock, RockingMode, housner_restitution
from conftest import load_sample_record

G = bd.STANDARD_GRAVITY
QUIET = bd.Record(np.zeros(3), 0.01, name="no shaking", units="m/s2")
mpmath.mp.dps = 40


def free_rocking_times(block, theta0):
    """Impact times [s] of the linearised block released at ``theta0`` [rad] (closed form,
    mpmath), and the accumulation point of the whole series [s]."""
    p, r, alpha = mpmath.mpf(block.frequency), mpmath.mpf(block.r), mpmath.mpf(block.alpha)
    theta0 = mpmath.mpf(theta0)
    times = [mpmath.acosh(alpha / (alpha - theta0)) / p]
    w = p * mpmath.sqrt(alpha**2 - (alpha - theta0) ** 2)
    while True:
        w *= r
        arc = 2 * mpmath.atanh(w / (p * alpha)) / p
        times.append(times[-1] + arc)
        if arc < mpmath.mpf(10) ** -30:
            return np.array([float(t) for t in times[:-1]]), float(times[-1])


@pytest.fixture(scope="module")
def linear_free():
    block = RockingBlock(b=0.2, h=1.0, mu=0.5, linearised=True)
    block = block.replace(theta0=block.alpha / 2)
    return block, bd.simulate(block, QUIET, backend="cvode", rtol=1e-12, atol=1e-14)


def test_housner_restitution_and_frequency():
    """r = 1 - 3/2 sin² alpha and p = sqrt(3 g / (4 R)) of a uniform block."""
    block = RockingBlock(b=0.3, h=1.2, mu=0.6)
    assert block.r == housner_restitution(math.atan(0.25)) == 1 - 1.5 * math.sin(math.atan(0.25)) ** 2
    assert block.frequency == pytest.approx(math.sqrt(0.75 * G / math.hypot(0.3, 1.2)), rel=1e-15)


def test_linearised_free_rocking_first_impacts_closed_form(linear_free):
    """Linearised free rocking from alpha/2: the impact times against the closed form.
    CVODE at rtol 1e-12 locates the first impact to 1e-11 s (measured 6e-12 s) and the
    first ten to 1e-9 s (measured 1.4e-10 s); the error grows as the arcs shorten."""
    block, sol = linear_free
    times, _ = free_rocking_times(block, block.alpha / 2)
    located = sol.impact_times
    assert abs(located[0] - times[0]) < 1e-11
    assert np.max(np.abs(located[:10] - times[:10])) < 1e-9
    # every impact multiplies theta' by r, and the pivot switches side
    for event in sol.impacts:
        assert event.rate_after == pytest.approx(block.r * event.rate, rel=1e-15)
        assert np.sign(int(event.mode_after)) == -np.sign(int(event.mode_before))


def test_linearised_free_rocking_every_impact_closed_form_exact_engine():
    """The compiled closed form (backend "exact") locates every impact of the linearised
    block released from alpha/2 to 1e-12 s of the closed form (measured 2e-14 s over 186
    impacts), and the rest at the accumulation point of the whole series to 1e-12 s
    (measured 1.2e-14 s): the tail summed past the last located impact."""
    block = RockingBlock(b=0.2, h=1.0, mu=0.5, linearised=True)
    block = block.replace(theta0=block.alpha / 2)
    sol = bd.simulate(block, QUIET, backend="exact")
    times, t_rest = free_rocking_times(block, block.alpha / 2)
    assert 100 < len(sol.impacts) < len(times)
    assert np.max(np.abs(sol.impact_times - times[:len(sol.impacts)])) < 1e-12
    assert sol.events[-2].kind == "zeno" and sol.events[-1].kind == "rest"
    assert abs(sol.rest_time - t_rest) < 1e-12


def test_exact_engine_agrees_with_cvode_under_a_record():
    """Under a record the compiled closed form and CVODE (rtol 1e-12) locate the same
    events of the linearised block (measured 1.3e-11 s) and the same dense motion."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    record = bd.Record(0.7 * kobe.acceleration_samples[:600], kobe.dt, name="Kobe TAK-090, 0-6 s, x 0.7",
                       units="m/s2")
    block = RockingBlock(b=0.3, h=0.9, mu=0.8, linearised=True)
    reference = bd.simulate(block, record, t_end=6.0, backend="cvode", rtol=1e-12)
    exact = bd.simulate(block, record, t_end=6.0, backend="exact")
    assert [e.kind for e in exact.events] == [e.kind for e in reference.events]
    assert len(exact.impacts) >= 4
    assert np.max(np.abs(np.array([e.t for e in exact.events]) - [e.t for e in reference.events])) < 1e-10
    t = np.linspace(0.0, 6.0, 3001)
    assert np.max(np.abs(exact(t)[0] - reference(t)[0])) < 1e-8 * block.alpha


def test_linearised_free_rocking_zeno_rest(linear_free):
    """The rest comes at the accumulation point of the impact series (closed form) after
    finitely many located impacts and one summed tail; theta is 0 from then on."""
    block, sol = linear_free
    times, t_rest = free_rocking_times(block, block.alpha / 2)
    assert sol.events[-1].kind == "rest" and sol.events[-2].kind == "zeno"
    assert 50 < len(sol.impacts) < len(times)
    assert abs(sol.rest_time - t_rest) < 1e-6 * t_rest
    assert 0 < sol.zeno_tail < 1e-3
    assert sol.mode[-1] == RockingMode.REST and sol.state[-1, 0] == 0.0


def test_housner_rectangular_pulse_threshold():
    """The linearised block under a rectangular pulse toward the side that tilts it
    overturns iff a_p / (g alpha) > 1 / (1 - exp(-p t_d)) (Housner 1963): bisection on
    the amplitude (the compiled closed form, until rest or overturning) finds the
    threshold to 1e-9 relative; just above overturns, just below does not."""
    block = RockingBlock(b=0.25, h=1.5, mu=0.8, linearised=True)
    t_d = 0.4
    threshold = 1.0 / (1.0 - math.exp(-block.frequency * t_d))

    def overturns(ratio):
        pulse = bd.RectangularPulse(-ratio * G * block.alpha, t_d)
        return bd.simulate(block, pulse, backend="exact").overturned

    low, high = 0.98 * threshold, 1.02 * threshold
    assert overturns(high) and not overturns(low)
    while high - low > 1e-9 * threshold:
        mid = 0.5 * (low + high)
        low, high = (low, mid) if overturns(mid) else (mid, high)
    assert abs(0.5 * (low + high) - threshold) < 1e-9 * threshold


def test_exact_free_rocking_first_impact_quadrature():
    """The exact block released at theta0: its first impact time is the quadrature of
    dtheta / theta' with theta'² = 2 p² [cos(alpha - theta0) - cos(alpha - theta)]."""
    block = RockingBlock(b=0.3, h=0.9, mu=0.7, theta0=0.2)
    sol = bd.simulate(block, QUIET, t_end=1.5, backend="cvode", rtol=1e-12, atol=1e-14)
    p, alpha, theta0 = (mpmath.mpf(v) for v in (block.frequency, block.alpha, block.theta0))
    rate = lambda theta: p * mpmath.sqrt(2 * (mpmath.cos(alpha - theta0) - mpmath.cos(alpha - theta)))
    t1 = float(mpmath.quad(lambda theta: 1 / rate(theta), [0, theta0]))
    assert abs(sol.impact_times[0] - t1) < 1e-10
    assert sol.impacts[0].rate == pytest.approx(-float(rate(0)), rel=1e-9)


def test_backends_agree_on_impacts_under_a_record():
    """CVODE, IDA and the JAX twin locate the same impacts under a recorded motion (Kobe
    TAK-090, its first 6 s at 0.7 times, so that a 0.6 m x 1.8 m block rocks without overturning):
    against CVODE at rtol 1e-12."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    record = bd.Record(0.7 * kobe.acceleration_samples[:600], kobe.dt, name="Kobe TAK-090, 0-6 s, x 0.7",
                       units="m/s2")
    block = RockingBlock(b=0.3, h=0.9, mu=0.8)
    reference = bd.simulate(block, record, t_end=6.0, backend="cvode", rtol=1e-12, atol=1e-14)
    assert len(reference.impacts) >= 4 and not reference.overturned
    # bars a decade above the worst differences measured: 5.3e-10 s (CVODE), 2.3e-9 s (IDA),
    # 8.1e-11 s (JAX), each at its default tolerances (rtol 1e-10)
    for backend, bar in (("cvode", 5e-9), ("ida", 3e-8), ("jax", 1e-9)):
        sol = bd.simulate(block, record, t_end=6.0, backend=backend)
        assert len(sol.impacts) == len(reference.impacts), backend
        assert np.max(np.abs(sol.impact_times - reference.impact_times)) < bar, backend


def test_slides_exactly_as_the_sliding_block():
    """mu < b/h: the block slides, never rocks, and its displacement is bit-identical to
    the SlidingBlock's on CVODE under the same record (Kobe TAK-090, 10 s)."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    block = RockingBlock(b=0.5, h=0.6, mu=0.3)
    assert block.slides
    rocking = bd.simulate(block, kobe, t_end=10.0, backend="cvode")
    sliding = bd.simulate(bd.SlidingBlock(mu=0.3), kobe, t_end=10.0, backend="cvode")
    assert rocking.displacement == sliding.displacement != 0.0
    assert np.array_equal(rocking.state, np.column_stack([sliding.u, sliding.v]))
    assert [e.t for e in rocking.events] == [e.t for e in sliding.events]
    assert {int(m) for m in rocking.mode} <= {-1, 0, 1}


def test_overturns_and_passes_alpha_first():
    """A strong pulse overturns the exact block: it passes alpha before it lies on its side."""
    block = RockingBlock(b=0.1, h=0.5, mu=0.6)
    sol = bd.simulate(block, bd.SinePulse(-1.0 * G, 0.6), backend="cvode")
    assert sol.overturned and 0 < sol.time_beyond_alpha < sol.overturn_time
    assert sol.state[-1, 0] == pytest.approx(math.pi / 2, abs=0)


def test_bad_input_names_the_field():
    with pytest.raises(ValueError, match="restitution"):
        RockingBlock(b=0.2, h=1.0, mu=0.5, restitution=1.5)
    with pytest.raises(ValueError, match="theta0"):
        RockingBlock(b=0.5, h=0.6, mu=0.3, theta0=0.1)


def test_contact_limits_located_and_reported():
    """Under Kobe TAK-090 a 0.2 m x 1 m block with mu = 0.3 rocks and overturns; on its way
    the base friction it needs reaches mu N: located where mu N - |F| is zero (to the dense
    output's error), listed on the solution without a warning, and an error naming the
    time with strict."""
    import warnings

    kobe = load_sample_record("Kobe_1995_TAK-090")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", bd.CompileNotice)  # a first run in a fresh cache compiles: not a contact limit
        sol = bd.simulate(RockingBlock(b=0.1, h=0.5, mu=0.3), kobe, t_end=6.0)
    assert sol.overturned and not sol.contact_holds
    slips = [row for row in sol.contact_events if row.kind == "slip_limit"]
    assert slips and slips[0].t < sol.overturn_time
    t, _, theta, rate, force, normal = slips[0]
    assert normal > 0 and abs(0.3 * normal - abs(force)) < 1e-6 * normal
    assert sol.check_contact() == sol.contact_events
    assert str(slips[0]).startswith(f"at t = {t:.9f} s the contact force leaves its limits (|F| >= mu N")
    with pytest.raises(ValueError, match=f"t = {sol.contact_events[0].t:.9f} s"):
        sol.check_contact(strict=True)


def test_vertical_shaking_scales_gravity():
    """Under a constant a_z the block rocks as under gravity g + a_z: the linearised
    block's first impact from alpha/2 is acosh(2) / p_e with p_e² = p² (g + a_z) / g
    (closed form); a base falling faster than g is an error naming the time."""
    block = RockingBlock(b=0.2, h=1.0, mu=0.5, linearised=True)
    block = block.replace(theta0=block.alpha / 2)
    quiet = bd.Record(np.zeros(301), 0.01, name="no shaking", units="m/s2")
    down = bd.Record(np.full(301, -0.4 * G), 0.01, name="a_z = -0.4 g", units="m/s2")
    sol = bd.simulate(block, bd.BaseMotion(quiet, z=down), t_end=3.0, backend="cvode", rtol=1e-12)
    p_e = block.frequency * math.sqrt(0.6)
    assert abs(sol.impact_times[0] - math.acosh(2.0) / p_e) < 1e-10
    falling = bd.Record(np.concatenate([np.zeros(50), np.full(251, -1.2 * G)]), 0.01, name="free fall",
                        units="m/s2", check_peak=False)
    with pytest.raises(ValueError, match=r"at t = 0\.49\d* s the base falls faster than g"):
        bd.simulate(RockingBlock(b=0.2, h=1.0, mu=0.5), bd.BaseMotion(quiet, z=falling), t_end=3.0)


def test_strict_stops_where_the_contact_force_leaves_its_limits():
    """strict=True: the run stops with an error at the first contact limit, located as a
    guard, at the time check_contact() locates on the dense output of the run that goes
    on (within 1e-6 s: the dense output's error)."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    block = RockingBlock(b=0.1, h=0.5, mu=0.3)
    goes_on = bd.simulate(block, kobe, t_end=6.0)
    first = goes_on.contact_events[0]
    with pytest.raises(ValueError, match="strict=True stops here") as error:
        bd.simulate(block.replace(strict=True), kobe, t_end=6.0)
    t_stop = float(str(error.value).split("at t = ")[1].split(" s")[0])
    assert abs(t_stop - first[0]) < 1e-6


def test_a_base_falling_faster_than_g_while_sliding_is_an_error():
    """A block that slides (mu < b/h) when the base starts to fall faster than g: every
    generic backend stops with an error naming the time where g + a_z reaches 0 (a_z
    ramps from 0 to -1.2 g over [0.49, 0.50] s: the closed form 0.49 + 0.01 / 1.2 s)."""
    t = np.arange(301) * 0.01
    x = bd.Record(0.6 * G * np.sin(np.pi * t), 0.01, name="half sine 0.6 g", units="m/s2")
    falling = bd.Record(np.concatenate([np.zeros(50), np.full(251, -1.2 * G)]), 0.01, name="free fall",
                        units="m/s2", check_peak=False)
    block = RockingBlock(b=0.5, h=0.6, mu=0.3)
    before = bd.simulate(block, bd.BaseMotion(x), t_end=0.49)
    assert before.mode[-1] == RockingMode.SLIDE_NEG  # sliding when the fall begins
    for backend in ("cvode", "ida"):
        with pytest.raises(ValueError, match=r"at t = 0\.49833333333\d* s the base falls faster than g") as error:
            bd.simulate(block, bd.BaseMotion(x, z=falling), t_end=3.0, backend=backend)
        value = float(str(error.value).split("g + a_z = ")[1].split(" m/s²")[0])
        assert abs(value) < 1e-9


def test_simulate_lists_where_the_contact_force_leaves_its_limits_on_every_backend():
    """A plain bd.simulate lists on the solution (no warning) the time, theta, F and N of
    every contact limit, the first a slip limit, on every backend that runs the block, for
    one motion and for many; strict=True stops there with an error naming the time. The
    linearised block (mu = 0.21, b/h = 0.2) under Kobe TAK-090's first 6 s at 0.7 times
    needs more friction than mu N while it rocks: every backend's first limit and error name
    that time as CVODE at rtol 1e-12 locates it (within 5e-10 s; the located times measured
    within 2e-14 s of it). A block that only rocks within its limits lists none."""
    import warnings

    kobe = load_sample_record("Kobe_1995_TAK-090")
    record = bd.Record(0.7 * kobe.acceleration_samples[:600], kobe.dt, name="Kobe TAK-090, 0-6 s, x 0.7",
                       units="m/s2")
    block = RockingBlock(b=0.2, h=1.0, mu=0.21, linearised=True)
    reference = bd.simulate(block, record, t_end=6.0, backend="cvode", rtol=1e-12).contact_events
    assert reference and reference[0][1] == "slip_limit"
    t_first = reference[0][0]
    backends = bd.backends.available(block)
    assert {"cvode", "ida", "jax", "exact"} <= set(backends)
    for backend in backends:
        with warnings.catch_warnings():
            warnings.simplefilter("error", UserWarning)
            limits = bd.simulate(block, record, t_end=6.0, backend=backend).contact_events
        assert limits[0].kind == "slip_limit" and abs(limits[0].t - t_first) <= 5e-10, backend
        assert limits[0].normal > 0 and abs(0.21 * limits[0].normal - abs(limits[0].force)) < 1e-6 * limits[0].normal
        with pytest.raises(ValueError, match="at t = ") as error:
            bd.simulate(block.replace(strict=True), record, t_end=6.0, backend=backend)
        message = str(error.value)
        assert abs(float(message.split("at t = ")[1].split(" s")[0]) - t_first) <= 5e-10, backend
        assert "F = " in message and "N = " in message and "|F| >= mu N" in message
    ensemble = bd.simulate(block, [record, QUIET], t_end=6.0, backend="exact")
    assert len(ensemble) == 2 and ensemble[0].contact_events[0].t == pytest.approx(t_first, abs=5e-10)
    assert ensemble[1].contact_holds
    assert bd.simulate(block.replace(mu=0.8), record, t_end=6.0, backend="exact").contact_holds


@pytest.mark.parametrize("backend, final_only", [("cvode", False), ("compiled", False), ("compiled", True)])
def test_ensemble_table_states_radians_and_overturning(backend, final_only):
    """The ensemble table of a rocking block held radians in ``theta_end_m`` and
    ``max_abs_displacement_m``: its columns are named in radians, with ``overturned`` and
    ``max_theta_over_alpha``, each equal to the row's own solution (run again); a block
    that slides keeps metres, never overturns."""
    block = RockingBlock(b=0.1, h=0.5, mu=0.6)
    motions = {"strong": bd.SinePulse(-1.0 * G, 0.6), "weak": bd.SinePulse(-0.3 * G, 0.6)}
    ensemble = bd.simulate(block, motions, scale=[0.5, 0.75, 1.0], backend=backend, final_only=final_only)
    table = ensemble.to_dataframe()
    solutions = [ensemble[i] for i in range(len(ensemble))]
    assert {"theta_end_rad", "max_abs_displacement_rad", "overturned", "max_theta_over_alpha"} <= set(table)
    assert not any(c.endswith("_m") for c in table)
    assert table["overturned"].tolist() == [s.overturned for s in solutions]
    assert table["max_theta_over_alpha"].tolist() == [s.max_theta_over_alpha for s in solutions]
    np.testing.assert_array_equal(table["max_theta_over_alpha"], table["max_abs_displacement_rad"] / block.alpha)
    assert table["overturned"].any() and not table["overturned"].all()
    assert ((table["max_theta_over_alpha"] > 0) & ~table["overturned"]).any()  # a row that rocks and stays up
    sliding = bd.simulate(RockingBlock(b=0.3, h=0.5, mu=0.2), motions, backend="cvode").to_dataframe()
    assert {"u_end_m", "max_abs_displacement_m"} <= set(sliding) and not sliding["overturned"].any()
    assert (sliding["max_theta_over_alpha"] == 0).all() and (sliding["max_abs_displacement_m"] > 0).all()


def test_a_block_that_rocks_runs_on_the_compiled_engine_by_default():
    """bd.simulate ran every rocking block on CVODE by default (about 60 times slower than
    the compiled engine, which the command line already used): a block that rocks now runs
    compiled, with the compiled backend's very events; one that slides on CVODE."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    record = kobe.scaled(0.4 * G / kobe.peak_acceleration)
    block = RockingBlock(b=0.2, h=0.8, mu=0.6)
    assert block.default_backend == "compiled"
    default, compiled = bd.simulate(block, record), bd.simulate(block, record, backend="compiled")
    assert default.backend == "compiled" and len(default.impacts) >= 2
    np.testing.assert_array_equal(default.impact_times, compiled.impact_times)
    np.testing.assert_array_equal(default.state, compiled.state)
    sliding = RockingBlock(b=0.5, h=0.6, mu=0.3)
    assert sliding.default_backend == "cvode"
    assert bd.simulate(sliding, record, t_end=5.0).backend == "cvode"
