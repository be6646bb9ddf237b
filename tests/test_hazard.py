"""Fragility fits (recovery, bias and bootstrap coverage on synthetic data), the hazard
integral against its closed form, empirical fragilities, hazard curves and bad input."""

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm

import blockdae as bd
from blockdae import empirical as em
from blockdae.hazard import (Deaggregation, EmpiricalFragility, Fragility, HazardCurve, displacement_hazard,
                             fit_fragility)

TRUE = dict(b0=1.0, b1=1.2, c0=-1.5, c1=1.4, sigma=0.5)  # P(slide) = Φ(b0 + b1 ln x); ln D ~ N(c0 + c1 ln x, σ)
D_CHECK, IM_CHECK = 0.05, 0.4  # [m], [g]


def synthetic_table(rng, n_records=30, scales=8):
    """Records × scales rows drawn from the fragility model TRUE (D = 0 where no slide)."""
    x = np.exp(rng.uniform(np.log(0.05), np.log(1.5), (n_records, scales))).ravel()
    u = np.log(x)
    slides = rng.random(x.size) < norm.cdf(TRUE["b0"] + TRUE["b1"] * u)
    d = np.where(slides, np.exp(TRUE["c0"] + TRUE["c1"] * u + TRUE["sigma"] * rng.standard_normal(x.size)), 0.0)
    return pd.DataFrame({"record": np.repeat([f"r{i}" for i in range(n_records)], scales), "mu": 0.1,
                         "pga_g": x, "max_abs_displacement_m": d})


def true_exceedance(d, x):
    return norm.cdf(TRUE["b0"] + TRUE["b1"] * np.log(x)) * \
        norm.cdf((TRUE["c0"] + TRUE["c1"] * np.log(x) - np.log(d)) / TRUE["sigma"])


def test_fit_recovers_the_parameters_of_a_large_sample():
    fit = fit_fragility(synthetic_table(np.random.default_rng(1), n_records=400), d0_m=1e-9, n_boot=0)
    for name, value in TRUE.items():
        assert getattr(fit, name) == pytest.approx(value, abs=0.12), name
    assert fit.n_records == 400 and fit.n_rows == 3200 and fit.boot.shape == (0, 5)


def test_bias_and_bootstrap_coverage_over_repeated_draws():
    """40 synthetic studies of 30 records × 8 scales, 100 bootstrap refits each: the mean
    estimate of each parameter lies within 3 standard errors of the truth (measured: at
    most 2.0, for b1), and the 90 % band of P(D > 5 cm | 0.4 g) covers the true value in
    >= 75 % of the draws (measured 87.5 %; with 40 draws the coverage's own standard error
    is 4.7 %, so the bar is 3 of them below 90 %)."""
    rng = np.random.default_rng(7)
    estimates, covered, widths = [], [], []
    truth = true_exceedance(D_CHECK, IM_CHECK)
    for _ in range(40):
        fit = fit_fragility(synthetic_table(rng), d0_m=1e-9, n_boot=100, seed=int(rng.integers(1 << 31)))
        estimates.append(fit.params)
        low, high = fit.band(D_CHECK, IM_CHECK)
        covered.append(low <= truth <= high)
        widths.append(high - low)
    estimates = np.array(estimates)
    bias = estimates.mean(axis=0) - np.array(list(TRUE.values()))
    error = estimates.std(axis=0, ddof=1) / np.sqrt(len(estimates))
    print(f"bias (b0, b1, c0, c1, sigma) = {np.round(bias, 3)}; standard errors {np.round(error, 3)}; "
          f"coverage of the 90 % band {np.mean(covered):.2f}, mean width {np.mean(widths):.3f}")
    assert np.all(np.abs(bias) <= 3 * error)
    assert np.mean(covered) >= 0.75


def test_band_brackets_the_fit_and_is_seeded():
    table = synthetic_table(np.random.default_rng(3))
    a = fit_fragility(table, d0_m=1e-9, n_boot=50, seed=11)
    b = fit_fragility(table, d0_m=1e-9, n_boot=50, seed=11)
    np.testing.assert_array_equal(a.boot, b.boot)
    x = np.array([0.1, 0.3, 0.9])
    low, high = a.band(0.02, x)
    p = a.exceedance(0.02, x)
    assert np.all(low <= p + 1e-12) and np.all(p <= high + 1e-12) and np.all(high > low)


