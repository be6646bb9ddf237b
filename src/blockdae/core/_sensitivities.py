"""Derivatives of a model's displacement with respect to its parameters.

:func:`sensitivities` and :func:`finite_differences` ask the model
(:class:`~blockdae.core.contract.DifferentiableModel`): by default its displacement at
t_end is differentiated along the trajectory the JAX twin locates, by the variational
equation and the saltation jump at every event (the JAX twin's ``displacement_jacobian``); a model
with a derivative method of its own (the 1-D block's compiled kernels, a spring-supported
mass's flights) overrides the hook in its own package, from the building blocks here
(:mod:`blockdae.core.derivatives`).
"""

import numpy as np

from .contract import DifferentiableModel, parameter_names
from ._simulate import of_run, simulate
from ._registry import AbstractBackend, Horizon, backend_name, make_backend
from ._sensitivity_result import Sensitivities, per
from ..excitation import BaseMotion


def sensitivities(block, motion, t_end: float | None = None, wrt=None, backend: str | AbstractBackend | None = None,
                  of=None, **options) -> Sensitivities:
    """d u(t_end) / d p for each parameter p in ``wrt``, by the model's own method (for a
    SpringSupportedMass: the derivatives of its flights, see ``of``). u is signed
    (x_block - x_base): for Newmark's one-way block (direction "negative") the downslope
    D = -u, so dD/dp = -du/dp.

    Args:
        block: a model that declares derivatives (a :class:`SlidingBlock`, a batch of
            parameter sets if its parameters are 1-D arrays, a :class:`PlanarBlock`, a
            :class:`SpringSupportedMass`, ...: a ``DifferentiableModel``).
        motion: base excitation (for a PlanarBlock also a :class:`BaseMotion`).
        t_end: final time [s]; None: when the block rests after the excitation ends.
        wrt: names among the model's ``parameter_units()``; None: its ``default_wrt()``.
            For a SlidingBlock any of "mu" (static friction; when
            ``block.mu_kinetic`` is None the kinetic coefficient follows it, so it
            moves both), "mu_kinetic" (kinetic alone), "bias" (R/Q), "A" (peak base
            acceleration in units of ``block.g``, the excitation scaled so that its
            peak is A g) and "scale" (a factor k on a(t), at k = 1); default ("mu",
            "mu_kinetic", "bias", "A"). For other models any of the model's
            ``parameters()`` (PlanarBlock: "mu", "mu_kinetic", "bias_x", "bias_y",
            "g", "restitution"), "A" (every component scaled so that the largest
            component peak is A g) and "A_<component>" (one component's scale
            factor, at 1: "A_x", "A_y", "A_z"; with y = R x, "A_y" is Elms's R);
            default: ("mu", "mu_kinetic", "bias_x", "bias_y", "A") for a PlanarBlock,
            ("frequency", "damping", "A") for a SpringSupportedMass (also "g").
        backend: "exact" (closed forms, differentiated through the JAX kernel of
            "exact-jax") or "jax" (the diffrax twin); None: "exact" for a
            SlidingBlock, "jax" (the only one) for other models.
        of: what is differentiated instead of the displacement: a name or names of the
            model's ``scalar_quantities()`` (a RockingBlock: "max_theta_over_alpha",
            max |theta| / alpha [-]); for a SpringSupportedMass any of
            "liftoff_velocity" (u' at the first liftoff [m/s]), "height" (the largest
            u - u0 of a flight [m], at a top) and "flight_time" (the sum of landing -
            liftoff [s]; a flight not landed by t_end counts to t_end), default all three.
        **options: settings of the backend.

    Returns:
        A :class:`~blockdae.Sensitivities`: ``.quantities`` (("u",); ("u_x", "u_y") for a
        PlanarBlock; a SpringSupportedMass's flight quantities), ``.parameters`` (``wrt``),
        ``.array`` of shape (n_quantities, n_parameters), or (n_sets, n_quantities,
        n_parameters) for a batch, ``.units`` (the quantity's unit per the parameter's:
        m per unit of the parameter, m/g for "A"), ``.to_dataframe()``. As a mapping by
        parameter: ``result["mu"]`` is a float for one quantity, (n_quantities,) for
        several (d(u_x, u_y)(t_end) / dp), and (n_sets,) or (n_sets, n_quantities) for a
        batch; ``result.of("height")`` is parameter -> derivative of one quantity.
    """
    _check_differentiable(block)
    wrt = _names(block, wrt)
    own = block.sensitivities(motion, t_end, wrt, backend, of, options)
    if own is NotImplemented:
        along = trajectory_displacement_sensitivities if of is None else trajectory_quantity_sensitivities
        return along(block, motion, t_end, wrt, backend, of, options)
    return own if isinstance(own, Sensitivities) else Sensitivities.make(block, own, backend=backend)


