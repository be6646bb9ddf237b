"""Conformance: every model × every backend that runs it × every feature.

Each test is parametrized over (model, backend) and named by its feature, so a model or
a backend that breaks a feature fails by name: ``test_dense_output[PlanarBlock-jax]``.
The cases (one small motion per model, several motions, a 3 s sample record, a batch,
the parameters to differentiate) are in :data:`CASES`; what fails today is in
:data:`KNOWN_GAPS` (strict xfails: removing an entry makes its test run); the JAX
twin's compiling features are in :data:`SLOW`. The references: each model's exact
backend where it has one (closed forms), else CVODE at rtol 1e-12, and for derivatives
central finite differences on that reference. Every bar (:data:`BARS`,
:data:`RECORD_BARS`, :data:`BATCH_BARS`, :data:`SENSITIVITY_BARS`,
:data:`CROSSCHECK_BARS`) is a decade above the worst agreement measured here, written
beside it.
"""

import dataclasses
import functools
import importlib.util
import pathlib

import matplotlib
import numpy as np
import pytest

import blockdae as bd
from conftest import load_sample_record

matplotlib.use("Agg")
ROOT = pathlib.Path(__file__).resolve().parents[1]
G = bd.STANDARD_GRAVITY


def backends_of(model) -> tuple[str, ...]:
    """The backends that run ``model`` today (the one place the suite asks)."""
    from blockdae.backends import available

    return available(model)