def test_every_row_sliding_gives_a_lognormal_fragility():
    table = synthetic_table(np.random.default_rng(4))
    table = table[table.max_abs_displacement_m > 0]
    fit = fit_fragility(table, d0_m=1e-9, n_boot=0)
    assert np.isinf(fit.b0) and fit.b1 == 0.0
    assert fit.exceedance(1e3, 0.5) < 1e-6 < fit.exceedance(1e-6, 0.5)


def test_hazard_integral_matches_the_closed_form():
    """A lognormal fragility P(D > d | x) = Φ((ln x - ln θ)/β) on λ(x) = k0 x^-k:
    ∫ Φ(·) k k0 x^(-k-1) dx = E[k0 X^-k] over ln X ~ N(ln θ, β²) = k0 θ^-k exp(k² β² / 2)
    (integrating by parts: the boundary terms vanish). With ln D | x ~ N(c0 + c1 ln x, σ),
    ln θ = (ln d - c0)/c1 and β = σ/c1. Measured 2.2e-16 relative; the bar ten ulps."""
    c0, c1, sigma, k0, k = -1.5, 1.4, 0.5, 1e-4, 2.7
    frag = Fragility("pga_g", 1e-9, np.inf, 0.0, c0, c1, sigma, 30, 240, np.empty((0, 5)))
    x = np.logspace(-4, 2, 121)
    curve = HazardCurve(x, k0 * x**-k)
    d = np.array([0.005, 0.02, 0.1, 0.5])
    theta, beta = np.exp((np.log(d) - c0) / c1), sigma / c1
    exact = k0 * theta**-k * np.exp(0.5 * k**2 * beta**2)
    np.testing.assert_allclose(displacement_hazard(curve, frag, d), exact, rtol=2.2e-15)


def test_empirical_fragility_and_deaggregation():
    one = EmpiricalFragility(em.jibson_2007_m, "pga_g", {"ky_g": 0.1}, magnitude=6.5)
    deagg = Deaggregation([0.05, 1.0], [6.5], [[1.0], [1.0]])
    same = EmpiricalFragility(em.jibson_2007_m, "pga_g", {"ky_g": 0.1}, magnitude=deagg)
    x = np.array([0.15, 0.3, 0.6])
    np.testing.assert_allclose(same.exceedance(0.05, x), one.exceedance(0.05, x), rtol=1e-14)
    mixed = EmpiricalFragility(em.jibson_2007_m, "pga_g", {"ky_g": 0.1},
                               magnitude=Deaggregation([0.05, 1.0], [6.0, 7.0], [[1.0, 0.0], [0.0, 1.0]]))
    at = lambda m: em.jibson_2007_m(0.1, x, m).exceedance(0.05)
    w7 = np.log(x / 0.05) / np.log(1.0 / 0.05)  # weights linear in ln im between the levels
    np.testing.assert_allclose(mixed.exceedance(0.05, x), (1 - w7) * at(6.0) + w7 * at(7.0), rtol=1e-12)
    curve = HazardCurve(np.logspace(-2, 0.5, 40), 1e-4 * np.logspace(-2, 0.5, 40) ** -2.5)
    d = np.array([0.01, 0.05, 0.2])
    rates = displacement_hazard(curve, one, d)
    assert np.all(np.diff(rates) < 0) and np.all(rates > 0)
    with pytest.raises(ValueError, match="magnitude"):
        EmpiricalFragility(em.jibson_2007_m, "pga_g", {"ky_g": 0.1})


