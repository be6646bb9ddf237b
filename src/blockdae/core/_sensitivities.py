"""Derivatives of the permanent displacement with respect to the parameters.

Forward-mode differentiation (``jax.jacfwd``) of a compiled kernel: the exact
backend's closed forms or the diffrax twin. Derivatives pass through the event
times by the implicit function theorem at each guard, not through a smoothed model.

Where u is not differentiable (a sliding episode starts exactly at the threshold,
|sigma| = mu g, and the demand turns back there), the result is the derivative of
the branch the transition rule takes: a demand that touches the threshold and
turns back does not slide, so the new episode is absent and the value is the
one-sided derivative from the side without it (A below, mu above the threshold).
With f < mu the displacement itself jumps there.

Other models (:class:`~blockdae.PlanarBlock`) are differentiated along the trajectory
the JAX twin locates, by the variational equation and the saltation jump at every
event (:mod:`._hybrid_sensitivities`); their displacement is a vector. For a
:class:`~blockdae.SpringSupportedMass` the derivatives are those of its flights (the
first liftoff velocity, the largest height, the total flight time; :mod:`blockdae.upthrow._sensitivities`).
"""

import functools

import numpy as np

from ._jax_config import jax_context
from ._simulate import simulate
from ..backends import AbstractBackend, Horizon, backend_name, make_backend
from ..engines._results import check
from ..excitation import BaseMotion

#: parameter name -> unit of d u / d parameter (SlidingBlock)
UNITS = {"mu": "m", "mu_kinetic": "m", "bias": "m", "A": "m/g", "scale": "m"}
#: the parameters differentiated by default (SlidingBlock)
DEFAULT_WRT = ("mu", "mu_kinetic", "bias", "A")


def unit(name: str) -> str:
    """Unit of d u / d ``name``: m/g for "A", else m (per unit of the parameter)."""
    return "m/g" if name == "A" else "m"


