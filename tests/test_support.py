"""A block on a compliant support (seed 004 with the sliding blocks of seeds 000/001):
PlanarBlock(support=SpringSupport) against SpringSupportedMass (exact closed forms),
the rigid support as the stiff limit, flight against its closed form, backends
against each other."""

import math

import numpy as np
import pytest

import blockdae as bd
from blockdae.planar import PlanarMode
from conftest import load_sample_record

G = bd.STANDARD_GRAVITY
RTOL = 1e-10
#: central differences of CVODE at rtol 1e-12 with steps near 1e-6 carry ~1e-12 |u| / 1e-6
#: of solver error, up to 6e-7 of the derivatives here (measured: 3.2e-9 to 3.2e-8)
REL_FD = 1e-6


def flights(sol):
    """(liftoff, landing) event pairs of a planar solution."""
    lifts = [e for e in sol.events if e.mode_after == PlanarMode.FLIGHT and e.mode_before != PlanarMode.FLIGHT]
    lands = [e for e in sol.events if e.mode_before == PlanarMode.FLIGHT]
    return list(zip(lifts, lands))


def sideways_motion(flight_push=0.0):
    """A horizontal push of 0.6 g (over by t = 0.06 s), then a = ``flight_push`` [g]
    along x from t = 0.07 s, and a base falling at 0.8 g from t = 0.07 s to 0.24 s:
    the block slides, then flies (seed 004, Fig. 4: it moves sideways in the air)."""
    ax = np.zeros(41)
    ax[1:6], ax[7:] = 0.6 * G, flight_push * G
    az = np.zeros(41)
    az[7:25] = -0.8 * G
    return bd.BaseMotion.from_samples(ax, az=az, dt=0.01)


SIDEWAYS_BLOCK = bd.PlanarBlock(0.3, support=bd.SpringSupport(8.0, 0.05))


@pytest.mark.parametrize("kwargs, field", [
    (dict(frequency=0.0), "frequency"), (dict(frequency=-2.0), "frequency"), (dict(frequency=math.inf), "frequency"),
    (dict(frequency=5.0, damping=-0.1), "damping"), (dict(frequency=5.0, damping=1.0), "damping"),
    (dict(frequency=5.0, damping=math.nan), "damping")])
def test_bad_spring_names_the_field(kwargs, field):
    with pytest.raises(ValueError, match=field):
        bd.SpringSupport(**kwargs)


def test_bad_support_is_named():
    with pytest.raises(ValueError, match="support"):
        bd.PlanarBlock(0.3, support="spring")


def test_spring_parameters_round_trip():
    block = bd.PlanarBlock(0.3, support=bd.SpringSupport(8.0, 0.05))
    assert block.parameters()["support_frequency"] == 8.0 and block.parameters()["support_damping"] == 0.05
    assert "support_frequency" not in bd.PlanarBlock(0.3).parameters()  # rigid: today's parameters
    stiffer = block.replace_parameter("support_frequency", 12.0)
    assert stiffer.support == bd.SpringSupport(12.0, 0.05)
    rebuilt = bd.PlanarBlock(0.3).with_parameters(block.parameters())
    assert (rebuilt.support.frequency, rebuilt.support.damping) == (8.0, 0.05)
    with pytest.raises(ValueError, match="damping"):
        block.replace_parameter("support_damping", 1.5)