def test_hazard_curve_from_csv_and_not_decreasing(tmp_path):
    good = tmp_path / "curve.csv"
    good.write_text("# site A\npga_g,annual_rate\n0.05,1e-2\n0.1,3e-3\n0.3,2e-4\n")
    curve = HazardCurve.read_csv(good, "pga_g", "annual_rate")
    np.testing.assert_array_equal(curve.rate, [1e-2, 3e-3, 2e-4])
    bad = tmp_path / "bad.csv"
    bad.write_text("pga_g,annual_rate\n0.05,1e-2\n0.1,3e-3\n0.3,4e-3\n")
    with pytest.raises(ValueError, match=r"bad.csv, line 4: the hazard curve is not decreasing"):
        HazardCurve.read_csv(bad)
    with pytest.raises(ValueError, match="point 2: the hazard curve is not decreasing"):
        HazardCurve([0.1, 0.2, 0.3], [1e-2, 1e-3, 1e-3])
    with pytest.raises(ValueError, match="rate=-0.001"):
        HazardCurve([0.1, 0.2], [1e-2, -1e-3])


# ---- hazard curves in the formats hazard programs export -------------------------------

OQ_RATES = np.array([2e-2, 5e-3, 1e-3, 2e-4])  # [1/yr], the curve the fixture's poe encode


def openquake_fixture(folder, poe_rows=None, comment_imt="PGA"):
    """An OpenQuake hazard-curve CSV written by hand after the engine's export
    (openquake/calculators/export/hazard.py, export_hcurves_csv; the layout of a file
    that OpenQuake engine 3.23.2 wrote): a '#' comment with investigation_time and imt, the
    header lon,lat,depth,poe-<level>, a line per site. Levels 0.01 ... 1.0 g; the first
    poe is 1 and the last 0 (left out), the others 1 - exp(-50 λ) of OQ_RATES (twice
    OQ_RATES at the second site)."""
    poe = [np.concatenate([[1.0], -np.expm1(-50.0 * k * OQ_RATES), [0.0]]) for k in (1, 2)]
    rows = poe_rows or poe
    levels = ["0.0100000", "0.0500000", "0.1000000", "0.2000000", "0.5000000", "1.0000000"]
    text = (f'#,,,,,,,,"generated_by=\'OpenQuake engine 3.23.2\', kind=\'mean\', investigation_time=50.0, '
            f'imt=\'{comment_imt}\'"\n' + "lon,lat,depth," + ",".join(f"poe-{v}" for v in levels) + "\n")
    for (lon, lat), row in zip([(27.65010, -27.46020), (28.00000, -26.00000)], rows):
        text += f"{lon:.5f},{lat:.5f},0.00000," + ",".join(f"{p:.6E}" if isinstance(p, float) else p
                                                          for p in row) + "\n"
    path = folder / "hazard_curve-mean-PGA_1.csv"
    path.write_text(text)
    return path


def test_hazard_curve_from_openquake_csv(tmp_path):
    path = openquake_fixture(tmp_path)
    curve = HazardCurve.from_openquake_csv(path, site=0, imt="PGA")
    np.testing.assert_array_equal(curve.im, [0.05, 0.1, 0.2, 0.5])
    np.testing.assert_allclose(curve.rate, OQ_RATES, rtol=1e-6)  # the poe are printed to 7 digits
    same = HazardCurve.from_openquake_csv(path, site=(27.6501, -27.4602))
    np.testing.assert_array_equal(same.rate, curve.rate)
    np.testing.assert_allclose(HazardCurve.from_openquake_csv(path, site=1).rate, 2 * OQ_RATES, rtol=1e-6)
    with pytest.raises(ValueError, match="2 sites; choose one with site="):
        HazardCurve.from_openquake_csv(path)
    with pytest.raises(ValueError, match=r"line 1, field imt: the file holds imt='PGA', not 'SA\(0.2\)'"):
        HazardCurve.from_openquake_csv(path, site=0, imt="SA(0.2)")
    with pytest.raises(ValueError, match=r"no site at \(lon, lat\) = \(10, 10\)"):
        HazardCurve.from_openquake_csv(path, site=(10.0, 10.0))
    typo = openquake_fixture(tmp_path, poe_rows=[["1.0", "0.6", "0.2", "x", "0.01", "0.0"]])
    with pytest.raises(ValueError, match=r"hazard_curve-mean-PGA_1.csv, line 3, field 'poe-0.2000000': 'x' is not"):
        HazardCurve.from_openquake_csv(typo)
    rising = openquake_fixture(tmp_path, poe_rows=[["1.0", "0.6", "0.2", "0.3", "0.01", "0.0"]])
    with pytest.raises(ValueError, match=r"line 3, field 'poe-0.2000000': the hazard curve is not decreasing"):
        HazardCurve.from_openquake_csv(rising)
    beyond = openquake_fixture(tmp_path, poe_rows=[["1.0", "1.6", "0.2", "0.1", "0.01", "0.0"]])
    with pytest.raises(ValueError, match=r"line 3, field 'poe-0.0500000': poe=1.6 is no probability"):
        HazardCurve.from_openquake_csv(beyond)