def _custom_model_module():
    spec = importlib.util.spec_from_file_location("custom_model", ROOT / "examples" / "custom_model.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


custom = _custom_model_module()


def sampled(function, duration, dt=0.01, name=""):
    """``function(t)`` [m/s²] sampled every ``dt`` [s] on [0, duration] as a Record."""
    t = np.arange(0.0, duration + dt / 2, dt)
    return bd.Record(function(t), dt, name=name, units="m/s2")


def kobe_segment(start, stop, name="Kobe TAK-090, 0-3 s"):
    """Samples ``start:stop`` of Kobe TAK-090 (dt 0.01 s) as a record of its own [m/s²]."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    return bd.Record(kobe.acceleration_samples[start:stop], kobe.dt, name=name, units="m/s2")


@dataclasses.dataclass(frozen=True)
class Case:
    """One model's small case.

    model: one parameter set; motions: excitations, the first is the one-run case's
    (the others: the many-motions feature); t_end [s] or None (until rest); record:
    (a 3 s sample record, its t_end [s]) for the slow record runs;
    reference: (backend, options) of the reference run; batch: the model with 1-D
    array parameters (None: the model has no batch_shape); wrt: parameters for
    sensitivities and crosscheck; of: the flight quantities differentiated (a
    SpringSupportedMass, whose derivatives are those of its flights), None: u(t_end).
    """

    model: object
    motions: tuple
    t_end: float | None
    record: tuple
    reference: tuple
    batch: object = None
    wrt: tuple = ()
    of: tuple | None = None

    @property
    def motion(self):
        return self.motions[0]


EXACT, CVODE_TIGHT = ("exact", {}), ("cvode", {"rtol": 1e-12})
KOBE = kobe_segment(0, 300)  # peak 0.62 g at 2.71 s

CASES = {
    "SlidingBlock": Case(
        model=bd.SlidingBlock(mu=0.2, mu_kinetic=0.15, bias=0.02),
        motions=(bd.SinePulse(0.5 * G, 0.5), bd.TriangularPulse(-0.6 * G, 0.4), bd.Harmonic(0.3 * G, 0.4, cycles=2)),
        t_end=None, record=(KOBE, None), reference=EXACT,
        batch=bd.SlidingBlock(mu=np.array([0.15, 0.2, 0.3]), mu_kinetic=np.array([0.1, 0.15, 0.25]), bias=0.02),
        wrt=("mu", "mu_kinetic", "bias")),
    "PlanarBlock": Case(
        model=bd.PlanarBlock(mu=0.2, mu_kinetic=0.15, bias=(0.02, 0.0)),
        motions=(bd.BaseMotion(bd.SinePulse(0.5 * G, 0.5), bd.SinePulse(0.3 * G, 0.4)),
                 bd.BaseMotion(bd.TriangularPulse(-0.6 * G, 0.4)),
                 bd.BaseMotion(bd.Harmonic(0.3 * G, 0.4, cycles=2), bd.Harmonic(0.2 * G, 0.5, cycles=1.5))),
        t_end=None, record=(bd.BaseMotion(KOBE), None), reference=CVODE_TIGHT,
        batch=bd.PlanarBlock(mu=np.array([0.15, 0.2, 0.3]), mu_kinetic=np.array([0.1, 0.15, 0.25]),
                             bias=(0.02, 0.0)),
        wrt=("mu", "mu_kinetic", "bias_x", "bias_y")),
    "SpringSupportedMass": Case(
        model=bd.SpringSupportedMass(frequency=5.0, damping=0.05),
        motions=(bd.SinePulse(-1.5 * G, 0.3), bd.TriangularPulse(-2.0 * G, 0.3), bd.Harmonic(-1.2 * G, 0.25, cycles=2)),
        t_end=1.0, record=(KOBE.scaled(-2.5), 3.0), reference=EXACT,
        wrt=("frequency", "damping"), of=("liftoff_velocity", "height", "flight_time")),
    "FlexibleSlidingMass": Case(
        model=bd.FlexibleSlidingMass(bd.ShearColumn(height=20.0, vs=300.0), ky=0.1),
        motions=(sampled(lambda t: 0.5 * G * np.sin(np.pi * t / 0.5), 0.5, name="sine pulse 0.5 g, 0.5 s"),
                 sampled(lambda t: 0.6 * G * (1 - np.abs(t - 0.25) / 0.25), 0.5, name="triangle 0.6 g, 0.5 s"),
                 kobe_segment(245, 296, "Kobe TAK-090, 2.45-2.95 s")),
        t_end=1.5, record=(KOBE, 3.0), reference=EXACT,
        wrt=("ky",)),
    "RockingBlock": Case(
        model=bd.RockingBlock(b=0.2, h=0.8, mu=0.6),
        motions=(bd.SinePulse(-0.4 * G, 0.5), bd.TriangularPulse(0.5 * G, 0.4), bd.Harmonic(0.3 * G, 0.5, cycles=2)),
        t_end=2.0, record=(KOBE.scaled(0.5), 3.0), reference=CVODE_TIGHT,
        batch=bd.RockingBlock(b=np.array([0.2, 0.25]), h=0.8, mu=0.6), wrt=("b", "h")),
    "OscillatorOnStop": Case(
        model=custom.OscillatorOnStop(omega=2 * np.pi * 2.0, zeta=0.2, omega_c=2 * np.pi * 8.0, gap=0.005),
        motions=(bd.SinePulse(0.5 * G, 0.5), bd.RectangularPulse(1.0, 2.0), bd.Harmonic(0.3 * G, 0.5, cycles=2)),
        t_end=1.0, record=(KOBE, 3.0), reference=CVODE_TIGHT,
        wrt=("omega", "zeta", "omega_c", "gap")),
}


# ---- what fails today, and the heavier combinations ----------------------------------------
#: (feature, model, backend or None) -> (the exception it fails with today, why); each is a
#: strict xfail that fails the test if it passes or raises anything else
KNOWN_GAPS = {
    ("replace_parameter", "FlexibleSlidingMass", None): (
        TypeError, "replace_parameter refuses omega, damping and slip_mass_fraction, which parameters() lists "
                   "(they derive from its column and method), so they have no finite differences"),
}


def known_gap(feature, model, backend=None) -> list:
    """The strict xfail of (feature, model, backend) if it is a known gap, else no mark."""
    if (feature, model, backend) not in KNOWN_GAPS:
        return []
    raises, reason = KNOWN_GAPS[feature, model, backend]
    return [pytest.mark.xfail(strict=True, raises=raises, reason=reason)]


#: (feature, model, backend) run only with ``-m slow``: each compiles JAX code of its own (a
#: few seconds to a minute on 2 cores); the cheap features of the JAX twin (one run, events,
#: dense output, plot, table: one compilation per model) and the exact backends'
#: derivatives stay in the quick run
SLOW = {(feature, model, "jax") for model in CASES
        for feature in ("batch", "many_motions", "sensitivities", "sensitivity_to_A", "sensitivity_shape",
                        "crosscheck", "crosscheck_derivatives")}

# ---- the bars, a decade above the worst agreement measured (the case's motions) ------------
#: (model, backend) -> largest |u - u_ref| at t_end "u" [m], largest event-time difference
#: "t" [s], largest dense-output difference "dense" [-] (of each state's size) against the
#: reference run, over the case's motions. Measured worst (u, t, dense) in the comments.
BARS = {
    ("SlidingBlock", "exact-jax"): dict(u=1e-15, t=1e-15, dense=4e-15),  # 0, 0, 3.5e-16 (rounding)
    ("SlidingBlock", "cvode"): dict(u=2e-9, t=2e-9, dense=3e-8),  # 1.5e-10, 1.2e-10, 2.9e-9
    ("SlidingBlock", "ida"): dict(u=3e-9, t=5e-9, dense=3e-8),  # 2.7e-10, 4.4e-10, 2.4e-9
    ("SlidingBlock", "jax"): dict(u=4e-11, t=3e-11, dense=5e-10),  # 3.9e-12, 2.3e-12, 4.3e-11
    ("PlanarBlock", "cvode"): dict(u=5e-9, t=2e-9, dense=1e-6),  # 4.2e-10, 1.5e-10, 9.8e-8 (rtol 1e-10)
    ("PlanarBlock", "ida"): dict(u=6e-9, t=7e-10, dense=3e-8),  # 5.1e-10, 7.0e-11, 2.9e-9
    ("PlanarBlock", "jax"): dict(u=7e-11, t=2e-11, dense=7e-8),  # 6.7e-12, 1.5e-12, 6.8e-9
    ("PlanarBlock", "compiled"): dict(u=7e-11, t=2e-11, dense=4e-7),  # 6.1e-12, 1.5e-12, 3.4e-8
    ("SpringSupportedMass", "cvode"): dict(u=2e-9, t=3e-9, dense=5e-8),  # 1.3e-10, 2.1e-10, 4.3e-9
    ("SpringSupportedMass", "ida"): dict(u=9e-9, t=8e-9, dense=2e-7),  # 8.7e-10, 7.4e-10, 1.4e-8
    ("SpringSupportedMass", "jax"): dict(u=2e-12, t=1e-12, dense=3e-8),  # 1.5e-13, 1.0e-13, 2.2e-9
    ("FlexibleSlidingMass", "cvode"): dict(u=8e-11, t=2e-10, dense=2e-8),  # 8.0e-12, 1.2e-11, 1.3e-9
    ("FlexibleSlidingMass", "ida"): dict(u=3e-9, t=8e-10, dense=2e-8),  # 2.9e-10, 7.7e-11, 1.3e-9
    ("FlexibleSlidingMass", "jax"): dict(u=3e-14, t=2e-13, dense=2e-8),  # 2.7e-15, 1.5e-14, 1.5e-9
    ("RockingBlock", "cvode"): dict(u=5e-9, t=2e-8, dense=8e-8),  # 4.6e-10 rad, 1.4e-9, 7.2e-9 (rtol 1e-10)
    ("RockingBlock", "ida"): dict(u=6e-9, t=2e-8, dense=9e-8),  # 5.6e-10 rad, 1.7e-9, 9.0e-9
    ("RockingBlock", "jax"): dict(u=7e-11, t=4e-10, dense=1e-9),  # 6.3e-12 rad, 3.8e-11, 1.0e-10
    ("RockingBlock", "compiled"): dict(u=7e-11, t=4e-10, dense=3e-9),  # 6.4e-12 rad, 3.8e-11, 2.4e-10
    ("OscillatorOnStop", "cvode"): dict(u=5e-11, t=4e-9, dense=5e-8),  # 4.5e-12, 4.0e-10, 4.1e-9 (rtol 1e-10)
    ("OscillatorOnStop", "ida"): dict(u=6e-11, t=8e-9, dense=7e-8),  # 5.9e-12, 7.7e-10, 6.3e-9
    ("OscillatorOnStop", "jax"): dict(u=3e-13, t=5e-11, dense=1e-9),  # 2.9e-14, 4.1e-12, 9.8e-11
}
#: as BARS, for the record case (Kobe TAK-090, its first 3 s); measured (u, t, dense)
RECORD_BARS = {
    ("SlidingBlock", "exact-jax"): dict(u=6e-16, t=1e-15, dense=2e-15),  # 5.6e-17, 0, 1.1e-16 (rounding)
    ("SlidingBlock", "cvode"): dict(u=2e-11, t=2e-11, dense=7e-11),  # 1.8e-12, 1.1e-12, 7.0e-12
    ("SlidingBlock", "ida"): dict(u=5e-9, t=4e-10, dense=3e-8),  # 4.5e-10, 3.2e-11, 2.8e-9
    ("SlidingBlock", "jax"): dict(u=1e-15, t=1e-15, dense=7e-16),  # 0, 0, 6.6e-17 (rounding)
    ("PlanarBlock", "cvode"): dict(u=4e-11, t=7e-12, dense=6e-11),  # 3.1e-12, 6.8e-13, 5.8e-12 (rtol 1e-10)
    ("PlanarBlock", "ida"): dict(u=8e-9, t=4e-10, dense=5e-8),  # 7.4e-10, 3.7e-11, 4.2e-9
    ("PlanarBlock", "jax"): dict(u=9e-12, t=2e-11, dense=9e-11),  # 9.0e-13, 1.2e-12, 8.2e-12
    ("PlanarBlock", "compiled"): dict(u=1e-11, t=2e-11, dense=9e-11),  # 9.3e-13, 1.2e-12, 8.3e-12
    ("SpringSupportedMass", "cvode"): dict(u=9e-9, t=9e-10, dense=3e-8),  # 8.6e-10, 8.8e-11, 2.4e-9
    ("SpringSupportedMass", "ida"): dict(u=8e-9, t=5e-10, dense=2e-8),  # 7.4e-10, 4.5e-11, 1.8e-9
    ("SpringSupportedMass", "jax"): dict(u=1e-12, t=2e-13, dense=2e-8),  # 1.0e-13, 1.7e-14, 1.1e-9
    ("FlexibleSlidingMass", "cvode"): dict(u=2e-10, t=7e-11, dense=8e-9),  # 1.7e-11, 6.6e-12, 7.6e-10
    ("FlexibleSlidingMass", "ida"): dict(u=6e-9, t=2e-10, dense=2e-8),  # 5.9e-10, 1.3e-11, 1.1e-9
    ("FlexibleSlidingMass", "jax"): dict(u=2e-13, t=8e-14, dense=2e-9),  # 1.2e-14, 7.5e-15, 1.3e-10
    # the rocking block: 34 events, among them tails of impacts whose small differences the
    # unstable rocking motion amplifies
    ("RockingBlock", "cvode"): dict(u=2e-8, t=2e-6, dense=9e-6),  # 1.3e-9 rad, 1.1e-7, 8.8e-7 (rtol 1e-10)
    ("RockingBlock", "ida"): dict(u=9e-8, t=8e-6, dense=6e-5),  # 8.6e-9 rad, 7.3e-7, 5.8e-6
    ("RockingBlock", "jax"): dict(u=5e-9, t=4e-7, dense=3e-6),  # 4.3e-10 rad, 3.6e-8, 2.9e-7
    # the reference's own error: the compiled engine at rtol 1e-14 is within 7.6e-12 s of its
    # run at 1e-12, CVODE at rtol 1e-13 within 3.0e-9 s of it
    ("RockingBlock", "compiled"): dict(u=4e-9, t=3e-7, dense=3e-6),  # 3.2e-10 rad, 2.7e-8, 2.2e-7
    ("OscillatorOnStop", "cvode"): dict(u=9e-10, t=4e-10, dense=3e-8),  # 8.1e-11, 3.8e-11, 2.2e-9 (rtol 1e-10)
    ("OscillatorOnStop", "ida"): dict(u=6e-10, t=9e-10, dense=3e-8),  # 5.6e-11, 8.6e-11, 2.9e-9
    ("OscillatorOnStop", "jax"): dict(u=2e-11, t=4e-12, dense=4e-10),  # 1.1e-12, 3.7e-13, 3.8e-11
}
#: the reference backend against its own run
THE_REFERENCE = dict(u=0.0, t=0.0, dense=0.0)
#: backend -> largest |u - u_single| of a batch item [m]; measured 1.2e-14 m (jax), 0 elsewhere
BATCH_BARS = {"jax": 2e-13}
#: model -> largest |S - FD| / |FD| [-] of bd.sensitivities against central differences at
#: the step 1e-4 (every parameter of the case and "A"). Measured worst, and the
#: differences' own error |FD(2e-4) - FD(1e-4)| / |FD| beside it: about 3 times the first,
#: as the step's h² error makes it.
SENSITIVITY_BARS = {
    "SlidingBlock": 8e-8,  # 7.8e-9 (mu_kinetic; 2.3e-8), all three backends
    "PlanarBlock": 5e-6,  # 4.2e-7 (bias_y; 1.3e-6)
    "SpringSupportedMass": 2e-7,  # 1.2e-8 (liftoff velocity by frequency; 3.6e-8)
    "FlexibleSlidingMass": 1e-9,  # 1.0e-10 (A; 3.1e-10)
    "OscillatorOnStop": 4e-4,  # 3.9e-5 (gap; 1.1e-4)
    "RockingBlock": 2e-5,  # 1.8e-6 (theta(t_end) by b, through 2 impacts; 5.5e-6)
}
#: (model, backend) -> largest relative difference rel_dsens [-] of a cross-check row's
#: derivatives against the reference row's (finite differences at the cross-check's own
#: step on backends that do not differentiate); measured in the comments
CROSSCHECK_BARS = {
    ("SlidingBlock", "exact-jax"): 1e-15,  # 0 (the same kernel)
    ("SlidingBlock", "cvode"): 3e-7,  # 2.6e-8
    ("SlidingBlock", "ida"): 5e-7,  # 4.6e-8
    ("SlidingBlock", "jax"): 2e-10,  # 1.8e-11
    ("PlanarBlock", "ida"): 3e-6,  # 2.7e-7
    ("PlanarBlock", "jax"): 5e-6,  # 4.2e-7
    ("PlanarBlock", "compiled"): 2e-6,  # 1.7e-7
    ("FlexibleSlidingMass", "cvode"): 2e-10,  # 1.4e-11
    ("FlexibleSlidingMass", "ida"): 2e-8,  # 1.6e-9
    ("FlexibleSlidingMass", "jax"): 4e-10,  # 3.7e-11
    ("RockingBlock", "ida"): 1e-7,  # 9.8e-9
    ("RockingBlock", "compiled"): 2e-8,  # 1.7e-9
    ("RockingBlock", "jax"): 2e-5,  # 1.8e-6 (the twin's derivatives against finite differences on CVODE)
    ("OscillatorOnStop", "ida"): 9e-5,  # 8.7e-6 (finite differences of an event-rich run: see SENSITIVITY_BARS)
    ("OscillatorOnStop", "jax"): 4e-4,  # 3.9e-5
}


def matrix(feature, backends=None, models=None):
    """pytest params (model, backend), id "model-backend", for ``feature``: every model of
    ``models`` (default: all) × every backend that runs it (or ``backends(name, case)``)."""
    params = []
    for name, case in CASES.items():
        if models is not None and name not in models:
            continue
        for backend in (backends_of(case.model) if backends is None else backends(name, case)):
            marks = ([pytest.mark.slow] if (feature, name, backend) in SLOW else []) + known_gap(feature, name, backend)
            params.append(pytest.param(name, backend, id=f"{name}-{backend}", marks=marks))
    return params


# ---- runs, each computed once per session -------------------------------------------------
@functools.cache
def run(name, backend, index=0, options=()):
    """Model ``name`` under its motion ``index`` ("record": its record case) on
    ``backend`` with ``options`` (pairs)."""
    case = CASES[name]
    motion, t_end = case.record if index == "record" else (case.motions[index], case.t_end)
    return bd.simulate(case.model, motion, t_end=t_end, backend=backend, **dict(options))


def reference(name, index=0):
    """The reference run of model ``name`` under its motion ``index`` ("record": its record case)."""
    backend, options = CASES[name].reference
    return run(name, backend, index, tuple(options.items()))


def displacement_difference(solution, ref) -> float:
    """|u - u_ref| at the end [m] (Euclidean norm of a displacement vector)."""
    return float(np.linalg.norm(np.subtract(solution.displacement, ref.displacement)))


def event_time_difference(solution, ref) -> float:
    """max |t - t_ref| over the events [s]; inf if the mode changes differ."""
    modes = [(e.mode_before, e.mode_after) for e in solution.events]
    if modes != [(e.mode_before, e.mode_after) for e in ref.events]:
        return np.inf
    return float(np.max(np.abs(solution.t_events - ref.t_events), initial=0.0))


def dense_difference(solution, ref, n=41) -> float:
    """Largest difference of the states at ``n`` interior times, each state relative to
    its largest size there [-]."""
    t = np.linspace(0.0, min(solution.t_end, ref.t_end), n + 2)[1:-1]
    worst = 0.0
    for mine, theirs in zip(solution(t), ref(t)):
        size = float(np.max(np.abs(theirs)))
        worst = max(worst, float(np.max(np.abs(np.subtract(mine, theirs)))) / (size if size > 0 else 1.0))
    return worst


# ---- derivatives: central finite differences on the reference backend ---------------------
#: relative steps of the finite differences [-]; their difference estimates the error
STEPS = (2e-4, 1e-4)


def outputs(case, solution) -> dict:
    """What the model's sensitivities differentiate: u(t_end) [m], or a
    SpringSupportedMass's flight quantities (first liftoff velocity [m/s], largest
    height [m], total flight time [s], a flight not landed counting to t_end)."""
    if case.of is None:
        return {"u": np.asarray(solution.displacement, dtype=float)}
    flights = solution.flights
    landings = [f.landing if np.isfinite(f.landing) else solution.t_end for f in flights]
    return {"liftoff_velocity": flights[0].liftoff_velocity, "height": max(f.height for f in flights),
            "flight_time": sum(landing - f.liftoff for f, landing in zip(flights, landings))}


def by_output(case, sensitivities) -> dict:
    """bd.sensitivities' answer as output -> parameter -> derivative."""
    if case.of is None:
        return {"u": {name: np.asarray(value, dtype=float) for name, value in sensitivities.items()}}
    return {quantity: sensitivities.of(quantity) for quantity in sensitivities.quantities}