@pytest.mark.parametrize("damping, motion", [
    (0.0, bd.RectangularPulse(-0.75 * G, 1.0)),  # test_upthrow's closed-form case
    (0.05, bd.Harmonic(0.9 * G, 1 / 7.0, cycles=3)),  # near resonance: flights, damped landings
])
@pytest.mark.parametrize("backend", ["cvode", "ida", pytest.param("jax", marks=pytest.mark.slow)])
def test_no_horizontal_motion_is_the_spring_supported_mass(damping, motion, backend):
    """Reference: SpringSupportedMass on the exact backend (closed forms). The planar
    block flies and lands at its liftoffs and landings and never slides. Measured: CVODE
    and IDA within 6.3e-10 s, JAX 3e-14 s (its bar a decade above)."""
    mass = bd.SpringSupportedMass(8.0, damping)
    ref = bd.simulate(mass, motion, t_end=0.5)
    ref_times = [e.t for e in ref.events if e.kind in ("liftoff", "landing")]
    block = bd.PlanarBlock(0.4, support=bd.SpringSupport(8.0, damping))
    base = bd.BaseMotion(bd.RectangularPulse(0.0, 0.5), z=motion)
    sol = bd.simulate(block, base, t_end=0.5, backend=backend, rtol=RTOL)
    assert len(ref_times) >= 3
    assert all({e.mode_before, e.mode_after} == {PlanarMode.STICK, PlanarMode.FLIGHT} for e in sol.events)
    np.testing.assert_allclose(sol.t_events, ref_times, rtol=0, atol=3e-13 if backend == "jax" else 1e-9)
    assert np.all(sol.u_x == 0) and np.all(sol.u_y == 0)
    heights = ref(ref.t)[0]
    np.testing.assert_allclose(sol(ref.t)[4], heights, rtol=0, atol=1e-7 * np.max(np.abs(heights)))


def test_a_stiff_spring_approaches_the_rigid_support():
    """In contact n = g + a_z + w'' with w'' = O(a_z'' / omega²): the displacement and
    the event times approach the rigid support's second order in 1 / f (measured with
    damping 0.5: du = 1.27e-3, 2.93e-4, 7.27e-5 m at 10, 20, 40 Hz; x4.3, x4.0)."""
    motion = bd.BaseMotion(bd.SinePulse(0.5 * G, 0.5), z=bd.SinePulse(-0.4 * G, 0.5))
    ref = bd.simulate(bd.PlanarBlock(0.3), motion, t_end=1.0, backend="cvode", rtol=RTOL)
    du, dt = [], []
    for frequency in (10.0, 20.0, 40.0):
        block = bd.PlanarBlock(0.3, support=bd.SpringSupport(frequency, 0.5))
        sol = bd.simulate(block, motion, t_end=1.0, backend="cvode", rtol=RTOL)
        assert [(e.mode_before, e.mode_after) for e in sol.events] == [(e.mode_before, e.mode_after) for e in ref.events]
        du.append(abs(sol.displacement[0] - ref.displacement[0]))
        dt.append(np.max(np.abs(sol.t_events - ref.t_events)))
    for coarse, fine in ((du[0], du[1]), (du[1], du[2]), (dt[0], dt[1]), (dt[1], dt[2])):
        assert 3.0 < coarse / fine < 5.0
    assert du[-1] < 1e-3 * abs(ref.displacement[0])


@pytest.mark.parametrize("flight_push", [0.0, 0.1])
def test_the_block_moves_sideways_in_flight(flight_push):
    """In flight there is no friction: the relative horizontal acceleration is -a_x,
    constant (``flight_push`` g) over the flight, so u_x is the parabola
    u + v tau - a tau² / 2 and v_x falls by a tau (closed form); the vertical motion is
    the ballistic w'' = -g - a_z of a block that left the spring (seed 004, Fig. 4)."""
    sol = bd.simulate(SIDEWAYS_BLOCK, sideways_motion(flight_push), t_end=0.4, backend="cvode", rtol=RTOL)
    (lift, land), = flights(sol)
    assert 0.07 < lift.t < land.t
    a, tau = flight_push * G, land.t - lift.t
    assert abs(lift.v_x) > 0.02  # it slides when it lifts off ...
    assert abs(land.u_x - lift.u_x) > 5e-3  # ... and moves sideways in the air
    assert land.u_x == pytest.approx(lift.u_x + lift.v_x * tau - a * tau**2 / 2, rel=1e-9)
    assert land.v_x == pytest.approx(lift.v_x - a * tau, rel=1e-9)
    times = np.linspace(lift.t, land.t, 7)[1:-1]
    np.testing.assert_allclose(sol(times)[0], lift.u_x + lift.v_x * (times - lift.t) - a * (times - lift.t) ** 2 / 2,
                               rtol=0, atol=1e-9 * abs(land.u_x))


