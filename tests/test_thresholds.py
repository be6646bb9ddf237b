"""Adversarial cross-checks on thresholds (issue 28): every solver backend against the
exact one where the demand touches or barely crosses mu g, and the planar backends
against each other and against the exact 1-D block.

Reference: the exact backend (closed-form motion, onsets decided on monotone pieces).
Bars at rtol 1e-10, per backend: event times within ``DT`` [s], the final displacement
within ``DU_REL`` of the path the reference slid (at least ``DU_ABS`` [m]), the same
modes in the same order.
A slide whose speed never exceeds ``V_FLOOR`` [m/s] (the solvers' velocity tolerance
atol: a demand one ulp over mu g slides for ~1e-8 s at ~1e-17 m/s) has no located end
(its v stays below every solver's tolerance well past the true stop): its two event
times are not compared, its modes and its displacement are. The planar backends are
held to the planar tests' bars (``tests/test_planar_ida.py``: 1e-9 s, 1e-7 of u).
The CI subset runs the cases marked ``fast`` on CVODE and IDA and a few on JAX and the
exact JAX kernel; every case on every backend runs under the slow mark.
"""

import io
import re
import sys

import numpy as np
import pytest

import blockdae as bd
from blockdae.sliding import Mode
from blockdae.planar import PlanarMode
from blockdae.core import _driver as driver
from threshold_cases import G, MU, planar_cases, sliding_cases

RTOL = 1e-10
DT = {"cvode": 1e-9, "ida": 1e-9, "jax": 1e-9, "exact-jax": 1e-12}  # [s]
DU_REL, DU_ABS = 1e-9, 1e-12  # [-], [m]
V_FLOOR = 1e-12  # [m/s]
PLANAR_DU_REL = 1e-7  # [-]
JAX_FAST = ("harmonic A=mu g+0ulp", "harmonic touch one side bias=+0.1", "record touch at a sample")

SLIDING = sliding_cases()
PLANAR = list(planar_cases())


def _params(cases, backends, fast_names):
    for case in cases:
        for backend in backends:
            fast = case.fast if backend in ("cvode", "ida") else case.name in fast_names
            yield pytest.param(case, backend, id=f"{case.name}-{backend}",
                               marks=() if fast else pytest.mark.slow)


def _slide_speeds(ref):
    """Largest |v| [m/s] of each slide of ``ref`` (between event i and i + 1), from its
    dense output."""
    t = ref.t_events
    speeds = []
    for a, b in zip(t[:-1], t[1:]):
        grid = np.linspace(a, b, 65)
        speeds.append(float(np.max(np.abs(np.asarray(ref(grid)[1])))) if b > a else 0.0)
    return speeds


def timed_events(ref):
    """Which events of ``ref`` have a located time: all but those that start or end a
    slide whose speed stays below V_FLOOR (see the module)."""
    timed = np.ones(len(ref.events), bool)
    for i, speed in enumerate(_slide_speeds(ref)):
        if ref.events[i].mode_after != Mode.STICK and speed < V_FLOOR:
            timed[i] = timed[i + 1] = False
    return timed


def du_bar(ref):
    """How far [m] another backend's final displacement may lie from ``ref``'s: DU_REL
    of the path slid (errors accumulate slide by slide), at least DU_ABS."""
    return max(DU_ABS, DU_REL * np.sum(np.abs(np.diff(ref.u))))


def assert_matches(sol, ref, dt_max):
    assert [(e.mode_before, e.mode_after) for e in sol.events] == \
        [(e.mode_before, e.mode_after) for e in ref.events]
    gaps = np.abs(np.asarray(sol.t_events) - np.asarray(ref.t_events))[timed_events(ref)]
    assert np.all(gaps <= dt_max), gaps
    assert abs(sol.displacement - ref.displacement) <= du_bar(ref)


@pytest.mark.parametrize("case, backend", _params(SLIDING, ("cvode", "ida", "jax", "exact-jax"), JAX_FAST))
def test_solver_backends_agree_with_exact_on_thresholds(case, backend):
    ref = bd.simulate(case.block, case.motion, t_end=case.t_end, backend="exact")
    options = {} if backend == "exact-jax" else {"rtol": RTOL}
    sol = bd.simulate(case.block, case.motion, t_end=case.t_end, backend=backend, **options)
    assert_matches(sol, ref, DT[backend])