def parameter_value(model, name) -> float:
    """The value of parameter ``name`` of ``model`` (its ``parameters()``, else the field)."""
    try:
        return float(model.parameters()[name])
    except NotImplementedError:
        return float(getattr(model, name))


def perturbed(case, name, step):
    """(model, motion) with parameter ``name`` moved by the relative ``step`` (by
    ``step`` where it is 0; "A", the largest peak of the motion's components in units
    of the model's g (standard gravity if it has none): the motion scaled by 1 + step)
    and the move."""
    if name == "A":
        peak = float(np.max(case.motion.peak_acceleration)) / getattr(case.model, "g", G)
        return case.model, case.motion.scaled(1 + step), step * peak
    value = parameter_value(case.model, name)
    move = step * (abs(value) if value != 0 else 1.0)
    return case.model.replace_parameter(name, value + move), case.motion, move


@functools.cache
def finite_differences(name, parameter, step) -> dict:
    """Central differences output -> d output / d ``parameter`` on the model's reference
    backend, relative step ``step``."""
    case = CASES[name]
    backend, options = case.reference
    values, moves = [], []
    for s in (step, -step):
        model, motion, move = perturbed(case, parameter, s)
        values.append(outputs(case, bd.simulate(model, motion, t_end=case.t_end, backend=backend, **options)))
        moves.append(move)
    return {key: (values[0][key] - values[1][key]) / (moves[0] - moves[1]) for key in values[0]}