def finite_differences(block, motion, t_end: float | None = None, wrt=None, backend: str = "cvode",
                       step: float = 1e-4, **options) -> Sensitivities:
    """Finite differences of u(t_end) on any backend, for checking derivatives.

    Same parameters and units as :func:`sensitivities` (one parameter set; ``wrt`` None:
    the model's ``default_wrt()``). ``step`` is relative: for a SlidingBlock mu and
    mu_kinetic move by step times their value, bias by step times mu, and a(t) is scaled
    by 1 +- step (other models: each parameter by step times its value, or by step where
    it is 0; each component's scale by step). Central differences, or second-order
    one-sided ones where a step would leave the block invalid (at a bound: mu_kinetic =
    mu, |bias| near mu), taken from the valid side. Returns a
    :class:`~blockdae.Sensitivities` of the displacement.
    """
    _check_differentiable(block)
    if block.batch_shape:
        raise ValueError("finite_differences takes one parameter set; use block.item(i)")
    if not (np.isfinite(step) and 0 < step < 0.1):
        raise ValueError(f"step must be a relative step in (0, 0.1), got {step!r}")
    wrt = _names(block, wrt)
    own = block.finite_differences(motion, t_end, wrt, backend, step, options)
    differences = parameter_differences(block, motion, t_end, wrt, backend, step, options) \
        if own is NotImplemented else own
    return Sensitivities.make(block, differences, backend=backend)


def derivative_unit(model, name: str, displacement_unit: str = "m") -> str:
    """Unit of d displacement / d ``name``: the displacement's unit per the parameter's
    (the model's ``parameter_units()``): "m" for a dimensionless one, "m/g" for "A"."""
    unit = model.parameter_units().get(name, "-") if isinstance(model, DifferentiableModel) else "-"
    return per(displacement_unit, unit)


def trajectory_displacement_sensitivities(model, motion, t_end, wrt, backend, of, options):
    """The core's derivatives (where the model has none of its own,
    :meth:`~blockdae.core.contract.DifferentiableModel.sensitivities`): d displacement(t_end)
    / dp along the JAX twin's trajectory per name, a :class:`~blockdae.Sensitivities` of the
    displacement states (a batch: one located trajectory per parameter set, stacked)."""
    if of is not None:
        raise _no_quantities(model, of)
    backend = _twin_backend(model, backend)
    if model.batch_shape:  # one located trajectory per parameter set
        sets = [trajectory_displacement_sensitivities(model.item(i), motion, t_end, wrt, backend, of, options)
                for i in range(model.batch_shape[0])]
        return Sensitivities.make(model, {name: np.array([one[name] for one in sets]) for name in sets[0]},
                                  backend=backend)
    wrt = checked_wrt(model, wrt)
    peak = largest_peak(motion) if "A" in wrt else None
    horizon = Horizon.resolve(motion, t_end)
    jacobian = make_backend(backend, **options).displacement_jacobian(model, motion, horizon)
    return Sensitivities.make(model, by_parameter(model, jacobian.T, wrt, peak), backend=backend)


def trajectory_quantity_sensitivities(model, motion, t_end, wrt, backend, of, options):
    """The core's derivatives of the scalar quantities ``of`` (a name or names of the
    model's :meth:`~blockdae.core.contract.DifferentiableModel.scalar_quantities`) along
    the JAX twin's trajectory, by the model's ``scalar_quantity_jacobian``: a
    :class:`~blockdae.Sensitivities` of those quantities in their units (a batch: one
    located trajectory per parameter set, stacked)."""
    units = model.scalar_quantities()
    of = (of,) if isinstance(of, str) else tuple(of)
    if not units:
        raise _no_quantities(model, of)
    unknown = [name for name in of if name not in units]
    if unknown or not of:
        raise ValueError(f"of={of!r}: choose among {tuple(units)}")
    backend = _twin_backend(model, backend)
    if model.batch_shape:  # one located trajectory per parameter set
        sets = [trajectory_quantity_sensitivities(model.item(i), motion, t_end, wrt, backend, of, options)
                for i in range(model.batch_shape[0])]
        return Sensitivities(sets[0].quantities, sets[0].quantity_units, sets[0].parameters,
                             np.stack([one.array for one in sets]), sets[0].units, model, sets[0].backend)
    wrt = checked_wrt(model, wrt)
    peak = largest_peak(motion) if "A" in wrt else None
    solution, final, events = make_backend(backend, **options).trajectory_sensitivities(
        model, motion, Horizon.resolve(motion, t_end))
    solution = of_run(solution, model, motion)
    derivatives = {name: by_parameter(model, model.scalar_quantity_jacobian(name, solution, final, events), wrt, peak)
                   for name in of}
    return Sensitivities.make(model, derivatives, quantity_units=[units[name] for name in of], backend=backend)


