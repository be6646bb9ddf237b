"""Newmark's conventions: positive downslope displacement, both polarities, k_y helpers."""

import numpy as np
import pytest

import blockdae as bd
from blockdae.sliding import Mode

G = bd.STANDARD_GRAVITY


def rectangular_pulse_downslope(a, t0, ky, g=G):
    """Closed form for one rectangular pulse a [m/s²] of t0 [s] on a one-way block of
    yield acceleration ky [g]: D = (a t0² / 2) (a / (ky g) - 1) (seed 000, the
    rectangular pulse; Newmark 1965)."""
    return 0.5 * a * t0**2 * (a / (ky * g) - 1.0) if a > ky * g else 0.0


def test_rectangular_pulse_normal_and_inverse_polarity():
    pulse = bd.RectangularPulse(0.4 * G, 0.5)
    result = bd.newmark(pulse, ky=0.1)
    assert result.normal == pytest.approx(rectangular_pulse_downslope(0.4 * G, 0.5, 0.1), rel=1e-14)
    assert result.normal > 0 and result.inverse == 0.0 and str(result.inverse) == "0.0"
    assert result.maximum == result.normal and result.mean == pytest.approx(result.normal / 2, rel=1e-15)


def test_batch_over_ky_matches_the_signed_block_on_both_polarities(kobe):
    """D is -u of SlidingBlock(mu=ky, direction="negative") on the record and on its inverse."""
    ky = np.array([0.05, 0.1, 0.2])
    result = bd.newmark(kobe, ky)
    for i, k in enumerate(ky):
        block = bd.SlidingBlock(mu=k, direction="negative")
        assert result.normal[i] == pytest.approx(-bd.simulate(block, kobe).displacement, rel=1e-12)
        assert result.inverse[i] == pytest.approx(-bd.simulate(block, kobe.inverted()).displacement, rel=1e-12)
    assert np.all(np.diff(result.normal) < 0)  # a stronger slope slides less
    table = result.to_dataframe()
    assert list(table.columns) == ["ky_g", "normal_m", "inverse_m", "mean_m", "max_m"]
    np.testing.assert_array_equal(table["max_m"], np.maximum(result.normal, result.inverse))
    only = bd.newmark(kobe, 0.1, polarity="inverse")
    assert only.normal is None and only.maximum == pytest.approx(result.inverse[1], rel=1e-12)


def test_yield_acceleration_from_factor_of_safety():
    """Jibson (1993): k_y = (FS - 1) sin(alpha); FS 1.5 at 30 degrees gives 0.25 g."""
    assert bd.sliding.yield_acceleration(1.5, 30.0) == pytest.approx(0.25, rel=1e-15)
    np.testing.assert_allclose(bd.sliding.yield_acceleration([1.0, 2.0], 30.0), [0.0, 0.5], rtol=1e-15)
    with pytest.raises(ValueError, match=r"factor_of_safety=0\.9 must be >= 1"):
        bd.sliding.yield_acceleration(0.9, 30.0)
    with pytest.raises(ValueError, match=r"thrust_angle=95\.0"):
        bd.sliding.yield_acceleration(1.2, 95.0)


def test_block_on_incline_yields_at_the_jibson_acceleration():
    """On a 20 degree slope with a 35 degree friction angle, FS = tan 35 / tan 20 and the
    block slides downslope under an upslope base pulse exactly as Newmark's block of
    k_y = (FS - 1) sin 20 under the downslope pulse (same equation of motion)."""
    block = bd.SlidingBlock.on_incline(slope_angle=20.0, friction_angle=35.0)
    fs = np.tan(np.radians(35.0)) / np.tan(np.radians(20.0))
    ky = bd.sliding.yield_acceleration(fs, 20.0)
    assert block.mu - block.bias == pytest.approx(ky, rel=1e-14)
    a = 2.5 * ky * G
    sol = bd.simulate(block, bd.RectangularPulse(-a, 0.4))
    assert [e.mode_after for e in sol.events] == [Mode.SLIP_POS, Mode.STICK]
    assert sol.displacement == pytest.approx(rectangular_pulse_downslope(a, 0.4, ky), rel=1e-12)
    held = bd.simulate(block, bd.RectangularPulse(-0.999 * ky * G, 0.4))
    assert held.events == ()


