"""The figures of a design study: exceedance curves and ky against D."""

import numpy as np


def exceedance_figure(results, *, title=None):
    """P(D > d) of each of ``results`` (label -> :class:`Exceedance`) against d [m]
    (log scale), with its confidence band and its threshold marked; a matplotlib Figure."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for label, result in results.items():
        curve = result.curve()
        line, = ax.plot(curve["D_m"], curve["P_exceed"], label=f"{label}: P(D > {result.threshold_m:g} m) = "
                                                                f"{result.probability:.3f}")
        ax.fill_between(curve["D_m"], curve["P_low"], curve["P_high"], color=line.get_color(), alpha=0.2, lw=0)
        ax.axvline(result.threshold_m, color="0.4", ls=":", lw=1)
    ax.set_xscale("log")
    ax.set_xlabel("displacement d [m]")
    ax.set_ylabel("P(D > d) [-]")
    ax.set_ylim(0, 1)
    level = next(iter(results.values())).confidence
    ax.legend(title=f"bands: {level:.0%} Wilson intervals", fontsize="small")
    ax.set_title(title or "Exceedance of the displacement")
    fig.tight_layout()
    return fig


def ky_figure(result, *, title=None):
    """D [m] against ky [g] (mu [-] for the block on a plane) of each sample of
    ``result``, a colour per record; a matplotlib Figure."""
    import matplotlib.pyplot as plt

    plane = "ky_g" not in result.table
    column, label = ("mu", "friction coefficient mu [-]") if plane else ("ky_g", "yield acceleration ky [g]")
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for name, rows in result.table.groupby("record", sort=False):
        ax.scatter(rows[column], np.maximum(rows["D_m"], 1e-4), s=8, label=name)
    ax.axhline(result.threshold_m, color="0.4", ls=":", lw=1)
    ax.set_yscale("log")
    ax.set_xlabel(label)
    ax.set_ylabel("displacement D [m] (1e-4 m where none)")
    ax.legend(fontsize="x-small", ncol=2)
    ax.set_title(title or f"Displacement against {column.split('_')[0]}")
    fig.tight_layout()
    return fig