def usgs_fixture(folder, name="hazard.json", legacy=False, total=(3e-2, 8e-3, 1.5e-3, 2e-4, 0.0)):
    """A USGS NSHMP hazard web-service response written by hand after nshmp-haz-ws's
    HazardService (response[i].metadata.imt/xvalues, response[i].data[j].component/yvalues,
    two IMTs, components Total and Fault); ``legacy``: the Unified Hazard Tool's static-curve
    layout (xvals, one data entry with yvals; usgs/earthquake-hazard-tool etc/curve/data.json)."""
    import json

    def response(imt, x, y):
        meta = {"latitude": 34.0, "longitude": -118.0, "imt": {"value": imt, "display": imt},
                "xlabel": "Ground Motion (g)", "ylabel": "Annual Frequency of Exceedence"}
        if legacy:
            return {"metadata": {**meta, "xvals": x}, "data": [{"id": 1, "yvals": y}]}
        return {"metadata": {**meta, "xvalues": x},
                "data": [{"component": "Total", "yvalues": y}, {"component": "Fault", "yvalues": [v / 2 for v in y]}]}

    document = {"status": "success", "date": "2019-01-01T00:00:00-07:00", "url": "...", "server": {},
                "response": [response("PGA", [0.05, 0.1, 0.2, 0.5, 1.0], list(total)),
                             response("SA1P0", [0.05, 0.1, 0.2, 0.5, 1.0], [2e-2, 5e-3, 1e-3, 1e-4, 1e-5])]}
    path = folder / name
    path.write_text(json.dumps(document, indent=2))
    return path


def test_hazard_curve_from_usgs_json(tmp_path):
    path = usgs_fixture(tmp_path)
    curve = HazardCurve.from_usgs_json(path, imt="PGA")
    np.testing.assert_array_equal(curve.im, [0.05, 0.1, 0.2, 0.5])  # the level of rate 0 left out
    np.testing.assert_array_equal(curve.rate, [3e-2, 8e-3, 1.5e-3, 2e-4])
    fault = HazardCurve.from_usgs_json(path, imt="PGA", component="Fault")
    np.testing.assert_array_equal(fault.rate, curve.rate / 2)
    np.testing.assert_array_equal(HazardCurve.from_usgs_json(path, imt="SA1P0").rate[-1], 1e-5)
    legacy = HazardCurve.from_usgs_json(usgs_fixture(tmp_path, "legacy.json", legacy=True), imt="PGA")
    np.testing.assert_array_equal(legacy.rate, curve.rate)
    with pytest.raises(ValueError, match=r"2 curves \(imt \['PGA', 'SA1P0'\]\); choose one with imt="):
        HazardCurve.from_usgs_json(path)
    with pytest.raises(ValueError, match="no curve of imt='SA0P2'"):
        HazardCurve.from_usgs_json(path, imt="SA0P2")
    with pytest.raises(ValueError, match=r"response\[0\].data: no component 'Slab'"):
        HazardCurve.from_usgs_json(path, imt="PGA", component="Slab")
    rising = usgs_fixture(tmp_path, "rising.json", total=(3e-2, 8e-3, 9e-3, 2e-4, 1e-5))
    with pytest.raises(ValueError, match=r"rising.json: response\[0\].data\[0\].yvalues\[2\]: the hazard curve is "
                                         r"not decreasing"):
        HazardCurve.from_usgs_json(rising, imt="PGA")
    broken = tmp_path / "broken.json"
    broken.write_text('{"response": [\n  {"metadata": }\n]}')
    with pytest.raises(ValueError, match=r"broken.json, line 2: not JSON"):
        HazardCurve.from_usgs_json(broken)


