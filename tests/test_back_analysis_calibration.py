"""Simulation-based calibration of design.back_analysis (Talts et al. 2018): truths of ky
drawn from the prior, one observation of each simulated from the forward model (the rigid
block's D, with its log-normal measurement error), the posterior computed from it. Where
the posterior is right, the rank of the truth among (independent) posterior draws is
uniform, and a 90 % interval holds the truth 90 % of the time.

The Laplace approximation runs on 200 truths (about 0.5 s each on one core); NUTS, whose
sampler JAX compiles afresh for each analysis (about 3 s) on top of its run, on 40 truths
with short chains (2 x 100 draws after 100 of warm-up, thinned by 4 to draws close to
independent). Both are slow tests: about 90 s and 250 s on one core of a shared 2-core
machine; faster wherever the rigid block's engine call is."""

import math
import warnings

import numpy as np
import pytest
from scipy import stats

import blockdae as bd
from blockdae import design

pytest.importorskip("numpyro")
pytest.importorskip("arviz")

PRIOR = design.LogNormal(median=0.1, sigma_ln=0.4)  # ky [g]
SIGMA_LN = 0.2  # the measurement's error in ln D [-]: "± 20 %"
PGA_G = 0.5  # P(ky >= 0.5 g) under the prior: 3e-5, so that every truth slides and D > 0
#: the p-value below which the ranks are called non-uniform (chi-square over 10 equal bins and
#: Kolmogorov-Smirnov, each): a calibrated posterior fails it once in 1000 seeds
P_MIN = 0.001


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 8, 0.01)
    return bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


def simulate(record, n, seed):
    """``n`` truths of ky [g] from the prior and each one's observed D [m]: the model's D
    times exp(SIGMA_LN ε), ε standard normal."""
    rng = np.random.default_rng(seed)
    truths = np.asarray(PRIOR.ppf(rng.uniform(size=n)), dtype=float)
    d = design.Rigid().displacements(record, PGA_G, {"ky": truths})
    assert np.all(d > 0), "a truth at or above the PGA: D = 0 cannot be observed as a displacement"
    return truths, d * np.exp(SIGMA_LN * rng.standard_normal(n))


def calibration(record, truths, observed, thin=1, **options):
    """The normalised rank of each truth among its posterior's draws (ties split by a
    uniform draw, so that a calibrated posterior gives exactly uniform values in (0, 1))
    and whether its central 90 % interval holds it."""
    rng = np.random.default_rng(1)
    ranks, covered = [], []
    for i, (truth, d) in enumerate(zip(truths, observed)):
        seen = design.Observation(record, sigma_ln=SIGMA_LN, displacement_m=float(d), pga_g=PGA_G)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", design.ConvergenceWarning)  # short chains: ESS below 100 per chain
            result = design.back_analysis(seen, design.Rigid(), {"ky": PRIOR}, seed=i, **options)
        draws = result.samples.sort_values(["chain", "draw"]).groupby("chain")["ky_g"]
        ky = np.concatenate([chain.to_numpy()[::thin] for _, chain in draws])
        ranks.append((np.sum(ky < truth) + rng.uniform()) / (ky.size + 1))
        low, high = np.quantile(ky, [0.05, 0.95])
        covered.append(low <= truth <= high)
    return np.array(ranks), np.array(covered)


def assert_calibrated(ranks, covered):
    """Ranks uniform (chi-square over 10 bins, KS; each p > P_MIN) and the 90 % intervals'
    hits within the central 99.9 % of Binomial(n, 0.9)."""
    counts = np.histogram(ranks, bins=10, range=(0, 1))[0]
    chi2 = stats.chisquare(counts)
    ks = stats.kstest(ranks, "uniform")
    assert chi2.pvalue > P_MIN and ks.pvalue > P_MIN, (counts, chi2, ks)
    n = len(covered)
    low, high = stats.binom.ppf([0.0005, 0.9995], n, 0.9)
    assert low <= covered.sum() <= high, (covered.sum(), n, low, high)
    return chi2.pvalue, ks.pvalue


@pytest.mark.slow
def test_the_laplace_posterior_is_calibrated_over_200_truths(record):
    """200 truths, each posterior 199 independent Laplace draws (normal in ln ky at the
    maximum). The Laplace approximation is exact only where ln D is linear in ln ky: the
    test states that its error is below what 200 truths can see. Bound on the hits:
    the central 99.9 % of Binomial(200, 0.9), 166 to 192."""
    truths, observed = simulate(record, 200, seed=2024)
    ranks, covered = calibration(record, truths, observed, method="laplace", chains=1, draws=199)
    assert_calibrated(ranks, covered)


@pytest.mark.slow
def test_the_nuts_posterior_is_calibrated_over_40_truths(record):
    """40 truths, each posterior from NUTS (2 chains of 100 draws after 100 of warm-up,
    every 4th draw kept: 50 draws). A smaller check than the Laplace one: 40 ranks see
    only gross miscalibration (a posterior too narrow or shifted by a fraction of its
    width). Bound on the hits: the central 99.9 % of Binomial(40, 0.9), 30 to 40."""
    truths, observed = simulate(record, 40, seed=2025)
    ranks, covered = calibration(record, truths, observed, thin=4, method="nuts", chains=2, draws=100, warmup=100)
    assert_calibrated(ranks, covered)