def _twin_backend(model, backend):
    """The backend of the core's derivatives along a trajectory: the JAX twin ("jax",
    also for None); ValueError for any other."""
    backend = "jax" if backend is None else backend
    if backend_name(backend) != "jax":
        raise ValueError(f"backend={backend!r} has no derivatives for a {type(model).__name__}; use 'jax'")
    return backend


def _no_quantities(model, of) -> ValueError:
    """The error for ``of`` given to a model that declares no scalar quantities."""
    return ValueError(f"of={of!r} does not apply to a {type(model).__name__}: it has the derivatives of its "
                      "displacement")


def by_parameter(model, columns, wrt, peak):
    """name -> derivative for each name in ``wrt`` from ``columns``, one per parameter
    of :func:`.contract.parameter_names`: "A" sums every component's scale
    factor times g / ``peak`` (k = A g / peak), a parameter adds those tied to it."""
    column = dict(zip(parameter_names(model), columns))
    derivatives = {}
    for name in wrt:
        if name == "A":  # every component scaled by k = A g / peak
            derivatives[name] = sum(column[f"A_{c}"] for c in model.component_names) * model.g / peak
        else:
            derivatives[name] = column[name] + sum(column[tied] for tied in model.tied_parameters().get(name, ()))
    return derivatives


def parameter_differences(model, motion, t_end, wrt, backend, step, options):
    """The core's finite differences (where the model has none of its own,
    :meth:`~blockdae.core.contract.DifferentiableModel.finite_differences`): see there."""
    wrt = checked_wrt(model, wrt)
    several = len(model.component_names) > 1  # a BaseMotion scales its components one by one
    motion = BaseMotion(motion) if several and not isinstance(motion, BaseMotion) else motion

    def u(blk, mot):
        return simulate(blk, mot, t_end=t_end, backend=backend, **options).displacement

    def parameter(name):
        value = model.parameters()[name]
        h = step * (abs(value) if value != 0 else 1.0)
        return step_difference(u, lambda s: (model.replace_parameter(name, value + s * h), motion)) / h

    def scaled(names, factor):
        return motion.scaled_components(**{c: factor for c in names}) if several else motion.scaled(factor)

    def scale(names):
        return step_difference(u, lambda s: (model, scaled(names, 1 + s * step))) / step

    derivatives = {}
    for name in wrt:
        if name == "A":
            derivatives[name] = scale(model.component_names) * model.g / largest_peak(motion)
        elif name.startswith("A_"):
            derivatives[name] = scale((name[2:],))
        else:
            derivatives[name] = parameter(name)
    return derivatives


def checked_wrt(model, wrt, known=None):
    """``wrt`` (a tuple), checked against ``known`` (default: the names of
    :func:`.contract.parameter_names` and "A"); ValueError names the choice."""
    known = parameter_names(model) + ("A",) if known is None else tuple(known)
    unknown = [name for name in wrt if name not in known]
    if unknown or not wrt:
        raise ValueError(f"wrt={wrt!r}: choose among {known}")
    return wrt


def largest_peak(motion):
    """The largest peak acceleration of the motion's components [m/s²] (> 0)."""
    peak = motion.peak_acceleration
    peak = max(peak) if isinstance(peak, tuple) else float(peak)
    if not peak > 0:
        raise ValueError(f"'A' needs a motion with a nonzero peak acceleration, got {peak} m/s²")
    return peak


def step_difference(u, change):
    """d u(change(s)) / d s at s = 0: central, or second-order one-sided from the side
    where ``change`` (a step of s = +-1, +-2 giving (block, motion)) stays a valid block."""
    valid = {}
    for s in (-2, -1, 1, 2):
        try:
            valid[s] = change(s)
        except ValueError:  # the block refuses this step: a bound of the parameter
            continue
    if 1 in valid and -1 in valid:
        return (u(*valid[1]) - u(*valid[-1])) / 2
    for side in (1, -1):
        if side in valid and 2 * side in valid:
            return side * (4 * u(*valid[side]) - u(*valid[2 * side]) - 3 * u(*change(0))) / 2
    raise ValueError("no step of the parameter leaves the block valid; use a smaller step")


def _check_differentiable(block):
    if not isinstance(block, DifferentiableModel):
        raise TypeError(f"a {type(block).__name__} declares no derivatives: a model is differentiated when it "
                        "subclasses blockdae.core.contract.DifferentiableModel (parameters, with_parameters, "
                        "parameter_units)")


def _names(block, wrt):
    """``wrt`` as a tuple of names; None: the model's ``default_wrt()``."""
    wrt = block.default_wrt() if wrt is None else wrt
    return (wrt,) if isinstance(wrt, str) else tuple(wrt)
