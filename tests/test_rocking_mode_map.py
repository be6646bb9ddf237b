"""The rest -> mode map (rocking.mode_map) and its figure, against Shenton's (1996) regions
written here from their closed forms: rest below min(mu, b/h) g_e, slide for mu <= b/h,
rock above the critical friction mu_cr(a), slide-rock between b/h and mu_cr."""

import matplotlib
import numpy as np
import pytest

from blockdae import rocking

matplotlib.use("Agg")


def shenton(lam, mu, a, e):
    """The regions for mu_s = mu_k = mu, |a_x| / g = a, g_e / g = e > 0 (arrays)."""
    mu_cr = ((a / e) * (1 + 4 * lam ** 2) + 3 * lam) / (4 + lam ** 2 + 3 * lam * (a / e))
    moving = np.where(mu <= lam, "slide", np.where(mu >= mu_cr, "rock", "slide-rock"))
    return np.where(a <= np.minimum(mu, lam) * e, "rest", moving)


@pytest.mark.parametrize("lam, av", [(0.25, 0.0), (0.6, 0.0), (0.25, -0.4), (1.5, 0.3)])
def test_mode_map_is_shentons(lam, av):
    mu = np.linspace(0.013, 2.0, 61)[:, None]
    a = np.linspace(0.0, 2.0, 67)[None, :]
    names = rocking.mode_map(lam, mu, a, av_over_g=av)
    assert names.shape == (61, 67)
    assert np.array_equal(names, shenton(lam, mu, a, 1.0 + av))
    assert np.array_equal(rocking.mode_map(lam, mu, -a, av_over_g=av), names)  # the side does not matter
    assert set(np.unique(names)) == {"rest", "slide", "rock", "slide-rock"}


def test_kinetic_friction_below_static():
    """mu_k <= b/h < mu_s: past the pivot's static limit the block slides flat (no slide-rock);
    mu_k > b/h: it slide-rocks; below that limit the pivot holds either way."""
    lam, mu_s = 0.25, 0.35
    a_sr = (mu_s * (4 + lam ** 2) - 3 * lam) / (1 + 4 * lam ** 2 - 3 * mu_s * lam)  # [g], 0.784
    assert list(rocking.mode_map(lam, mu_s, [0.2, 0.5, a_sr, a_sr + 0.01], mu_k=0.2)) == ["rest", "rock", "rock",
                                                                                          "slide"]
    assert rocking.mode_map(lam, mu_s, a_sr + 0.01, mu_k=0.3) == "slide-rock"


def test_flight_where_the_base_falls_faster_than_g():
    assert set(np.unique(rocking.mode_map(0.3, [0.1, 0.8], [[0.0], [0.5]], av_over_g=-1.2))) == {"flight"}


@pytest.mark.parametrize("kwargs, field", [(dict(b_over_h=0.0), "b_over_h"), (dict(mu_s=-0.1), "mu_s"),
                                           (dict(mu_k=0.9), "mu_k"), (dict(a_over_g=np.nan), "a_over_g"),
                                           (dict(av_over_g=np.inf), "av_over_g")])
def test_mode_map_names_a_bad_field(kwargs, field):
    args = dict(b_over_h=0.3, mu_s=0.5, a_over_g=0.4) | kwargs
    with pytest.raises(ValueError, match=field):
        rocking.mode_map(**args)


def test_plot_mode_map_shades_the_map():
    fig = rocking.plot_mode_map(0.25, mu_k_ratio=0.8, n=50)
    ax = fig.axes[0]
    assert "[-]" in ax.get_xlabel() and "[-]" in ax.get_ylabel()
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["rest", "slide", "rock", "slide-rock"]
    mu, a = np.linspace(0, 1.0, 50)[:, None], np.linspace(0, 1.0, 50)[None, :]
    shaded = ax.get_images()[0].get_array()
    names = rocking.mode_map(0.25, mu, a, mu_k=0.8 * mu)
    assert np.array_equal(np.array(["rest", "slide", "rock", "slide-rock", "flight"])[shaded], names)
    assert [t.get_text() for t in rocking.plot_mode_map(0.3, av_over_g=-1.5, n=5).axes[0].get_legend().get_texts()] \
        == ["flight"]
    with pytest.raises(ValueError, match="mu_k_ratio"):
        rocking.plot_mode_map(0.3, mu_k_ratio=1.2)
