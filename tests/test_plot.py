"""``bd.plot``: panels, event markers, and the block's acceleration from the model's flow."""

import matplotlib
import numpy as np
import pytest

import blockdae as bd


@pytest.fixture(scope="module")
def example_5():
    """Seed 000, Example 5: triangular pulse; slides from t* = 0.1635 s to t** = 0.4588 s."""
    matplotlib.use("Agg", force=True)
    example = next(e for e in bd.sliding.seed_examples() if e.name == "Example 5")
    return example, bd.simulate(example.block, example.motion, example.t_end)


def _events_line(ax):
    return next(line for line in ax.lines if line.get_label() == "events")


def test_full_figure_has_six_panels_with_units_and_event_markers(example_5):
    import matplotlib.pyplot as plt

    example, solution = example_5
    fig = bd.plot(solution, example.motion, example.block, title="Example 5")
    try:
        assert len(fig.axes) == 6
        labels = [ax.get_ylabel() for ax in fig.axes]
        for unit in ("[m/s²]", "[m/s]", "[m]"):
            assert any(unit in label for label in labels)
        rel_u = next(ax for ax in fig.axes if ax.get_ylabel().startswith("relative displacement"))
        markers = _events_line(rel_u)
        np.testing.assert_array_equal(markers.get_xdata(), solution.t_events)
        np.testing.assert_array_equal(markers.get_ydata(), [e.u for e in solution.events])
        phase = next(ax for ax in fig.axes if ax.get_title() == "phase plane")
        assert len(_events_line(phase).get_xdata()) == len(solution.events) == 2
    finally:
        plt.close(fig)


def test_block_acceleration_while_sliding_is_the_seeds_constant(example_5):
    """Seed 000, Eq. 17: a_b = 5.886 m/s² (= mu g) while the block slides."""
    import matplotlib.pyplot as plt

    example, solution = example_5
    fig = bd.plot(solution, example.motion, example.block)
    try:
        acc = next(ax for ax in fig.axes if ax.get_ylabel() == "acceleration [m/s²]")
        block = next(line for line in acc.lines if line.get_label() == "block")
        t, a = block.get_xdata(), block.get_ydata()
        t_star, t_stop = solution.t_events
        sliding = (t > t_star) & (t < t_stop)
        np.testing.assert_allclose(a[sliding], 0.6 * 9.81, rtol=1e-12)
        np.testing.assert_allclose(a[t < t_star], example.motion.acceleration(t[t < t_star]))
    finally:
        plt.close(fig)


def test_relative_only_figure_and_bad_input(example_5):
    import matplotlib.pyplot as plt

    _, solution = example_5
    fig = bd.plot(solution)
    try:
        assert len(fig.axes) == 3
    finally:
        plt.close(fig)
    with pytest.raises(TypeError, match="solution must be a Solution"):
        bd.plot("not a solution")
    with pytest.raises(ValueError, match="n_points"):
        bd.plot(solution, n_points=1)


def test_plot_draws_spectra_and_relative_motion():
    """bd.plot dispatches: a spectrum is PSa against T on log-log axes (the curve is the
    spectrum's own psa), a RelativeMotion is R against tau."""
    import matplotlib.pyplot as plt

    record = bd.Record(np.sin(np.linspace(0, 30, 1501)), 0.01, units="m/s2")
    spectrum = bd.motions.response_spectrum(record, np.geomspace(0.05, 5, 30))
    fig = bd.plot(spectrum)
    try:
        ax = fig.axes[0]
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        np.testing.assert_allclose(ax.lines[0].get_ydata(), spectrum.psa)
    finally:
        plt.close(fig)
    fig = bd.plot(bd.motions.relative_motion(record, [0.1, 0.5, 1.0]))
    try:
        assert "[s]" in fig.axes[0].get_xlabel() and "[m]" in fig.axes[0].get_ylabel()
    finally:
        plt.close(fig)


@pytest.fixture(scope="module")
def elms_planar():
    """Seed 001, Figure 6 set-up (g = 1): C_x = sin(pi t) for one wave, C_y = 0.8 C_x,
    mu = 0.8, N/A = 0.5 (bias 0.3 in -x)."""
    matplotlib.use("Agg", force=True)
    wave = bd.Harmonic(1.0, 2.0, cycles=1)
    block = bd.PlanarBlock(mu=0.8, bias=(-0.3, 0.0), g=1.0)
    return bd.simulate(block, bd.BaseMotion(wave, wave.scaled(0.8)), backend="ida")


def test_planar_figure_draws_the_solutions_path_components_and_speed(elms_planar):
    """The drawn curves are the solution's own values at the drawn times (dense output at
    the knots equals the knots), and the events sit at their located times and places."""
    import matplotlib.pyplot as plt

    sol = elms_planar
    fig = bd.plot(sol, n_points=400, title="Elms R = 0.8")
    try:
        path, disp, speed = fig.axes
        assert (path.get_xlabel(), path.get_ylabel()) == ("u_x [g s²]", "u_y [g s²]")  # g = 1: lengths in g s²
        assert disp.get_ylabel() == "relative displacement [g s²]" and "[g s]" in speed.get_ylabel()
        u_x, u_y = path.lines[0].get_xdata(), path.lines[0].get_ydata()
        t = next(line for line in disp.lines if line.get_label() == "u_x").get_xdata()
        knot_t, first = np.unique(sol.t, return_index=True)  # an event is a knot on either side
        drawn = np.isin(t, knot_t)
        np.testing.assert_array_equal(t[drawn], knot_t)
        np.testing.assert_allclose(u_x[drawn], sol.u_x[first], rtol=0, atol=1e-15)
        np.testing.assert_allclose(u_y[drawn], sol.u_y[first], rtol=0, atol=1e-15)
        markers = _events_line(path)
        np.testing.assert_array_equal(markers.get_xdata(), [e.u_x for e in sol.events])
        np.testing.assert_array_equal(markers.get_ydata(), [e.u_y for e in sol.events])
        np.testing.assert_array_equal(_events_line(disp).get_xdata(), np.tile(sol.t_events, 2))
        on_speed = _events_line(speed)
        np.testing.assert_array_equal(on_speed.get_xdata(), sol.t_events)
        np.testing.assert_allclose(on_speed.get_ydata(), 0.0, atol=1e-12)  # an onset and a stop: at rest
        v_x, v_y = sol.velocity
        drawn_speed = speed.lines[0].get_ydata()
        np.testing.assert_allclose(drawn_speed[drawn], np.hypot(v_x, v_y)[first], rtol=0, atol=1e-12)
        assert np.max(drawn_speed) > 0.1  # it slides
    finally:
        plt.close(fig)


def test_newmark_figure_draws_each_line_along_increasing_ky():
    """ky given out of order ([0.15, 0.05, 0.1]) was drawn as a zigzag in the given order;
    each line runs along increasing ky, with the D of each ky."""
    record = bd.Record(0.4 * bd.STANDARD_GRAVITY * np.sin(2 * np.pi * np.arange(300) * 0.01), 0.01, name="sine",
                       units="m/s2")
    result = bd.newmark(record, ky=[0.15, 0.05, 0.1])
    line = result.figure().axes[0].get_lines()[0]
    assert line.get_xdata().tolist() == [0.05, 0.1, 0.15]
    d = dict(zip([0.15, 0.05, 0.1], result.normal))
    assert line.get_ydata().tolist() == [d[0.05], d[0.1], d[0.15]]