def sensitivities(block, motion, t_end: float | None = None, wrt=None, backend: str | AbstractBackend | None = None,
                  of=None, **options) -> dict:
    """d u(t_end) / d p for each parameter p in ``wrt`` (for a SpringSupportedMass: the
    derivatives of its flights, see ``of``). u is signed (x_block - x_base): for Newmark's
    one-way block (direction "negative") the downslope D = -u, so dD/dp = -du/dp.

    Args:
        block: a :class:`SlidingBlock` (a batch of parameter sets if its parameters are
            1-D arrays) or another model (a :class:`PlanarBlock`, a
            :class:`SpringSupportedMass`).
        motion: base excitation (for a PlanarBlock also a :class:`BaseMotion`).
        t_end: final time [s]; None: when the block rests after the excitation ends.
        wrt: for a SlidingBlock any of "mu" (static friction; when
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
            "exact-jax") or "jax" (the diffrax twin), or such a backend object
            (``bd.Exact(window=32)``, ``bd.ExactJax()``, ``bd.JaxTwin(rtol=1e-12)``);
            None: "exact" for a SlidingBlock, "jax" (the only one) for other models.
        of: SpringSupportedMass only: the quantities differentiated, any of
            "liftoff_velocity" (u' at the first liftoff [m/s]), "height" (the largest
            u - u0 of a flight [m], at a top) and "flight_time" (the sum of landing -
            liftoff [s]; a flight not landed by t_end counts to t_end); default all three.
        **options: settings of the backend given by name.

    Returns:
        name -> derivative [m per unit of the parameter; m/g for "A"]: a float, or an
        array of shape (n,) for a batch of n parameter sets; for other models an
        array of shape (2,), d(u_x, u_y)(t_end) / dp, or (n, 2) for a batch. For a
        SpringSupportedMass: quantity -> parameter -> float, in the quantity's unit
        per unit of the parameter (per Hz, per unit damping ratio, per g for "A",
        per m/s² for "g").
    """
    if block.derivatives == "flights":
        return _upthrow_sensitivities(block, motion, t_end, wrt, "jax" if backend is None else backend, of, options)
    if of is not None:
        raise ValueError(f"of={of!r} applies to a SpringSupportedMass only; a {type(block).__name__} has the "
                         "derivatives of its displacement")
    if block.derivatives != "sliding":
        return _hybrid_sensitivities(block, motion, t_end, wrt, "jax" if backend is None else backend, options)
    backend = "exact" if backend is None else backend
    wrt = _names(DEFAULT_WRT if wrt is None else wrt)
    if backend_name(backend) not in ("exact", "exact-jax", "jax"):
        raise ValueError(f"backend={backend!r} has no derivatives; use 'exact' or 'jax'")
    import jax  # loads only when derivatives are asked for
    if "A" in wrt and not motion.peak_acceleration > 0:
        raise ValueError(f"'A' needs a motion with a nonzero peak acceleration, got {motion.peak_acceleration} m/s²")
    horizon = Horizon.resolve(motion, t_end)
    solver = make_backend(_differentiated(backend), **options)
    pieces = motion.pieces(horizon.integration_end(motion))
    kernel, static, device = _kernel(solver, block, pieces)

    shape = block.batch_shape
    params = tuple(column.reshape(shape) for column in block.engine_parameters().T)
    with jax_context():
        jac, aux = _jacobian()(params, device, len(pieces.t0), (block.allow_negative, block.allow_positive),
                             kernel=kernel, static=static, until_rest=horizon.until_rest, batched=bool(shape))
        jac, aux = jax.device_get((jac, aux))
    for i in range(shape[0]) if shape else [None]:
        one = aux if i is None else jax.tree.map(lambda x: x[i], aux)
        _raise_if_bad(solver, block if i is None else block.item(i), one,
                      "" if i is None else f" (parameter set {i})")

    d_mu, d_f, d_bias, _, d_scale = (np.asarray(d) for d in jac)
    derivatives = {
        "mu": d_mu + d_f if block.mu_kinetic is None else d_mu,
        "mu_kinetic": d_f,
        "bias": d_bias,
        "A": d_scale * block.g / motion.peak_acceleration,  # scale = A g / peak
        "scale": d_scale,
    }
    return {name: (float(derivatives[name]) if not shape else derivatives[name]) for name in wrt}


def finite_differences(block, motion, t_end: float | None = None, wrt=DEFAULT_WRT, backend: str = "cvode",
                       step: float = 1e-4, **options) -> dict:
    """Finite differences of u(t_end) on any backend, for checking derivatives.

    Same parameters and units as :func:`sensitivities` (one parameter set). ``step`` is
    relative: mu and mu_kinetic move by step times their value, bias by step times mu,
    and a(t) is scaled by 1 +- step (other models: each parameter by step times its
    value, or by step where it is 0; each component's scale by step). Central differences, or second-order one-sided
    ones where a step would leave the block invalid (at a bound: mu_kinetic = mu,
    |bias| near mu), taken from the valid side.
    """
    if block.batch_shape:
        raise ValueError("finite_differences takes one parameter set; use block.item(i)")
    if not (np.isfinite(step) and 0 < step < 0.1):
        raise ValueError(f"step must be a relative step in (0, 0.1), got {step!r}")
    if block.derivatives != "sliding":
        return _hybrid_differences(block, motion, t_end, wrt, backend, step, options)
    wrt = _names(wrt)

    def u(blk, mot):
        return simulate(blk, mot, t_end=t_end, backend=backend, **options).displacement

    f = block.friction_kinetic
    h_mu, h_f = step * block.mu, step * (f if f > 0 else block.mu)
    d_scale = functools.cache(lambda: _difference(u, lambda s: (block, motion.scaled(1 + s * step))) / step)
    derivatives = {
        "mu": lambda: _difference(u, lambda s: (block.replace(mu=block.mu + s * h_mu), motion)) / h_mu,
        "mu_kinetic": lambda: _difference(u, lambda s: (block.replace(mu_kinetic=f + s * h_f), motion)) / h_f,
        "bias": lambda: _difference(u, lambda s: (block.replace(bias=block.bias + s * h_mu), motion)) / h_mu,
        "A": lambda: d_scale() * block.g / motion.peak_acceleration,
        "scale": d_scale,
    }
    return {name: float(derivatives[name]()) for name in wrt}


