"""The app's design page: the design form, checked field by field, and the design studies
it runs (:func:`blockdae.design.exceedance`; the design inverse
:func:`~blockdae.design.mean_ky_for_probability` and, per record,
:func:`~blockdae.design.ky_for_displacement`) on a thread, each batch of analyses counted
and a cancel honoured between batches."""

import dataclasses
import threading
import time

import numpy as np

from ..design import Flexible, LogNormal, Rigid, exceedance, ky_for_displacement, mean_ky_for_probability
from ._analysis import METHODS, FieldError, _number
from ._caught import caught_warnings

#: the samplers offered, by key
SAMPLINGS = {"sobol": "scrambled Sobol", "lhs": "Latin hypercube", "mc": "Monte Carlo"}
#: how D is read from the two polarities
POLARITIES = {"normal": "as recorded", "inverse": "inverted", "larger": "the larger of the two"}
#: the uncertain properties: key -> (the field's name, unit); height and vs for the flexible mass only
PROPERTIES = {"ky": ("ky", "g"), "height": ("slope height H", "m"), "vs": ("shear-wave velocity Vs", "m/s")}


@dataclasses.dataclass(frozen=True)
class DesignSettings:
    """A design study as the form sets it.

    Attributes:
        method: a key of :data:`METHODS` (the analysis).
        parameters: name -> a number or a :class:`LogNormal` (ky [g]; flexible: height
            [m], vs [m/s], damping [-]).
        reference_strain: gamma_ref [-] (equivalent-linear only).
        polarity: a key of :data:`POLARITIES`.
        pga: target PGA [g], None: each record as read.
        sampling: a key of :data:`SAMPLINGS`; seed: an integer.
        rse: the relative standard error of the mean D to stop at [-] (None: no criterion).
        halfwidth: the half-width of the 95 % interval of P(D > threshold) to stop at [-]
            (None: no criterion); neither: a fixed number of runs, ``max_runs``.
        runs_per_block: runs between checks; max_runs: the most runs.
        threshold: the displacement of interest [m].
    """

    method: str
    parameters: dict
    reference_strain: float | None = None
    polarity: str = "normal"
    pga: float | None = None
    sampling: str = "sobol"
    seed: int = 0
    rse: float | None = 0.05
    halfwidth: float | None = None
    runs_per_block: int = 16
    max_runs: int = 256
    threshold: float = 0.1

    @property
    def model(self):
        """The design model (:class:`Rigid` or :class:`Flexible`)."""
        if self.method == "rigid":
            return Rigid(polarity=self.polarity)
        linear = self.method == "equivalent-linear"
        return Flexible("coupled" if linear else self.method, linear, self.reference_strain, self.polarity)

    def study_options(self) -> dict:
        """The keywords of :func:`exceedance` (a fixed number of runs where no precision is given)."""
        precise = self.rse is not None or self.halfwidth is not None
        return {"pga": self.pga, "threshold": self.threshold, "sampling": self.sampling, "seed": self.seed,
                "rse": self.rse, "halfwidth": self.halfwidth, "runs": None if precise else self.max_runs,
                "runs_per_block": self.runs_per_block, "max_runs": self.max_runs}

    def means(self) -> dict:
        """The parameters at their means (name -> number)."""
        return {name: getattr(value, "mean", value) for name, value in self.parameters.items()}


@dataclasses.dataclass(frozen=True)
class InverseSettings:
    """The design inverse: the allowable displacement [m], the target probability of
    exceeding it [-] and the samples per record."""

    allowable: float
    target: float
    runs: int


def _integer(field, text, low):
    """``text`` as an integer >= ``low``; FieldError naming the field and the value."""
    try:
        value = int(str(text).strip())
    except ValueError:
        raise FieldError(field, text, "is not an integer") from None
    if value < low:
        raise FieldError(field, text, f"must be >= {low}")
    return value


