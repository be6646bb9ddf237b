"""The analyses a design study runs: the rigid block (:func:`blockdae.newmark`) and the
flexible sliding mass (:func:`blockdae.flexible`), each taking a batch of parameter sets
on one record scaled to a target PGA in one call."""

import dataclasses
import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ..excitation import UnitsWarning
from ..flexible_mass import flexible
from ..sliding import newmark

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
    kind = "flexible"

    def __post_init__(self):
        _check_polarity(self.polarity)
        if self.equivalent_linear and self.reference_strain is None:
            raise ValueError("equivalent_linear=True needs reference_strain (gamma_ref, a fraction, e.g. 0.0005)")

    def _run(self, record, pga, values):
        options = {name: values[name] for name in ("ky", "height", "vs", "vr", "damping") if name in values}
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


MODELS = (Rigid, Flexible)