def _hybrid_sensitivities(block, motion, t_end, wrt, backend, options):
    """:func:`sensitivities` for a model other than SlidingBlock."""
    from . import _hybrid_sensitivities as hybrid

    if backend_name(backend) != "jax":
        raise ValueError(f"backend={backend!r} has no derivatives for a {type(block).__name__}; use 'jax'")
    if block.batch_shape:  # one located trajectory per parameter set
        sets = [_hybrid_sensitivities(block.item(i), motion, t_end, wrt, backend, options)
                for i in range(block.batch_shape[0])]
        return {name: np.array([one[name] for one in sets]) for name in sets[0]}
    wrt = _hybrid_names(block, wrt, ("mu", "mu_kinetic", "bias_x", "bias_y", "A"))
    peak = _largest_peak(motion) if "A" in wrt else None
    horizon = Horizon.resolve(motion, t_end)
    jacobian = hybrid.displacement_jacobian(block, motion, horizon, make_backend(backend, **options))
    return _by_name(block, jacobian.T, wrt, peak)


def _upthrow_sensitivities(mass, motion, t_end, wrt, backend, of, options):
    """:func:`sensitivities` for a SpringSupportedMass: quantity -> parameter -> float."""
    from . import _hybrid_sensitivities as hybrid
    from ..upthrow._sensitivities import QUANTITIES, flight_quantity_jacobians

    if backend_name(backend) != "jax":
        raise ValueError(f"backend={backend!r} has no derivatives for a SpringSupportedMass; use 'jax'")
    of = tuple(QUANTITIES) if of is None else ((of,) if isinstance(of, str) else tuple(of))
    unknown = [name for name in of if name not in QUANTITIES]
    if unknown or not of:
        raise ValueError(f"of={of!r}: choose among {tuple(QUANTITIES)}")
    wrt = _hybrid_names(mass, wrt, ("frequency", "damping", "A"))
    peak = _largest_peak(motion) if "A" in wrt else None
    horizon = Horizon.resolve(motion, t_end)
    solution, _, events = hybrid.trajectory_sensitivities(mass, motion, horizon, make_backend(backend, **options))
    with jax_context():
        rows = flight_quantity_jacobians(mass, solution, events, of)
    return {quantity: {name: float(value) for name, value in _by_name(mass, row, wrt, peak).items()}
            for quantity, row in rows.items()}


def _by_name(block, columns, wrt, peak):
    """name -> derivative for each name in ``wrt`` from ``columns``, one per parameter
    of :func:`._hybrid_sensitivities.parameter_names`: "A" sums every component's scale
    factor times g / ``peak`` (k = A g / peak), a parameter adds those tied to it."""
    from ._hybrid_sensitivities import parameter_names

    column = dict(zip(parameter_names(block), columns))
    derivatives = {}
    for name in wrt:
        if name == "A":  # every component scaled by k = A g / peak
            derivatives[name] = sum(column[f"A_{c}"] for c in block.component_names) * block.g / peak
        else:
            derivatives[name] = column[name] + sum(column[tied] for tied in block.tied_parameters().get(name, ()))
    return derivatives


def _hybrid_differences(block, motion, t_end, wrt, backend, step, options):
    """:func:`finite_differences` for a model other than SlidingBlock."""
    wrt = _hybrid_names(block, wrt, ())
    motion = motion if isinstance(motion, BaseMotion) else BaseMotion(motion)

    def u(blk, mot):
        return simulate(blk, mot, t_end=t_end, backend=backend, **options).displacement

    def parameter(name):
        value = block.parameters()[name]
        h = step * (abs(value) if value != 0 else 1.0)
        return _difference(u, lambda s: (block.replace_parameter(name, value + s * h), motion)) / h

    def scale(names):
        return _difference(u, lambda s: (block, motion.scaled_components(**{c: 1 + s * step for c in names}))) / step

    derivatives = {}
    for name in wrt:
        if name == "A":
            derivatives[name] = scale(block.component_names) * block.g / _largest_peak(motion)
        elif name.startswith("A_"):
            derivatives[name] = scale((name[2:],))
        else:
            derivatives[name] = parameter(name)
    return derivatives


