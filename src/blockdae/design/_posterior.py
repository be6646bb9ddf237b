"""What every back-analysis result shares: its summary, its predictive table, ArviZ's
``InferenceData`` and its figures, over every parameter it inferred."""

import numpy as np
import pandas as pd

from . import _back_analysis_figures as figures
from ._back_analysis_result import inference_data


class Posterior:
    """The posterior draws of one or several parameters given observed displacements, as
    a table and as ArviZ's ``InferenceData``, with its figures. A result provides:

    - ``samples`` (a table: ``chain``, ``draw``, a column per parameter),
      ``method``, ``priors`` (parameter name -> distribution), ``sample_stats`` (NUTS's
      statistics per draw, a table; empty for the Laplace approximation);
    - ``inferred``: (name, column, unit) of each parameter inferred;
    - ``observed()``: (observation, the arguments of ``predict`` that give its D) of each
      observation, under a name unique among them;
    - ``predict(*arguments)``: a table with the model's D [m] (``D_m``) at each draw;
    - ``map_values``: parameter name -> its maximum a posteriori, where computed."""

    map_values = {}

    def summarised(self):
        """(label, column, unit) of each row of :meth:`summary`: the parameters inferred."""
        return self.inferred

    def summary(self) -> pd.DataFrame:
        """Each parameter's mean, standard deviation, median and 90 % interval, one row
        each (``parameter``, ``unit``, ``mean``, ``sd``, ``median``, ``q05``, ``q95``: in
        its unit)."""
        rows = []
        for label, column, unit in self.summarised():
            value = self.samples[column].to_numpy()
            q05, q50, q95 = np.quantile(value, [0.05, 0.5, 0.95])
            rows.append({"parameter": label, "unit": unit, "mean": value.mean(), "sd": value.std(ddof=1),
                         "median": q50, "q05": q05, "q95": q95})
        return pd.DataFrame(rows)

    def predictive(self) -> pd.DataFrame:
        """Each observation beside its posterior predictive D [m] (median and 90 %
        interval of the model's D over the posterior draws): ``observation``, ``kind``,
        ``observed_m``, ``median_D_m``, ``q05_D_m``, ``q95_D_m``."""
        rows = []
        for obs, arguments in self.observed():
            q05, q50, q95 = np.quantile(self.predict(*arguments)["D_m"].to_numpy(), [0.05, 0.5, 0.95])
            rows.append({"observation": obs.name, "kind": obs.kind, "observed_m": obs.value_m,
                         "median_D_m": q50, "q05_D_m": q05, "q95_D_m": q95})
        return pd.DataFrame(rows)

    def to_inference_data(self, *, seed=0):
        """The result as ArviZ's ``InferenceData``; each variable's unit in its
        ``attrs["units"]``. Groups: ``posterior`` (each parameter by name, e.g. ``ky``, shape
        (chain, draw)); ``sample_stats`` (NUTS's ``diverging``, ``acceptance_rate``,
        ``n_steps``, ``step_size``, ``energy``, ``lp`` of each draw; none for the Laplace
        approximation); ``posterior_predictive`` (``D``: the model's D [m] at each draw for
        each observation; ``D_measured``: D with its log-normal measurement error, drawn
        with ``seed``); ``observed_data`` (``D_measured``: the value or bound [m], each
        observation's ``kind`` and ``sigma_ln`` as coordinates); ``log_likelihood``
        (``D_measured``: ln of the normal density of ln D_observed, or ln P of the bound,
        per draw and observation); ``prior`` (each parameter drawn from its prior, as many
        draws as the posterior, with ``seed``). Needs ArviZ (the ``inference`` extra)."""
        return inference_data(self, seed=seed)

    def posterior_figure(self, *, title=None):
        """Each parameter's prior and posterior densities, the maximum a posteriori (where
        computed) and the 90 % interval marked; a matplotlib Figure."""
        return figures.posterior_figure(self, title=title)

    def predictive_figure(self, *, scenarios=None, title=None):
        """Each observation (with its measurement error, or its bound) beside the posterior
        predictive D [m], and the D predicted under each of ``scenarios`` (label -> the
        arguments of :meth:`predict`: (record, pga_g [g])); a matplotlib Figure."""
        return figures.predictive_figure(self, scenarios=scenarios, title=title)

    def pair_figure(self, *, title=None):
        """The posterior draws of each pair of parameters (two or more); a matplotlib Figure."""
        return figures.pair_figure(self, title=title)