def sensitivity_errors(name, backend, wrt):
    """Per output and parameter: (|S - FD| / |FD|, the FD's own error estimate
    |FD(h) - FD(h/2)| / |FD|) [-], S from bd.sensitivities on ``backend``."""
    case = CASES[name]
    found = by_output(case, bd.sensitivities(case.model, case.motion, t_end=case.t_end, wrt=wrt, backend=backend,
                                             **({} if case.of is None else {"of": case.of})))
    errors = {}
    for parameter in wrt:
        coarse, fine = finite_differences(name, parameter, STEPS[0]), finite_differences(name, parameter, STEPS[1])
        for key, derivative in fine.items():
            size = max(float(np.linalg.norm(derivative)), 1e-300)
            errors[key, parameter] = (float(np.linalg.norm(found[key][parameter] - derivative)) / size,
                                      float(np.linalg.norm(coarse[key] - derivative)) / size)
    return errors


def differentiating(name, case):
    """The backends that differentiate the model (its ``differentiated_backends``)."""
    return [b for b in backends_of(case.model) if b in case.model.differentiated_backends]


def compared(name, case):
    """The backends compared with the reference run: all that run the model, less the
    reference itself (a backend at other settings than the reference's is compared)."""
    return [b for b in backends_of(case.model) if b != case.reference[0] or case.reference[1]]


