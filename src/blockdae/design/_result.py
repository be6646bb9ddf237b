"""The result of a design study: the exceedance curve with its confidence band, the
probability of exceeding the threshold with its interval, each record's contribution and
the tidy table of every sample."""

import dataclasses

import numpy as np

from ..core import compact_repr, unit_suffix
from ._statistics import relative_standard_error, wilson

def column_name(parameter, model):
    """The table column of ``parameter`` of ``model``, its unit in the name (ky_g, vs_m_s,
    damping_ratio), or the model's own name for it (the plane's mu, bias_x: coefficients)."""
    own = getattr(model, "COLUMNS", {})
    if parameter in own:
        return own[parameter]
    return f"{parameter}_{unit_suffix(model.PARAMETERS[parameter])}"


@dataclasses.dataclass(frozen=True, eq=False)
class Exceedance:
    """The displacements of a design study and what they say.

    Attributes:
        table: one row per (run, record) (pandas): run, record, pga_g [g] (the target;
            nan: as given), the parameters with their units in the names (ky_g, height_m,
            vs_m_s, vr_m_s, damping_ratio; the plane's mu, mu_kinetic, bias_x, bias_y [-])
            and D_m, the displacement [m].
        threshold_m: the displacement of interest [m].
        confidence: the level of the intervals [-].
        sampling, seed: how the samples were drawn.
        converged: whether the stopping rule was met (True for a fixed number of runs).
        history: the estimates after each block of runs (pandas): runs, analyses,
            mean_D_m [m], rse [-], P_exceed [-], halfwidth [-] (of its interval).
    """

    table: object
    threshold_m: float
    confidence: float
    sampling: str
    seed: int
    converged: bool
    history: object

    def __repr__(self):
        low, high = self.probability_interval
        return compact_repr(self, f"{len(self.table)} analyses, P(D > {self.threshold_m:g} m) = "
                                  f"{self.probability:.4g} [{low:.4g}, {high:.4g}], mean D {self.mean_m:.4g} m")

    @property
    def displacements(self) -> np.ndarray:
        """D [m] of every sample, shape (runs, records)."""
        n_records = self.table["record"].nunique()
        return self.table["D_m"].to_numpy().reshape(-1, n_records)

    @property
    def mean_m(self) -> float:
        """The mean displacement [m]."""
        return relative_standard_error(self.displacements)[0]

    @property
    def rse(self) -> float:
        """The relative standard error of the mean displacement [-] (from the spread of
        the run means; for Latin hypercube and Sobol samples an upper bound)."""
        return relative_standard_error(self.displacements)[1]

    @property
    def probability(self) -> float:
        """P(D > threshold) [-]: the fraction of the samples above it."""
        return float(np.mean(self.table["D_m"].to_numpy() > self.threshold_m))

    @property
    def probability_interval(self) -> tuple[float, float]:
        """The Wilson score interval of :attr:`probability` at :attr:`confidence` [-]."""
        d = self.table["D_m"].to_numpy()
        low, high = wilson(np.count_nonzero(d > self.threshold_m), d.size, self.confidence)
        return float(low), float(high)

    def curve(self, displacements=None):
        """The exceedance curve P(D > d) with its confidence band (pandas: D_m [m],
        P_exceed, P_low, P_high [-]) at ``displacements`` [m] (default: 200 values
        spaced logarithmically from 1 mm to the largest D)."""
        import pandas as pd

        d = np.sort(self.table["D_m"].to_numpy())
        if displacements is None:
            top = max(float(d[-1]), 2e-3)
            displacements = np.geomspace(1e-3, top, 200)
        grid = np.asarray(displacements, dtype=float)
        counts = d.size - np.searchsorted(d, grid, side="right")
        low, high = wilson(counts, d.size, self.confidence)
        return pd.DataFrame({"D_m": grid, "P_exceed": counts / d.size, "P_low": low, "P_high": high})

    def contributions(self):
        """Each record's part (pandas, one row per record): samples, mean_D_m [m],
        P_exceed [-] (its own samples' fraction above the threshold) and share [-] (its
        part of all the samples above the threshold; they sum to 1 where any is)."""
        table = self.table.assign(above=self.table["D_m"] > self.threshold_m)
        grouped = table.groupby("record", sort=False)
        out = grouped.agg(samples=("D_m", "size"), mean_D_m=("D_m", "mean"), P_exceed=("above", "mean"),
                          above=("above", "sum")).reset_index()
        total = out["above"].sum()
        out["share"] = out["above"] / total if total else 0.0
        return out.drop(columns="above")

    def figure(self, *, label=None, title=None):
        """The exceedance curve P(D > d) with its confidence band and the threshold
        marked; a matplotlib Figure."""
        from ._figures import exceedance_figure

        return exceedance_figure({label or "samples": self}, title=title)

    def ky_figure(self, *, title=None):
        """D [m] against ky [g] (the plane's mu [-]) of every sample (a colour per
        record), the threshold marked; a matplotlib Figure."""
        from ._figures import ky_figure

        return ky_figure(self, title=title)