def test_pga_scales_the_record_to_a_peak_in_g(kobe):
    """newmark(rec, ky, pga=0.3) is newmark on the record scaled to a peak of 0.3 g; with
    pga_rounding="slammer" the record's own peak is first rounded to 0.001 g (SLAMMER)."""
    ky = np.array([0.05, 0.1])
    scaled = bd.newmark(kobe, ky, pga=0.3)
    direct = bd.newmark(kobe.scaled(0.3 * G / kobe.peak_acceleration), ky)
    np.testing.assert_array_equal(scaled.normal, direct.normal)
    np.testing.assert_array_equal(scaled.inverse, direct.inverse)
    assert np.all(scaled.normal > 0)
    own = round(kobe.peak_acceleration / G, 3)
    assert own != kobe.peak_acceleration / G  # the rounding changes the factor here
    slammer = bd.newmark(kobe, ky, pga=0.3, pga_rounding="slammer")
    np.testing.assert_array_equal(slammer.normal, bd.newmark(kobe.scaled(0.3 / own), ky).normal)
    assert not np.array_equal(slammer.normal, scaled.normal)
    with pytest.raises(ValueError, match=r"pga=9\.81 g is implausible .*looks like m/s² \(9\.81 m/s² = 1 g\)"):
        bd.newmark(kobe, 0.1, pga=9.81)


def test_target_pga_is_the_deprecated_name_of_pga(kobe):
    """``target_pga=`` scales as ``pga=`` does, bit for bit (one motion and a sweep), with a
    DeprecationWarning that names ``pga`` and points at the caller's line; both are refused."""
    ky = np.array([0.05, 0.1])
    for pga in (0.3, [0.2, 0.4]):
        with pytest.warns(DeprecationWarning, match=r"^bd\.newmark\(\.\.\., target_pga=\.\.\.\) is deprecated; "
                                                    r"use bd\.newmark\(\.\.\., pga=\.\.\.\)") as caught:
            old = bd.newmark(kobe, ky, target_pga=pga)
        assert [w.filename for w in caught if w.category is DeprecationWarning] == [__file__]
        new = bd.newmark(kobe, ky, pga=pga)
        np.testing.assert_array_equal(old.normal, new.normal)
        np.testing.assert_array_equal(old.inverse, new.inverse)
        assert np.all(new.normal > 0)
    with pytest.raises(ValueError, match=r"pga=0\.3 and target_pga=0\.4 name the same target peak \[g\]; give pga "
                                         r"only"):
        bd.newmark(kobe, 0.1, pga=0.3, target_pga=0.4)


def test_ky_in_m_s2_is_refused_and_ky_above_the_peak_warns():
    """ky = 9.81 (m/s² meant as 1 g) under a 0.4 g pulse is refused; ky = 0.5 g >= PGA 0.4 g
    warns that D = 0 (and D is 0); ky = 1.5 g under a 2 g pulse slides, no warning."""
    pulse = bd.RectangularPulse(0.4 * G, 0.5)
    with pytest.raises(ValueError, match=r"ky=9\.81 g is above 1 g and the motion's peak \(0\.4 g\): it looks "
                                         r"like m/s² \(9\.81 m/s² = 1 g\); give ky in g"):
        bd.newmark(pulse, ky=[0.1, 9.81])
    with pytest.warns(bd.UnitsWarning, match=r"ky=0\.4, 0\.5 g >= PGA = 0\.4 g: the block does not slide, D = 0 m"):
        result = bd.newmark(pulse, ky=[0.1, 0.4, 0.5])
    assert result.maximum[0] > 0 and result.maximum[1] == result.maximum[2] == 0.0
    strong = bd.newmark(bd.RectangularPulse(2.0 * G, 0.5), ky=1.5, polarity="normal")
    assert strong.normal == pytest.approx(rectangular_pulse_downslope(2.0 * G, 0.5, 1.5), rel=1e-14)


@pytest.mark.parametrize("kwargs, message", [
    ({"ky": 0.0}, r"ky=0\.0 must be a positive yield acceleration \[g\]"),
    ({"ky": 0.1, "polarity": "up"}, r"polarity must be one of"),
])
def test_bad_newmark_input_names_the_field(kwargs, message):
    with pytest.raises(ValueError, match=message):
        bd.newmark(bd.RectangularPulse(3.0, 0.5), **kwargs)


