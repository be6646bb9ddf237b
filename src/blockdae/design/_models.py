"""The analyses a design study runs, each a :class:`DesignModel`: the rigid block
(:func:`blockdae.newmark`), the flexible sliding mass (:func:`blockdae.flexible`), the
block on a plane (:class:`blockdae.PlanarBlock` through :func:`blockdae.simulate`), each
taking a batch of parameter sets on one record scaled to a target PGA in one call, and any
model of the contract (:class:`Simulated`)."""

import abc
import dataclasses
import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ..core import sensitivities, simulate
from ..core.contract import AbstractHybridModel, BatchedModel, DifferentiableModel
from ..excitation import BaseMotion, Record, UnitsWarning, pga_factor
from ..flexible_mass import FlexibleSlidingMass, displacement_sensitivities, flexible, prechecked_column, \
    with_zero_sample
from ..planar import PlanarBlock
from ..sliding import downslope, newmark

#: the smallest value of the design parameter tried (ky [g]; mu above |bias| [-])
PARAMETER_FLOOR = 1e-4

#: polarity -> how D is read from the two polarities: the record as given, inverted, or the larger
POLARITIES = ("normal", "inverse", "larger")


def _check_polarity(polarity):
    if polarity not in POLARITIES:
        raise ValueError(f"polarity={polarity!r} is unknown; choose one of {POLARITIES}")


def _read(polarity, normal, inverse):
    """D [m] of ``polarity`` from the arrays of each polarity run."""
    if polarity == "normal":
        return np.asarray(normal, dtype=float)
    if polarity == "inverse":
        return np.asarray(inverse, dtype=float)
    return np.maximum(normal, inverse)


def _engine_polarity(polarity):
    return "both" if polarity == "larger" else polarity


class DesignModel(abc.ABC):
    """What :func:`exceedance`, the inverses (:func:`ky_for_displacement`,
    :func:`ky_for_percentile`, :func:`mean_ky_for_probability`) and the app's design page
    ask of a model: its parameters with their units, the one the inverses solve for, and
    a batched forward map from parameter sets to the displacement of interest D [m].

    Class attributes: ``PARAMETERS`` (name -> unit, e.g. {"ky": "g", "height": "m"}),
    ``REQUIRED`` (the names a study must give), ``DESIGN`` (the parameter the inverses
    solve for: D must not rise as it rises, and be 0 from :meth:`sliding_limit` on),
    ``kind`` (the model's name in messages); optional ``MOTIONS`` (what a record may be:
    a :class:`blockdae.Record` by default), ``COLUMNS`` (name -> the table column, where
    not the name with its unit) and ``has_derivative`` (whether :meth:`displacements`
    gives dD/d``DESIGN``: the inverses then take Newton steps for one record).
    :meth:`gradient` gives dD/dp for each parameter p of :attr:`differentiable` (what
    :func:`back_analysis` runs on); by default that is ``DESIGN`` where ``has_derivative``.
    """

    PARAMETERS: dict
    REQUIRED: tuple
    DESIGN: str
    kind: str
    MOTIONS = (Record,)
    COLUMNS: dict = {}
    has_derivative = False

    @abc.abstractmethod
    def displacements(self, record, pga, values, derivative=False):
        """D [m] of ``record`` scaled to ``pga`` [g] (None: as given) for each parameter set
        of ``values`` (name -> an array of shape (n,) or a number), shape (n,); with
        ``derivative`` also dD/d``DESIGN`` [m per its unit], shape (n,) (only where
        ``has_derivative``)."""

    @abc.abstractmethod
    def sliding_limit(self, record, pga, values):
        """The value of ``DESIGN`` at and above which D = 0, per parameter set of
        ``values``, shape (n,): the inverses' upper bracket."""

    def floor(self, values):
        """The smallest value of ``DESIGN`` the inverses try, per parameter set."""
        return np.full(np.shape(values[self.DESIGN]), PARAMETER_FLOOR)

    @property
    def differentiable(self) -> tuple:
        """The parameters :meth:`gradient` differentiates D by: ``DESIGN`` where
        ``has_derivative``, else none."""
        return (self.DESIGN,) if self.has_derivative else ()

    def gradient(self, record, pga, values, names):
        """D [m] of ``record`` scaled to ``pga`` [g] (None: as given) for each parameter set
        of ``values`` (name -> an array of shape (n,) or a number), shape (n,), and dD/dp
        [m per unit of p] for each p of ``names`` (among :attr:`differentiable`), name ->
        shape (n,). By default dD/d``DESIGN`` from :meth:`displacements`."""
        self.check_differentiable(names)
        d, slope = self.displacements(record, pga, values, derivative=True)
        return d, {self.DESIGN: slope}

    def check_differentiable(self, names):
        """ValueError naming the model and the first of ``names`` :meth:`gradient` does
        not differentiate D by."""
        for name in names:
            if name not in self.differentiable:
                raise ValueError(f"the {self.kind} model gives no dD/d{name}: it differentiates D by "
                                 f"{list(self.differentiable) or 'no parameter'}")