def test_bad_study_tables_are_refused():
    rng = np.random.default_rng(5)
    table = synthetic_table(rng)
    with pytest.raises(ValueError, match="9 records, fewer than 10"):
        fit_fragility(table[table.record.isin([f"r{i}" for i in range(9)])])
    zero = table.copy()
    zero.loc[5, "pga_g"] = 0.0
    with pytest.raises(ValueError, match=r"pga_g must be positive and finite: row 5 \('r0'\) has pga_g=0.0"):
        fit_fragility(zero)
    two = pd.concat([table, table.assign(mu=0.2)])
    with pytest.raises(ValueError, match="2 values of mu"):
        fit_fragility(two)
    with pytest.raises(ValueError, match="no column 'arias_m_s'"):
        fit_fragility(table, im="arias_m_s")
    with pytest.raises(ValueError, match="d0_m"):
        fit_fragility(table, d0_m=-1.0)


# ---- fragilities from the flexible mass and the block on a plane -------------------------

STUDY_PGA = (0.1, 0.2, 0.3, 0.45, 0.6, 0.8)  # [g]


@pytest.fixture(scope="module")
def ten_records():
    """Ten of pySLAMMER's sample records (the fewest a fragility takes)."""
    from conftest import sample_record_paths

    return [bd.read_record(path, units="g") for path in sample_record_paths()[:10]]


def assert_maximum_likelihood(fit, x, d):
    """The fit's first-order conditions, computed here from the table's values: the
    probit's score vanishes, and the lognormal's residuals are orthogonal to (1, ln x)
    with σ² their mean square."""
    u, slid = np.log(x), d > fit.d0_m
    z = np.where(slid, 1.0, -1.0) * (fit.b0 + fit.b1 * u)
    ratio = norm.pdf(z) / norm.cdf(z)
    score = np.array([np.sum(np.where(slid, ratio, -ratio)), np.sum(np.where(slid, ratio, -ratio) * u)])
    assert np.all(np.abs(score) <= 1e-6 * u.size), score
    residual = np.log(d[slid]) - fit.c0 - fit.c1 * u[slid]
    assert abs(residual.sum()) < 1e-9 * slid.sum() and abs(residual @ u[slid]) < 1e-9 * slid.sum()
    assert fit.sigma == pytest.approx(np.sqrt(np.mean(residual**2)), rel=1e-12)


def test_fragility_from_a_flexible_study(ten_records):
    """bd.flexible (coupled, ky = 0.1 g, H = 20 m, Vs = 300 m/s; 8 s of each record) at six
    target PGA, concatenated with a pga_g column: the worse polarity of each row
    (displacement=("normal_m", "inverse_m")) is the maximum likelihood fit's data."""
    table = pd.concat([bd.flexible(ten_records, ky=0.1, height=20.0, vs=300.0, pga=a, t_end=8.0)
                       .to_dataframe().assign(pga_g=a) for a in STUDY_PGA], ignore_index=True)
    fit = fit_fragility(table, "pga_g", ("normal_m", "inverse_m"), d0_m=0.005, n_boot=20)
    worse = np.maximum(table["normal_m"].abs(), table["inverse_m"].abs()).to_numpy()
    assert fit.n_records == 10 and fit.n_rows == 60 and 0 < np.count_nonzero(worse > 0.005) < 60
    assert_maximum_likelihood(fit, table["pga_g"].to_numpy(), worse)
    same = fit_fragility(table.assign(worse_m=worse), "pga_g", "worse_m", d0_m=0.005, n_boot=0)
    np.testing.assert_array_equal(same.params, fit.params)
    one_polarity = table.assign(inverse_m=np.nan, normal_m=worse)  # a polarity not run: NaN, skipped
    np.testing.assert_array_equal(fit_fragility(one_polarity, "pga_g", ("normal_m", "inverse_m"), d0_m=0.005,
                                                n_boot=0).params, fit.params)
    assert np.all(np.diff(fit.exceedance(0.05, np.array(STUDY_PGA))) > 0)
    with pytest.raises(ValueError, match="2 values of ky_g"):
        fit_fragility(pd.concat([table, table.assign(ky_g=0.2)]), "pga_g", ("normal_m", "inverse_m"))