def test_incline_steeper_than_friction_angle_is_an_error():
    with pytest.raises(ValueError, match=r"slope_angle=40\.0 must be below friction_angle=35\.0"):
        bd.SlidingBlock.on_incline(40.0, 35.0)


def _sine_file(path, amplitude_g, frequency=2.0, dt=0.01, cycles=2):
    """A sine of ``amplitude_g`` [g] written as CSV (time [s], acceleration [g]); the Record read back."""
    t = dt * np.arange(int(round(cycles / frequency / dt)) + 1)
    a = amplitude_g * np.sin(2 * np.pi * frequency * t)
    path.write_text("time (s), acceleration (g)\n" + "".join(f"{x:.17g}, {y:.17g}\n" for x, y in zip(t, a)))
    return bd.read_record(path)


def test_many_records_by_pga_by_ky_is_one_row_per_case_equal_to_single_runs(sample_records):
    """newmark(records, ky, pga=[...]) gives, for every (record, pga, ky), the D of the
    one-record call, in a table with units in its column names; a single excitation with
    several pga is a sweep of one record."""
    records, ky, pga = sample_records[:3], np.array([0.05, 0.1, 0.2]), [0.3, 0.5]
    sweep = bd.newmark(records, ky, pga=pga)
    assert isinstance(sweep, bd.sliding.NewmarkSweep) and sweep.shape == (3, 2, 3)
    table = sweep.to_dataframe()
    assert list(table.columns) == ["record", "pga_g", "ky_g", "normal_m", "inverse_m", "mean_m", "max_m"]
    assert len(table) == 18
    for i, record in enumerate(records):
        for j, target in enumerate(pga):
            one = bd.newmark(record, ky, pga=target)
            rows = table[(table["record"] == record.name) & (table["pga_g"] == target)]
            np.testing.assert_array_equal(rows["ky_g"], ky)
            np.testing.assert_array_equal(rows["normal_m"], one.normal)
            np.testing.assert_array_equal(rows["inverse_m"], one.inverse)
            np.testing.assert_array_equal(sweep.maximum[i, j], one.maximum)
    assert np.all(sweep.normal[:, 1] >= sweep.normal[:, 0]) and np.any(sweep.normal[:, 1] > sweep.normal[:, 0])
    alone = bd.newmark(records[0], ky, pga=pga)
    np.testing.assert_array_equal(alone.normal, sweep.normal[:1])
    as_given = bd.newmark(records, 0.1, polarity="normal").to_dataframe()
    assert "inverse_m" not in as_given and list(as_given["record"]) == [r.name for r in records]
    np.testing.assert_array_equal(as_given["pga_g"], [r.peak_acceleration / G for r in records])


def test_a_folder_is_every_record_file_in_it_by_name_and_an_empty_one_is_refused(tmp_path):
    folder = tmp_path / "records"
    folder.mkdir()
    second = _sine_file(folder / "b_strong.csv", 0.5)
    first = _sine_file(folder / "a_weak.csv", 0.3)
    (folder / "notes.md").write_text("not a record")
    sweep = bd.newmark(folder, [0.1, 0.2])
    assert sweep.records == ("a_weak", "b_strong")
    for i, record in enumerate((first, second)):
        np.testing.assert_array_equal(sweep.normal[i, 0], bd.newmark(record, [0.1, 0.2]).normal)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(ValueError, match=rf"{empty}: no record files \(\.csv, \.txt, \.dat, \.at2, \.v1, .*, \.mseed, "
                                         r"\.miniseed, each also \.gz\)"):
        bd.newmark(empty, 0.1)
    with pytest.raises(ValueError, match=r"motions is empty"):
        bd.newmark([], 0.1)