def other_than_reference(name, case):
    """The backends that run the model, less the reference's backend."""
    return [b for b in backends_of(case.model) if b != case.reference[0]]


def with_batch(name, case):
    """The backends that run the model, where it has a batch (1-D array parameters)."""
    return backends_of(case.model) if case.batch is not None else []


# ---- the features --------------------------------------------------------------------------
@pytest.mark.parametrize("model, backend", matrix("one_run", compared))
def test_one_run(model, backend):
    """u(t_end) of bd.simulate agrees with the reference run within BARS[...]["u"] [m]."""
    solution, ref = run(model, backend), reference(model)
    assert solution.backend == backend
    assert displacement_difference(solution, ref) <= BARS[model, backend]["u"]


@pytest.mark.parametrize("model, backend", matrix("events", compared))
def test_events(model, backend):
    """The same mode changes as the reference run, located within BARS[...]["t"] [s]."""
    solution, ref = run(model, backend), reference(model)
    assert len(ref.events) >= 1
    assert event_time_difference(solution, ref) <= BARS[model, backend]["t"]


@pytest.mark.parametrize("model, backend", matrix("dense_output", compared))
def test_dense_output(model, backend):
    """The states at 41 interior times agree with the reference run's dense output
    within BARS[...]["dense"] of each state's size [-]."""
    assert dense_difference(run(model, backend), reference(model)) <= BARS[model, backend]["dense"]


