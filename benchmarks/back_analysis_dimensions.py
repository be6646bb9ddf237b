"""Back-analysis in more parameters: NUTS on the exact gradient (``design.back_analysis``)
against tuned random-walk Metropolis, on one unit of N slopes sharing c' [kPa] and phi'
[deg], each slope with its thickness t [m] a prior and one observed D: d = 2 + N
parameters, N = 2, 6, 14 and 30.

The slopes: the two of ``benchmarks/back_analysis.py`` (its four-parameter case is the
first row here), then slopes drawn once with a fixed seed: angle 22-34 deg, unit weight
18-21 kN/m³, saturated fraction 0, 0.2 or 0.4, prior of t log-normal (median 1.5-4 m,
sigma_ln 0.2), the true t one draw of that prior, kept where the true ky lies in
0.05-0.25 g. Truth c' = 8 kPa, phi' = 30 deg; each slope's D computed at its true ky
under pySLAMMER's Northridge 1994 PAC-175 scaled to 0.4 g and observed with sigma_ln
0.3 (all slopes under one motion: one engine call per evaluation for every slope and
chain). Priors of c' and phi' those of back_analysis.py.

Each sampler timed whole, as in back_analysis.py (NUTS: 500 warm-up + 500 draws per
chain, 4 chains run together, every JAX compile in its call; the random walk: its
compile, pilot and steps: 8,000 steps after a 1,500-step pilot, or 500 d steps after a
10 d²-step pilot where these are more, enough for it to learn the d x d covariance);
effective samples per second with every compile counted and without JAX's compiling
(the seconds its monitoring events report, taken off). The rigid block is timed and
counted inside each run (a ``design.Rigid`` whose ``displacements`` adds up its calls
and seconds), so that each run's time splits into the engine and the rest (for NUTS:
JAX's callback, NumPyro's tree building, its chains waiting for the longest tree).

The ceiling: NUTS (NumPyro's, the same settings: dense mass, its default adaptation, 4
chains vectorised, 500 + 500) and the same random walk (same tuning and steps) on an
exactly Gaussian target with the covariance of NUTS's posterior draws in the space each
sampler samples (NUTS: each parameter mapped to the real line, ln c', ln t, the logit
of phi' in its prior's bounds; the random walk: the parameters as they are), its log
density free: the effective samples per 1,000 evaluations each gets when the posterior
is as easy as it can be. Multiplied by the ratio of the costs of one evaluation for the
4 chains, engine included (the random walk's value over NUTS's value and gradient),
timed alone (NUTS's in a compiled loop, the walk's a compiled call from Python) or in
the runs (compile out, over the engine calls), it bounds NUTS / random-walk effective
samples per second from above.

    python benchmarks/back_analysis_dimensions.py           # about 5 minutes on 2 shared cores
    python benchmarks/back_analysis_dimensions.py --quick   # a smoke run: 2 and 3 slopes, short chains
"""

import argparse
import math
import os
import sys
import time
import warnings

import numpy as np

import blockdae as bd
from blockdae import design
from _common import SMOKE_RUN, print_table, sample_records
from back_analysis import (CHAINS, PGA, RECORD, SIGMA_LN, SLOPES, STRENGTH_PRIORS, TRUTH, Clock, ess_and_mcse,
                           nuts_run, random_walk_metropolis, rwm_run)

SLOPE_COUNTS = (2, 6, 14, 30)
RATIO_BAR = 10.0
#: the drawn slopes' ranges: angle [deg], unit weight [kN/m³], saturated fractions [-],
#: prior median of t [m], true ky [g]
ANGLE, WEIGHT, SATURATED, THICKNESS, KY_RANGE = (22.0, 34.0), (18.0, 21.0), (0.0, 0.0, 0.2, 0.4), (1.5, 4.0), \
    (0.05, 0.25)


class TimedRigid(design.Rigid):
    """The rigid block, its calls of :meth:`displacements` and their seconds added up
    (class attributes, reset by :meth:`reset`)."""

    calls, seconds = 0, 0.0

    @classmethod
    def reset(cls):
        cls.calls, cls.seconds = 0, 0.0

    def displacements(self, record, pga, values, derivative=False):
        began = time.perf_counter()
        try:
            return super().displacements(record, pga, values, derivative)
        finally:
            TimedRigid.calls += 1
            TimedRigid.seconds += time.perf_counter() - began