def biased_touch_closed_form(t_end=5.0):
    """Closed form, in mpmath (40 digits), of ``SlidingBlock(mu=0.4, bias=0.1, g=9.81)``
    under ``Harmonic(0.5 g, 1 s)``: a = A sin(w t) only touches (mu + bias) g = A on one
    side, and slides the other way where -a > (mu - bias) g = k: from sin(w t0) = -0.6
    with u'' = -a - k, v = (A/w)(cos w t - cos w t0) - k (t - t0) until v = 0 (Sawicki &
    Chybicki 2005, Eqs. 1-2 for the base). Returns (event times [s], u(t_end) [m])."""
    import mpmath as mp

    mp.mp.dps = 40
    g = mp.mpf("9.81")
    amplitude, w, k = g / 2, 2 * mp.pi, mp.mpf("0.3") * g
    v = lambda t, t0: amplitude / w * (mp.cos(w * t) - mp.cos(w * t0)) - k * (t - t0)
    du = lambda t, t0: (amplitude / w * ((mp.sin(w * t) - mp.sin(w * t0)) / w - mp.cos(w * t0) * (t - t0))
                        - k * (t - t0) ** 2 / 2)
    events, u = [], mp.mpf(0)
    for n in range(int(t_end) + 1):
        t0 = n + (mp.pi + mp.asin(mp.mpf("0.6"))) / w
        if t0 >= t_end:
            break
        t1 = mp.findroot(lambda t: v(t, t0), t0 + mp.mpf("0.5"))
        events.append(t0)
        if t1 >= t_end:
            u += du(mp.mpf(t_end), t0)
            break
        events.append(t1)
        u += du(t1, t0)
    return np.array(events, dtype=float), float(u)


def test_a_touch_of_mu_g_gives_the_exact_answer():
    """A touch of mu g is no slide (exact 0 m, no event); with a bias
    the touch on one side must not poison the real slides on the other. Reference for
    the biased case: its closed form (``biased_touch_closed_form``: 9 events, u(5 s) =
    0.48204903463452867 m); measured: events within 4.4e-16 s, u within 5.6e-16 m."""
    touch = bd.Harmonic(amplitude=0.5 * 9.81, period=1.0)
    for block in (bd.SlidingBlock(mu=0.5, g=9.81), bd.SlidingBlock(mu=0.5, g=9.81, direction="negative")):
        for backend in ("cvode", "ida"):
            sol = bd.simulate(block, touch, t_end=5.0, backend=backend)
            assert sol.displacement == 0.0 and sol.events == ()
    block = bd.SlidingBlock(mu=0.4, bias=0.1, g=9.81)
    ref = bd.simulate(block, touch, t_end=5.0, backend="exact")
    t_events, u = biased_touch_closed_form()
    np.testing.assert_allclose(ref.t_events, t_events, rtol=0, atol=4.4e-15)
    assert ref.displacement == pytest.approx(u, rel=0, abs=5.6e-15)
    for backend in ("cvode", "ida"):
        assert_matches(bd.simulate(block, touch, t_end=5.0, backend=backend), ref, 1e-8)


@pytest.mark.parametrize("backend", ["cvode", "ida", pytest.param("jax", marks=pytest.mark.slow)])
def test_planar_block_on_a_touch_does_not_slide(backend):
    """Issue 28: PlanarBlock(mu=0.5) under a_x = mu g sin: zero slip (was 55.21 m)."""
    sol = bd.simulate(bd.PlanarBlock(mu=0.5, g=9.81), bd.Harmonic(0.5 * 9.81, 1.0), t_end=5.0, backend=backend)
    assert np.all(sol.displacement == 0.0) and sol.events == ()


def _planar_params():
    for case, twin in PLANAR:
        yield pytest.param(case, twin, id=case.name, marks=() if case.fast else pytest.mark.slow)


