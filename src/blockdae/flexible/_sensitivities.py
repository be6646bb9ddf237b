"""Derivatives of the sliding displacement of a flexible sliding mass by its inputs,
through the located events (the core's hybrid sensitivities on the JAX twin: the
variational equation along the trajectory and the saltation jump at every onset and
stop), mapped from the model's parameters (omega, total damping, ky) to the column's."""

from ..core._sensitivities import sensitivities
from ._column import IMPEDANCE_CAP, IMPEDANCE_EXPONENT

#: the inputs differentiated, name -> unit of the derivative
INPUTS = {"ky": "m/g", "height": "m/m", "vs": "m/(m/s)", "damping": "m", "A": "m/g"}


def displacement_sensitivities(model, motion, t_end, wrt=tuple(INPUTS), **options) -> dict:
    """d s(t_end) / d p [m per unit of p] for p in ``wrt``: "ky" [g], "height" [m], "vs"
    [m/s] (vr held), "damping" (the soil's ratio) and "A" (the motion scaled so that its
    peak is A g). ``options``: the JAX twin's settings (e.g. rtol, atol)."""
    if model.table is not None:
        raise ValueError(f"ky={model.ky}: displacement_sensitivities takes a constant ky (not yet a ky table)")
    unknown = [name for name in wrt if name not in INPUTS]
    if unknown:
        raise ValueError(f"wrt={unknown[0]!r} is unknown; choose from {tuple(INPUTS)}")
    core = sensitivities(model, motion, t_end, wrt=("omega", "damping", "ky", "A"), backend="jax", **options)
    d = {name: float(value.ravel()[0]) for name, value in core.items()}
    column = model.column
    impedance = column.impedance_damping
    # impedance damping 0.55016 (vr/vs)^-0.9904 below its cap moves with vs
    d_impedance_d_vs = -IMPEDANCE_EXPONENT * impedance / column.vs if 0 < impedance < IMPEDANCE_CAP else 0.0
    chained = {"ky": d["ky"], "A": d["A"], "damping": d["damping"],
               "height": -d["omega"] * model.omega / column.height,
               "vs": d["omega"] * model.omega / column.vs + d["damping"] * d_impedance_d_vs}
    return {name: chained[name] for name in wrt}