def unit(n, seed=3):
    """(the InfiniteSlope of ``n`` slopes on TimedRigid, the truth: name -> value): the
    two slopes of back_analysis.py, then ``n`` - 2 drawn (see the module's docstring)."""
    rng = np.random.default_rng(seed)
    slopes, truth = dict(SLOPES.slopes), dict(TRUTH)
    while len(slopes) < n:
        name = f"s{len(slopes) + 1:02d}"
        slope = design.Slope(slope_deg=round(rng.uniform(*ANGLE), 1), unit_weight_kn_m3=round(rng.uniform(*WEIGHT), 1),
                             saturated_fraction=float(rng.choice(SATURATED)),
                             thickness_m=design.LogNormal(median=round(rng.uniform(*THICKNESS), 2), sigma_ln=0.2))
        t = round(slope.thickness_m.median * math.exp(0.2 * rng.standard_normal()), 2)
        _, ky = design.InfiniteSlope({name: slope}).yield_accelerations(truth | {f"t_{name}_m": t})
        if KY_RANGE[0] <= ky[name] <= KY_RANGE[1]:
            slopes[name], truth[f"t_{name}_m"] = slope, t
    return design.InfiniteSlope(slopes, model=TimedRigid()), truth


def priors_of(slopes):
    """name -> the prior of each parameter (c_kPa, phi_deg, t_<slope>_m)."""
    return dict(STRENGTH_PRIORS) | {slopes.thickness_names[n]: s.thickness_m for n, s in slopes.slopes.items()}


def to_real_line(prior, x):
    """``x`` mapped to the real line as NumPyro's NUTS samples it (biject_to of the
    prior's support): ln x for a log-normal, the logit in a truncated prior's bounds."""
    if isinstance(prior, design.Truncated):
        p = (x - prior.low) / (prior.high - prior.low)
        return np.log(p / (1 - p))
    return np.log(x)


def gaussian_nuts(covariance, draws, warmup, seed=1):
    """NumPyro's NUTS (as design.back_analysis runs it: dense mass, default adaptation,
    ``CHAINS`` chains vectorised, warm-up then draws in one compiled program) on N(0,
    ``covariance``): (draws (chains, draws, d), leapfrog steps of every iteration
    (chains, warmup + draws))."""
    import jax
    from numpyro.infer.hmc import hmc

    precision = jax.numpy.asarray(np.linalg.inv(covariance))
    init_kernel, sample_kernel = hmc(potential_fn=lambda z: 0.5 * z @ precision @ z, algo="NUTS")

    def chain(key, start):
        state = init_kernel(start, warmup, dense_mass=True, rng_key=key)

        def step(state, _):
            state = sample_kernel(state)
            return state, (state.z, state.num_steps)

        state, (_, warm_steps) = jax.lax.scan(step, state, None, length=warmup)
        _, (z, steps) = jax.lax.scan(step, state, None, length=draws)
        return z, jax.numpy.concatenate([warm_steps, steps])

    run = jax.jit(lambda key, starts: jax.vmap(chain)(jax.random.split(key, CHAINS), starts))
    rng = np.random.default_rng(seed)
    starts = rng.standard_normal((CHAINS, len(covariance))) @ np.linalg.cholesky(covariance).T
    z, steps = run(jax.random.PRNGKey(seed), starts)
    return np.asarray(z), np.asarray(steps)


def least_ess(draws):
    """The smallest bulk ESS over the last axis of ``draws`` (chains, draws, d)."""
    return min(ess_and_mcse(draws[..., i])[0] for i in range(draws.shape[-1]))


def ceiling(posterior, names, priors, steps, pilot, draws, warmup):
    """Effective samples per 1,000 evaluations (one chain's value, with the gradient for
    NUTS; the kept draws) of NUTS and of the random walk on the Gaussian with the
    covariance of the ``posterior`` draws (NUTS's, name -> (chains, draws)) in the space
    each samples (NUTS: the real line; the walk: the parameters)."""
    real = np.stack([to_real_line(priors[n], posterior[n]) for n in names], axis=-1)
    z, n_steps = gaussian_nuts(np.cov(real.reshape(-1, len(names)).T), draws, warmup)
    kept = n_steps[:, warmup:]
    nuts = 1000 * least_ess(z) / kept.sum()
    raw = np.stack([posterior[n] for n in names], axis=-1)
    mean, precision = raw.reshape(-1, len(names)).mean(axis=0), np.linalg.inv(np.cov(raw.reshape(-1, len(names)).T))

    def log_p(x):
        return -0.5 * np.einsum("ci,ij,cj->c", x - mean, precision, x - mean)

    walk, _, _ = random_walk_metropolis(log_p, mean * (1 + 0.01 * np.arange(CHAINS)[:, None]), steps, pilot)
    return nuts, 1000 * least_ess(walk) / (CHAINS * steps)