def _sets(values):
    """(n, name -> an array of shape (n,)) of parameter sets given as arrays or numbers."""
    n = max(np.size(v) for v in values.values())
    return n, {name: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for name, v in values.items()}


def _scale(record, pga, g):
    """The factor [-] that scales ``record`` to ``pga`` [g] (1 for None)."""
    return 1.0 if pga is None else pga_factor(record.peak_acceleration, pga, g)


def _inverse_read(polarity, normal, inverse):
    """Per set, whether D of ``polarity`` is read from the inverse run, shape (n,)."""
    normal = np.asarray(normal, dtype=float)
    if polarity == "larger":
        return np.asarray(inverse, dtype=float) > normal
    return np.full(normal.shape, polarity == "inverse")


def _size_slopes(u, du):
    """d|u|/dp = u . du/dp / |u| [m per unit of p] (0 where u = 0: nothing moved) of
    final displacements ``u`` (n, d) and their derivatives ``du`` (n, d), shape (n,)."""
    size = np.linalg.norm(u, axis=-1)
    moved = size > 0
    return np.where(moved, np.sum(u * du, axis=-1) / np.where(moved, size, 1.0), 0.0)


@dataclasses.dataclass(frozen=True)
class Rigid(DesignModel):
    """Newmark's rigid block: D [m] downslope of a block of yield acceleration ky [g].

    Attributes:
        polarity: "normal" (the record as given), "inverse" (times -1) or "larger" (the
            larger D of the two).
        g: the value of one g [m/s²].
    """

    polarity: str = "normal"
    g: float = STANDARD_GRAVITY

    #: its parameters and their units
    PARAMETERS = {"ky": "g"}
    REQUIRED = ("ky",)
    #: the parameter the design inverses solve for
    DESIGN = "ky"
    kind = "rigid"
    has_derivative = True

    def __post_init__(self):
        _check_polarity(self.polarity)

    def displacements(self, record, pga, values, derivative=False):
        """D [m] (and dD/dky [m/g] with ``derivative``) of ``record`` scaled to ``pga``
        [g] (None: as given) for each ky of ``values["ky"]`` (shape (n,)).

        With ``derivative``, both come straight from the compiled exact engine, the
        record prepared once and kept (the last few records), dD/dky in closed form from
        the located sliding episodes (:mod:`blockdae.sliding`'s ``downslope``): tens of
        microseconds per ky, the inner loop of :func:`back_analysis` and of the
        inverses' Newton steps."""
        ky = np.asarray(values["ky"], dtype=float)
        if derivative:
            return self._with_derivative(record, pga, ky)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UnitsWarning)  # a sample at or above the peak slides nowhere: D = 0
            result = newmark(record, ky=ky, pga=pga, polarity=_engine_polarity(self.polarity), g=self.g)
        return _read(self.polarity, result.normal, result.inverse)

    def _with_derivative(self, record, pga, ky):
        """D [m] and dD/dky [m/g] at each ky [g] from :func:`blockdae.sliding.downslope`."""
        if not np.all(np.isfinite(ky) & (ky > 0)):
            bad = ky[~(np.isfinite(ky) & (ky > 0))].flat[0]
            raise ValueError(f"ky={float(bad)!r} must be a positive yield acceleration [g]")
        factor = 1.0 if pga is None else pga_factor(record.peak_acceleration, pga, self.g)
        runs = {name: downslope(record, ky.reshape(-1), sign * factor, self.g)
                for name, sign in (("normal", 1.0), ("inverse", -1.0)) if self.polarity in (name, "larger")}
        if self.polarity != "larger":
            d, slope = runs[self.polarity]
        else:
            (normal, normal_dky), (inverse, inverse_dky) = runs["normal"], runs["inverse"]
            d, slope = np.maximum(normal, inverse), np.where(normal >= inverse, normal_dky, inverse_dky)
        return d.reshape(ky.shape), slope.reshape(ky.shape)

    def sliding_limit(self, record, pga, values):
        """The ky [g] at and above which D = 0: the scaled record's peak [g]."""
        peak = record.peak_acceleration / self.g if pga is None else pga
        return np.full(np.shape(values["ky"]), float(peak))

    def floor(self, values):
        """The smallest ky [g] the inverses try, per parameter set."""
        return np.full(np.shape(values["ky"]), PARAMETER_FLOOR)


