"""Back-analysis (blockdae.design.back_analysis): NUTS on the exact gradient against a
gradient-free sampler of the same posterior, in effective samples per second.

1. One parameter: the rigid block's ky [g] from one observed displacement (one of
   pySLAMMER's sample records at a target PGA of 0.4 g, D observed at ky = 0.12 g with
   sigma_ln 0.3; prior ky log-normal, median 0.1 g, sigma_ln 0.5).
2. Four parameters: two slopes of one unit sharing c' [kPa] and phi' [deg], each with
   its thickness t [m] a prior (design.InfiniteSlope), one observed D each.

NUTS: ``design.back_analysis`` (NumPyro, 4 chains run together), timed whole: the start,
every JAX compile in the call, warmup and draws (JAX, NumPyro and ArviZ imported before,
numba's engine loaded from its disk cache). The gradient-free sampler: random-walk
Metropolis (4 chains run together, one engine call per step for all of them) on the
same log posterior (``design.log_posterior``, compiled once), its proposal covariance
tuned on a pilot run (2.38²/d times the pilot's covariance, then its scale adapted toward
a 25 % acceptance) whose time counts. Effective samples: ArviZ's bulk ESS over the
chains (the smallest over the parameters in 2.). Both samplers' posterior means are
printed with their Monte Carlo standard errors; they must agree within 5 combined
standard errors. Wall and CPU seconds (the process's, all threads) are both printed.

Bars: case 1 reaches 1,000 effective samples within 10 s of wall time; in case 2 NUTS
gives at least 10 times the effective samples per second of random-walk Metropolis.
Exit status 1 when a bar fails.

    python benchmarks/back_analysis.py
"""

import sys
import time
import warnings

import numpy as np

import blockdae as bd
from blockdae import design
from _common import print_table, sample_records

RECORD = "Northridge_1994_PAC-175"
PGA = 0.4  # g
KY_TRUE = 0.12  # g
SIGMA_LN = 0.3
KY_PRIOR = {"ky": design.LogNormal(median=0.1, sigma_ln=0.5)}
SLOPES = design.InfiniteSlope({
    "north": design.Slope(slope_deg=30.0, unit_weight_kn_m3=19.0,
                          thickness_m=design.LogNormal(median=3.0, sigma_ln=0.2)),
    "south": design.Slope(slope_deg=25.0, unit_weight_kn_m3=19.0, saturated_fraction=0.3,
                          thickness_m=design.LogNormal(median=2.0, sigma_ln=0.2))})
STRENGTH_PRIORS = {"c_kPa": design.LogNormal(median=6.0, sigma_ln=0.5),
                   "phi_deg": design.Truncated(design.Normal(32.0, 3.0), low=15.0, high=45.0)}
TRUTH = {"c_kPa": 8.0, "phi_deg": 30.0, "t_north_m": 3.0, "t_south_m": 2.0}
CHAINS = 4
ESS_BAR, SECONDS_BAR, RATIO_BAR = 1000.0, 10.0, 10.0


def clocks():
    return time.perf_counter(), time.process_time()


def since(start):
    wall, cpu = clocks()
    return wall - start[0], cpu - start[1]


def ess_and_mcse(x):
    """Bulk ESS and the Monte Carlo standard error of the mean of draws ``x`` (chains, draws)."""
    import arviz

    return float(arviz.ess(x, method="bulk")), float(np.std(x) / np.sqrt(arviz.ess(x, method="mean")))


