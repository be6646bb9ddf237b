"""design.back_analysis of several parameters of one design model at once: a model of
one's own in closed form against a 2-D quadrature of its exact posterior (NUTS, the
Laplace approximation, the log posterior's gradient), the plane's mu and mu_kinetic by
the Laplace approximation against differences of its log posterior, the result's tables
and figures, and the inputs refused."""

import dataclasses
import math
import re

import numpy as np
import pytest
from scipy import integrate, optimize, stats

import blockdae as bd
from blockdae import design

pytest.importorskip("numpyro")
pytest.importorskip("arviz")


@pytest.fixture(scope="module")
def record():
    t = np.arange(0, 3, 0.01)
    return bd.Record(0.3 * 9.80665 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")


@dataclasses.dataclass(frozen=True)
class Scaled(design.DesignModel):
    """A model of one's own in closed form: D = scale (pga / ky - 1)² [m] below ky = pga,
    0 from it on, with its exact dD/dky and dD/dscale."""

    PARAMETERS = {"ky": "g", "scale": "m"}
    REQUIRED = ("ky", "scale")
    DESIGN = "ky"
    kind = "scaled power law"
    differentiable = ("ky", "scale")

    def displacements(self, record, pga, values, derivative=False):
        return self.gradient(record, pga, values, ())[0]

    def gradient(self, record, pga, values, names):
        self.check_differentiable(names)
        ky, scale = (np.asarray(values[name], dtype=float) for name in ("ky", "scale"))
        ratio = np.maximum(pga / ky - 1.0, 0.0)
        slopes = {"ky": -2.0 * scale * ratio * pga / ky ** 2, "scale": ratio ** 2}
        return scale * ratio ** 2, {name: slopes[name] for name in names}

    def sliding_limit(self, record, pga, values):
        return np.full(np.shape(values["ky"]), float(pga))


TRUE = {"ky": 0.12, "scale": 0.08}  # [g], [m]
PRIORS = {"ky": design.LogNormal(0.1, 0.5), "scale": design.LogNormal(0.1, 0.5)}
#: what is seen: (PGA [g], kind, sigma_ln, the value [m]: D of the true parameters, 80 % of it for the bound)
SEEN = [(pga, kind, sigma_ln, TRUE["scale"] * (pga / TRUE["ky"] - 1.0) ** 2 * (0.8 if kind == "more_than" else 1.0))
        for pga, kind, sigma_ln in ((0.3, "displacement", 0.1), (0.5, "displacement", 0.15), (0.2, "more_than", 0.2))]


def observations(record):
    return [design.Observation(record, sigma_ln=sigma_ln, pga_g=pga, name=f"PGA {pga} g", **{f"{kind}_m": value})
            for pga, kind, sigma_ln, value in SEEN]


def log_density_in_u(u, xp=np):
    """ln of the posterior density of u = (ln ky, ln scale) (last axis) up to a constant,
    from the closed form with SciPy's or JAX's special functions, independent of
    blockdae's: the log-normal priors are normal in u; a measured D's likelihood is
    normal in ln D, a bound's ln Phi((ln D - ln bound) / sigma_ln); -inf where ky >= pga
    (D = 0)."""
    if xp is np:
        from scipy.special import log_ndtr
    else:
        from jax.scipy.special import log_ndtr
    total = sum(-0.5 * ((u[..., i] - math.log(prior.median)) / prior.sigma_ln) ** 2
                for i, prior in enumerate(PRIORS.values()))
    for pga, kind, sigma_ln, value in SEEN:
        slides = u[..., 0] < math.log(pga)
        ratio = xp.where(slides, pga / xp.exp(u[..., 0]) - 1.0, 1.0)
        z = (u[..., 1] + 2 * xp.log(ratio) - math.log(value)) / sigma_ln
        total = total + xp.where(slides, -0.5 * z ** 2 if kind == "displacement" else log_ndtr(z), -xp.inf)
    return total


def quadrature(n):
    """The posterior by quadrature on an n x n grid in u over the box where its density
    exceeds e^-40 of the peak (found on a 201 x 201 pass over each prior's ±6 sd): each
    parameter's mean and 5 %, 95 % quantiles [its unit] (trapezoid rule; the marginal's
    distribution function by cumulative trapezoids)."""
    coarse = [np.linspace(math.log(p.median) - 6 * p.sigma_ln, math.log(p.median) + 6 * p.sigma_ln, 201)
              for p in PRIORS.values()]
    grid = np.stack(np.meshgrid(*coarse, indexing="ij"), axis=-1)
    inside = np.argwhere(log_density_in_u(grid) > np.nanmax(log_density_in_u(grid)) - 40)
    axes = [np.linspace(coarse[i][max(inside[:, i].min() - 1, 0)], coarse[i][min(inside[:, i].max() + 1, 200)], n)
            for i in range(2)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    log_q = log_density_in_u(grid)
    q = np.exp(log_q - log_q.max())
    result = {}
    for i, name in enumerate(PRIORS):
        marginal = integrate.trapezoid(q, axes[1 - i], axis=1 - i)
        marginal /= integrate.trapezoid(marginal, axes[i])
        cdf = integrate.cumulative_trapezoid(marginal, axes[i], initial=0.0)
        result[name] = {"mean": integrate.trapezoid(np.exp(axes[i]) * marginal, axes[i]),
                        **{key: math.exp(np.interp(level, cdf, axes[i])) for key, level in (("q05", 0.05),
                                                                                           ("q95", 0.95))}}
    return result


def closed_form_maximum():
    """The maximum of the posterior in u and the inverse of the Hessian of -ln posterior
    there, by the closed form in JAX (its exact gradient and Hessian; scipy's BFGS from
    the priors' medians to a gradient norm of 1e-12)."""
    import jax

    with jax.enable_x64(True):
        minus = jax.jit(lambda u: -log_density_in_u(u, jax.numpy))
        found = optimize.minimize(lambda u: float(minus(u)), np.log([0.1, 0.1]), method="BFGS",
                                  jac=lambda u: np.asarray(jax.grad(minus)(u)), options={"gtol": 1e-12})
        return found.x, np.linalg.inv(np.asarray(jax.hessian(minus)(found.x)))


def test_the_quadrature_is_converged():
    """The reference's own error: 1601 against 3201 points a side move each mean by less
    than 1e-12 relative and each quantile by less than 1e-5 (measured: 1e-14 and 5.6e-6,
    the quantiles limited by the linear interpolation of the distribution function),
    far below the Monte Carlo errors the reference is held to (above 1e-3 relative)."""
    fine, finer = quadrature(1601), quadrature(3201)
    for name in PRIORS:
        assert fine[name]["mean"] == pytest.approx(finer[name]["mean"], rel=1e-12), name
        for key in ("q05", "q95"):
            assert fine[name][key] == pytest.approx(finer[name][key], rel=1e-5), (name, key)


@pytest.fixture(scope="module")
def laplace(record):
    return design.back_analysis(observations(record), Scaled(), PRIORS, method="laplace", chains=2, draws=1000)


def test_laplace_matches_the_closed_form_maximum_and_hessian(laplace):
    """The maximum a posteriori in u matches the closed form's within 1e-7 (L-BFGS-B's
    gradient tolerance 1e-10 over curvatures above 100); the covariance (the inverse of
    the Hessian by central differences of the model's gradient, step 1e-4 in u: error
    about 1e-8 relative) matches the inverse of the closed form's exact Hessian within
    1e-6 relative of its largest entry."""
    u, covariance = closed_form_maximum()
    assert np.log([laplace.map_values[name] for name in PRIORS]) == pytest.approx(u, abs=1e-7)
    assert list(laplace.laplace_covariance.index) == list(laplace.laplace_covariance.columns) == list(PRIORS)
    np.testing.assert_allclose(laplace.laplace_covariance.to_numpy(), covariance, rtol=0,
                               atol=1e-6 * np.abs(covariance).max())


def test_the_laplace_draws_weighted_toward_the_posterior_match_the_quadrature(laplace):
    """The draws returned (the normal's, weighted by Pareto-smoothed importance sampling
    and resampled) against the quadrature (converged far below these errors, above):
    each parameter's mean within 4 Monte Carlo standard errors (sd (1/ESS + 1/n)^1/2, ESS
    the importance sampling's, n the draws resampled), and the share of draws below the
    quadrature's 5 % and 95 % quantiles within 4 binomial standard errors of 0.05 and
    0.95 (the same variance factor); k̂ below 0.7 and one k̂ for the joint draws."""
    reference = quadrature(1601)
    k = laplace.diagnostics.pareto_k.to_numpy()
    assert list(laplace.diagnostics.parameter) == list(PRIORS) and k[0] == k[1] and k[0] < 0.7
    factor = math.sqrt(1 / laplace.diagnostics.ess_importance.iloc[0] + 1 / len(laplace.samples))
    for name, column in zip(PRIORS, ("ky_g", "scale_m")):
        drawn = laplace.samples[column].to_numpy()
        assert abs(drawn.mean() - reference[name]["mean"]) < 4 * drawn.std() * factor, name
        for key, level in (("q05", 0.05), ("q95", 0.95)):
            share = np.mean(drawn < reference[name][key])
            assert abs(share - level) < 4 * math.sqrt(level * (1 - level)) * factor, (name, key, share)


def test_the_log_posterior_is_a_function_of_the_vector_and_its_gradient_is_exact(record):
    """design.log_posterior of two parameters: a function of [ky, scale]; its
    differences between points equal the closed form's (ln posterior in p: the density in
    u less ln ky + ln scale) within 1e-9, and jax.grad (the model's own dD/dp through the
    custom derivative) equals central differences of it at a relative step of 1e-6
    within 1e-6 relative (their own error, h² f''' / 6 + eps f / h, below 1e-8 here;
    measured at most 1.4e-10)."""
    import jax

    log_p = design.log_posterior(observations(record), Scaled(), PRIORS)
    points = [np.array([0.11, 0.09]), np.array([0.13, 0.07])]
    with jax.enable_x64(True):
        values = [float(log_p(theta)) for theta in points]
        reference = [float(log_density_in_u(np.log(theta))) - float(np.log(theta).sum()) for theta in points]
        assert values[0] - values[1] == pytest.approx(reference[0] - reference[1], abs=1e-9)
    for theta in points:
        _gradient_matches_central_differences(log_p, theta)


@pytest.mark.slow
def test_nuts_matches_the_quadrature_within_monte_carlo_error(record):
    """4 chains of 1000 draws after 500 of warm-up: each parameter's mean within 4 Monte
    Carlo standard errors (sd / sqrt(ESS), the bulk ESS of the diagnostics) of the
    quadrature's (1601 points a side, its own error below 1e-5 relative:
    test_the_quadrature_is_converged), its 5 % and 95 % quantiles within 4 of theirs
    (sqrt(q (1 - q) / ESS) / density, the density from a kernel estimate of the draws);
    the chains mixed (no ConvergenceWarning). Measured: the means within 0.22 and 0.18
    standard errors, the quantiles within 0.55, 0.84 (ky) and 0.37, 1.37 (scale); bulk
    ESS 1881 and 1762, R-hat 1.0001."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", design.ConvergenceWarning)
        result = design.back_analysis(observations(record), Scaled(), PRIORS, chains=4, draws=1000, warmup=500,
                                      seed=2)
    reference = quadrature(1601)
    assert list(result.diagnostics.parameter) == ["ky", "scale"]
    for name, column, _ in result.inferred:
        ess = float(result.diagnostics.set_index("parameter").loc[name, "ess_bulk"])
        drawn = result.samples[column].to_numpy()
        assert abs(drawn.mean() - reference[name]["mean"]) < 4 * drawn.std() / math.sqrt(ess), name
        for key, q in (("q05", 0.05), ("q95", 0.95)):
            density = stats.gaussian_kde(drawn)(reference[name][key])[0]
            assert abs(np.quantile(drawn, q) - reference[name][key]) < 4 * math.sqrt(q * (1 - q) / ess) / density, \
                (name, key)


def test_a_result_of_several_parameters_has_their_tables_and_figures(laplace, record):
    """A column per parameter in the draws, the summary, predict, the InferenceData and
    every figure; the one-parameter attributes say to read the several's."""
    import matplotlib

    matplotlib.use("Agg")
    assert list(laplace.samples.columns) == ["chain", "draw", "ky_g", "scale_m"]
    assert laplace.inferred == [("ky", "ky_g", "g"), ("scale", "scale_m", "m")]
    summary = laplace.summary()
    assert list(summary.parameter) == ["ky", "scale"] and list(summary.unit) == ["g", "m"]
    assert set(laplace.map_values) == {"ky", "scale"} and list(laplace.diagnostics.parameter) == ["ky", "scale"]
    future = laplace.predict(record, pga_g=0.4)
    assert list(future.columns) == ["chain", "draw", "ky_g", "scale_m", "D_m"]
    np.testing.assert_allclose(future.D_m, future.scale_m * (0.4 / future.ky_g - 1.0) ** 2, rtol=1e-12)
    assert list(laplace.predictive().observation) == [name for name in (o.name for o in observations(record))]
    idata = laplace.to_inference_data()
    assert set(idata.posterior.data_vars) == set(idata.prior.data_vars) == {"ky", "scale"}
    assert idata.posterior["scale"].attrs["units"] == "m" and idata.log_likelihood["D_measured"].shape == (2, 1000, 3)
    assert len(laplace.posterior_figure().axes) == 2
    assert sum(ax.get_visible() for ax in laplace.pair_figure().axes) == 3
    assert laplace.predictive_figure(scenarios={"design": (record, 0.4)}).axes
    assert re.fullmatch(r"BackAnalysis\(method='laplace', 2000 draws, 3 observations, ky median 0\.1\d+ g, 90 % "
                        r"interval [\d.]+-[\d.]+ g; scale median [\d.]+ m, 90 % interval [\d.]+-[\d.]+ m\)",
                        repr(laplace))
    for attribute in ("parameter", "unit", "column", "map_value", "laplace_sd"):
        with pytest.raises(AttributeError, match=rf"{attribute} names one parameter, and this posterior is of 2: "
                                                 r"ky, scale; read inferred, map_values and laplace_covariance"):
            getattr(laplace, attribute)


@dataclasses.dataclass(frozen=True)
class Product(design.DesignModel):
    """D = 0.01 m · pga / (a b): a and b [-] enter only through their product."""

    PARAMETERS = {"a": "-", "b": "-"}
    REQUIRED = ("a", "b")
    DESIGN = "a"
    COLUMNS = {"a": "a", "b": "b"}
    kind = "product"
    differentiable = ("a", "b")

    def displacements(self, record, pga, values, derivative=False):
        return self.gradient(record, pga, values, ())[0]

    def gradient(self, record, pga, values, names):
        a, b = (np.asarray(values[name], dtype=float) for name in ("a", "b"))
        d = 0.01 * pga / (a * b)
        return d, {name: -d / {"a": a, "b": b}[name] for name in names}

    def sliding_limit(self, record, pga, values):
        return np.full(np.shape(values["a"]), np.inf)


def test_a_ridge_is_refused_by_the_laplace_approximation(record):
    """a and b with flat priors seen only through a b: the posterior in (ln a, ln b) is
    flat along ln a - ln b, its Hessian singular: an error naming both and the ridge."""
    seen = design.Observation(record, sigma_ln=0.1, displacement_m=0.01 * 0.3, pga_g=0.3)
    priors = {"a": design.Uniform(0.5, 2.0), "b": design.Uniform(0.5, 2.0)}
    with pytest.raises(ValueError, match=r"the posterior of ln a, ln b is not peaked at its maximum: the Hessian of "
                                         r"-ln posterior in \(ln a, ln b\) has eigenvalues .* flat or falls along "
                                         r"[+-]0\.71 ln a [+-]0\.71 ln b .* use method='nuts'"):
        design.back_analysis(seen, Product(), priors, method="laplace")


def test_nuts_runs_where_the_laplace_approximation_does_not_hold(record):
    """The ridge above by NUTS: its chains start from the best of the points the search
    for the maximum tried, the result holds no Laplace covariance, and ln(a b) centres on
    the observed 0 (its posterior sd about 0.1, the measurement's; within 4 Monte Carlo
    standard errors, sd / sqrt(the smaller bulk ESS))."""
    import warnings

    seen = design.Observation(record, sigma_ln=0.1, displacement_m=0.01 * 0.3, pga_g=0.3)
    priors = {"a": design.Uniform(0.5, 2.0), "b": design.Uniform(0.5, 2.0)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", design.ConvergenceWarning)  # a ridge mixes slowly along itself
        result = design.back_analysis(seen, Product(), priors, chains=4, draws=500, warmup=500)
    assert result.laplace_covariance is None
    s = np.log(result.samples.a * result.samples.b).to_numpy()
    ess = float(result.diagnostics.ess_bulk.min())
    assert abs(s.mean()) < 4 * s.std() / math.sqrt(ess)
    assert 0.07 < s.std() < 0.13


def test_the_inputs_of_several_are_checked(record):
    """A parameter among several that the model does not differentiate D by, a prior
    giving negative values a probability, no distribution at all, an observation beyond
    what the priors reach, a combination of values the model refuses: each an error
    naming what is wrong, before any sampling."""
    seen = design.Observation(record, sigma_ln=0.2, displacement_m=0.1, pga_g=0.3)
    flexible = {"ky": design.LogNormal(0.1, 0.3), "height": 10.0, "vs": 250.0, "vr": design.LogNormal(800.0, 0.2)}
    with pytest.raises(ValueError, match=r"the flexible model gives no dD/dvr, and back_analysis needs it .* by "
                                         r"\['ky', 'height', 'vs', 'damping'\]"):
        design.back_analysis(seen, design.Flexible(), flexible, method="laplace")
    with pytest.raises(ValueError, match=r"priors\['scale'\]=.* gives scale < 0 \[m\] a probability"):
        design.back_analysis(seen, Scaled(), {"ky": PRIORS["ky"], "scale": design.Normal(0.1, 0.05)})
    with pytest.raises(ValueError, match=r"infers the parameters of the scaled power law model that priors gives a "
                                         r"distribution; got none"):
        design.back_analysis(seen, Scaled(), {"ky": 0.1, "scale": 0.1})
    far = design.Observation(record, sigma_ln=0.1, displacement_m=1e4, pga_g=0.3)
    with pytest.raises(ValueError, match=r"displacement_m=10000.0 m lies beyond what the priors reach: D = .* m at "
                                         r"most \(at ky = .* g, scale = .* m, over the priors' quantiles .* widen "
                                         r"the priors of ky, scale"):
        design.back_analysis(far, Scaled(), PRIORS, method="laplace")
    both = {"mu": design.Truncated(design.LogNormal(0.2, 0.3), low=0.06),
            "mu_kinetic": design.Truncated(design.LogNormal(0.15, 0.3), low=0.06), "bias_x": -0.05}
    with pytest.raises(ValueError, match=r"the planar model refuses a set of values of mu, mu_kinetic the priors "
                                         r"give .*mu_kinetic=.* must lie in \[0, mu=.*truncate the priors"):
        design.back_analysis(seen, design.Planar(), both, method="laplace")


#: mu and the slope's pull bias_x (along +x here: a positive prior), mu_kinetic following mu; mu > |bias| everywhere
PLANE = {"mu": design.Truncated(design.LogNormal(0.15, 0.3), low=0.1),
         "bias_x": design.Truncated(design.LogNormal(0.05, 0.3), high=0.09)}
PLANE_TRUE = {"mu": 0.15, "bias_x": 0.05}


def test_the_plane_s_mu_and_bias_by_laplace(record):
    """mu and bias_x of a plane from displacements seen at PGA 0.3 and 0.45 g (sigma_ln
    0.1): the log posterior's gradient (the twin's dD/dmu and dD/dbias_x) against central
    differences of the log posterior at a relative step of 1e-6, within 1e-6 relative;
    the Laplace covariance (central differences of that gradient) against the inverse of
    the Hessian from second differences of the log posterior's values in u (the compiled
    engine's D alone; step 3e-4, their own error measured by the step 1e-3: 5e-5
    relative), within 1e-4 of its largest entry (measured 6e-6; the gradient 1.8e-10
    and 1.2e-10 relative); the draws of both, and
    the two strongly correlated (mu - bias is what D sees most)."""
    import jax

    model = design.Planar()
    seen = []
    for pga in (0.3, 0.45):
        d = float(model.displacements(record, pga, {k: np.array([v]) for k, v in PLANE_TRUE.items()})[0])
        seen.append(design.Observation(record, sigma_ln=0.1, displacement_m=d, pga_g=pga, name=f"PGA {pga} g"))
    log_p = design.log_posterior(seen, model, PLANE)
    theta = np.array([0.14, 0.055])
    _gradient_matches_central_differences(log_p, theta)
    result = design.back_analysis(seen, model, PLANE, method="laplace", chains=1, draws=400)
    u = np.log([result.map_values[name] for name in PLANE])

    with jax.enable_x64(True):
        def minus(v):  # -ln posterior in u
            return -float(log_p(np.exp(v))) - float(v.sum())

        h, eye = 3e-4, np.eye(2)
        hessian = np.array([[(minus(u + h * eye[i] + h * eye[j]) - minus(u + h * eye[i] - h * eye[j])
                              - minus(u - h * eye[i] + h * eye[j]) + minus(u - h * eye[i] - h * eye[j])) / (4 * h * h)
                             for j in range(2)] for i in range(2)])
    covariance = np.linalg.inv(hessian)
    np.testing.assert_allclose(result.laplace_covariance.to_numpy(), covariance, rtol=0,
                               atol=1e-4 * np.abs(covariance).max())
    assert list(result.samples.columns) == ["chain", "draw", "mu", "bias_x"]
    assert covariance[0, 1] / math.sqrt(covariance[0, 0] * covariance[1, 1]) > 0.8


@pytest.mark.slow
def test_the_flexible_mass_s_ky_and_vs_gradient_matches_central_differences(record):
    """A decoupled flexible mass (H 10 m, vr 800 m/s held), ky and vs both inferred: one
    call of the JAX twin gives dD/dky and dD/dvs, and the log posterior's gradient equals
    central differences of the log posterior (relative step 1e-6) within 1e-6 relative
    (measured 3.3e-11 for ky, 9.9e-10 for vs)."""
    model = design.Flexible(method="decoupled")
    priors = {"ky": design.LogNormal(0.1, 0.3), "height": 10.0, "vs": design.LogNormal(250.0, 0.3), "vr": 800.0}
    d = float(model.displacements(record, 0.3, {"ky": np.array([0.1]), "height": 10.0, "vs": np.array([250.0]),
                                                "vr": 800.0})[0])
    log_p = design.log_posterior(design.Observation(record, sigma_ln=0.2, displacement_m=d, pga_g=0.3), model, priors)
    theta = np.array([0.09, 270.0])
    _gradient_matches_central_differences(log_p, theta)


def _gradient_matches_central_differences(log_p, theta):
    """jax.grad of ``log_p`` at ``theta`` equals its central differences (relative step
    1e-6) within 1e-6 relative, each component."""
    import jax

    with jax.enable_x64(True):
        grad = np.asarray(jax.grad(log_p)(theta))
        for i in range(len(theta)):
            step = 1e-6 * theta[i] * np.eye(len(theta))[i]
            central = (float(log_p(theta + step)) - float(log_p(theta - step))) / (2 * step[i])
            assert grad[i] == pytest.approx(central, rel=1e-6), i


def test_nuts_starts_inside_the_priors_where_the_laplace_draws_reach_beyond(record):
    """A uniform prior on ky ending just above the posterior's maximum: the Laplace
    approximation's draws for the chains' starts reach beyond it (checked here on the same
    seed), and those chains start at the maximum instead; the draws stay in the support
    with no warning of it."""
    import warnings

    priors = {"ky": design.Uniform(0.08, 0.1215), "scale": PRIORS["scale"]}
    laplace = design.back_analysis(observations(record), Scaled(), priors, method="laplace", chains=4, draws=1)
    factor = np.linalg.inv(np.linalg.cholesky(np.linalg.inv(laplace.laplace_covariance.to_numpy()))).T
    mean = np.log([laplace.map_values[name] for name in priors])
    starts = np.exp(mean + np.random.default_rng(0).standard_normal((4, 2)) @ factor.T)  # as back_analysis draws them
    assert (starts[:, 0] >= 0.1215).any()
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        result = design.back_analysis(observations(record), Scaled(), priors, chains=4, draws=200, warmup=200)
    assert not [w for w in seen if "support" in str(w.message)]
    assert result.samples.ky_g.between(0.08, 0.1215).all() and np.isfinite(result.samples.scale_m).all()
