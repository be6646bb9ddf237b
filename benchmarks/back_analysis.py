"""Back-analysis (blockdae.design.back_analysis): NUTS on the exact gradient against a
gradient-free sampler of the same posterior, in effective samples per second.

1. One parameter: the rigid block's ky [g] from one observed displacement (one of
   pySLAMMER's sample records at a target PGA of 0.4 g, D observed at ky = 0.12 g with
   sigma_ln 0.3; prior ky log-normal, median 0.1 g, sigma_ln 0.5).
2. Four parameters: two slopes of one unit sharing c' [kPa] and phi' [deg], each with
   its thickness t [m] a prior (design.InfiniteSlope), one observed D each.
3. The same four parameters from a tight measurement: each D observed with sigma_ln 0.05.

NUTS: ``design.back_analysis`` (NumPyro, 4 chains run together), timed whole: the start,
every JAX compile in the call, warm-up and draws (JAX, NumPyro and ArviZ imported before,
numba's engine loaded from its disk cache). The gradient-free sampler: random-walk
Metropolis (4 chains run together, one engine call per motion and step for all of them) on
the same log posterior (``design.log_posterior``, compiled once), its proposal covariance
tuned on a pilot run (2.38²/d times the pilot's covariance, then its scale adapted toward
a 25 % acceptance) whose time counts. Effective samples: ArviZ's bulk ESS over the
chains (the smallest over the parameters in 2.). Both samplers' posterior means are
printed with their Monte Carlo standard errors; they must agree within 5 combined
standard errors. Wall and CPU seconds (the process's, all threads) are both printed, and
where the wall time went: JAX's tracing and compiling (its monitoring events), the random
walk's pilot, the sampling (NUTS's warm-up, its tuning, runs in the loop of its draws);
and the effective samples per 1,000 evaluations of the log posterior in the kept draws
(NUTS: its leapfrog steps, each the value and gradient), the samplers' cost without their
fixed costs.

Cases 1 and 2 run twice: a first analysis, then one of the same set-up with another
observed D (another truth), where NUTS runs the programs the first compiled (the
observed values and the priors are their arguments) and the random walk's compile is
left out of its time too. Case 3 runs once, after case 2, whose programs NUTS runs
(sigma_ln is their argument), the random walk's compile left out likewise; its ratio is
reported. The bars are judged on the first analyses (every compile counted).
benchmarks/back_analysis_dimensions.py follows the ratio to 32 parameters and measures
its ceiling.

Bars: case 1 reaches 1,000 effective samples within 10 s of wall time; in case 2 NUTS
gives at least 10 times the effective samples per second of random-walk Metropolis.
Exit status 1 when a bar fails.

    python benchmarks/back_analysis.py
"""

import os
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
TIGHT_SIGMA_LN = 0.05  # case 3
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
TIGHT = f"four parameters, sigma_ln {TIGHT_SIGMA_LN:g}"
#: the truths of the repeated analyses (ky [g]; c' [kPa], phi' [deg], t [m])
AGAIN = {"ky": 0.14, "four parameters": {"c_kPa": 7.0, "phi_deg": 31.0, "t_north_m": 3.2, "t_south_m": 1.9}}
ESS_BAR, SECONDS_BAR, RATIO_BAR = 1000.0, 10.0, 10.0


#: JAX's monitoring events of tracing, lowering and compiling a program
COMPILE_EVENTS = ("/jax/core/compile/jaxpr_trace_duration", "/jax/core/compile/jaxpr_to_mlir_module_duration",
                  "/jax/core/compile/backend_compile_duration")


class Clock:
    """Wall and CPU seconds since the start, and the seconds JAX spent compiling in them
    (its monitoring events, summed)."""

    compiling = 0.0

    @classmethod
    def listen(cls):
        import jax

        def listener(event, seconds, **_):
            if event in COMPILE_EVENTS:
                cls.compiling += seconds

        jax.monitoring.register_event_duration_secs_listener(listener)

    def __init__(self):
        self.wall, self.cpu, self.compile = time.perf_counter(), time.process_time(), Clock.compiling

    def since(self):
        """(wall [s], CPU [s], compiling [s]) since this clock started."""
        return time.perf_counter() - self.wall, time.process_time() - self.cpu, Clock.compiling - self.compile


def ess_and_mcse(x):
    """Bulk ESS and the Monte Carlo standard error of the mean of draws ``x`` (chains, draws)."""
    import arviz

    return float(arviz.ess(x, method="bulk")), float(np.std(x) / np.sqrt(arviz.ess(x, method="mean")))


