"""Maps drawn over a hillshade of the terrain, units on every colour bar (matplotlib on demand)."""

import numpy as np

from ._infinite_slope import FLAT, NODATA, UNSTABLE

_LABELS = {"median_displacement_m": "median D, time histories [m]",
           "jibson_2007_median_m": "Jibson (2007) median D [m]",
           "saygili_rathje_2008_median_m": "Saygili & Rathje (2008) median D [m]"}


def map_figure(dataset, dem, variables=("median_displacement_m", "jibson_2007_median_m"), *, d_min_m: float = 1e-3,
               title: str | None = None):
    """One panel per displacement variable of ``dataset`` [m] over the hillshade of ``dem``
    (elevations [m] on the same grid), on one logarithmic colour scale from ``d_min_m`` [m]
    (smaller D left transparent: the hillshade shows); statically unstable cells in
    black. Also ``"exceedance"`` (its first threshold, 0-1). Returns a matplotlib Figure."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import LightSource, LogNorm, Normalize

    x, y = np.asarray(dataset["x"]), np.asarray(dataset["y"])
    extent = (x[0] - (x[1] - x[0]) / 2, x[-1] + (x[1] - x[0]) / 2, y[-1] + (y[0] - y[1]) / 2, y[0] - (y[1] - y[0]) / 2)
    z = np.asarray(dem, dtype=float)
    shade = LightSource(azdeg=315, altdeg=45).hillshade(np.nan_to_num(z, nan=np.nanmean(z)), vert_exag=2,
                                                        dx=abs(x[1] - x[0]), dy=abs(y[1] - y[0]))
    category = np.asarray(dataset["category"])
    shown = [np.asarray(dataset[v].isel(threshold_m=0) if v == "exceedance" else dataset[v]) for v in variables]
    top = max(float(np.nanmax(s)) for s, v in zip(shown, variables) if v != "exceedance") \
        if any(v != "exceedance" for v in variables) else 1.0
    figure, axes = plt.subplots(1, len(variables), figsize=(5.2 * len(variables), 4.6), squeeze=False,
                                sharex=True, sharey=True)
    for ax, name, values in zip(axes[0], variables, shown):
        ax.imshow(shade, cmap="gray", extent=extent, origin="upper", vmin=0, vmax=1)
        if name == "exceedance":
            d = float(dataset["threshold_m"][0])
            norm, label = Normalize(0, 1), f"P(D > {d:g} m) over the suite [-]"
            masked = np.ma.masked_less_equal(values, 0)
        else:
            norm, label = LogNorm(d_min_m, max(top, 10 * d_min_m)), _LABELS.get(name, f"{name} [m]")
            masked = np.ma.masked_less(np.ma.masked_invalid(values), d_min_m)
        image = ax.imshow(masked, cmap="magma_r", norm=norm, extent=extent, origin="upper", alpha=0.85)
        unstable = np.ma.masked_where(category != UNSTABLE, np.ones(category.shape))
        ax.imshow(unstable, cmap="gray_r", vmin=0, vmax=1, extent=extent, origin="upper")
        figure.colorbar(image, ax=ax, shrink=0.8, label=label)
        ax.set(xlabel="easting [m]", title=_LABELS.get(name, name).replace(" [m]", ""))
        ax.ticklabel_format(useOffset=False, style="plain")
        ax.tick_params(axis="x", labelrotation=30)
    axes[0][0].set_ylabel("northing [m]")
    counts = {name: int(np.count_nonzero(category == code)) for code, name in
              ((UNSTABLE, "statically unstable (black)"), (FLAT, "flat"), (NODATA, "nodata"))}
    figure.suptitle(title or "Newmark displacement; cells: " + ", ".join(f"{n} {k}" for k, n in counts.items()),
                    fontsize=10)
    figure.tight_layout()
    return figure