def evaluation_costs(log_posterior, at, repeat):
    """Seconds of one evaluation for the ``CHAINS`` chains at the points ``at`` (chains,
    d), each timed alone: (NUTS's value and gradient, ``repeat`` of them in one compiled
    loop; the random walk's value, a compiled call from Python)."""
    import jax

    value_and_grad = jax.vmap(jax.value_and_grad(log_posterior))
    at = jax.numpy.asarray(at)

    def body(i, total):
        value, grad = value_and_grad(at * (1 + 1e-9 * i))
        return total + value.sum() + grad.sum()

    loop = jax.jit(lambda: jax.lax.fori_loop(0, repeat, body, 0.0))
    value = jax.jit(jax.vmap(log_posterior))
    loop().block_until_ready(), value(at).block_until_ready()
    began = time.perf_counter()
    loop().block_until_ready()
    gradient_seconds = (time.perf_counter() - began) / repeat
    began = time.perf_counter()
    for i in range(repeat):
        np.asarray(value(at * (1 + 1e-9 * i)))
    return gradient_seconds, (time.perf_counter() - began) / repeat


def one_unit(record, n, draws, warmup, steps, pilot):
    """The N-slope case: both samplers on the posterior, timed, their engine calls counted,
    the ceiling and the evaluation costs."""
    slopes, truth = unit(n)
    _, ky = slopes.yield_accelerations(truth)
    displacement = dict(zip(ky, slopes.model.displacements(record, PGA, {"ky": np.array(list(ky.values()))})))
    observations = {name: design.Observation(record, sigma_ln=SIGMA_LN, pga_g=PGA, displacement_m=float(d))
                    for name, d in displacement.items()}
    priors = priors_of(slopes)
    TimedRigid.reset()
    nuts, result = nuts_run(observations, slopes, STRENGTH_PRIORS, draws, warmup)
    nuts |= {"calls": TimedRigid.calls, "engine": TimedRigid.seconds}
    n_steps = result.sample_stats.pivot(index="draw", columns="chain", values="n_steps").to_numpy()
    nuts["waiting"] = n_steps.max(axis=1).sum() / n_steps.mean(axis=1).sum()
    names = list(priors)  # the order of log_posterior's vector
    begin = np.array([[truth[name] for name in names]] * CHAINS) * (1 + 0.01 * np.arange(CHAINS)[:, None])
    log_posterior = design.log_posterior(observations, slopes, STRENGTH_PRIORS)
    TimedRigid.reset()
    rwm = rwm_run(log_posterior, names, begin, steps, pilot)
    rwm |= {"calls": TimedRigid.calls, "engine": TimedRigid.seconds}
    at = np.stack([rwm["draws"][name][:, -1] for name in names], axis=-1)
    costs = evaluation_costs(log_posterior, at, 200)
    gaussian = ceiling(nuts["draws"], names, priors, steps, pilot, draws, warmup)
    return {"d": len(names), "nuts": nuts, "rwm": rwm, "costs": costs, "gaussian": gaussian}


def rates(run):
    """(smallest bulk ESS, per wall second [1/s], per wall second without JAX's compiling
    [1/s], per 1,000 evaluations (one chain's, kept draws) [-])."""
    ess = min(ess_and_mcse(x)[0] for x in run["draws"].values())
    chains, kept = next(iter(run["draws"].values())).shape
    return ess, ess / run["wall"], ess / (run["wall"] - run["compile"]), 1000 * ess / (chains * kept * run["per_draw"])


def arguments(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="2 and 3 slopes, short chains (smoke run)")
    return parser.parse_args(argv)