@pytest.mark.slow
@pytest.mark.parametrize("model, backend", matrix("record", compared))
def test_record(model, backend):
    """Under 3 s of a sample record (Kobe TAK-090, peak 0.62 g; scaled by -2.5 as the
    vertical motion of a SpringSupportedMass): u(t_end), the events and the dense
    output agree with the reference run within RECORD_BARS."""
    solution, ref = run(model, backend, "record"), reference(model, "record")
    bars = RECORD_BARS[model, backend]
    assert len(ref.events) >= 1
    assert displacement_difference(solution, ref) <= bars["u"]
    assert event_time_difference(solution, ref) <= bars["t"]
    assert dense_difference(solution, ref) <= bars["dense"]


@pytest.mark.parametrize("model, backend", matrix("batch", with_batch))
def test_batch(model, backend):
    """A batch of parameter sets gives, per set, the single run's u(t_end) (within
    BATCH_BARS [m]) and event times (exactly)."""
    case = CASES[model]
    batch = bd.simulate(case.batch, case.motion, t_end=case.t_end, backend=backend)
    assert len(batch) == case.batch.batch_shape[0] >= 2
    for i in range(len(batch)):
        one = bd.simulate(case.batch.item(i), case.motion, t_end=case.t_end, backend=backend)
        difference = float(np.max(np.abs(np.subtract(batch.displacement[i], one.displacement))))
        assert difference <= BATCH_BARS.get(backend, 0.0)
        assert event_time_difference(batch[i], one) == 0.0