def test_a_sweep_warns_once_naming_the_cases_where_ky_reaches_the_pga(tmp_path):
    weak, strong = _sine_file(tmp_path / "weak.csv", 0.15), _sine_file(tmp_path / "strong.csv", 0.5)
    peak = f"{weak.peak_acceleration / G:.4g}"
    with pytest.warns(bd.UnitsWarning, match=r"ky >= PGA in 1 of 2 \(record, PGA\) cases: the block does not slide "
                                             rf"there, D = 0 m: weak \(PGA {peak} g\): ky=0\.2 g$") as caught:
        sweep = bd.newmark([weak, strong], [0.1, 0.2])
    assert len(caught) == 1
    assert sweep.maximum[0, 0, 1] == 0.0 and sweep.maximum[1, 0, 1] > 0
    with pytest.raises(ValueError, match=rf"weak: ky=9\.81 g is above 1 g and the motion's peak \({peak} g\)"):
        bd.newmark([weak, strong], [0.1, 9.81])


def test_the_sweeps_figure_draws_d_against_ky_per_record(sample_records):
    """One curve per (record, PGA), coloured by record with a legend keyed by record, a
    line style per PGA with its own legend; D >= 0 drawn as computed; log axes where the
    values span a decade; beyond 12 records a colour scale replaces the legend."""
    import matplotlib
    import matplotlib.pyplot as plt

    matplotlib.use("Agg", force=True)
    ky = [0.02, 0.05, 0.1, 0.2]
    sweep = bd.newmark(sample_records[:2], ky, pga=[0.3, 0.5])
    fig = bd.plot(sweep)
    try:
        ax = fig.axes[0]
        curves = [line for line in ax.get_lines() if len(line.get_xdata()) == len(ky)]
        assert len(curves) == 4
        for curve, d in zip(curves, sweep.maximum.reshape(4, len(ky))):
            np.testing.assert_array_equal(curve.get_xdata(), ky)
            np.testing.assert_array_equal(curve.get_ydata(), d)
        assert curves[0].get_color() == curves[1].get_color() != curves[2].get_color()  # a colour per record
        assert curves[0].get_linestyle() != curves[1].get_linestyle()  # a style per PGA
        assert [t.get_text() for t in fig.legends[0].get_texts()] == [r.name for r in sample_records[:2]]
        assert fig.legends[0].get_title().get_text() == "record"
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["0.3 g", "0.5 g"]
        assert ax.get_xscale() == "log" and ax.get_xlabel() == "yield acceleration k_y [g]"
        positive = sweep.maximum[sweep.maximum > 0]
        assert ax.get_yscale() == ("log" if positive.max() >= 10 * positive.min() else "linear")
        assert ax.get_ylabel().startswith("downslope displacement D [m]")
    finally:
        plt.close(fig)
    many = bd.newmark(sample_records[:13], [0.1, 0.2])
    fig = bd.plot(many)
    try:
        assert not fig.legends and len(fig.axes) == 2  # the axes and the colour scale
        assert fig.axes[1].get_ylabel() == "record number (1 to 13, in the table's order)"
    finally:
        plt.close(fig)


def test_a_ky_table_is_taken_and_anything_else_refused_saying_what_newmark_takes(kobe):
    """A varying table (or pySLAMMER's pair) runs the exact ky-table slide (its checks:
    test_newmark_ky_table.py); a constant one is its ky; a word is refused."""
    varying = bd.KyTable((0.0, 0.1), (0.1, 0.2))
    assert bd.newmark(kobe, ((0.0, 0.1), (0.1, 0.2))).normal == bd.newmark(kobe, varying).normal
    assert bd.newmark(kobe, varying).normal < bd.newmark(kobe, 0.1).normal
    with pytest.raises(TypeError, match=r"ky='steep': newmark takes yield accelerations \[g\]"):
        bd.newmark(kobe, "steep")
    constant = bd.newmark(kobe, bd.KyTable((0.0,), (0.1,)))
    assert constant.ky == 0.1 and constant.normal == bd.newmark(kobe, 0.1).normal


def test_results_sign_and_repr(kobe, sample_records):
    """D >= 0 in NewmarkResult and NewmarkSweep, their tables named *_m; reprs one short line."""
    result = bd.newmark(kobe, np.linspace(0.02, 0.3, 40))
    sweep = bd.newmark(sample_records[:3], [0.05, 0.1], pga=[0.2, 0.4])
    for r in (result, sweep):
        assert np.all(r.normal >= 0) and np.all(r.inverse >= 0)
        assert {"normal_m", "inverse_m", "mean_m", "max_m"} <= set(r.to_dataframe().columns)
        text = repr(r)
        assert len(text) < 400 and "\n" not in text and "largest D" in text