def main(argv=None):
    args = arguments(argv)
    import jax

    import arviz  # noqa: F401 -- imported before the clocks start, as in back_analysis.py
    import numpyro  # noqa: F401

    jax.config.update("jax_enable_x64", True)
    Clock.listen()
    warnings.simplefilter("ignore", bd.CompileNotice)
    warnings.simplefilter("ignore", FutureWarning)  # ArviZ's notice of its coming refactor
    warnings.simplefilter("ignore", design.ConvergenceWarning)  # short --quick chains; ESS is reported
    record = next(r for r in sample_records() if r.name == RECORD)
    design.Rigid().displacements(record, PGA, {"ky": np.array([0.1])}, derivative=True)  # numba's disk cache, loaded
    counts, draws, warmup = ((2, 3), 100, 100) if args.quick else (SLOPE_COUNTS, 500, 500)
    print(f"{RECORD} scaled to {PGA} g ({record.acceleration_samples.size} samples, dt {record.dt} s); {CHAINS} chains "
          f"per sampler, NUTS {warmup} warm-up + {draws} draws; load average {os.getloadavg()[0]:.1f} at the start")
    cases = {}
    for n in counts:
        steps = 1000 if args.quick else max(8000, 500 * (n + 2))
        pilot = 300 if args.quick else max(1500, 10 * (n + 2) ** 2)  # a d x d covariance to learn
        cases[n] = one_unit(record, n, draws, warmup, steps, pilot)
    rows, ratios, profile = [], [], []
    for n, case in cases.items():
        for label, run in (("NUTS", case["nuts"]), ("random walk", case["rwm"])):
            ess, per_second, compiled, per_thousand = run["rates"] = rates(run)
            rows.append((str(n), str(case["d"]), label, run["iterations"], f"{run['wall']:.1f}",
                         f"{run['compile']:.1f}", f"{run['engine']:.1f}", f"{run['calls']:,}", f"{ess:.0f}",
                         f"{per_second:.1f}", f"{compiled:.1f}", f"{run['per_draw']:.1f}", f"{per_thousand:.1f}"))
        nuts, rwm = case["nuts"], case["rwm"]
        gauss_nuts, gauss_rwm = case["gaussian"]
        gradient_alone, value_alone = case["costs"]
        case["ratios"] = [nuts["rates"][i] / rwm["rates"][i] for i in (1, 2, 3)]
        # seconds per evaluation (one chain's) in the runs, compile out: NUTS's engine calls
        # are its vectorised leapfrog steps, each waiting for the chains' longest tree
        nuts_call = (nuts["wall"] - nuts["compile"]) / nuts["calls"]
        rwm_call = (rwm["wall"] - rwm["compile"]) / rwm["calls"]
        in_runs = rwm_call / (nuts_call * nuts["waiting"])
        per_evaluation = gauss_nuts / gauss_rwm
        case["bounds"] = per_evaluation * value_alone / gradient_alone, per_evaluation * in_runs
        ratios.append((str(case["d"]), *(f"{r:.2f}" for r in case["ratios"]), f"{gauss_nuts:.0f}", f"{gauss_rwm:.1f}",
                       f"{per_evaluation:.1f}", f"{value_alone / gradient_alone:.2f}", f"{in_runs:.2f}",
                       *(f"{b:.1f}" for b in case["bounds"])))
        profile.append((str(case["d"]), f"{nuts['calls']:,}", f"{nuts['waiting']:.2f}", f"{1e3 * nuts_call:.2f}",
                        f"{1e3 * nuts['engine'] / nuts['calls']:.2f}", f"{1e3 * gradient_alone:.2f}",
                        f"{1e3 * rwm_call:.2f}", f"{1e3 * rwm['engine'] / rwm['calls']:.2f}",
                        f"{1e3 * value_alone:.2f}"))
    print_table(("slopes", "parameters d", "sampler", "iterations per chain", "wall [s]", "JAX compile [s]",
                 "engine [s]", "engine calls", "least bulk ESS [-]", "ESS per wall s [1/s]",
                 "ESS per wall s, compile out [1/s]", "evaluations per draw [-]", "ESS per 1,000 evaluations [-]"),
                rows)
    print("engine: the rigid block's calls and seconds inside the run (one call per evaluation of the 4 chains, for "
          "every slope; one more for NUTS's starting points); an evaluation: one chain's value of the log posterior, "
          "with its gradient for NUTS (its leapfrog steps), in the kept draws; ESS: the smallest over the parameters\n")
    print_table(("d", "NUTS / walk ESS per s [-]", "compile out [-]", "per evaluation [-]",
                 "Gaussian: NUTS ESS per 1,000 ev. [-]", "walk [-]", "NUTS / walk [-]",
                 "cost walk / NUTS, alone [-]", "in the runs [-]", "bound, alone [-]", "bound, in the runs [-]"),
                ratios)
    print("Gaussian: the same samplers on N(mean, the covariance of NUTS's posterior draws), each in its own space; "
          "cost walk / NUTS: seconds of one evaluation, the value against the value and gradient, engine included, "
          "timed alone or in the runs (compile out; NUTS's tree building and its chains waiting for the longest "
          "tree included); bound: the Gaussian's NUTS / walk per evaluation times that cost ratio\n")
    print_table(("d", "NUTS engine calls", "calls / mean leapfrog steps [-]", "NUTS per call [ms]", "of it engine [ms]",
                 "value and gradient alone [ms]", "walk per step [ms]", "of it engine [ms]", "value alone [ms]"),
                profile)
    print("per call: a run's wall time, compile out, over its engine calls (NUTS: one a vectorised leapfrog step of "
          "the 4 chains; the walk: one a step, its pilot included); calls / mean leapfrog steps: the vectorised "
          "chains wait for the longest tree (kept draws); alone: one evaluation of the 4 chains timed by itself "
          "(NUTS's in a compiled loop, the walk's a compiled call from Python)")
    largest = max(case["d"] for case in cases.values())

    def first(column):
        reached = [case["d"] for case in cases.values() if case["ratios"][column] >= RATIO_BAR]
        return f"first at d = {reached[0]}" if reached else f"at no d up to {largest}"

    verdict = SMOKE_RUN if args.quick else f"{RATIO_BAR:g} x reached {first(0)} with every compile counted, " \
                                           f"{first(1)} with compiling left out"
    print(f"NUTS / random-walk ESS per second: {verdict}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