@pytest.mark.parametrize("case, twin", _planar_params())
def test_planar_backends_agree_on_thresholds(case, twin):
    """CVODE, IDA (and under the slow mark JAX) against each other; under x-only motion
    u_x and the event times against the exact 1-D block; n touching zero is no flight."""
    backends = ("cvode", "ida") if case.fast else ("cvode", "ida", "jax")
    sols = {b: bd.simulate(case.block, case.motion, t_end=case.t_end, backend=b, rtol=RTOL) for b in backends}
    for sol in sols.values():
        assert all(e.mode_after != PlanarMode.FLIGHT for e in sol.events)
    if twin is not None:
        ref = bd.simulate(twin, case.motion, t_end=case.t_end, backend="exact")
        timed = timed_events(ref)
        for sol in sols.values():
            assert len(sol.events) == len(ref.events)
            assert np.all(np.abs(np.asarray(sol.t_events) - ref.t_events)[timed] <= 1e-9)
            assert abs(sol.displacement[0] - ref.displacement) <= du_bar(ref)
            assert sol.displacement[1] == 0.0
    else:
        timed = np.ones(len(sols["cvode"].events), bool)
    first = sols["cvode"]
    for sol in sols.values():
        assert [(e.mode_before, e.mode_after) for e in sol.events] == \
            [(e.mode_before, e.mode_after) for e in first.events]
        np.testing.assert_allclose(np.asarray(sol.t_events)[timed], np.asarray(first.t_events)[timed], rtol=0,
                                   atol=1e-9)
        np.testing.assert_allclose(sol.displacement, first.displacement, rtol=PLANAR_DU_REL, atol=DU_ABS)


def test_n_touching_zero_at_a_trough_is_no_flight():
    """A vertical Harmonic of amplitude exactly g brings n = g + a_z to 0 at its troughs,
    where n turns back up: the block stays on the base (was a flight through it, -0.76 m)."""
    motion = bd.BaseMotion(bd.Harmonic(0.0, 1.0), z=bd.Harmonic(G, 1.0))
    for backend in ("cvode", "ida"):
        sol = bd.simulate(bd.PlanarBlock(mu=MU, g=G), motion, t_end=3.0, backend=backend)
        assert sol.events == ()


class _WrongKick(bd.SlidingBlock):
    """A block whose entry rule is broken on purpose: it enters a slide moving at 1 m/s
    against it, so its velocity contradicts its mode until it turns."""

    def state_on_entry(self, before, after, t, y, excitation, xp):
        return np.array([y[0], -float(after) * 1.0]) if after != Mode.STICK else y


class _WrongKickUnchecked(_WrongKick):
    """The same, its slides declared instant modes: the driver's check on entering a mode
    skips them, so the state runs on in its contradiction."""

    instant_modes = (Mode.SLIP_POS, Mode.SLIP_NEG)


@pytest.mark.parametrize("backend", ["cvode", "ida"])
def test_a_mode_entered_with_a_guard_below_zero_is_an_error(backend):
    """The driver's check on entering a mode: slip- entered at v = +1 m/s has its guard
    (-v) at -1 m/s, named with the mode, the time and the state, before any step."""
    with pytest.raises(bd.core.ModelContractError,
                       match=r"mode SLIP_NEG entered at t = 0 s with guard 0 = -1 below zero.*'v': 1.0"):
        bd.simulate(_WrongKick(mu=0.2, g=G), bd.RectangularPulse(0.25 * G, 1.0), backend=backend)


@pytest.mark.parametrize("backend", ["cvode", "ida"])
def test_a_state_that_contradicts_its_mode_is_an_error(backend):
    """The driver's consistency guard, where the entry check is skipped: a forced
    inconsistent state raises, naming the time, the mode and the values, and never returns
    a result. Under a = 0.25 g for 1 s slip- has dv/dt = -0.05 g, so v = +1 m/s is still
    positive when the pulse ends."""
    with pytest.raises(bd.InconsistentStateError, match=r"at t = 1 s .*SLIP_NEG: v = \+0.509.* m/s points against"):
        bd.simulate(_WrongKickUnchecked(mu=0.2, g=G), bd.RectangularPulse(0.25 * G, 1.0), backend=backend)


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_long_solver_runs_show_progress_on_a_terminal(monkeypatch):
    """A run past PROGRESS_DELAY writes one refreshed line to a terminal's stderr: the
    time reached of the end [s], the events and the wall time; none to a file."""
    monkeypatch.setattr(driver, "PROGRESS_DELAY", 0.0)
    motion, block = bd.Harmonic(0.8 * G, 0.1), bd.SlidingBlock(mu=MU, g=G)
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    bd.simulate(block, motion, t_end=1.0, backend="cvode")
    assert re.fullmatch(r"(\rcvode: t = [0-9.e-]+ s of 1 s \(\d+ %\), \d+ events, \d+ s elapsed)+\n",
                        terminal.getvalue())
    plain = io.StringIO()
    monkeypatch.setattr(sys, "stderr", plain)
    bd.simulate(block, motion, t_end=1.0, backend="cvode")
    assert plain.getvalue() == ""