def _hybrid_names(block, wrt, default):
    from ._hybrid_sensitivities import parameter_names

    known = parameter_names(block) + ("A",)
    wrt = default if wrt is None else wrt
    wrt = (wrt,) if isinstance(wrt, str) else tuple(wrt)
    unknown = [name for name in wrt if name not in known]
    if unknown or not wrt:
        raise ValueError(f"wrt={wrt!r}: choose among {known}")
    return wrt


def _largest_peak(motion):
    """The largest peak acceleration of the motion's components [m/s²] (> 0)."""
    peak = motion.peak_acceleration
    peak = max(peak) if isinstance(peak, tuple) else float(peak)
    if not peak > 0:
        raise ValueError(f"'A' needs a motion with a nonzero peak acceleration, got {peak} m/s²")
    return peak


def _difference(u, change):
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


def _differentiated(backend):
    """The backend whose kernel is differentiated: for "exact" (or a :class:`~blockdae.Exact`)
    the JAX kernel of the same closed forms, "exact-jax" (at the object's window)."""
    if isinstance(backend, AbstractBackend) and backend.name == "exact":
        return make_backend("exact-jax", window=backend.window)
    return "exact-jax" if backend == "exact" else backend


def _names(wrt):
    wrt = (wrt,) if isinstance(wrt, str) else tuple(wrt)
    unknown = [name for name in wrt if name not in UNITS]
    if unknown or not wrt:
        raise ValueError(f"wrt={wrt!r}: choose among {tuple(UNITS)}")
    return wrt


def _kernel(solver, block, pieces):
    """(kernel name, its static settings, the pieces padded for it)."""
    from ..engines._exact_jax import _device, _kernel_input
    from ..sliding._twin import _config

    if solver.name == "exact-jax":
        return "exact", (solver.window, pieces.has_sine), _kernel_input(pieces, solver.window)
    return "jax", _config(block, pieces, solver), _device(pieces, 1)


def _final_u(params, pieces, n_pieces, allowed, *, kernel, static, until_rest):
    """u(t_end) [m], and what tells whether the run was sound."""
    if kernel == "exact":
        from ..engines import _exact_kernel

        window, is_sine = static
        _, _, rests, finished = out = _exact_kernel._run(params, allowed, pieces, n_pieces, until_rest,
                                                         window=window, log_capacity=0, is_sine=is_sine)
        return out[0].u, (rests, finished)
    from ..engines import _jax_kernel

    final, _, rests, flags, _ = _jax_kernel._run(params, pieces, cfg=static, until_rest=until_rest, full_output=False)
    return final.u, (rests, flags)


@functools.cache
def _jacobian():
    """:func:`_jacobian_of_u`, compiled (JAX loads on the first call)."""
    import jax

    return jax.jit(_jacobian_of_u, static_argnames=("kernel", "static", "until_rest", "batched"))


def _jacobian_of_u(params, pieces, n_pieces, allowed, *, kernel, static, until_rest, batched):
    """d u / d (mu, f, bias, g, scale), for one parameter set or mapped over a batch."""
    import jax

    fun = jax.jacfwd(functools.partial(_final_u, pieces=pieces, n_pieces=n_pieces, allowed=allowed, kernel=kernel,
                                       static=static, until_rest=until_rest), has_aux=True)
    return jax.lax.map(fun, params) if batched else fun(params)  # map, not vmap: see run_batch


def _raise_if_bad(solver, block, aux, where):
    from ..sliding._twin import _check

    if solver.name == "exact-jax":
        check(block, *aux, where)
    else:
        _check(block, *aux, solver, where)
