"""What :func:`blockdae.sensitivities` returns for every model: derivatives of quantities
(a displacement, or a model's other quantities) by parameters, with their units."""

import warnings
from collections.abc import Mapping

import numpy as np

from .contract import DifferentiableModel


class Sensitivities(Mapping):
    """d quantity / d parameter for every quantity and parameter, with units.

    Attributes:
        quantities: what is differentiated, e.g. ("u",), ("u_x", "u_y") or a
            SpringSupportedMass's ("liftoff_velocity", "height", "flight_time").
        quantity_units: the unit of each quantity, e.g. ("m",).
        parameters: the names differentiated by (``wrt``), in order.
        array: the derivatives, shape (n_quantities, n_parameters), or (n_sets,
            n_quantities, n_parameters) for a batch of parameter sets.
        units: the unit of each derivative, ``units[i][j]`` that of ``array[..., i, j]``
            (the quantity's unit per the parameter's: "m", "m/g", "m/(m/s²)", "(m/s)/Hz").
        model: the model differentiated; backend: the name of the backend whose
            derivatives these are ("exact", "jax", ...).

    As a mapping it is by parameter: ``result["mu"]`` is a float for one quantity, an
    array (n_quantities,) for several, and for a batch (n_sets,) or (n_sets,
    n_quantities). ``result.of("u")`` is parameter -> derivative of one quantity;
    :meth:`to_dataframe` is a table.
    """

    def __init__(self, quantities, quantity_units, parameters, array, units, model=None, backend=None,
                 by_quantity=False):
        self.quantities, self.quantity_units = tuple(quantities), tuple(quantity_units)
        self.parameters, self.array, self.units = tuple(parameters), np.asarray(array, dtype=float), tuple(units)
        self.model, self.backend = model, backend
        self._by_quantity = by_quantity  # results once indexed by quantity (result["height"]) still are, deprecated
        expected = (len(self.quantities), len(self.parameters))
        if self.array.shape[-2:] != expected or self.array.ndim not in (2, 3):
            raise ValueError(f"array of shape {self.array.shape}: expected (n_sets,) + {expected} or {expected}")

    @classmethod
    def make(cls, model, derivatives: Mapping, *, quantities=None, quantity_units=None, parameter_units=None,
             backend=None) -> "Sensitivities":
        """The result from what a derivative method computes: ``derivatives`` is
        parameter -> value (a float, (n_quantities,), or for a batch (n_sets,) or (n_sets,
        n_quantities)), or quantity -> parameter -> float.

        Args:
            model: the model differentiated (its ``batch_shape``, ``state_names``,
                ``displacement_states`` and ``parameter_units()``).
            quantities: default: the model's displacement states, or the keys of a nested
                ``derivatives``.
            quantity_units: one per quantity; default "m" each.
            parameter_units: name -> unit; default: the model's ``parameter_units()``.
            backend: the backend's name (or a backend object with a ``name``).
        """
        by_quantity = bool(derivatives) and isinstance(next(iter(derivatives.values())), Mapping)
        if by_quantity:
            quantities = tuple(derivatives)
            parameters = tuple(next(iter(derivatives.values())))
            columns = [[derivatives[q][p] for q in quantities] for p in parameters]
        else:
            quantities = displacement_names(model) if quantities is None else tuple(quantities)
            parameters = tuple(derivatives)
            columns = [derivatives[p] for p in parameters]
        quantity_units = ("m",) * len(quantities) if quantity_units is None else tuple(quantity_units)
        if parameter_units is None:
            parameter_units = model.parameter_units() if isinstance(model, DifferentiableModel) else {}
        n_sets = int(np.prod(model.batch_shape)) if getattr(model, "batch_shape", ()) else None
        shape = (len(quantities),) if n_sets is None else (n_sets, len(quantities))
        array = np.stack([np.asarray(c, dtype=float).reshape(shape) for c in columns], axis=-1) if columns \
            else np.zeros(shape + (0,))
        units = tuple(tuple(per(q_unit, parameter_units.get(p, "-")) for p in parameters) for q_unit in quantity_units)
        return cls(quantities, quantity_units, parameters, array, units, model,
                   getattr(backend, "name", backend), by_quantity)

    @property
    def batch(self) -> bool:
        """Whether these are the derivatives of a batch of parameter sets."""
        return self.array.ndim == 3

    def __getitem__(self, name):
        if name in self.parameters:
            column = self.array[..., self.parameters.index(name)]
            column = column[..., 0] if len(self.quantities) == 1 else column
            return float(column) if column.ndim == 0 else column
        if self._by_quantity and name in self.quantities:
            warnings.warn(f"result[{name!r}] (quantity -> parameter -> derivative) is deprecated: a result is "
                          f"by parameter; use result.of({name!r}) or result.to_dataframe()",
                          DeprecationWarning, stacklevel=2)
            return self.of(name)
        raise KeyError(f"{name!r} is none of the parameters {self.parameters} (result.of(quantity) for one of "
                       f"{self.quantities})")

    def __iter__(self):
        return iter(self.parameters)

    def __len__(self):
        return len(self.parameters)

    def __contains__(self, name):
        return name in self.parameters

    def of(self, quantity: str) -> dict:
        """parameter -> d ``quantity`` / d parameter: a float, or (n_sets,) for a batch."""
        if quantity not in self.quantities:
            raise KeyError(f"quantity {quantity!r}: choose among {self.quantities}")
        row = self.array[..., self.quantities.index(quantity), :]
        return {p: (float(row[j]) if row.ndim == 1 else row[:, j]) for j, p in enumerate(self.parameters)}

    def columns(self) -> list[str]:
        """The table's column names, "d<quantity>/d<parameter> [unit]", quantity by quantity."""
        return [f"d{q}/d{p} [{self.units[i][j]}]" for i, q in enumerate(self.quantities)
                for j, p in enumerate(self.parameters)]

    def to_dataframe(self):
        """A pandas DataFrame: one row (one per parameter set for a batch, index "set"), a
        column per quantity and parameter named with its unit, e.g. "du/dmu [m]"."""
        import pandas as pd

        rows = self.array.reshape(-1, self.array.shape[-2] * self.array.shape[-1])
        table = pd.DataFrame(rows, columns=self.columns())
        table.index.name = "set" if self.batch else None
        return table

    def __repr__(self):
        owner = f"a {type(self.model).__name__}" if self.model is not None else "a model"
        sets = f", {self.array.shape[0]} parameter sets" if self.batch else ""
        backend = f", backend {self.backend!r}" if self.backend else ""
        lines = [f"Sensitivities of {owner}{sets}{backend}:"]
        for i, q in enumerate(self.quantities):
            parts = []
            for j, p in enumerate(self.parameters):
                value = self.array[..., i, j]
                shown = f"{float(value):.6g}" if value.ndim == 0 else \
                    (f"{value.min():.6g} to {value.max():.6g}" if value.size else "none")
                parts.append(f"d{q}/d{p} = {shown} {self.units[i][j]}")
            lines.append("  " + ", ".join(parts))
        return "\n".join(lines)


def per(numerator: str, denominator: str) -> str:
    """The unit ``numerator`` per ``denominator`` ("-" or "": none): "m/g", "m/(m/s²)",
    "(m/s)/Hz", "1/m" (a dimensionless quantity per m)."""
    if denominator in ("-", ""):
        return numerator
    wrap = lambda unit: f"({unit})" if "/" in unit else unit
    return f"{wrap('1' if numerator in ('-', '') else numerator)}/{wrap(denominator)}"


def displacement_names(model) -> tuple[str, ...]:
    """The names of the model's displacement states (its ``state_names`` at
    ``displacement_states``), e.g. ("u",) or ("u_x", "u_y")."""
    return tuple(model.state_names[i] for i in model.displacement_states)
