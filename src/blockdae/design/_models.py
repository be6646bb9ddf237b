"""The analyses a design study runs: the rigid block (:func:`blockdae.newmark`), the
flexible sliding mass (:func:`blockdae.flexible`) and the block on a plane
(:class:`blockdae.PlanarBlock` through :func:`blockdae.simulate`), each taking a batch of
parameter sets on one record scaled to a target PGA in one call."""

import dataclasses
import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ..core import simulate
from ..excitation import BaseMotion, Record, UnitsWarning, pga_factor
from ..flexible_mass import flexible
from ..planar import PlanarBlock
from ..sliding import newmark

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


@dataclasses.dataclass(frozen=True)
class Rigid:
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

    def __post_init__(self):
        _check_polarity(self.polarity)

    def displacements(self, record, pga, values, derivative=False):
        """D [m] (and dD/dky [m/g] with ``derivative``) of ``record`` scaled to ``pga``
        [g] (None: as given) for each ky of ``values["ky"]`` (shape (n,))."""
        ky = np.asarray(values["ky"], dtype=float)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UnitsWarning)  # a sample at or above the peak slides nowhere: D = 0
            result = newmark(record, ky=ky, pga=pga, polarity=_engine_polarity(self.polarity), g=self.g,
                             derivative=derivative)
        d = _read(self.polarity, result.normal, result.inverse)
        if not derivative:
            return d
        if self.polarity == "larger":
            slope = np.where(result.normal >= result.inverse, result.normal_dky, result.inverse_dky)
        else:
            slope = result.normal_dky if self.polarity == "normal" else result.inverse_dky
        return d, np.asarray(slope, dtype=float)

    def sliding_limit(self, record, pga, values):
        """The ky [g] at and above which D = 0: the scaled record's peak [g]."""
        peak = record.peak_acceleration / self.g if pga is None else pga
        return np.full(np.shape(values["ky"]), float(peak))

    def floor(self, values):
        """The smallest ky [g] the inverses try, per parameter set."""
        return np.full(np.shape(values["ky"]), PARAMETER_FLOOR)


@dataclasses.dataclass(frozen=True)
class Flexible:
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
        must be False)."""
        if derivative:
            raise ValueError("the flexible mass has no dD/dky here; root finding brackets instead")
        result = self._run(record, pga, values)
        return _read(self.polarity, result["normal_m"], result["inverse_m"])

    def sliding_limit(self, record, pga, values):
        """The ky [g] at and above which D = 0: the supremum over time of the
        no-sliding response's |HEA| [g] (``kmax_sup_g``) of each parameter set."""
        result = self._run(record, pga, values | {"ky": np.full(np.shape(values["ky"]), 1e-3)})
        return np.asarray(result["kmax_sup_g"], dtype=float)

    def floor(self, values):
        """The smallest ky [g] the inverses try, per parameter set."""
        return np.full(np.shape(values["ky"]), PARAMETER_FLOOR)


@dataclasses.dataclass(frozen=True)
class Planar:
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
        n = max(np.size(v) for v in values.values())
        sets = {name: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for name, v in values.items()}
        ensemble = simulate(self.block(sets), [record], pga=None if pga is None else [pga],
                            polarity=_engine_polarity(self.polarity), final_only=True, backend="compiled")
        u = ensemble.displacement[0, 0]  # (polarities, sets, 2)
        d = np.hypot(u[..., 0], u[..., 1])
        return _read(self.polarity, d[0], d[-1])

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


MODELS = (Rigid, Flexible, Planar)