def random_walk_metropolis(log_p, start, steps, pilot, seed=0):
    """(draws (chains, steps, d), acceptance, the pilot's wall seconds) of random-walk
    Metropolis, ``len(start)`` chains together (``log_p`` takes (chains, d)); the
    proposal tuned on ``pilot`` steps first (not kept)."""
    rng = np.random.default_rng(seed)
    x = np.array(start, dtype=float)
    chains, d = x.shape
    lp = np.asarray(log_p(x))
    cov, scale = np.diag((0.05 * np.abs(x).mean(axis=0)) ** 2), 2.38 / np.sqrt(d)

    def run(n, adapt):
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

    began = time.perf_counter()
    for _ in range(3):  # pilot: learn the covariance, then the scale
        draws, _ = run(pilot // 3, True)
        cov = np.cov(draws[:, draws.shape[1] // 2:].reshape(-1, d).T).reshape(d, d) + 1e-12 * np.eye(d)
        scale = 2.38 / np.sqrt(d)
    pilot_seconds = time.perf_counter() - began
    draws, acceptance = run(steps, True)
    return draws, acceptance, pilot_seconds


def nuts_run(observations, model, priors, draws, warmup):
    """NUTS through design.back_analysis, timed: a dict of its draws (name -> (chains,
    draws)), clocks and the mean leapfrog steps per kept draw."""
    clock = Clock()
    result = design.back_analysis(observations, model, priors, chains=CHAINS, draws=draws, warmup=warmup)
    wall, cpu, compiling = clock.since()
    names = list(result.diagnostics.parameter)
    columns = [result.column] if hasattr(result, "column") else names
    samples = {n: result.samples[c].to_numpy().reshape(CHAINS, -1) for n, c in zip(names, columns)}
    return {"draws": samples, "wall": wall, "cpu": cpu, "compile": compiling, "tuning": None,
            "sampling": wall - compiling, "per_draw": float(result.sample_stats.n_steps.mean()),
            "iterations": f"{warmup} warm-up + {draws}"}, result


def rwm_run(log_posterior, names, begin, steps, pilot):
    """Random-walk Metropolis on ``log_posterior`` (a JAX function of the parameters' vector),
    compiled once, timed like :func:`nuts_run`."""
    import jax

    clock = Clock()
    log_p = jax.jit(jax.vmap(log_posterior))
    draws, acceptance, pilot_seconds = random_walk_metropolis(log_p, begin, steps, pilot)
    wall, cpu, compiling = clock.since()
    return {"draws": {n: draws[..., i] for i, n in enumerate(names)}, "wall": wall, "cpu": cpu,
            "compile": compiling, "tuning": pilot_seconds, "sampling": wall - compiling - pilot_seconds,
            "per_draw": 1.0, "iterations": f"{pilot} pilot + {steps}", "acceptance": acceptance}


def one_parameter(record, ky_true=KY_TRUE):
    d = float(design.Rigid().displacements(record, PGA, {"ky": np.array([ky_true])})[0])
    observation = design.Observation(record, sigma_ln=SIGMA_LN, displacement_m=d, pga_g=PGA)
    nuts, result = nuts_run(observation, design.Rigid(), KY_PRIOR, 1000, 400)
    log_p = design.log_posterior(observation, design.Rigid(), KY_PRIOR)
    rwm = rwm_run(lambda theta: log_p(theta[0]), ["ky"], np.full((CHAINS, 1), result.map_value), 4000, 600)
    return nuts, rwm


def four_parameters(record, truth=TRUTH, sigma_ln=SIGMA_LN):
    _, ky = SLOPES.yield_accelerations(truth)
    observations = {name: design.Observation(record, sigma_ln=sigma_ln, pga_g=PGA, displacement_m=float(
        design.Rigid().displacements(record, PGA, {"ky": np.array([ky[name]])})[0])) for name in ky}
    nuts, _ = nuts_run(observations, SLOPES, STRENGTH_PRIORS, 500, 500)
    names = [*STRENGTH_PRIORS, *SLOPES.thickness_names.values()]  # the order of log_posterior's vector
    begin = np.array([[truth[n] for n in names]] * CHAINS) * (1 + 0.01 * np.arange(CHAINS)[:, None])
    rwm = rwm_run(design.log_posterior(observations, SLOPES, STRENGTH_PRIORS), names, begin, 8000, 1500)
    return nuts, rwm


def compiled_before(run):
    """``run`` timed without its JAX compiling (the random walk's, in a repeated analysis)."""
    return run | {"wall": run["wall"] - run["compile"], "compile": 0.0}


def summarised(run):
    """Per parameter (bulk ESS, MCSE, mean), the smallest ESS per wall second [1/s] and per
    1,000 evaluations of the log posterior in the kept draws."""
    per = {n: (*ess_and_mcse(x), x.mean()) for n, x in run["draws"].items()}
    least = min(p[0] for p in per.values())
    chains, kept = next(iter(run["draws"].values())).shape
    return per, least / run["wall"], 1000 * least / (chains * kept * run["per_draw"])


def main():
    import jax

    import arviz  # noqa: F401 -- imported before the clocks start (a session imports them once); compiles count
    import numpyro  # noqa: F401

    jax.config.update("jax_enable_x64", True)
    Clock.listen()
    warnings.simplefilter("ignore", bd.CompileNotice)
    warnings.simplefilter("ignore", FutureWarning)  # ArviZ's notice of its coming refactor
    record = next(r for r in sample_records() if r.name == RECORD)
    design.Rigid().displacements(record, PGA, {"ky": np.array([0.1])}, derivative=True)  # numba's disk cache, loaded
    print(f"{RECORD} scaled to {PGA} g ({record.acceleration_samples.size} samples, dt {record.dt} s); "
          f"{CHAINS} chains per sampler; CPU = the process's CPU seconds over all its threads; load average "
          f"{os.getloadavg()[0]:.1f} at the start")
    cases = {"ky": one_parameter(record), "four parameters": four_parameters(record)}
    nuts, rwm = four_parameters(record, sigma_ln=TIGHT_SIGMA_LN)  # sigma_ln is an argument of the compiled programs
    cases[TIGHT] = nuts, compiled_before(rwm)
    nuts, rwm = one_parameter(record, ky_true=AGAIN["ky"])
    cases["ky, again"] = nuts, compiled_before(rwm)
    nuts, rwm = four_parameters(record, truth=AGAIN["four parameters"])
    cases["four parameters, again"] = nuts, compiled_before(rwm)
    labels = ("NUTS (exact gradient)", "random-walk Metropolis")
    rows, timing, ratios, agree = [], [], {}, True
    for case, runs in cases.items():
        results = [summarised(run) for run in runs]
        for label, run, (per, per_second, per_thousand) in zip(labels, runs, results):
            for name, (ess, mcse, mean) in per.items():
                rows.append((name, label, f"{ess:.0f}", f"{ess / run['wall']:.1f}", f"{mean:.5g}", f"{mcse:.2g}"))
            tuning = "in sampling" if run["tuning"] is None else f"{run['tuning']:.2f}"
            timing.append((case, label, run["iterations"], f"{run['wall']:.2f}", f"{run['cpu']:.2f}",
                           f"{run['compile']:.2f}", tuning, f"{run['sampling']:.2f}", f"{run['per_draw']:.1f}",
                           f"{per_second:.1f}", f"{per_thousand:.1f}"))
        ratios[case] = results[0][1] / results[1][1]
        agree &= all(abs(a[2] - b[2]) <= 5 * np.hypot(a[1], b[1])
                     for a, b in zip(results[0][0].values(), results[1][0].values()))
    print_table(("parameter", "sampler", "bulk ESS [-]", "ESS per wall s [1/s]", "posterior mean [unit]",
                 "MCSE [unit]"), rows)
    print("units: ky [g], c_kPa [kPa], phi_deg [deg], t_*_m [m]")
    print_table(("case", "sampler", "iterations per chain", "wall [s]", "CPU [s]", "JAX compile [s]", "tuning [s]",
                 "sampling [s]", "evaluations per draw [-]", "least ESS per wall s [1/s]",
                 "least ESS per 1,000 evaluations [-]"), timing)
    print("NUTS's sampling: its wall time but JAX's compiling (its start, its warm-up (its tuning, run in the loop of "
          "its draws), draws and diagnostics); "
          "evaluations per draw: NUTS's mean leapfrog steps (the log posterior and its gradient, one engine call "
          "per motion for all chains), one for random-walk Metropolis; per 1,000 evaluations: of the kept draws; "
          f"random-walk acceptance {cases['ky'][1]['acceptance']:.0%} (ky), "
          f"{cases['four parameters'][1]['acceptance']:.0%} (four parameters), {cases[TIGHT][1]['acceptance']:.0%} "
          f"({TIGHT}); again: another observed D of the "
          "same set-up, NUTS running the programs the first analysis compiled, the random walk's compile left out")
    nuts = cases["ky"][0]
    ess_ky = ess_and_mcse(nuts["draws"]["ky"])[0]
    per_bar = ess_ky / nuts["wall"] * SECONDS_BAR  # effective samples per SECONDS_BAR of wall time
    checks = [
        (f"ky: NUTS bulk ESS {ess_ky:.0f} in {nuts['wall']:.2f} s wall, {nuts['cpu']:.2f} s CPU (compile included), "
         f"{per_bar:.0f} per {SECONDS_BAR:g} s wall", per_bar >= ESS_BAR, f">= {ESS_BAR:.0f} per {SECONDS_BAR:g} s"),
        (f"ky: NUTS / random-walk ESS per second {ratios['ky']:.2f} x", True, "reported"),
        (f"four parameters: NUTS / random-walk ESS per second (smallest over the parameters) "
         f"{ratios['four parameters']:.2f} x", ratios["four parameters"] >= RATIO_BAR, f">= {RATIO_BAR:g} x"),
        (f"{TIGHT}: NUTS / random-walk ESS per second {ratios[TIGHT]:.2f} x", True, "reported"),
        (f"again, the set-up compiled: NUTS / random-walk ESS per second {ratios['ky, again']:.2f} x (ky), "
         f"{ratios['four parameters, again']:.2f} x (four parameters)", True, "reported"),
        ("posterior means agree within 5 combined Monte Carlo standard errors", agree, "required"),
    ]
    failures = []
    for text, ok, bar in checks:
        print(f"{text} (bar {bar}): {'met' if ok else 'NOT met'}")
        if not ok:
            failures.append(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
