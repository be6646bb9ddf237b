"""What :func:`blockdae.study` asks of a model, each hook optional (see
:class:`blockdae.core.contract.StudyModel`): the parameter it sweeps and the batch that runs
its values. A model that declares neither is swept in the keyword it is given, one model per
value, each motion run by :func:`blockdae.simulate` (:class:`SimulatedBatch`)."""

import dataclasses

import numpy as np

from ..core import simulate, unit_suffix
from ..core.contract import StudyBatch


def study_parameter(block, given: dict) -> tuple[str, str, str]:
    """(keyword, table column, unit) of what the study sweeps in ``block``, from ``given``
    (keyword -> the values given to the study, None where not given): the model's
    ``study_parameter_for(given)`` or ``study_parameter`` where it declares one; else the
    one keyword given, naming a parameter of the model (ValueError otherwise)."""
    hook = getattr(block, "study_parameter_for", None)
    declared = hook(given) if hook is not None else getattr(block, "study_parameter", None)
    if declared is not None:
        return tuple(declared)
    model = type(block).__name__
    named = [keyword for keyword, values in given.items() if values is not None]
    if len(named) != 1:
        raise ValueError(f"give one of {', '.join(f'{k}=' for k in given)}: the parameter of {model} the study sweeps "
                         f"(got {len(named)})")
    name = named[0]
    names = _parameter_names(block)
    if name not in names:
        raise ValueError(f"{name}=: {model} has no parameter {name!r} (its parameters: {sorted(names)}); a model "
                         "declares what a study sweeps in study_parameter")
    unit = _units(block).get(name)
    column = name if unit in (None, "-") else f"{name}_{unit_suffix(unit)}"
    return name, column, unit if unit is not None else "unit not declared"


def study_batch(block, parameter: str, sweep) -> StudyBatch:
    """``block`` at every value of ``sweep``: the model's own ``study_batch(sweep)`` where it
    declares one, else a :class:`SimulatedBatch` of ``parameter``; each value checked by the
    model (ValueError)."""
    hook = getattr(block, "study_batch", None)
    batch = NotImplemented if hook is None else hook(sweep)
    return SimulatedBatch(block, parameter, np.asarray(sweep, dtype=float)) if batch is NotImplemented else batch


@dataclasses.dataclass(frozen=True, eq=False)
class SimulatedBatch(StudyBatch):
    """``model`` at each of ``values`` of its parameter ``parameter`` (a model each, made by
    its ``replace``, or :func:`dataclasses.replace`, and checked by it), each run on the
    study's motions and factors by :func:`blockdae.simulate` on the model's default backend:
    the columns of an ensemble's table (:meth:`blockdae.Ensemble.final_columns`)."""

    model: object
    parameter: str
    values: np.ndarray

    def __post_init__(self):
        replace = getattr(self.model, "replace", None) or (lambda **changes: dataclasses.replace(self.model, **changes))
        object.__setattr__(self, "models", tuple(replace(**{self.parameter: float(v)}) for v in self.values))
        kinds = {}  # what each model reports as its displacement -> the first value that gives it
        for model, value in zip(self.models, self.values):
            kinds.setdefault(_displacement(model), float(value))
        if len(kinds) > 1:
            raise ValueError(f"{self.parameter}: the values {list(kinds.values())} give {type(self.model).__name__}s "
                             f"whose displacements differ ({', '.join(kinds)}); one table's columns share one "
                             "unit: study them apart")

    def check_motions(self, motions, t_end) -> None:
        """Each motion checked by the model (its ``check_motion``)."""
        for motion in motions:
            self.model.check_motion(motion)

    def study_columns(self, motions, t_end, scale, rtol=None) -> dict:
        """One row per motion x value x factor: each value's ensemble of ``motions`` at the
        factors ``scale`` [-] (final numbers), ``rtol`` [-] passed to the backend where given."""
        options = {} if rtol is None else {"rtol": rtol}
        cases = {str(i): motion for i, motion in enumerate(motions)}  # labels only: motions may share names
        each = [simulate(model, cases, t_end, scale=scale, final_only=True, progress=False, **options).final_columns()
                for model in self.models]
        shape = (len(motions), 1, len(scale))
        return {name: np.concatenate([np.reshape(c[name], shape) for c in each], axis=1).ravel() for name in each[0]}


def _displacement(model) -> str:
    """What ``model`` reports as its displacement: its states' names and unit ("u [m]")."""
    return f"{', '.join(model.state_names[s] for s in model.displacement_states)} [{model.displacement_unit}]"


def _parameter_names(block) -> set:
    """The names of ``block``'s parameters: its ``parameters()`` and dataclass fields."""
    names = {field.name for field in dataclasses.fields(block)} if dataclasses.is_dataclass(block) else set()
    try:
        names |= set(block.parameters())
    except (AttributeError, NotImplementedError):
        pass
    return names


def _units(block) -> dict:
    """name -> unit of ``block``'s parameters where it declares them (``parameter_units()``)."""
    try:
        return dict(block.parameter_units())
    except (AttributeError, NotImplementedError, TypeError):
        return {}
