"""The 1-D block's own derivatives: forward-mode differentiation (``jax.jacfwd``) of
its compiled kernels, the exact backend's closed forms or the diffrax twin.
Derivatives pass through the event times by the implicit function theorem at each
guard, not through a smoothed model.

Where u is not differentiable (a sliding episode starts exactly at the threshold,
|sigma| = mu g, and the demand turns back there), the result is the derivative of
the branch the transition rule takes: a demand that touches the threshold and
turns back does not slide, so the new episode is absent and the value is the
one-sided derivative from the side without it (A below, mu above the threshold).
With f < mu the displacement itself jumps there.
"""

import functools

import numpy as np

from ._model import PARAMETER_UNITS


def kernel_sensitivities(block, motion, t_end, wrt, backend, of, options):
    """:meth:`SlidingBlock.sensitivities`: d u(t_end) / d p [m per unit of p; m/g for "A"]
    for p in ``wrt`` (names of :data:`PARAMETER_UNITS`), through the kernel of ``backend``
    ("exact": the JAX kernel of "exact-jax"; "jax"; None: "exact"): a
    :class:`~blockdae.Sensitivities` of u (n parameter sets for a batch)."""
    if of is not None:
        raise ValueError(f"of={of!r} does not apply to a SlidingBlock: it has the derivatives of its displacement")
    from ..core import Horizon, backend_name, make_backend  # here: the backends import this package
    from ..core.derivatives import Sensitivities, checked_wrt, jax_context

    backend = "exact" if backend is None else backend
    wrt = checked_wrt(block, wrt, PARAMETER_UNITS)
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
    return Sensitivities.make(block, {name: derivatives[name] for name in wrt}, backend=backend)


def block_differences(block, motion, t_end, wrt, backend, step, options) -> dict:
    """:meth:`SlidingBlock.finite_differences`: finite differences of u(t_end) on ``backend``:
    mu and mu_kinetic move by ``step`` times their value, bias by step times mu, and
    a(t) is scaled by 1 +- step."""
    from ..core.derivatives import checked_wrt, simulate, step_difference

    wrt = checked_wrt(block, wrt, PARAMETER_UNITS)

    def u(blk, mot):
        return simulate(blk, mot, t_end=t_end, backend=backend, **options).displacement

    f = block.friction_kinetic
    h_mu, h_f = step * block.mu, step * (f if f > 0 else block.mu)
    d_scale = functools.cache(lambda: step_difference(u, lambda s: (block, motion.scaled(1 + s * step))) / step)
    derivatives = {
        "mu": lambda: step_difference(u, lambda s: (block.replace(mu=block.mu + s * h_mu), motion)) / h_mu,
        "mu_kinetic": lambda: step_difference(u, lambda s: (block.replace(mu_kinetic=f + s * h_f), motion)) / h_f,
        "bias": lambda: step_difference(u, lambda s: (block.replace(bias=block.bias + s * h_mu), motion)) / h_mu,
        "A": lambda: d_scale() * block.g / motion.peak_acceleration,
        "scale": d_scale,
    }
    return {name: float(derivatives[name]()) for name in wrt}


def _differentiated(backend):
    """The backend whose kernel is differentiated: for "exact" (or an :class:`~blockdae.Exact`)
    the JAX kernel of the same closed forms, "exact-jax" (at the object's window)."""
    from ..core import AbstractBackend, make_backend

    if isinstance(backend, AbstractBackend) and backend.name == "exact":
        return make_backend("exact-jax", window=backend.window)
    return "exact-jax" if backend == "exact" else backend


def _kernel(solver, block, pieces):
    """(kernel name, its static settings, the pieces padded for it)."""
    from ._exact_jax import _device, _kernel_input
    from ._twin import _config

    if solver.name == "exact-jax":
        return "exact", (solver.window, pieces.has_sine), _kernel_input(pieces, solver.window)
    return "jax", _config(block, pieces, solver), _device(pieces, 1)


def _final_u(params, pieces, n_pieces, allowed, *, kernel, static, until_rest):
    """u(t_end) [m], and what tells whether the run was sound."""
    if kernel == "exact":
        from . import _exact_kernel

        window, is_sine = static
        _, _, rests, finished = out = _exact_kernel._run(params, allowed, pieces, n_pieces, until_rest,
                                                         window=window, log_capacity=0, is_sine=is_sine)
        return out[0].u, (rests, finished)
    from . import _jax_kernel

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
    from ._results import check
    from ._twin import _check

    if solver.name == "exact-jax":
        check(block, *aux, where)
    else:
        _check(block, *aux, solver, where)