def assert_agree(sol, ref):
    assert [(e.mode_before, e.mode_after) for e in sol.events] == [(e.mode_before, e.mode_after) for e in ref.events]
    np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=1e-9)
    np.testing.assert_allclose(sol.displacement, ref.displacement, rtol=0, atol=1e-7 * abs(ref.displacement[0]))


def test_cvode_and_ida_agree_on_a_flight():
    motion = sideways_motion(0.1)
    ref = bd.simulate(SIDEWAYS_BLOCK, motion, t_end=0.4, backend="cvode", rtol=RTOL)
    assert_agree(bd.simulate(SIDEWAYS_BLOCK, motion, t_end=0.4, backend="ida", rtol=RTOL), ref)


@pytest.mark.slow
def test_jax_agrees_with_cvode_on_a_flight():
    motion = sideways_motion(0.1)
    ref = bd.simulate(SIDEWAYS_BLOCK, motion, t_end=0.4, backend="cvode", rtol=RTOL)
    assert_agree(bd.simulate(SIDEWAYS_BLOCK, motion, t_end=0.4, backend="jax", rtol=RTOL), ref)


def test_a_spring_never_rests_so_t_end_is_needed():
    with pytest.raises(ValueError, match="t_end"):
        bd.simulate(SIDEWAYS_BLOCK, sideways_motion(), backend="cvode")


@pytest.mark.slow
def test_jax_keeps_rigid_and_spring_blocks_apart():
    """Compiled rules are shared by models with the same parameter names only: a spring
    block, then a rigid one (run first in a process, the spring's rules once served
    the rigid block too), then the spring again each agree with CVODE."""
    motion = sideways_motion(0.1)
    for block in (SIDEWAYS_BLOCK, bd.PlanarBlock(0.3), SIDEWAYS_BLOCK):
        ref = bd.simulate(block, motion, t_end=0.4, backend="cvode", rtol=RTOL)
        assert_agree(bd.simulate(block, motion, t_end=0.4, backend="jax", rtol=RTOL), ref)


@pytest.mark.slow
@pytest.mark.parametrize("backend", ["ida", "jax"])
def test_backends_agree_on_records_in_three_components(backend):
    """Kobe TAK-090 in x, Duzce 375-090 in y and 1.2 times it in z, first 10 s, on a
    5 Hz, 5 % spring: 22 events, two flights (measured: IDA 3.0e-10 s, jax 3.1e-10 s
    from CVODE)."""
    kobe, duzce = load_sample_record("Kobe_1995_TAK-090"), load_sample_record("Duzce_1999_375-090")
    first = lambda samples, scale=1.0: bd.Record(scale * samples[:1000], 0.01)
    motion = bd.BaseMotion(first(kobe.acceleration_samples), first(duzce.acceleration_samples),
                           first(duzce.acceleration_samples, 1.2))
    block = bd.PlanarBlock(mu=0.15, mu_kinetic=0.12, bias=(0.03, 0.01), support=bd.SpringSupport(5.0, 0.05))
    ref = bd.simulate(block, motion, t_end=10.0, backend="cvode", rtol=RTOL)
    assert len(flights(ref)) == 2
    assert_agree(bd.simulate(block, motion, t_end=10.0, backend=backend, rtol=RTOL), ref)


@pytest.mark.slow
def test_sensitivities_to_the_spring_match_central_differences():
    """d u_x(t_end) / d p through the located trajectory (jax) against central
    differences of CVODE at rtol 1e-12 (an independent computation)."""
    motion = sideways_motion(0.1)
    names, steps = ("mu", "support_frequency", "support_damping"), (1e-6, 1e-5, 1e-6)
    derivatives = bd.sensitivities(SIDEWAYS_BLOCK, motion, t_end=0.4, wrt=names, rtol=RTOL)
    for name, step in zip(names, steps):
        value = SIDEWAYS_BLOCK.parameters()[name]
        ux = [bd.simulate(SIDEWAYS_BLOCK.replace_parameter(name, value + s * step), motion, t_end=0.4,
                          backend="cvode", rtol=1e-12).displacement[0] for s in (1, -1)]
        assert derivatives[name][0] == pytest.approx((ux[0] - ux[1]) / (2 * step), rel=REL_FD), name
