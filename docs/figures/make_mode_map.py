"""Draw the rocking-block page's rest -> mode map (PNG, committed beside this script): a
block of b/h = 0.25 with mu_k = mu_s and with mu_k = 0.8 mu_s. Run from anywhere:
``python docs/figures/make_mode_map.py``."""

import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from blockdae import rocking  # noqa: E402

fig, axes = plt.subplots(1, 2, figsize=(11, 4.3), sharey=True, constrained_layout=True)
for ax, ratio in zip(axes, (1.0, 0.8)):
    rocking.plot_mode_map(0.25, mu_k_ratio=ratio, a_max=1.2, mu_max=1.0, n=600, ax=ax)
fig.savefig(pathlib.Path(__file__).with_name("rocking_mode_map.png"), dpi=100, metadata={"Software": None})