@dataclasses.dataclass(frozen=True)
class Flexible(DesignModel):
    """The flexible sliding mass of :func:`blockdae.flexible` (its parameters ky [g],
    height [m], vs [m/s], vr [m/s] and damping [-] batched).

    Attributes:
        method: "coupled" or "decoupled".
        equivalent_linear: run the equivalent-linear iteration (needs ``reference_strain``).
        reference_strain: gamma_ref, a fraction (e.g. 0.0005).
        polarity: "normal", "inverse" or "larger" (the larger D of the two).
        g: the value of one g [m/s²].
    """

    method: str = "coupled"
    equivalent_linear: bool = False
    reference_strain: float | None = None
    polarity: str = "normal"
    g: float = STANDARD_GRAVITY

    PARAMETERS = {"ky": "g", "height": "m", "vs": "m/s", "vr": "m/s", "damping": "-"}
    REQUIRED = ("ky", "height", "vs")
    DESIGN = "ky"
    kind = "flexible"

    def __post_init__(self):
        _check_polarity(self.polarity)
        if self.equivalent_linear and self.reference_strain is None:
            raise ValueError("equivalent_linear=True needs reference_strain (gamma_ref, a fraction, e.g. 0.0005)")

    def _run(self, record, pga, values):
        options = {name: values[name] for name in ("ky", "height", "vs", "vr", "damping") if name in values}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UnitsWarning)  # a sample at or above kmax slides nowhere: D = 0
            return flexible(record, method=self.method, equivalent_linear=self.equivalent_linear,
                            reference_strain=self.reference_strain, pga=pga, polarity=_engine_polarity(self.polarity),
                            g=self.g, **options)

    def displacements(self, record, pga, values, derivative=False):
        """D [m] of ``record`` scaled to ``pga`` [g] for each parameter set of ``values``
        (name -> an array of shape (n,) or a number); no derivative (``derivative``
        must be False: the inverses bracket on the compiled engine, faster than
        :meth:`gradient`)."""
        if derivative:
            raise ValueError("the flexible mass has no dD/dky here; root finding brackets instead")
        result = self._run(record, pga, values)
        return _read(self.polarity, result["normal_m"], result["inverse_m"])

    @property
    def differentiable(self) -> tuple:
        """ky [g], height [m], vs [m/s] (vr held) and damping [-]; none with the
        equivalent-linear iteration (its converged column has no derivative here)."""
        return () if self.equivalent_linear else ("ky", "height", "vs", "damping")

    def gradient(self, record, pga, values, names):
        """D [m] from the compiled engine, shape (n,), and dD/dp for p in ``names``
        (name -> shape (n,), [m per unit of p]) from
        :func:`blockdae.flexible_mass.displacement_sensitivities`: the JAX twin's
        variational equation and saltation jumps through the located events (exact to
        its tolerance, rtol 1e-10), one JAX run per sliding set (seconds each:
        benchmarks/back_analysis_models.py)."""
        self.check_differentiable(names)
        result = self._run(record, pga, values)
        d = _read(self.polarity, result["normal_m"], result["inverse_m"])
        inverse = _inverse_read(self.polarity, result["normal_m"], result["inverse_m"])
        n, sets = _sets(values)
        factor = _scale(record, pga, self.g)
        slopes = {name: np.zeros(n) for name in names}
        for i in np.flatnonzero(d > 0):  # D = 0: no slide, no change to first order
            one = {name: float(v[i]) for name, v in sets.items()}
            column = prechecked_column(**{k: one[k] for k in ("height", "vs", "vr", "damping") if k in one})
            mass = FlexibleSlidingMass(column, ky=one["ky"], method=self.method, g=self.g)
            motion = with_zero_sample(record.scaled(-factor if inverse[i] else factor))
            derivatives = displacement_sensitivities(mass, motion, record.duration + record.dt, wrt=tuple(names))
            for name in names:
                slopes[name][i] = derivatives[name]
        return d, slopes

    def sliding_limit(self, record, pga, values):
        """The ky [g] at and above which D = 0: the supremum over time of the
        no-sliding response's |HEA| [g] (``kmax_sup_g``) of each parameter set."""
        result = self._run(record, pga, values | {"ky": np.full(np.shape(values["ky"]), 1e-3)})
        return np.asarray(result["kmax_sup_g"], dtype=float)

    def floor(self, values):
        """The smallest ky [g] the inverses try, per parameter set."""
        return np.full(np.shape(values["ky"]), PARAMETER_FLOOR)


