"""The yield acceleration a design needs: per record, the ky at which D equals an
allowable displacement; over a record set, the ky whose p-th percentile of D equals it;
under uncertainty, the mean ky (same spread) that brings P(D > allowable) to a target.
For the block on a plane the same inverses solve for the friction coefficient mu.

D falls as ky (mu) rises, to 0 at the value above which nothing slides (the scaled
record's peak for the rigid block, the supremum of the no-sliding |HEA| for the flexible
mass, the largest friction demand for the plane): every root is bracketed. For one
record the rigid block steps by Newton on its exact dD/dky (:func:`blockdae.newmark`'s
``derivative=True``); otherwise the steps are the Illinois variant of regula falsi (a
batch of roots at once) or Brent's method (a percentile); a step that leaves the bracket
bisects it."""

import dataclasses

import numpy as np
from ._models import PARAMETER_FLOOR as KY_FLOOR
from ._records import record_set
from ._result import column_name
from ._study import Draws

#: the relative tolerance of D at the root [-]
D_TOLERANCE = 1e-10


def _check_allowable(allowable):
    if not (isinstance(allowable, (int, float)) and not isinstance(allowable, bool) and np.isfinite(allowable)
            and allowable > 0):
        raise ValueError(f"allowable={allowable!r} must be a displacement > 0 [m]")
    return float(allowable)


def critical_ky(model, record, pga, values, allowable, newton=False, max_iterations=100):
    """The ky [g] (the model's design parameter: mu [-] on a plane) at which D of each
    parameter set of ``values`` (name -> array (n,) or a number; ky, if there, ignored)
    equals ``allowable`` [m] on ``record`` scaled to ``pga`` [g]; 0 where D stays below
    it even at the model's floor (ky = :data:`KY_FLOOR`). Shape (n,).
    ``newton``: Newton steps on the exact dD/dky (the rigid block only; its derivative
    kernel compiles once per batch shape, so it suits one parameter set, not many)."""
    allowable = _check_allowable(allowable)
    key = model.DESIGN
    n = max([np.size(v) for name, v in values.items() if name != key] + [1])
    others = {name: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for name, v in values.items() if name != key}
    lo = np.asarray(model.floor(others | {key: np.full(n, KY_FLOOR)}), dtype=float)
    hi = np.asarray(model.sliding_limit(record, pga, others | {key: lo}), dtype=float)

    def excess(ky, where):
        chosen = {name: v[where] for name, v in others.items()} | {key: ky}
        if newton:
            d, slope = model.displacements(record, pga, chosen, derivative=True)
            return d - allowable, slope
        return model.displacements(record, pga, chosen) - allowable, None

    f_lo, _ = excess(lo, np.arange(n))
    result = np.zeros(n)
    active = np.flatnonzero((f_lo > 0) & (hi > lo))
    if not active.size:
        return result
    f_lo, f_hi, lo, hi = f_lo[active], np.full(active.size, -allowable), lo[active], hi[active]
    replaced = np.zeros(active.size, dtype=int)  # the end the last step replaced: -1 lo, 1 hi
    x = 0.5 * (lo + hi)
    f, slope = excess(x, active)
    for _ in range(max_iterations):
        done = (np.abs(f) <= D_TOLERANCE * allowable) | (hi - lo <= 4 * np.finfo(float).eps * hi)
        if done.all():
            break
        above = f > 0
        lo, f_lo = np.where(above, x, lo), np.where(above, f, f_lo)
        hi, f_hi = np.where(above, hi, x), np.where(above, f_hi, f)
        if newton:
            with np.errstate(divide="ignore", invalid="ignore"):
                step = x - f / slope
        else:  # Illinois: the end kept a second time in a row has its value halved
            f_hi = np.where(above & (replaced == -1), 0.5 * f_hi, f_hi)
            f_lo = np.where(~above & (replaced == 1), 0.5 * f_lo, f_lo)
            step = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        replaced = np.where(above, -1, 1)
        inside = np.isfinite(step) & (step > lo) & (step < hi)
        x = np.where(done, x, np.where(inside, step, 0.5 * (lo + hi)))
        pending = np.flatnonzero(~done)
        f_new, slope_new = excess(x[pending], active[pending])
        f[pending] = f_new
        if newton:
            slope[pending] = slope_new
    else:
        raise ValueError(f"the {key} for D = {allowable!r} m did not converge in {max_iterations} iterations")
    result[active] = x
    return result