def test_fragility_from_a_planar_study(ten_records):
    """bd.study(block=bd.PlanarBlock) of ten two-component motions at six PGA, two μ, 8 s:
    the defaults (pga_g, max_abs_displacement_m) fit each μ; the plot draws it."""
    import matplotlib

    matplotlib.use("Agg")
    from blockdae.hazard import plot_fragility

    motions = [bd.BaseMotion(record, record.scaled(0.5)) for record in ten_records]
    table = bd.study(motions, mu=[0.15, 0.25], pga=STUDY_PGA, block=bd.PlanarBlock(mu=0.3, bias=(-0.03, 0.0)),
                     t_end=8.0, progress=False)
    with pytest.raises(ValueError, match="2 values of mu"):
        fit_fragility(table)
    weak = table[table.mu == 0.15]
    fit = fit_fragility(weak, d0_m=0.005, n_boot=20)
    assert fit.im == "pga_g" and fit.n_records == 10 and fit.n_rows == 60
    assert_maximum_likelihood(fit, weak["pga_g"].to_numpy(), weak["max_abs_displacement_m"].to_numpy())
    strong = fit_fragility(table[table.mu == 0.25], d0_m=0.005, n_boot=0)
    assert strong.exceedance(0.05, 0.6) < fit.exceedance(0.05, 0.6)  # more friction, less sliding
    x = np.geomspace(0.1, 0.8, 20)
    ax = plot_fragility(fit, 0.05, x, others={"Jibson 2007": EmpiricalFragility(em.jibson_2007, "pga_g",
                                                                                  {"ky_g": 0.15})})
    np.testing.assert_allclose(ax.lines[0].get_ydata(), fit.exceedance(0.05, x))
    assert len(ax.collections) == 1  # the bootstrap band


def test_exported():
    """The subpackages are attributes of the top level (their names are not in its short __all__)."""
    assert bd.hazard.fit_fragility is fit_fragility and "fit_fragility" in bd.hazard.__all__
    assert bd.empirical.jibson_2007 is em.jibson_2007 and "jibson_2007" in bd.empirical.__all__


def test_benchmark_quick(monkeypatch, capsys):
    """benchmarks/hazard.py --quick runs (a smoke run: it judges no bar)."""
    import importlib.util
    import pathlib

    folder = pathlib.Path(__file__).parents[1] / "benchmarks"
    monkeypatch.syspath_prepend(str(folder))
    spec = importlib.util.spec_from_file_location("benchmark_hazard", folder / "hazard.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "Jibson 2007" in out and "smoke run, not a measurement" in out and "NOT met" not in out


def test_plots_draw_the_fit_its_band_and_the_others():
    import matplotlib

    matplotlib.use("Agg")
    from blockdae.hazard import plot_displacement_hazard, plot_fragility

    fit = fit_fragility(synthetic_table(np.random.default_rng(6)), d0_m=1e-9, n_boot=20)
    jibson = EmpiricalFragility(em.jibson_2007, "pga_g", {"ky_g": 0.1})
    x = np.geomspace(0.05, 1.5, 30)
    ax = plot_fragility(fit, 0.05, x, others={"Jibson 2007": jibson})
    assert len(ax.lines) == 2 and len(ax.collections) == 1  # the fit, Jibson; the band
    np.testing.assert_allclose(ax.lines[1].get_ydata(), jibson.exceedance(0.05, x))
    d = np.geomspace(0.01, 1.0, 10)
    curve = HazardCurve(x, 1e-4 * x**-2.5)
    assert ax.get_xlabel() == "Peak ground acceleration [g]" and ax.get_ylabel() == "probability of D > 0.05 m [-]"
    ax = plot_displacement_hazard(d, {"fit": displacement_hazard(curve, fit, d)})
    assert ax.get_xscale() == ax.get_yscale() == "log" and len(ax.lines) == 1
    np.testing.assert_array_equal(ax.lines[0].get_xdata(), d)  # d drawn in m, as given and labelled
    assert ax.get_xlabel() == "downslope displacement d [m]"