@dataclasses.dataclass(frozen=True)
class Planar(DesignModel):
    """The block on a plane (:class:`blockdae.PlanarBlock`) shaken by one horizontal
    component along x (a Record, scaled to its target PGA) or by a
    :class:`blockdae.BaseMotion` of Records (x, y and the vertical z, at its own
    amplitude), run by :func:`blockdae.simulate` on the compiled engine with final
    numbers only: a record's batch of parameter sets (in both polarities where asked) in
    one compiled call.

    D [m] is the permanent sliding distance: |u| = sqrt(u_x² + u_y²) at the end, once
    the block has come to rest. Its parameters (all [-]) are mu (the static friction
    coefficient, the plane's counterpart of ky: the block sticks while
    |a_h(t) - bias g| <= mu (g + a_z(t)), a_h the horizontal and a_z the vertical base
    acceleration), mu_kinetic (default mu), and bias_x, bias_y (a constant horizontal
    force on the block as a fraction of its weight, a slope's pull downhill: Elms's P
    along -x is ``bias_x=-P``; |bias| < mu_kinetic, or the block would never stop).
    The design inverses solve for mu; they need D to fall as mu rises, as it does with a
    bias (sliding one way); on a level plane slides to either side may cancel.

    Attributes:
        polarity: "normal" (the record as given), "inverse" (times -1) or "larger" (the
            larger D of the two).
        g: the value of one g [m/s²].
    """

    polarity: str = "normal"
    g: float = STANDARD_GRAVITY

    PARAMETERS = {"mu": "-", "mu_kinetic": "-", "bias_x": "-", "bias_y": "-"}
    REQUIRED = ("mu",)
    DESIGN = "mu"
    #: the table's columns: the names :class:`blockdae.PlanarBlock` gives them
    COLUMNS = {name: name for name in PARAMETERS}
    #: what a record of a study may be
    MOTIONS = (Record, BaseMotion)
    kind = "planar"

    def __post_init__(self):
        _check_polarity(self.polarity)

    def block(self, sets):
        """The :class:`blockdae.PlanarBlock` of the parameter sets ``sets`` (name -> an
        array of shape (n,))."""
        mu = sets["mu"]
        kinetic = sets.get("mu_kinetic", mu)
        bias = tuple(sets.get(name, np.zeros_like(mu)) for name in ("bias_x", "bias_y"))
        slow = np.flatnonzero(np.hypot(*bias) >= kinetic)
        if slow.size:
            i = slow[0]
            raise ValueError(f"mu_kinetic={float(kinetic[i])!r} must exceed |bias| = "
                             f"{float(np.hypot(bias[0][i], bias[1][i])):.6g} [-]: else the block, once sliding, "
                             "never stops")
        return PlanarBlock(mu=mu, mu_kinetic=sets.get("mu_kinetic"), bias=bias, g=self.g)

    def displacements(self, record, pga, values, derivative=False):
        """D [m], the final |u|, of ``record`` (a Record along x, or a BaseMotion) scaled
        to ``pga`` [g] (None: as given) for each parameter set of ``values`` (name -> an array of shape (n,) or a
        number); no derivative (``derivative`` must be False). Shape (n,)."""
        if derivative:
            raise ValueError("the block on a plane has no dD/dmu here; root finding brackets instead")
        return self._final(record, pga, values)[0]

    def _final(self, record, pga, values):
        """(D [m] shape (n,), the final u [m] of each polarity run shape (polarities, n, 2))."""
        _, sets = _sets(values)
        ensemble = simulate(self.block(sets), [record], pga=None if pga is None else [pga],
                            polarity=_engine_polarity(self.polarity), final_only=True, backend="compiled")
        u = np.asarray(ensemble.displacement, dtype=float)[0, 0]  # (polarities, sets, 2)
        d = np.hypot(u[..., 0], u[..., 1])
        return _read(self.polarity, d[0], d[-1]), u

    #: the parameters :meth:`gradient` differentiates D by
    differentiable = ("mu", "mu_kinetic", "bias_x", "bias_y")

    def gradient(self, record, pga, values, names):
        """D [m] from the compiled engine, shape (n,), and dD/dp [m] for p in ``names``
        (name -> shape (n,)): d|u|/dp = u . du/dp / |u|, du/dp from
        :func:`blockdae.sensitivities` (the JAX twin's variational equation and
        saltation jumps through the located events: exact to its tolerance, rtol 1e-10)."""
        self.check_differentiable(names)
        d, u = self._final(record, pga, values)
        runs = {False: u[0], True: u[-1]}  # the final u of the record as given, and inverted
        inverse = _inverse_read(self.polarity, *(np.hypot(*runs[flip].T) for flip in (False, True)))
        n, sets = _sets(values)
        follows = "mu_kinetic" not in sets  # the kinetic coefficient is mu: dD/dmu moves both
        sets = {"mu_kinetic": sets["mu"]} | sets  # given explicitly, each set's derivatives keep them apart
        wrt = tuple(dict.fromkeys((*names, "mu_kinetic") if follows and "mu" in names else names))
        factor = _scale(record, pga, self.g)
        slopes = {name: np.zeros(n) for name in names}
        for flip in (False, True):
            where = np.flatnonzero((inverse == flip) & (d > 0))  # D = 0: no slide, no change to first order
            if where.size:
                block = self.block({name: v[where] for name, v in sets.items()})
                du = {name: np.reshape(value, (where.size, 2)) for name, value in
                      sensitivities(block, record.scaled(-factor if flip else factor), None, wrt=wrt).items()}
                if follows and "mu" in names:
                    du["mu"] = du["mu"] + du["mu_kinetic"]
                for name in names:
                    slopes[name][where] = _size_slopes(runs[flip][where], du[name])
        return d, slopes

    def sliding_limit(self, record, pga, values):
        """The mu [-] at and above which D = 0: the largest friction demand
        |(s a_x - bias_x g, s a_y - bias_y g)| / (g + s a_z) over the record's samples, s
        the factor to ``pga`` [g] (and -s in the inverse polarity); the components are
        linear between samples, so the largest demand is at one. ValueError where the
        base falls faster than g (the block flies whatever mu is)."""
        s = 1.0 if pga is None else pga_factor(record.peak_acceleration, pga, self.g)
        if isinstance(record, BaseMotion):
            a_x, a_y, a_z = record.acceleration(record.breakpoints)[:, :, None]
        else:
            a_x, a_y, a_z = np.asarray(record.acceleration_samples, dtype=float)[:, None], 0.0, 0.0
        n = np.size(values["mu"])
        bias_x, bias_y = (np.broadcast_to(np.asarray(values.get(k, 0.0), dtype=float), (n,))
                          for k in ("bias_x", "bias_y"))
        signs = {"normal": (1.0,), "inverse": (-1.0,), "larger": (1.0, -1.0)}[self.polarity]
        demands = []
        for sign in signs:
            normal = self.g + sign * s * a_z
            if np.any(normal <= 0):
                raise ValueError(f"the base falls faster than g (its vertical acceleration down to "
                                 f"{float(np.min(normal)) - self.g:.4g} m/s²): the block flies whatever mu is")
            demands.append(np.max(np.hypot(sign * s * a_x - bias_x * self.g, sign * s * a_y - bias_y * self.g)
                                  / normal, axis=0))
        return np.max(demands, axis=0)

    def floor(self, values):
        """The smallest mu [-] the inverses try, per parameter set: above |bias| (and at
        least mu_kinetic where that is given)."""
        n = np.size(values["mu"])
        bias = np.hypot(*(np.broadcast_to(np.asarray(values.get(k, 0.0), dtype=float), (n,))
                          for k in ("bias_x", "bias_y")))
        kinetic = np.broadcast_to(np.asarray(values.get("mu_kinetic", 0.0), dtype=float), (n,))
        return np.maximum(bias + PARAMETER_FLOOR, kinetic)