def ky_for_displacement(record, model, parameters, allowable, *, pga=None):
    """The yield acceleration ky [g] at which ``record`` (scaled to ``pga`` [g]) moves
    ``model`` by exactly ``allowable`` [m]; for :class:`Planar` the friction coefficient
    mu [-].

    Args:
        record: a Record (ground acceleration along the slope [m/s²]); for
            :class:`Planar` also a BaseMotion of Records (``pga`` None).
        model: :class:`Rigid`, :class:`Flexible`, :class:`Planar`, :class:`Simulated` (any model) or
            a :class:`DesignModel` of your own.
        parameters: the model's other parameters (name -> number): flexible height [m],
            vs [m/s], vr [m/s], damping [-]; the plane's mu_kinetic, bias_x, bias_y [-];
            nothing for the rigid block.
        allowable: the allowable displacement [m].
        pga: target PGA [g] (None: the record as given).

    Raises:
        ValueError: D stays below ``allowable`` even at ky = 1e-4 g (no ky is needed;
            on a plane, at mu = |bias| + 1e-4).
    """
    (_, record, pga), = record_set(record, pga, model)
    ky = critical_ky(model, record, pga, dict(parameters), allowable, newton=model.has_derivative)[0]
    if ky == 0:
        raise ValueError(f"D stays below allowable={allowable!r} m even at {_floor_words(model, parameters)}: "
                         f"no {model.DESIGN} is needed")
    return float(ky)


def _floor_words(model, parameters):
    """'ky = 0.0001 g' or 'mu = 0.0301 [-]': the lowest value of the design parameter the inverses try."""
    key = model.DESIGN
    floor = float(model.floor({name: float(v) for name, v in parameters.items()} | {key: np.array([KY_FLOOR])})[0])
    unit = model.PARAMETERS[key]
    return f"{key} = {floor:.6g} {unit if unit == 'g' else f'[{unit}]'}"


def ky_for_percentile(records, model, parameters, allowable, *, percentile=50.0, pga=None):
    """The ky [g] (mu [-] for :class:`Planar`) at which the ``percentile``-th percentile
    of D over ``records`` (linear interpolation between them, numpy's default) equals
    ``allowable`` [m]. Arguments as for :func:`ky_for_displacement`; ``records`` a
    sequence or dict name -> Record, ``pga`` a number or a dict name -> number."""
    allowable = _check_allowable(allowable)
    if not 0 <= percentile <= 100:
        raise ValueError(f"percentile={percentile!r} must lie in [0, 100]")
    entries = record_set(records, pga, model)
    key = model.DESIGN
    fixed = {name: float(v) for name, v in parameters.items() if name != key}

    def excess(ky):
        d = [model.displacements(record, target, fixed | {key: np.array([ky])})[0] for _, record, target in entries]
        return float(np.percentile(d, percentile)) - allowable

    lo = float(model.floor(fixed | {key: np.array([KY_FLOOR])})[0])
    hi = max(float(model.sliding_limit(record, target, fixed | {key: np.array([lo])})[0])
             for _, record, target in entries)
    if excess(lo) <= 0:
        raise ValueError(f"the {percentile}th percentile of D stays below allowable={allowable!r} m even at "
                         f"{_floor_words(model, fixed)}: no {key} is needed")
    from scipy import optimize  # on first use: slow to import

    return optimize.brentq(excess, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)


