"""The Laplace back-analysis (design.back_analysis with method="laplace") against the
posterior by quadrature: its normal in ln ky at the maximum alone, and its draws weighted
toward the exact posterior by Pareto-smoothed importance sampling and resampled (what it
returns), with their Pareto k̂ and importance effective sample size.

The rigid block's ky [g] (prior log-normal, median 0.1 g, sigma_ln 0.5) from one
observation under a decaying 1 Hz sine of 8 s, peak 0.3 g (the tests' record): the block's
D at ky = 0.12 g seen with sigma_ln 0.05, 0.2 and 0.3, and a bound ("it moved more than
0.5 m", sigma_ln 0.05) under a wider prior (sigma_ln 1.0), whose posterior follows the
prior toward low ky and falls off sharply above. The reference: the posterior on 8001 ky
evenly spread in ln ky from the prior's 1e-6 quantile to 0.3 g (above the record's peak,
0.279 g, D = 0), the exact forward model at each, the trapezoid rule, the density from
scipy. Each estimate's error is printed in posterior sd and in Monte Carlo standard errors
of the returned draws: sd sqrt(1 / ESS + 1 / n) for the mean, sqrt(q (1 - q) (1 / ESS +
1 / n)) / density for a quantile (ESS the importance sampling's, n the draws).

Bars: where k̂ is within its limit (0.7), the returned draws' mean, 5 % and 95 % quantiles
lie within 4 Monte Carlo standard errors of the quadrature's; the bound's k̂ exceeds 0.7
and warns. Exit status 1 when a bar fails.

    python benchmarks/laplace_importance.py [--draws N] [--quick]

--quick (a smoke run, not a measurement): sigma_ln 0.2 alone, 4000 draws.
"""

import argparse
import math
import time
import warnings

import numpy as np
from scipy import integrate, stats

import blockdae as bd
from blockdae import design
from _common import G, print_table, verdict

KY_TRUE = 0.12  # [g]
#: (label, observation's kind, its sigma_ln, the prior's sigma_ln)
CASES = (("D, sigma_ln 0.05", "displacement", 0.05, 0.5), ("D, sigma_ln 0.2", "displacement", 0.2, 0.5),
         ("D, sigma_ln 0.3", "displacement", 0.3, 0.5), ("D > 0.5 m, sigma_ln 0.05", "more_than", 0.05, 1.0))
QUANTILES = (0.05, 0.95)
BOUND_M = 0.5


def quadrature(record, observation, prior):
    """(mean [g], sd [g], {q: quantile [g]}, {q: density at it [1/g]}) of the posterior of
    ky by quadrature."""
    grid = np.exp(np.linspace(math.log(prior.ppf(1e-6)), math.log(0.3), 8001))
    d = design.Rigid().displacements(record, None, {"ky": grid})
    with np.errstate(divide="ignore"):
        z = np.log(d / observation.value_m) / observation.sigma_ln
    likelihood = stats.norm.logpdf(z) if observation.kind == "displacement" else stats.norm.logcdf(z)
    log_density = likelihood + stats.lognorm.logpdf(grid, prior.sigma_ln, scale=prior.median)
    density = np.exp(log_density - log_density.max())
    density /= integrate.trapezoid(density, grid)
    cdf = integrate.cumulative_trapezoid(density, grid, initial=0.0)
    mean = integrate.trapezoid(grid * density, grid)
    sd = math.sqrt(integrate.trapezoid((grid - mean) ** 2 * density, grid))
    at = {q: float(np.interp(q, cdf, grid)) for q in QUANTILES}
    return mean, sd, at, {q: float(np.interp(x, grid, density)) for q, x in at.items()}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=8000, help="the draws returned (4 chains)")
    parser.add_argument("--quick", action="store_true", help="sigma_ln 0.2 alone, 4000 draws (smoke run)")
    args = parser.parse_args(argv)
    cases, n = (CASES[1:2], 4000) if args.quick else (CASES, args.draws)
    warnings.simplefilter("ignore", bd.CompileNotice)
    t = np.arange(0, 8, 0.01)
    record = bd.Record(0.3 * G * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")
    d_true = float(design.Rigid().displacements(record, None, {"ky": np.array([KY_TRUE])})[0])
    print(f"record {record.name!r}: {record.duration:.2f} s, peak 0.279 g; D = {d_true:.4f} m at ky = {KY_TRUE} g; "
          f"{n} draws")
    rows, ok = [], True
    for label, kind, sigma_ln, prior_sd in cases:
        value = d_true if kind == "displacement" else BOUND_M
        seen = design.Observation(record, sigma_ln=sigma_ln, **{f"{kind}_m": value})
        prior = design.LogNormal(median=0.1, sigma_ln=prior_sd)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", design.ConvergenceWarning)
            start = time.perf_counter()
            result = design.back_analysis(seen, design.Rigid(), {"ky": prior}, method="laplace", chains=4,
                                          draws=n // 4)
            seconds = time.perf_counter() - start
        warned = any(issubclass(w.category, design.ConvergenceWarning) for w in caught)
        k, ess = float(result.diagnostics.pareto_k.iloc[0]), float(result.diagnostics.ess_importance.iloc[0])
        mean, sd, at, density = quadrature(record, seen, prior)
        ky = result.samples.ky_g.to_numpy()
        relative = math.sqrt(1 / ess + 1 / len(ky))
        sd_ln = result.laplace_sd / result.map_value
        normal = {"mean": result.map_value * math.exp(sd_ln ** 2 / 2)} | {
            q: result.map_value * math.exp(stats.norm.ppf(q) * sd_ln) for q in QUANTILES}
        drawn = {"mean": ky.mean()} | {q: np.quantile(ky, q) for q in QUANTILES}
        exact = {"mean": mean} | at
        mcse = {"mean": sd * relative} | {q: math.sqrt(q * (1 - q)) * relative / density[q] for q in QUANTILES}
        errors = {key: (normal[key] - exact[key], drawn[key] - exact[key]) for key in exact}
        reliable = k <= 0.7
        if reliable:
            ok &= all(abs(corrected) < 4 * mcse[key] for key, (_, corrected) in errors.items())
        else:
            ok &= warned
        cells = [f"{normal_error / sd:+.3f} / {corrected / sd:+.3f} ({corrected / mcse[key]:+.1f})"
                 for key, (normal_error, corrected) in errors.items()]
        rows.append([label, f"{k:.2f}", f"{ess:.0f}", "yes" if warned else "no", f"{seconds:.2f}",
                     f"{exact['mean']:.4f} [{exact[0.05]:.4f}, {exact[0.95]:.4f}]", *cells])
    print_table(["observation", "k̂", "ESS", "warned", "time [s]", "quadrature mean [q05, q95] [g]",
                 "mean: normal / drawn [sd] (MCSE)", "q05: normal / drawn [sd] (MCSE)",
                 "q95: normal / drawn [sd] (MCSE)"], rows)
    print(f"bar: where k̂ <= 0.7 the drawn mean, q05 and q95 within 4 Monte Carlo standard errors of the "
          f"quadrature's, and the bound warned: {verdict(ok, args.quick)}")
    return 0 if ok or args.quick else 1


if __name__ == "__main__":
    raise SystemExit(main())