@pytest.mark.parametrize("model, backend", matrix("many_motions"))
def test_many_motions(model, backend):
    """bd.simulate over the model's motions gives one bd.Ensemble whose every row is that
    motion's single run (the same displacement and event times, exactly), and each run
    agrees with the reference run of that motion within the one-run bars."""
    case = CASES[model]
    ensemble = bd.simulate(case.model, list(case.motions), t_end=case.t_end, backend=backend)
    assert isinstance(ensemble, bd.Ensemble) and len(ensemble) == len(case.motions)
    assert ensemble.shape == (len(case.motions), 1, 1)
    table = ensemble.to_dataframe()
    for i in range(len(case.motions)):
        one = run(model, backend, i)
        np.testing.assert_array_equal(ensemble.displacement[i, 0, 0], one.displacement)
        assert table[f"max_abs_displacement_{case.model.displacement_unit}"][i] == one.max_abs_displacement
        assert event_time_difference(ensemble[i], one) == 0.0
    for i in range(len(case.motions)):
        solution, ref = run(model, backend, i), reference(model, i)
        bars = BARS.get((model, backend), THE_REFERENCE)
        assert displacement_difference(solution, ref) <= bars["u"]
        assert event_time_difference(solution, ref) <= bars["t"]


@pytest.mark.parametrize("model, backend", matrix("sensitivities", differentiating))
def test_sensitivities(model, backend):
    """bd.sensitivities agrees with central finite differences on the reference backend
    (relative step 1e-4) within SENSITIVITY_BARS [-] of the derivative; the differences'
    own error, estimated by the step 2e-4, is below that bar too."""
    bar = SENSITIVITY_BARS[model]
    for (output, parameter), (error, fd_error) in sensitivity_errors(model, backend, CASES[model].wrt).items():
        assert fd_error <= bar, (output, parameter)
        assert error <= bar, (output, parameter, error)