def _uncertain(key, form):
    """The property ``key`` of the form: a LogNormal of its mean and cov, or its mean where the cov is 0."""
    name, unit = PROPERTIES[key]
    mean = _number(f"mean {name} [{unit}]", form.get(f"{key}_mean"), low=0.0)
    if key == "ky" and mean > 1.0:
        raise FieldError(f"mean {name} [{unit}]", form.get(f"{key}_mean"),
                         "is above 1 g: a ky in m/s²? (0.05 g is 0.49 m/s²)")
    cov = _number(f"cov of {name} [-]", form.get(f"{key}_cov"), low=0.0, low_open=False)
    return mean if cov == 0 else LogNormal(mean=mean, cov=cov)


def parse_design(form: dict) -> DesignSettings:
    """The :class:`DesignSettings` of the form's values (text as typed; keys: method,
    polarity, ky_mean, ky_cov, height_mean, height_cov, vs_mean, vs_cov, damping,
    reference_strain, pga, sampling, seed, rse, halfwidth, runs_per_block, max_runs,
    threshold); FieldError naming a bad field."""
    method = form.get("method")
    if method not in METHODS:
        raise FieldError("analysis", method, f"is none of {', '.join(METHODS)}")
    polarity = form.get("polarity")
    if polarity not in POLARITIES:
        raise FieldError("polarity", polarity, f"is none of {', '.join(POLARITIES)}")
    parameters = {"ky": _uncertain("ky", form)}
    strain = None
    if method != "rigid":
        parameters |= {"height": _uncertain("height", form), "vs": _uncertain("vs", form),
                       "damping": _number("damping ratio [-]", form.get("damping"), low=-1.0, high=1.0)}
        if method == "equivalent-linear":
            strain = _number("reference strain [-]", form.get("reference_strain"), low=0.0, high=1.0)
    pga = _number("target PGA [g]", form.get("pga"), low=0.0, optional=True)
    if pga is not None and pga > 2.0:
        raise FieldError("target PGA [g]", form.get("pga"), "is above 2 g: a PGA in m/s²? (0.3 g is 2.94 m/s²)")
    sampling = form.get("sampling")
    if sampling not in SAMPLINGS:
        raise FieldError("sampling", sampling, f"is none of {', '.join(SAMPLINGS)}")
    seed = _integer("seed", form.get("seed"), 0)
    rse = _number("relative standard error of the mean D [-]", form.get("rse"), low=0.0, optional=True)
    halfwidth = _number("half-width of the 95 % interval of P [-]", form.get("halfwidth"), low=0.0, high=0.5,
                        optional=True)
    block = _integer("runs per block", form.get("runs_per_block"), 2)
    if sampling == "sobol" and block & (block - 1):
        raise FieldError("runs per block", form.get("runs_per_block"),
                         "must be a power of 2 for Sobol samples (e.g. 16)")
    max_runs = _integer("at most runs", form.get("max_runs"), block)
    if sampling == "sobol" and max_runs % block:
        raise FieldError("at most runs", form.get("max_runs"),
                         f"must be a multiple of the runs per block ({block}) for Sobol samples")
    threshold = _number("threshold displacement [m]", form.get("threshold"), low=0.0)
    return DesignSettings(method, parameters, strain, polarity, pga, sampling, seed, rse, halfwidth, block, max_runs,
                          threshold)


def parse_inverse(form: dict, settings: DesignSettings) -> InverseSettings:
    """The :class:`InverseSettings` of the form (keys: allowable, target, inverse_runs);
    FieldError naming a bad field (ky must be uncertain: its mean is what is found)."""
    if not isinstance(settings.parameters["ky"], LogNormal):
        raise FieldError("cov of ky [-]", form.get("ky_cov"),
                         "must be > 0 for the design inverse (it scales the mean of ky)")
    allowable = _number("allowable displacement [m]", form.get("allowable"), low=0.0)
    target = _number("target probability [-]", form.get("target"), low=0.0, high=1.0)
    runs = _integer("samples per record", form.get("inverse_runs"), 2)
    if settings.sampling == "sobol" and runs & (runs - 1):
        raise FieldError("samples per record", form.get("inverse_runs"),
                         "must be a power of 2 for Sobol samples (e.g. 64)")
    return InverseSettings(allowable, target, runs)


