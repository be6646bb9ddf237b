"""Derivatives of the sliding displacement of a flexible sliding mass by its inputs,
through the located events (the core's hybrid sensitivities on the JAX twin: the
variational equation along the trajectory and the saltation jump at every onset, stop
and breakpoint), mapped from the model's parameters (omega, total damping, ky) to the
column's.

For a ky table (:class:`KyTable`) "ky" is a uniform shift of all its ky values [g]:
each linear piece's intercept moves by as much, its slope and breakpoints stay.
"""

from ..core.derivatives import Sensitivities, trajectory_displacement_sensitivities
from ._column import IMPEDANCE_CAP, IMPEDANCE_EXPONENT

#: the inputs differentiated, name -> unit of the input
INPUTS = {"ky": "g", "height": "m", "vs": "m/s", "damping": "-", "A": "g"}


def displacement_sensitivities(model, motion, t_end, wrt=tuple(INPUTS), **options) -> Sensitivities:
    """d s(t_end) / d p [m per unit of p] for p in ``wrt``: "ky" [g] (of a ky table: all
    its ky values shifted together), "height" [m], "vs" [m/s] (vr held), "damping" (the
    soil's ratio) and "A" (the motion scaled so that its peak is A g), a
    :class:`~blockdae.Sensitivities` of s. ``options``: the JAX twin's settings (e.g.
    rtol, atol)."""
    wrt = (wrt,) if isinstance(wrt, str) else tuple(wrt)
    unknown = [name for name in wrt if name not in INPUTS]
    if unknown or not wrt:
        raise ValueError(f"wrt={wrt!r}: choose from {tuple(INPUTS)}")
    parameters = tuple(model.parameters())
    friction = ("ky",) if model.table is None else tuple(name for name in parameters
                                                        if name.startswith("ky_intercept_"))
    core = trajectory_displacement_sensitivities(model, motion, t_end, ("omega", "damping", *friction, "A"), "jax",
                                                 None, options)
    d = {name: float(core[name]) for name in core}
    column = model.column
    impedance = column.impedance_damping
    # impedance damping 0.55016 (vr/vs)^-0.9904 below its cap moves with vs
    d_impedance_d_vs = -IMPEDANCE_EXPONENT * impedance / column.vs if 0 < impedance < IMPEDANCE_CAP else 0.0
    chained = {"ky": sum(d[name] for name in friction), "A": d["A"], "damping": d["damping"],
               "height": -d["omega"] * model.omega / column.height,
               "vs": d["omega"] * model.omega / column.vs + d["damping"] * d_impedance_d_vs}
    return Sensitivities.make(model, {name: chained[name] for name in wrt}, parameter_units=INPUTS, backend="jax")