@pytest.mark.parametrize("model, backend", matrix("sensitivity_to_A", differentiating))
def test_sensitivity_to_peak_acceleration(model, backend):
    """d/dA (A: the motion's largest peak in g) agrees with central finite differences
    on the reference backend as in test_sensitivities."""
    bar = SENSITIVITY_BARS[model]
    for (output, parameter), (error, fd_error) in sensitivity_errors(model, backend, ("A",)).items():
        assert fd_error <= bar, output
        assert error <= bar, (output, error)


@pytest.mark.parametrize("model, backend", matrix("sensitivity_shape", differentiating,
                                                  models=[m for m, c in CASES.items() if c.of is None]))
def test_sensitivities_have_the_displacement_shape(model, backend):
    """Each derivative of u(t_end) has the shape of the solution's displacement (a
    float for one displacement state, (2,) for a PlanarBlock)."""
    case = CASES[model]
    found = bd.sensitivities(case.model, case.motion, t_end=case.t_end, wrt=case.wrt, backend=backend)
    for value in found.values():
        assert np.shape(value) == np.shape(reference(model).displacement)


@pytest.mark.parametrize("model, backend", matrix("crosscheck", other_than_reference))
def test_crosscheck(model, backend):
    """bd.crosscheck of the reference and this backend: one row each, and they agree
    (same events and modes; event times and u(t_end) within the cross-check's bars)."""
    case = CASES[model]
    check = bd.crosscheck(case.model, case.motion, backends=(case.reference[0], backend), t_end=case.t_end,
                          **case.reference[1])
    assert [row["backend"] for row in check.rows] == [case.reference[0], backend]
    assert check.agrees, str(check)


@pytest.mark.parametrize("model, backend", matrix("crosscheck_derivatives", other_than_reference,
                                                  models=[m for m, c in CASES.items() if c.of is None]))
def test_crosscheck_derivatives(model, backend):
    """bd.crosscheck(wrt=...): the rows agree, and each backend's derivatives (its own, or
    finite differences) agree with the reference's within CROSSCHECK_BARS [-]."""
    case = CASES[model]
    check = bd.crosscheck(case.model, case.motion, backends=(case.reference[0], backend), t_end=case.t_end,
                          wrt=case.wrt, **case.reference[1])
    assert check.agrees, str(check)
    assert check.row(backend)["rel_dsens"] <= CROSSCHECK_BARS[model, backend]


def lists_parameters(model) -> bool:
    """Whether ``model`` lists its parameters (a SlidingBlock's derivatives come from its
    own kernels: it lists none)."""
    try:
        return bool(model.parameters())
    except NotImplementedError:
        return False


@pytest.mark.parametrize("model", [
    pytest.param(name, marks=known_gap("replace_parameter", name))
    for name, case in CASES.items() if lists_parameters(case.model)])
def test_replace_parameter(model):
    """Every parameter a model lists (what its derivatives are taken by, and finite
    differences move) can be set by replace_parameter."""
    original = CASES[model].model
    for name, value in original.parameters().items():
        moved = value * 1.01 if value != 0 else 0.01
        assert original.replace_parameter(name, moved).parameters()[name] == pytest.approx(moved, rel=1e-15), name


@pytest.mark.parametrize("model, backend", matrix("plot"))
def test_plot(model, backend):
    """bd.plot(solution) returns a matplotlib Figure with curves drawn."""
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    figure = bd.plot(run(model, backend))
    try:
        assert isinstance(figure, Figure)
        assert any(len(line.get_xdata()) >= 2 for ax in figure.axes for line in ax.get_lines())
    finally:
        plt.close(figure)


@pytest.mark.parametrize("model, backend", matrix("table"))
def test_table(model, backend):
    """The solution's events as a DataFrame (one row each, t_s [s] their times) and as text
    (a header and one line each)."""
    solution = run(model, backend)
    frame = solution.to_dataframe()
    assert len(frame) == len(solution.events) >= 1
    np.testing.assert_array_equal(frame["t_s"].to_numpy(), solution.t_events)
    assert len(solution.event_table().splitlines()) == len(solution.events) + 1