@dataclasses.dataclass(frozen=True, eq=False)
class MeanKyDesign:
    """The mean ky a design needs under uncertainty (the mean mu for :class:`Planar`).

    Attributes:
        mean: the smallest mean of the design parameter (ky [g]; mu [-] on a plane; the
            distribution scaled, its cov kept) for which P(D > allowable) over the
            samples is at most ``target``.
        parameter: which parameter that is: "ky" or "mu".
        allowable_m: the allowable displacement [m]; target: the probability [-].
        table: one row per (run, record) (pandas): the samples at the distribution's
            own mean (ky_g or mu and the other parameters, units in the names),
            ky_ratio (mu_ratio: the sample over the mean [-], common to every mean: the
            common random numbers) and critical_mean_ky_g [g] (critical_mean_mu [-]),
            the mean above which that sample stays within the allowable.
    """

    mean: float
    parameter: str
    allowable_m: float
    target: float
    table: object

    @property
    def mean_ky_g(self) -> float:
        """The mean ky [g] (:attr:`mean` of a design over ky)."""
        if self.parameter != "ky":
            raise AttributeError(f"this design is over {self.parameter}, not ky: read .mean")
        return self.mean

    def probability(self, mean):
        """P(D > allowable) [-] over the same samples at a mean ky [g] (mu [-])."""
        return float(np.mean(self.critical_means > mean))

    @property
    def critical_means(self) -> np.ndarray:
        """Each sample's critical mean (the table's last column) [g] or [-], shape (samples,)."""
        return self.table[self.table.columns[-1]].to_numpy()


def mean_ky_for_probability(records, model, parameters, allowable, target, *, pga=None, runs=64,
                            sampling="sobol", seed=0, correlation=None) -> MeanKyDesign:
    """The mean ky [g] (its distribution scaled: same cov) that brings P(D > allowable)
    to at most ``target`` over ``records``; for :class:`Planar` the mean mu [-].

    The samples are drawn once (``runs`` per record, as :func:`exceedance` draws them) and
    kept for every mean (common random numbers): at mean m each sample's ky is m times its
    ratio to the distribution's mean, so each sample exceeds the allowable exactly below
    its own critical mean (its ky for D = allowable, found as :func:`ky_for_displacement`
    finds it, over its ratio), and P(m) is the fraction of the critical means above m.
    The answer is the smallest m with P(m) <= target: a sample's critical mean, at which
    that sample moves exactly ``allowable`` (0 where the target holds at any mean: too few
    samples exceed the allowable even at ky = 1e-4 g). The arguments not listed below are
    those of :func:`exceedance`.

    Args:
        parameters: name -> number or distribution as for :func:`exceedance`; ``ky``
            (the plane's ``mu``) a distribution (its mean scaled).
        target: the probability of exceedance allowed, in (0, 1).
        runs: samples per record (a power of 2 for "sobol").
    """
    allowable = _check_allowable(allowable)
    if not 0 < target < 1:
        raise ValueError(f"target={target!r} must be a probability in (0, 1)")
    if not (isinstance(runs, int) and runs >= 2) or (sampling == "sobol" and runs & (runs - 1)):
        raise ValueError(f"runs={runs!r} must be an integer >= 2 (a power of 2 for sampling='sobol', e.g. 64)")
    entries = record_set(records, pga, model)
    draws = Draws(model, parameters, len(entries), sampling, seed, correlation, runs)
    key = model.DESIGN
    if key not in draws.uncertain:
        raise ValueError(f"parameters[{key!r}] must be a distribution (its mean is what the design finds)")
    base_mean = float(draws.uncertain[key].mean)
    frames = []
    for i, (name, record, target_pga) in enumerate(entries):
        values = draws.block(i, runs)
        critical = critical_ky(model, record, target_pga, values, allowable)
        ratio = values[key] / base_mean
        frames.append(_frame(name, target_pga, model, values, ratio, critical / ratio))
    import pandas as pd

    table = pd.concat(frames, ignore_index=True)
    means = np.sort(table[table.columns[-1]].to_numpy())[::-1]  # the critical means, largest first
    allowed = int(np.floor(target * means.size + 1e-9))  # samples that may exceed
    return MeanKyDesign(mean=float(means[allowed]), parameter=key, allowable_m=allowable, target=target, table=table)


def _frame(name, pga, model, values, ratio, critical_mean):
    """One record's rows of a :class:`MeanKyDesign` table, the critical means last."""
    import pandas as pd

    key = model.DESIGN
    columns = {"run": np.arange(ratio.size), "record": name, "pga_g": np.nan if pga is None else pga}
    columns |= {column_name(p, model): values[p] for p in model.PARAMETERS if p in values}
    return pd.DataFrame(columns | {f"{key}_ratio": ratio, f"critical_mean_{column_name(key, model)}": critical_mean})
