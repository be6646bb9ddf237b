"""The complete block's figure (``bd.plot`` / ``solution.figure``): theta [rad], the slip
[m], the corners' heights [m] and a_x [m/s²] against t [s], each panel shaded by the
motion (slide, rock, slide-rock, flight) over the spans the run's modes give, with a
legend; the curves are the solution's own (its dense output, the slip of
``solution.slip``, the corners' heights of the model)."""

import matplotlib
import numpy as np
import pytest

import blockdae as bd
from blockdae.rocking import FreeMode, FreeStandingBlock
from blockdae.rocking import _slide_rock_laws as laws
from blockdae.rocking._figures import MOTION_SPANS, motion_spans

G = bd.STANDARD_GRAVITY


def _chatter():
    """mu_k = 0.2 <= b/h = 1/4 < mu_s = 0.3 under a half-sine: rock, slide-rock with
    impacts, then a slide that sticks."""
    return bd.simulate(FreeStandingBlock(b=0.25, h=1.0, mu=0.3, mu_kinetic=0.2), bd.SinePulse(-0.6 * G, 0.4),
                       t_end=1.5)


def _flight():
    """A tilted block whose base falls faster than g: rock, slide-rock, flight, rock."""
    ramps = np.array([0.0, 0.0, -2 * G, -2 * G, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    motion = bd.BaseMotion(x=bd.Record(np.zeros(10), 0.1, name="none", units="m/s2"),
                           z=bd.Record(ramps, 0.1, name="drop", units="m/s2"))
    return bd.simulate(FreeStandingBlock(b=0.2, h=0.6, mu=1.0, theta0=0.15), motion, t_end=0.9)


@pytest.mark.parametrize("run, shaded", [(_chatter, {"rock", "slide-rock", "slide"}),
                                         (_flight, {"rock", "slide-rock", "flight"})])
def test_panels_have_units_and_each_motion_is_shaded_where_the_modes_say(run, shaded):
    import matplotlib.pyplot as plt

    matplotlib.use("Agg", force=True)
    solution = run()
    spans = motion_spans(solution)
    assert {label for label, found in spans.items() if found} == shaded
    for i in np.flatnonzero(np.diff(solution.t) > 0):  # each stretch between knots: shaded by its mode's motion
        mid = 0.5 * (solution.t[i] + solution.t[i + 1])
        covering = [label for label, found in spans.items() for start, end in found if start < mid < end]
        expected = [label for label, (_, kinds) in MOTION_SPANS.items() if int(abs(solution.mode[i])) in kinds]
        assert covering == expected, (solution.t[i], solution.mode[i])
    fig = bd.plot(solution, title="run")
    try:
        assert [ax.get_ylabel() for ax in fig.axes] == ["theta [rad]", "slip [m]", "corner heights [m]",
                                                        "a_x [m/s²]"]
        assert fig.axes[-1].get_xlabel() == "t [s]"
        for ax in fig.axes:
            for label, found in spans.items():
                patches = [p for p in ax.patches if p.get_gid() == label]
                assert len(patches) == len(found)
                drawn = np.array([(p.get_x(), p.get_x() + p.get_width()) for p in patches]).reshape(-1, 2)
                assert np.allclose(drawn, np.array(found).reshape(-1, 2), rtol=0, atol=1e-12)
        legend = [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
        assert shaded <= set(legend)
        line = lambda ax, label: next(line for line in ax.lines if line.get_label() == label).get_data()
        t, theta = line(fig.axes[0], "theta")
        assert len(t) >= 2000 and np.array_equal(theta, solution(t)[2])
        t, slip = line(fig.axes[1], "slip")
        x, _, angle = solution(t)[:3]
        assert slip[-1] == solution.final_slip
        assert np.array_equal(slip, laws.base_slip(x, angle, solution.block.b, solution.block.h, np))
        heights = [line(fig.axes[2], f"corner {c}")[1] for c in ("+b", "-b")]
        knots = np.isin(t, solution.t)
        low = np.minimum(heights[0], heights[1])
        # no corner below the base: at the knots to the integration's error (measured 1.1e-11
        # m on these runs), between them to the cubic Hermite dense output's (6.5e-9 m)
        assert low[knots].min() >= -1e-10 and low.min() >= -1e-8
        if "flight" in shaded:
            start, end = spans["flight"][0]
            assert solution.events_of("lift")[0].t == start and solution.events_of("land")[0].t == end
            middle = (t > start + 0.1 * (end - start)) & (t < end - 0.1 * (end - start))
            assert np.all(np.minimum(heights[0][middle], heights[1][middle]) > 0)  # both corners off the base
    finally:
        plt.close(fig)


def test_rest_and_overturned_are_not_shaded():
    solution = bd.simulate(FreeStandingBlock(b=0.25, h=1.0, mu=0.3), bd.SinePulse(-0.6 * G, 0.4), t_end=3.0)
    assert solution.mode[-1] in (FreeMode.OVERTURNED_POS, FreeMode.OVERTURNED_NEG)
    spans = motion_spans(solution)
    last = max(end for found in spans.values() for _, end in found)
    assert last == solution.overturn_time and solution.t[0] < min(s for f in spans.values() for s, _ in f)
