"""The figures of a back-analysis: prior against posterior, the observations against the
posterior predictive D, and the posterior's pairs of parameters (matplotlib, imported on
first use)."""

import math

import numpy as np

from ._back_analysis_result import axis_label, prior_density, predictive_draws

#: the central interval drawn [-]
LEVEL = 0.90
_Z = 1.6448536269514722  # the standard normal's 95 % quantile: a 90 % central interval


def posterior_figure(result, *, title=None):
    """One panel per parameter: its prior density (dashed), its posterior density (a
    Gaussian kernel estimate over the draws, solid), the posterior's 90 % interval
    shaded and the maximum a posteriori (dotted) where the result holds it; densities
    per unit of the parameter. A matplotlib Figure."""
    import matplotlib.pyplot as plt
    from scipy import stats

    listed = result.inferred
    fig, axes = plt.subplots(1, len(listed), figsize=(5.4 * len(listed), 3.8), squeeze=False)
    for ax, (name, column, unit) in zip(axes[0], listed):
        draws = result.samples[column].to_numpy()
        prior = result.priors[name]
        ends = [draws.min(), draws.max(), float(prior.ppf(0.005)), float(prior.ppf(0.995))]
        x = np.linspace(min(ends), max(ends), 400)
        ax.plot(x, prior_density(prior, x), "--", color="0.45", label="prior")
        density = stats.gaussian_kde(draws)(x)
        ax.plot(x, density, color="C0", label=f"posterior ({result.method}, {len(draws)} draws)")
        low, high = np.quantile(draws, [(1 - LEVEL) / 2, (1 + LEVEL) / 2])
        inside = (x >= low) & (x <= high)
        in_unit = "" if unit == "-" else f" {unit}"
        ax.fill_between(x[inside], density[inside], color="C0", alpha=0.2, lw=0,
                        label=f"{LEVEL * 100:.0f} % interval {low:.4g}-{high:.4g}{in_unit}")
        best = result.map_values.get(name)
        if best is not None:
            ax.axvline(best, color="C3", ls=":", label=f"maximum a posteriori {best:.4g}{in_unit}")
        ax.set_xlabel(axis_label(name, unit))
        ax.set_ylabel("density" + (" [-]" if unit == "-" else f" [1/{unit}]"))
        ax.set_ylim(bottom=0)
        ax.legend(fontsize="small")
    n = len(result.observed())
    fig.suptitle(title or f"Prior and posterior, {n} observation{'s' if n > 1 else ''}")
    fig.tight_layout()
    return fig


def predictive_figure(result, *, scenarios=None, title=None):
    """Each observation (black: the measured D with its 90 % measurement interval,
    exp(± 1.645 sigma_ln); a triangle at a bound, pointing the way D lies, with the same
    interval) beside the posterior predictive D [m] of the model (blue: median and 90 %
    interval over the draws), and each of ``scenarios`` (label -> the arguments of the
    result's ``predict``: (record, pga_g [g] or None), and the slope for
    :class:`SlopesBackAnalysis`) predicted (orange). D on a log axis where every value drawn is above 0. A
    matplotlib Figure."""
    import matplotlib.pyplot as plt
    from matplotlib import ticker

    scenarios = dict(scenarios or {})
    observations = [obs for obs, _ in result.observed()]
    d = predictive_draws(result)
    columns = [d[..., i].reshape(-1) for i in range(len(observations))]
    columns += [result.predict(*arguments)["D_m"].to_numpy() for arguments in scenarios.values()]
    q_low, q50, q_high = np.quantile(np.stack(columns, axis=1), [(1 - LEVEL) / 2, 0.5, (1 + LEVEL) / 2], axis=0)
    fig, ax = plt.subplots(figsize=(max(5.0, 1.3 * len(columns) + 2.5) + 3.0, 4.2))
    n = len(observations)
    position = np.arange(len(columns), dtype=float)
    ax.errorbar(position[:n] - 0.12, q50[:n], yerr=[q50[:n] - q_low[:n], q_high[:n] - q50[:n]], fmt="o",
                color="C0", capsize=4, label=f"posterior predictive D: median, {LEVEL * 100:.0f} % interval")
    if scenarios:
        ax.errorbar(position[n:], q50[n:], yerr=[q50[n:] - q_low[n:], q_high[n:] - q50[n:]], fmt="s", color="C1",
                    capsize=4, label=f"predicted D: median, {LEVEL * 100:.0f} % interval")
    markers = {"displacement": ("o", "observed D"), "more_than": ("^", "observed: D more than"),
               "less_than": ("v", "observed: D less than")}
    drawn = set()
    for x, obs in zip(position[:n] + 0.12, observations):
        marker, label = markers[obs.kind]
        spread = math.exp(_Z * obs.sigma_ln)
        ax.errorbar([x], [obs.value_m], yerr=[[obs.value_m * (1 - 1 / spread)], [obs.value_m * (spread - 1)]],
                    fmt=marker, color="k", mfc="k" if obs.kind == "displacement" else "w", capsize=4,
                    label=None if obs.kind in drawn else f"{label} ({LEVEL * 100:.0f} % measurement interval)")
        drawn.add(obs.kind)
    values = np.concatenate([q_low, [o.value_m / math.exp(_Z * o.sigma_ln) for o in observations]])
    if np.all(values > 0):
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(ticker.FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(ticker.FormatStrFormatter("%g"))
    names = [f"{o.name}\n{_scaling(o.pga_g)}" for o in observations]
    names += [f"{label}\n{_scaling(arguments[1])}" for label, arguments in scenarios.items()]
    ax.set_xticks(position, names, fontsize="small")
    ax.set_xlim(-0.6, len(columns) - 0.4)
    ax.set_ylabel("displacement D [m]")
    ax.set_xlabel("observation" + (" | scenario" if scenarios else ""))
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title(title or "Observed and predicted displacements")
    fig.tight_layout()
    return fig


def _scaling(pga_g):
    """How a record was scaled, for a tick label."""
    return "as recorded" if pga_g is None else f"PGA {pga_g:g} g"


def pair_figure(result, *, title=None):
    """The posterior's draws of each pair of parameters (below the diagonal) and each
    one's histogram (on it), axes with their units; a matplotlib Figure. A posterior of
    one parameter has no pairs: a ValueError says so."""
    import matplotlib.pyplot as plt

    listed = result.inferred
    if len(listed) < 2:
        raise ValueError(f"a pair figure needs two or more parameters; this posterior has one ({listed[0][0]}): "
                         "draw its density with posterior_figure()")
    k = len(listed)
    fig, axes = plt.subplots(k, k, figsize=(2.6 * k + 1, 2.6 * k + 0.5), squeeze=False)
    for i, (name_i, column_i, unit_i) in enumerate(listed):
        for j, (name_j, column_j, unit_j) in enumerate(listed):
            ax = axes[i, j]
            if j > i:
                ax.set_visible(False)
                continue
            if i == j:
                ax.hist(result.samples[column_i], bins=40, color="C0", alpha=0.7)
                ax.set_yticks([])
            else:
                ax.scatter(result.samples[column_j], result.samples[column_i], s=3, alpha=0.3, color="C0")
                if j == 0:
                    ax.set_ylabel(axis_label(name_i, unit_i))
            if i == k - 1:
                ax.set_xlabel(axis_label(name_j, unit_j))
    fig.suptitle(title or f"Posterior draws ({result.method}, {len(result.samples)})")
    fig.tight_layout()
    return fig
