"""``blockdae.design.exceedance``: the displacement of a slope with uncertain properties
over a record set, sampled run after run until the estimate is precise enough."""

import numpy as np

from ._checkpoint import Checkpoint, manifest
from ._records import record_set
from ._result import Exceedance, column_name
from ._sampling import RecordSampler, check_sampling, correlation_matrix, split_parameters, to_parameters
from ._statistics import relative_standard_error, wilson


class Draws:
    """The parameter sets of a study, drawn per (run, record): a sampler per record,
    seeded from ``seed`` (a NumPy SeedSequence spawned per record), so that a study is
    reproduced by its seed."""

    def __init__(self, model, parameters, n_records, sampling, seed, correlation, runs_per_block):
        check_sampling(sampling, runs_per_block)
        self.fixed, self.uncertain = split_parameters(parameters, model)
        names = list(self.uncertain)
        self.cholesky = correlation_matrix(correlation, names)
        children = np.random.SeedSequence(seed).spawn(n_records)
        self.samplers = [RecordSampler(sampling, max(len(names), 1), child) for child in children]

    def block(self, record_index, n):
        """name -> values (shape (n,)) of the next ``n`` runs of record ``record_index``."""
        uniforms = self.samplers[record_index].uniforms(n)
        drawn = to_parameters(uniforms[:, :len(self.uncertain)], self.uncertain, self.cholesky)
        return {name: np.full(n, value) for name, value in self.fixed.items()} | drawn


def exceedance(records, model, parameters, *, pga=None, threshold, sampling="sobol", seed=0, correlation=None,
               rse=0.05, halfwidth=None, confidence=0.95, runs=None, runs_per_block=16, max_runs=4096,
               checkpoint=None, executor=None) -> Exceedance:
    """The probability that the displacement D exceeds ``threshold`` over a record set,
    for a slope whose parameters are uncertain.

    Each run draws one parameter set per record (each record scaled to its target PGA);
    runs go in blocks of ``runs_per_block`` (each record's block one batched engine
    call), and after each block the stopping rule is checked.

    Args:
        records: a Record, a sequence or a dict name -> Record (ground acceleration along
            the slope [m/s²]); for :class:`Planar` also BaseMotions of Records (pga None).
        model: :class:`Rigid`, :class:`Flexible`, :class:`Planar`, :class:`Simulated` (any model) or
            a :class:`DesignModel` of your own.
        parameters: name -> a number or a distribution (:class:`LogNormal`,
            :class:`Normal`, :class:`Uniform`, :class:`Truncated`) for the model's
            parameters (rigid: ky [g]; flexible: ky [g], height [m], vs [m/s], vr [m/s],
            damping [-]; planar: mu, mu_kinetic, bias_x, bias_y [-]).
        pga: target PGA [g]: a number for every record, a dict name -> number, or None
            (the records as given).
        threshold: the displacement of interest [m] (e.g. 0.25).
        sampling: "sobol" (scrambled Sobol; runs_per_block a power of 2), "lhs" (Latin
            hypercube, one design per block) or "mc" (Monte Carlo).
        seed: the seed of the whole study (an integer): the same seed draws the same samples.
        correlation: {(name, name): rho} between uncertain parameters (the correlation of
            their normal scores: a Gaussian copula); None: independent.
        rse: stop once the relative standard error of the mean D is at most this [-]
            (None: not a criterion).
        halfwidth: stop once the half-width of the ``confidence`` interval of
            P(D > threshold) is at most this [-] (None: not a criterion).
        confidence: the level of the intervals [-].
        runs: a fixed number of runs instead of a stopping rule (rse and halfwidth then unused).
        runs_per_block: runs between checks of the stopping rule.
        max_runs: the most runs before the study stops unconverged (``converged`` False).
        checkpoint: a folder where each finished block is saved as it completes; a rerun
            of the same study with it resumes (the result bit-identical to an
            uninterrupted run's); a folder of another study is refused (ValueError).
        executor: None (run here, on every core), a ``dask.distributed.Client`` or a
            ``concurrent.futures.Executor``: each record's block is submitted to it as a
            task (the stopping rule is checked here after each block).

    Returns:
        An :class:`Exceedance`.
    """
    threshold = _positive("threshold", threshold, "m")
    entries = record_set(records, pga, model)
    if runs is None and rse is None and halfwidth is None:
        raise ValueError("give a stopping rule (rse and/or halfwidth) or a fixed number of runs")
    if runs is not None and not (isinstance(runs, int) and runs >= 2):
        raise ValueError(f"runs={runs!r} must be an integer >= 2")
    if not (isinstance(max_runs, int) and max_runs >= runs_per_block):
        raise ValueError(f"max_runs={max_runs!r} must be an integer >= runs_per_block={runs_per_block!r}")
    draws = Draws(model, parameters, len(entries), sampling, seed, correlation, runs_per_block)
    saved = None if checkpoint is None else Checkpoint(checkpoint, manifest(entries, model, parameters, sampling, seed,
                                                                             correlation, runs_per_block))
    limit = runs if runs is not None else max_runs
    tables, history, done, converged = [], [], 0, runs is not None
    everything = np.empty((0, len(entries)))
    while done < limit:
        n = min(runs_per_block, limit - done)
        values = [draws.block(i, n) for i in range(len(entries))]
        table = None if saved is None else saved.load(len(tables))
        if table is None:
            d = np.stack(_displacements(model, entries, values, executor), axis=1)
            table = _block_table(entries, model, values, d, done)
            if saved is not None:
                saved.save(len(tables), table)
        else:
            _check_saved(table, _block_table(entries, model, values, np.full((n, len(entries)), np.nan), done),
                         saved.path(len(tables)))
        tables.append(table)
        done += n
        everything = np.concatenate([everything, table["D_m"].to_numpy().reshape(n, len(entries))])
        mean, error = relative_standard_error(everything)
        exceed = int(np.count_nonzero(everything > threshold))
        low, high = wilson(exceed, everything.size, confidence)
        history.append({"runs": done, "analyses": everything.size, "mean_D_m": mean, "rse": error,
                        "P_exceed": exceed / everything.size, "halfwidth": float(high - low) / 2})
        precise = (rse is None or error <= rse) and (halfwidth is None or history[-1]["halfwidth"] <= halfwidth)
        if runs is None and precise:
            converged = True
            break
    import pandas as pd

    return Exceedance(table=pd.concat(tables, ignore_index=True), threshold_m=threshold, confidence=confidence,
                      sampling=sampling, seed=seed, converged=converged, history=pd.DataFrame(history))