@dataclasses.dataclass(frozen=True)
class Simulated(DesignModel):
    """Any model of the contract as a design model: D [m] is the size (Euclidean norm) of
    its displacement at the end of a :func:`blockdae.simulate` run (or its largest size
    over the run: ``measure="peak"``), the parameter sets
    given to the model's ``replace`` (a :class:`~blockdae.core.contract.BatchedModel`
    takes them all at once, as 1-D arrays; another model runs once per set). Where the
    model is a :class:`~blockdae.core.contract.DifferentiableModel` with ``design`` among
    its ``parameters()`` and D is the final displacement, dD/d``design`` comes from
    :func:`blockdae.sensitivities` (its JAX twin): ``has_derivative`` is then True and the
    inverses take Newton steps for one record.

    Attributes:
        model: the model at its nominal parameters (those not sampled keep their values).
        parameters: name -> unit of the parameters a study may give (names ``replace`` takes).
        design: the parameter the inverses solve for (D must not rise as it rises).
        polarity: "normal" (the record as given), "inverse" (times -1) or "larger".
        measure: "final" (|displacement| at the end) or "peak" (its largest over the run).
        t_end: final time [s]; None: until the model has come to rest after the record.
        backend: the backend (None: the model's default).
        sliding_limit_value: the value of ``design`` at and above which D = 0 (a number in
            its unit); None: found by doubling from the floor until D = 0 (at most 60 times).
        floor_value: the smallest value of ``design`` the inverses try (default 1e-4).
        required: the names a study must give (default: ``design``).
        kind: the model's name in messages (default: its class name).
    """

    model: AbstractHybridModel
    parameters: dict
    design: str
    polarity: str = "normal"
    measure: str = "final"
    t_end: float | None = None
    backend: str | None = None
    sliding_limit_value: float | None = None
    floor_value: float = PARAMETER_FLOOR
    required: tuple | None = None
    kind: str | None = None

    def __post_init__(self):
        _check_polarity(self.polarity)
        if self.measure not in ("final", "peak"):
            raise ValueError(f"measure={self.measure!r} is unknown; choose 'final' or 'peak'")
        if not isinstance(self.model, AbstractHybridModel):
            raise TypeError(f"model must be a model of the contract (an AbstractHybridModel), got "
                            f"{type(self.model).__name__}")
        if not isinstance(self.parameters, dict) or self.design not in self.parameters:
            raise ValueError(f"parameters must be a dict name -> unit holding design={self.design!r}, got "
                             f"{self.parameters!r}")
        if not hasattr(self.model, "replace"):
            raise TypeError(f"{type(self.model).__name__} needs replace(**changes) to take sampled parameters")
        object.__setattr__(self, "has_derivative", self.measure == "final"
                           and isinstance(self.model, DifferentiableModel) and self.design in self.model.parameters())
        object.__setattr__(self, "required", tuple(self.required or (self.design,)))
        object.__setattr__(self, "kind", self.kind or type(self.model).__name__)
        for name, value in (("PARAMETERS", dict(self.parameters)), ("REQUIRED", self.required),
                            ("DESIGN", self.design)):  # the contract's names
            object.__setattr__(self, name, value)

    def displacements(self, record, pga, values, derivative=False):
        """D [m], shape (n,), of ``record`` scaled to ``pga`` [g] for each parameter set of
        ``values``; with ``derivative`` (only where ``has_derivative``) also dD/d``design``
        [m per its unit], shape (n,)."""
        if derivative and not self.has_derivative:
            raise ValueError(f"{self.kind} has no dD/d{self.design} here (a DifferentiableModel with "
                             f"{self.design!r} among its parameters() and measure='final' has); root finding brackets "
                             f"instead")
        if derivative:
            d, slopes = self.gradient(record, pga, values, (self.design,))
            return d, slopes[self.design]
        return self._final(record, pga, values)[0]

    def _final(self, record, pga, values):
        """(D [m] shape (n,), what D is the size of per polarity run, shape (polarities, n, d))."""
        n, sets = _sets(values)
        run = dict(t_end=self.t_end, backend=self.backend, pga=None if pga is None else [pga],
                   polarity=_engine_polarity(self.polarity), final_only=True)
        if isinstance(self.model, BatchedModel):
            ends = self._ends(simulate(self.model.replace(**{k: v.copy() for k, v in sets.items()}), [record], **run))
        else:
            ends = np.concatenate([self._ends(simulate(self.model.replace(**{k: float(v[i]) for k, v in sets.items()}),
                                                       [record], **run)) for i in range(n)], axis=1)
        sizes = np.linalg.norm(ends, axis=-1)
        return _read(self.polarity, sizes[0], sizes[-1]), ends

    @property
    def differentiable(self) -> tuple:
        """Those of ``parameters`` among the model's ``parameters()`` where it is a
        :class:`~blockdae.core.contract.DifferentiableModel` and D is the final
        displacement; else none."""
        if self.measure != "final" or not isinstance(self.model, DifferentiableModel):
            return ()
        return tuple(name for name in self.parameters if name in self.model.parameters())

    def gradient(self, record, pga, values, names):
        """D [m], shape (n,), and dD/dp [m per unit of p] for p in ``names`` (name ->
        shape (n,)): d|u|/dp = u . du/dp / |u| (0 where u = 0: nothing moved), du/dp
        from :func:`blockdae.sensitivities` (the JAX twin), one parameter set at a time."""
        self.check_differentiable(names)
        d, ends = self._final(record, pga, values)
        n, sets = _sets(values)
        inverse = _inverse_read(self.polarity, *np.linalg.norm(ends[[0, -1]], axis=-1))
        factor = _scale(record, pga, getattr(self.model, "g", STANDARD_GRAVITY))
        slopes = {name: np.zeros(n) for name in names}
        for i in np.flatnonzero(d > 0):
            model = self.model.replace(**{k: float(v[i]) for k, v in sets.items()})
            du = sensitivities(model, record.scaled(-factor if inverse[i] else factor), self.t_end, wrt=tuple(names))
            u = ends[-1 if inverse[i] else 0, i]
            for name in names:
                slopes[name][i] = _size_slopes(u, np.reshape(du[name], u.shape))
        return d, slopes

    def sliding_limit(self, record, pga, values):
        """The given ``sliding_limit_value``, else per set the floor doubled until D = 0."""
        n = max(np.size(v) for v in values.values())
        if self.sliding_limit_value is not None:
            return np.full(n, float(self.sliding_limit_value))
        sets = {name: np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy() for name, v in values.items()}
        limit = np.maximum(np.asarray(self.floor(sets), dtype=float), PARAMETER_FLOOR)
        moving = np.ones(n, dtype=bool)
        for _ in range(60):
            where = np.flatnonzero(moving)
            d = self.displacements(record, pga, {k: v[where] for k, v in sets.items()} | {self.design: limit[where]})
            moving[where] = d > 0
            if not moving.any():
                return limit
            limit = np.where(moving, 2 * limit, limit)
        raise ValueError(f"{self.kind}: D stays above 0 up to {self.design} = {float(np.max(limit)):.6g} "
                         f"[{self.parameters[self.design]}]; give sliding_limit_value")

    def floor(self, values):
        return np.full(np.shape(values[self.design]), float(self.floor_value))

    def _ends(self, ensemble):
        """Of an ensemble of one motion at one scale, shape (polarities, sets, d): the
        displacement [m] at the end (``measure="final"``), or its largest size (d = 1)."""
        n_polarities, n_sets = ensemble.shape[2], max(1, int(np.prod(ensemble.model.batch_shape)))
        if self.measure == "peak":
            return np.asarray(ensemble.max_abs_displacement, dtype=float)[0, 0].reshape(n_polarities, n_sets, 1)
        u = np.asarray(ensemble.displacement, dtype=float)[0, 0]  # (polarities[, sets][, d])
        return u.reshape(n_polarities, n_sets, -1)