def random_walk_metropolis(log_p, start, steps, pilot, seed=0):
    """(draws (chains, steps, d), acceptance) of random-walk Metropolis, ``len(start)``
    chains together (``log_p`` takes (chains, d)); the proposal tuned on ``pilot`` steps
    first (not kept)."""
    rng = np.random.default_rng(seed)
    x = np.array(start, dtype=float)
    chains, d = x.shape
    lp = np.asarray(log_p(x))
    cov, scale = np.diag((0.05 * np.abs(x).mean(axis=0)) ** 2), 2.38 / np.sqrt(d)

    def run(n, keep, adapt):
        nonlocal x, lp, scale
        chol = np.linalg.cholesky(cov)
        out, accepted = np.empty((chains, n, d)), 0
        for i in range(n):
            proposal = x + scale * rng.standard_normal((chains, d)) @ chol.T
            lp_new = np.asarray(log_p(proposal))
            accept = np.log(rng.uniform(size=chains)) < lp_new - lp
            x, lp = np.where(accept[:, None], proposal, x), np.where(accept, lp_new, lp)
            accepted += accept.sum()
            if adapt:
                scale *= np.exp((accept.mean() - 0.25) / np.sqrt(i + 1))
            out[:, i] = x
        return out, accepted / (n * chains)

    for _ in range(3):  # pilot: learn the covariance, then the scale
        draws, _ = run(pilot // 3, False, True)
        cov = np.cov(draws[:, draws.shape[1] // 2:].reshape(-1, d).T).reshape(d, d) + 1e-12 * np.eye(d)
        scale = 2.38 / np.sqrt(d)
    return run(steps, True, True)


def one_parameter(record):
    d = float(design.Rigid().displacements(record, PGA, {"ky": np.array([KY_TRUE])})[0])
    observation = design.Observation(record, sigma_ln=SIGMA_LN, displacement_m=d, pga_g=PGA)
    start = clocks()
    result = design.back_analysis(observation, design.Rigid(), KY_PRIOR, chains=CHAINS, draws=1000, warmup=400)
    nuts_wall, nuts_cpu = since(start)
    ky = result.samples.ky_g.to_numpy().reshape(CHAINS, -1)
    nuts = (nuts_wall, nuts_cpu, *ess_and_mcse(ky), ky.mean())

    import jax

    start = clocks()
    log_p = jax.jit(jax.vmap(lambda theta: design.log_posterior(observation, design.Rigid(), KY_PRIOR)(theta[0])))
    draws, acceptance = random_walk_metropolis(log_p, np.full((CHAINS, 1), result.map_value), 4000, 600)
    rwm_wall, rwm_cpu = since(start)
    rwm = (rwm_wall, rwm_cpu, *ess_and_mcse(draws[..., 0]), draws.mean())
    return nuts, rwm, acceptance


def four_parameters(record):
    _, ky = SLOPES.yield_accelerations(TRUTH)
    observations = {name: design.Observation(record, sigma_ln=SIGMA_LN, pga_g=PGA, displacement_m=float(
        design.Rigid().displacements(record, PGA, {"ky": np.array([ky[name]])})[0])) for name in ky}
    start = clocks()
    result = design.back_analysis(observations, SLOPES, STRENGTH_PRIORS, chains=CHAINS, draws=500, warmup=500)
    nuts_wall, nuts_cpu = since(start)
    names = list(result.diagnostics.parameter)
    nuts_draws = np.stack([result.samples[n].to_numpy().reshape(CHAINS, -1) for n in names], axis=-1)

    import jax

    start = clocks()
    log_p = jax.jit(jax.vmap(design.log_posterior(observations, SLOPES, STRENGTH_PRIORS)))
    begin = np.array([[TRUTH[n] for n in names]] * CHAINS) * (1 + 0.01 * np.arange(CHAINS)[:, None])
    draws, acceptance = random_walk_metropolis(log_p, begin, 8000, 1500)
    rwm_wall, rwm_cpu = since(start)
    return names, (nuts_wall, nuts_cpu, nuts_draws), (rwm_wall, rwm_cpu, draws), acceptance


def main():
    import jax

    import arviz  # noqa: F401 -- imported before the clocks start (a session imports them once); compiles count
    import numpyro  # noqa: F401

    jax.config.update("jax_enable_x64", True)
    warnings.simplefilter("ignore", bd.CompileNotice)
    warnings.simplefilter("ignore", FutureWarning)  # ArviZ's notice of its coming refactor
    record = next(r for r in sample_records() if r.name == RECORD)
    design.Rigid().displacements(record, PGA, {"ky": np.array([0.1])}, derivative=True)  # numba's disk cache, loaded
    print(f"{RECORD} scaled to {PGA} g ({record.acceleration_samples.size} samples, dt {record.dt} s); "
          f"{CHAINS} chains per sampler; CPU = the process's CPU seconds over all its threads")
    rows, failures = [], []
    nuts, rwm, acceptance = one_parameter(record)
    for name, (wall, cpu, ess, mcse, mean) in (("NUTS (exact gradient)", nuts), ("random-walk Metropolis", rwm)):
        rows.append(("ky", name, f"{wall:.2f}", f"{cpu:.2f}", f"{ess:.0f}", f"{ess / wall:.1f}", f"{mean:.5f}",
                     f"{mcse:.5f}"))
    one_ratio = (nuts[2] / nuts[0]) / (rwm[2] / rwm[0])
    agree_1 = abs(nuts[4] - rwm[4]) <= 5 * np.hypot(nuts[3], rwm[3])

    names, (n_wall, n_cpu, n_draws), (r_wall, r_cpu, r_draws), acceptance_4 = four_parameters(record)
    stats = {}
    for label, wall, cpu, draws in (("NUTS (exact gradient)", n_wall, n_cpu, n_draws),
                                    ("random-walk Metropolis", r_wall, r_cpu, r_draws)):
        per = [ess_and_mcse(draws[..., i]) + (draws[..., i].mean(),) for i in range(len(names))]
        stats[label] = (wall, per)
        for i, name in enumerate(names):
            ess, mcse, mean = per[i]
            rows.append((name, label, f"{wall:.2f}", f"{cpu:.2f}", f"{ess:.0f}", f"{ess / wall:.1f}", f"{mean:.5g}",
                         f"{mcse:.2g}"))
    least = {label: min(p[0] for p in per) / wall for label, (wall, per) in stats.items()}
    four_ratio = least["NUTS (exact gradient)"] / least["random-walk Metropolis"]
    agree_4 = all(abs(a[2] - b[2]) <= 5 * np.hypot(a[1], b[1])
                  for a, b in zip(stats["NUTS (exact gradient)"][1], stats["random-walk Metropolis"][1]))
    print_table(("parameter", "sampler", "wall [s]", "CPU [s]", "bulk ESS [-]", "ESS per wall s [1/s]",
                 "posterior mean [unit]", "MCSE [unit]"), rows)
    print(f"units: ky [g], c_kPa [kPa], phi_deg [deg], t_*_m [m]; random-walk acceptance {acceptance:.0%} (ky), "
          f"{acceptance_4:.0%} (four parameters)")
    per_bar = nuts[2] / nuts[0] * SECONDS_BAR  # effective samples per SECONDS_BAR of wall time
    checks = [
        (f"ky: NUTS bulk ESS {nuts[2]:.0f} in {nuts[0]:.2f} s wall, {nuts[1]:.2f} s CPU (compile included), "
         f"{per_bar:.0f} per {SECONDS_BAR:g} s wall", per_bar >= ESS_BAR, f">= {ESS_BAR:.0f} per {SECONDS_BAR:g} s"),
        (f"ky: NUTS / random-walk ESS per second {one_ratio:.1f} x", True, "reported"),
        (f"four parameters: NUTS / random-walk ESS per second (smallest over the parameters) {four_ratio:.1f} x",
         four_ratio >= RATIO_BAR, f">= {RATIO_BAR:g} x"),
        ("posterior means agree within 5 combined Monte Carlo standard errors", agree_1 and agree_4, "required"),
    ]
    for text, ok, bar in checks:
        print(f"{text} (bar {bar}): {'met' if ok else 'NOT met'}")
        if not ok:
            failures.append(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