def _displacements(model, entries, values, executor):
    """D [m] of each record's block of parameter sets ``values``, here or on ``executor``."""
    if executor is None:
        return [model.displacements(record, target, v) for (_, record, target), v in zip(entries, values)]
    futures = [executor.submit(model.displacements, record, target, v)
               for (_, record, target), v in zip(entries, values)]
    return [future.result() for future in futures]


def _block_table(entries, model, values, d, start):
    """The tidy table of one block (runs ``start`` on, ``d`` of shape (runs, records)):
    one row per (run, record), by run, the records in their order within each."""
    import pandas as pd

    frames = []
    for i, (name, record, target) in enumerate(entries):
        columns = {"run": np.arange(start, start + d.shape[0]), "record": name,
                   "pga_g": np.nan if target is None else target}
        columns |= {column_name(p, model): values[i][p] for p in model.PARAMETERS if p in values[i]}
        frames.append(pd.DataFrame(columns | {"D_m": d[:, i]}))
    return pd.concat(frames, ignore_index=True).sort_values("run", kind="stable", ignore_index=True)


def _check_saved(saved, drawn, path):
    """ValueError naming ``path`` unless the saved block holds the parameter sets drawn now."""
    columns = [c for c in drawn.columns if c != "D_m"]
    same = list(saved.columns) == list(drawn.columns) and len(saved) == len(drawn) and all(
        _same(saved[c].to_numpy(), drawn[c].to_numpy()) for c in columns)
    if not same:
        raise ValueError(f"{path}: its samples are not those this study draws (another version, or an edited file): "
                         "delete the file to run the block again")


def _same(a, b):
    """Whether two columns hold the same values (numbers to the last bit, nan equal to nan)."""
    if a.dtype.kind in "fiu" and b.dtype.kind in "fiu":
        return np.array_equal(a.astype(float), b.astype(float), equal_nan=True)
    return a.tolist() == b.tolist()


def _positive(field, value, unit):
    if not (isinstance(value, (int, float)) and not isinstance(value, bool) and np.isfinite(value) and value > 0):
        raise ValueError(f"{field}={value!r} must be a positive number [{unit}]")
    return float(value)
