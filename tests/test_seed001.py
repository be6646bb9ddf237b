"""Seed 001 (Elms): the block on a plane against the numbers the paper gives in its text.

The paper's figures are not in its text; what it says is "almost", "about", "nearly" or
"roughly" a value, so each comparison states a tolerance for reading its words, and the
trends it describes are checked on a grid of R. R = 0 is checked against an independent
answer: the 1-D block's exact backend (closed forms).
"""

import math

import numpy as np
import pytest

import blockdae as bd
from blockdae.planar import PlanarMode
from blockdae.planar import _elms as elms

#: reading "almost / about / nearly X %" off the text: within 10 % of X (relative)
WORDS = 0.10


def test_r0_is_newmarks_block_with_the_plateau_n():
    """Fig. 4: with R = 0 the planar block is the 1-D block (closed form), and while it
    slides its acceleration stays at N = 0.5 (seed eq. 2): the relative acceleration is
    N - C_x, so v_x(t) = N (t - t_on) + (cos(pi t) - cos(pi t_on)) / pi."""
    sol = elms.elms_run(0.5, 0.8, 0.0)
    exact = bd.simulate(elms.elms_one_d(0.5, 0.8), elms.WAVE)
    assert abs(sol.displacement[0] - exact.displacement) <= 1e-7 * abs(exact.displacement)
    np.testing.assert_allclose(sol.t_events, exact.t_events, rtol=0, atol=1e-9)
    t_on = math.asin(0.5) / math.pi
    t = np.linspace(t_on, sol.t_events[1], 50)
    np.testing.assert_allclose(sol(t)[2], 0.5 * (t - t_on) + (np.cos(np.pi * t) - math.cos(math.pi * t_on)) / np.pi,
                               rtol=0, atol=1e-8)


def test_fig6_v_x_turns_positive_and_k_x_reaches_a_passive_plateau():
    """Fig. 6 (R = 0.8): v_x "changes sign and becomes positive for a while towards the
    end"; k_x reaches "a negative plateau of about -0.8" near t = 1.3 (Elms's estimate
    -0.866, "roughly"). k_x = -(v_x / |v|) mu - P while sliding (his eq. 14)."""
    sol = elms.elms_run(0.5, 0.8, 0.8)
    t = np.linspace(1.3, 1.7, 81)
    _, _, v_x, v_y, _ = sol(t)
    assert np.all(sol.mode[np.searchsorted(sol.t, t, side="right") - 1] == PlanarMode.SLIP)
    k_x = -v_x / np.hypot(v_x, v_y) * 0.8 - 0.3
    assert np.max(sol(np.linspace(1.3, sol.t_events[-1], 200))[2]) > 0
    assert abs(np.mean(k_x) - (-0.8)) <= WORDS * 0.8
    assert abs(np.min(k_x) - elms.SEED_FIG6_PLATEAU) <= WORDS * abs(elms.SEED_FIG6_PLATEAU)


@pytest.mark.parametrize("n_over_a", [0.3, 0.5, 0.7, 0.9])
def test_fig7_the_increase_grows_with_r(n_over_a):
    """Fig. 7 (mu = 0.8): the x displacement grows with the lateral ratio R."""
    pct = elms.percent_increase(n_over_a, 0.8, [0.0, 0.5, 1.0])
    assert pct[0] == 0.0 and np.all(np.diff(pct) > 0)


def test_fig7_the_increase_at_r1_grows_with_n_over_a():
    """Fig. 7: "the percentage increase is greater for higher values of N/A"."""
    pct = [elms.percent_increase(n_over_a, 0.8, [1.0])[0] for n_over_a in (0.3, 0.5, 0.7, 0.9)]
    assert np.all(np.diff(pct) > 0)


@pytest.mark.xfail(strict=True, reason=(
    "measured 76.3 % at N/A = 0.9, R = 1 (34.0, 46.3, 49.2 % at N/A = 0.3, 0.5, 0.7) against "
    "the seed's 'reaching almost 60 %': above it by more than reading its words allows; the "
    "seed's R range and N/A = 0.9 > mu = 0.8 (P = -0.1) are not stated beside its figure"))
def test_fig7_largest_increase_is_almost_60_percent():
    largest = elms.percent_increase(0.9, 0.8, [1.0])[0]
    assert abs(largest - elms.SEED_FIG7_MAX_PERCENT) <= WORDS * elms.SEED_FIG7_MAX_PERCENT


def test_fig8_largest_increase_is_about_60_percent():
    """Fig. 8 (N/A = 0.5): "a maximum of about 60 % for high values of R" (mu = 1.0, R = 1:
    65.1 % measured; mu = 0.5 has P = 0, an unbiased block, and is left out)."""
    largest = max(elms.percent_increase(0.5, mu, [1.0])[0] for mu in (0.6, 0.7, 0.9, 1.0))
    assert abs(largest - elms.SEED_FIG8_MAX_PERCENT) <= WORDS * elms.SEED_FIG8_MAX_PERCENT


def test_r1_mu1_n_over_a_09_is_nearly_700_percent():
    """"For the combination R = 1.0, mu = 1.0 and N/A = 0.9, the final displacement is
    increased by nearly 700 %" (measured 655.0 %)."""
    pct = elms.percent_increase(0.9, 1.0, [0.0, 1.0])[1]
    assert elms.SEED_EXTREME_PERCENT * (1 - WORDS) <= pct < elms.SEED_EXTREME_PERCENT


@pytest.mark.slow
@pytest.mark.parametrize("n_over_a, mu", [
    (0.3, 0.8), (0.5, 0.8), (0.7, 0.8), (0.9, 0.8), (0.5, 0.6), (0.5, 0.7), (0.5, 0.9), (0.5, 1.0)])
def test_figs7_8_increase_is_monotone_in_r_on_a_fine_grid(n_over_a, mu):
    pct = elms.percent_increase(n_over_a, mu, np.linspace(0.0, 1.0, 11))
    assert np.all(np.diff(pct) > 0)


def test_tables_of_g_1_cases_give_lengths_in_g_s2_not_m():
    """Elms's set-up is dimensionless (g = 1): its event tables, planar and 1-D, label
    lengths g s² (1 m at g = 1 m/s²); the same block at standard gravity says m."""
    planar = bd.simulate(elms.elms_block(0.5, 0.8), elms.elms_motion(0.8))
    one_d = bd.simulate(elms.elms_one_d(0.5, 0.8), elms.WAVE)
    assert planar.event_table().splitlines()[0].split()[4:8] == ["u_x", "[g", "s²]", "u_y"]
    assert "[m]" not in planar.event_table() and "u [g s²]" in one_d.event_table()
    standard = bd.simulate(bd.PlanarBlock(mu=0.8, bias=(-0.3, 0.0)), elms.elms_motion(0.8).scaled(bd.STANDARD_GRAVITY))
    assert "u_x [m]" in standard.event_table() and "[g s²]" not in standard.event_table()
    assert "u [m]" in bd.simulate(bd.SlidingBlock(mu=0.8, bias=-0.3), elms.WAVE.scaled(bd.STANDARD_GRAVITY)).event_table()