class Cancelled(Exception):
    """Raised in a design study's thread at its next batch of analyses after a cancel."""


@dataclasses.dataclass
class Inverse:
    """The design inverse's answer: the mean ky (:class:`~blockdae.design.MeanKyDesign`)
    and per record (name, target PGA [g] or None, the ky [g] at which D = allowable at
    the properties' means, or None where D stays below it at any ky)."""

    design: object
    per_record: list


class DesignJob:
    """A design study (``kind``: "exceedance" or "inverse") of ``records`` (name -> Record)
    on a thread of its own.

    Attributes (read while it runs): analyses (counted batch by batch), notes (warnings,
    one line each), error (what stopped it, a line; None), cancelled and finished
    (threading.Event), result (an Exceedance or an :class:`Inverse` once done; None if
    cancelled or stopped), seconds (its wall time when finished [s]).
    """

    def __init__(self, records: dict, settings: DesignSettings, kind: str, inverse: InverseSettings | None = None):
        self.records, self.settings, self.kind, self.inverse = dict(records), settings, kind, inverse
        self.analyses, self.notes, self.error, self.result, self.seconds = 0, [], None, None, None
        self.cancelled, self.finished = threading.Event(), threading.Event()
        self._start = time.perf_counter()
        threading.Thread(target=self._run, name="blockdae-app-design", daemon=True).start()

    def _run(self):
        model = watched(self.settings.model, self)
        try:
            if self.kind == "exceedance":
                self.result = exceedance(self.records, model, self.settings.parameters,
                                         **self.settings.study_options())
            else:
                self.result = design_inverse(self.records, model, self.settings, self.inverse)
        except Cancelled:
            pass
        except ValueError as err:
            self.error = str(err)
        except Exception as err:  # shown in the page; the app keeps running
            self.error = f"the design study stopped: {type(err).__name__}: {err}"
        finally:
            self.seconds = time.perf_counter() - self._start
            self.finished.set()

    def count(self, values, notes):
        """Count a batch of analyses done (``values``: the parameter sets) and keep its warnings."""
        self.analyses += int(np.size(values["ky"]))
        self.notes += [note for note in notes if note not in self.notes]


def watched(model, job):
    """``model`` (the same analyses, the same numbers) with each batch of its analyses
    counted on ``job``, its warnings kept there, and a cancel of ``job`` raising
    :class:`Cancelled` at the next batch."""

    class Watched(type(model)):
        def displacements(self, record, pga, values, derivative=False):
            if job.cancelled.is_set():
                raise Cancelled
            with caught_warnings() as notes:
                result = super().displacements(record, pga, values, derivative)
            job.count(values, notes)
            return result

        def sliding_limit(self, record, pga, values):
            if job.cancelled.is_set():
                raise Cancelled
            with caught_warnings() as notes:
                result = super().sliding_limit(record, pga, values)
            job.count(values, notes)
            return result

    return Watched(**{field.name: getattr(model, field.name) for field in dataclasses.fields(model)})


def design_inverse(records: dict, model, settings: DesignSettings, inverse: InverseSettings) -> Inverse:
    """The mean ky for P(D > allowable) <= target over ``records`` (samples drawn as the
    study draws them: its sampling and seed), and each record's ky for D = allowable at
    the properties' means."""
    design = mean_ky_for_probability(records, model, settings.parameters, inverse.allowable, inverse.target,
                                     pga=settings.pga, runs=inverse.runs, sampling=settings.sampling,
                                     seed=settings.seed)
    others = {name: value for name, value in settings.means().items() if name != "ky"}
    per_record = []
    for name, record in records.items():
        try:
            ky = ky_for_displacement(record, model, others, inverse.allowable, pga=settings.pga)
        except ValueError as err:
            if "no ky is needed" not in str(err):
                raise
            ky = None
        per_record.append((name, settings.pga, ky))
    return Inverse(design, per_record)
