"""The parameters a back-analysis infers: one or several of a design model's parameters,
each with a prior, the others held at given values, and the model's D [m] as a function
of them, in NumPy and in JAX (differentiable through the model's own dD/dp:
:meth:`DesignModel.gradient`, called back from JAX with ``jax.pure_callback`` inside a
``jax.custom_jvp``, its float64 arguments and values passed as their bits so that JAX's
float64 is needed only on the calling thread)."""

import dataclasses
import math

import numpy as np

from ._distributions import LogNormal, Normal, Uniform
from ._models import DesignModel
from ._result import column_name
from ._sampling import split_parameters


def support(prior):
    """(low, high) of ``prior``'s values."""
    if isinstance(prior, LogNormal):
        return 0.0, np.inf
    if isinstance(prior, Normal):
        return -np.inf, np.inf
    if isinstance(prior, Uniform):
        return prior.low, prior.high
    low, high = support(prior.distribution)
    return max(low, -np.inf if prior.low is None else prior.low), min(high, np.inf if prior.high is None
                                                                      else prior.high)


def numpyro_prior(prior):
    """The NumPyro distribution of a :mod:`blockdae.design` distribution."""
    import numpyro.distributions as dist

    if isinstance(prior, LogNormal):
        return dist.LogNormal(math.log(prior.median), prior.sigma_ln)
    if isinstance(prior, Normal):
        return dist.Normal(prior.mean, prior.std)
    if isinstance(prior, Uniform):
        return dist.Uniform(prior.low, prior.high)
    low, high = support(prior)
    parent = prior.distribution
    if isinstance(parent, Uniform):
        return dist.Uniform(low, high)
    if isinstance(parent, LogNormal):  # exp of a truncated normal of ln X
        log_bounds = {"low": math.log(low) if low > 0 else None, "high": math.log(high) if high < math.inf else None}
        return dist.TransformedDistribution(
            dist.TruncatedNormal(math.log(parent.median), parent.sigma_ln, **log_bounds),
            dist.transforms.ExpTransform())
    return dist.TruncatedNormal(parent.mean, parent.std, low=None if low == -math.inf else low,
                                high=None if high == math.inf else high)


@dataclasses.dataclass(frozen=True)
class InferredParameters:
    """The parameters of ``model`` that ``priors`` names (name -> its distribution, or
    None where only D is wanted), in that order; ``fixed`` (name -> number) the values
    of the model's other parameters."""

    model: DesignModel
    priors: dict
    fixed: dict

    @property
    def names(self) -> tuple:
        """The parameters' names, in order."""
        return tuple(self.priors)

    @property
    def units(self) -> dict:
        """name -> the parameter's unit (the model's)."""
        return {name: self.model.PARAMETERS[name] for name in self.names}

    @property
    def columns(self) -> dict:
        """name -> its column in tables (``ky_g``, ``vs_m_s``, the plane's ``mu``)."""
        return {name: column_name(name, self.model) for name in self.names}

    def displacements(self, record, pga_g, values, derivative=False):
        """D [m] of ``record`` scaled to ``pga_g`` [g] at each set of the parameters'
        ``values`` (name -> an array, all of one shape), and with ``derivative`` dD/dp
        [m per unit of p] of each (name -> an array of that shape): one batched call of
        the model. Where the model's design parameter is inferred, D = 0 and dD/dp = 0
        from the model's sliding limit on; those sets run at a stand-in that slides, so
        that the call has the batch's shape (the design parameter alone: at half the
        limit; with others: a set of the batch that slides; none sliding, no call)."""
        shape = np.shape(values[self.names[0]])
        flat = {name: np.asarray(values[name], dtype=float).reshape(-1) for name in self.names}
        n = flat[self.names[0]].size
        sets = {name: np.full(n, v) for name, v in self.fixed.items()} | flat
        slides = np.ones(n, dtype=bool)
        design = self.model.DESIGN
        if design in self.names:
            limit = self.model.sliding_limit(record, pga_g, sets)
            slides = flat[design] < limit
            if len(self.names) == 1:
                sets[design] = np.where(slides, flat[design], 0.5 * limit)
            elif not slides.any():
                zeros = np.zeros(shape)
                return (zeros, {name: zeros for name in self.names}) if derivative else zeros
            else:
                stand_in = np.where(slides, np.arange(n), np.argmax(slides))
                sets = {name: v[stand_in] for name, v in sets.items()}
        if not derivative:
            d = self.model.displacements(record, pga_g, sets)
            return np.where(slides, d, 0.0).reshape(shape)
        d, slopes = self.model.gradient(record, pga_g, sets, self.names)
        return (np.where(slides, d, 0.0).reshape(shape),
                {name: np.where(slides, slopes[name], 0.0).reshape(shape) for name in self.names})

    def displacement_function(self, record, pga_g):
        """D [m] of ``record`` scaled to ``pga_g`` [g] as a JAX function of the parameters'
        values (one argument each, in order; any shape, broadcast together): the model's
        D, and in a derivative its dD/dp (a ``jax.custom_jvp`` around
        ``jax.pure_callback``, its tangent Σ dD/dp_i · dp_i; batches under ``jax.vmap``
        into one model call)."""
        import jax
        import jax.numpy as jnp

        def numpy_call(derivative, *bits):
            values = dict(zip(self.names, (_from_bits(b) for b in bits)))
            out = self.displacements(record, pga_g, values, derivative)
            return _as_bits((out[0], *out[1].values()) if derivative else out)

        def call(values, derivative):
            if jax.dtypes.canonicalize_dtype(np.float64) != np.float64:
                raise ValueError("the model's D is passed to JAX in float64, and JAX is in float32 here: evaluate "
                                 "the log posterior inside `with jax.enable_x64(True):`")
            values = jnp.broadcast_arrays(*(jnp.asarray(v, jnp.float64) for v in values))
            bits = jax.ShapeDtypeStruct(jnp.shape(values[0]) + (2,), jnp.uint32)
            out = jax.pure_callback(lambda *b: numpy_call(derivative, *b),
                                    (bits,) * (1 + len(values)) if derivative else bits,
                                    *(jax.lax.bitcast_convert_type(v, jnp.uint32) for v in values),
                                    vmap_method="broadcast_all")
            return jax.tree.map(lambda b: jax.lax.bitcast_convert_type(b, jnp.float64), out)

        @jax.custom_jvp
        def displacement(*values):
            return call(values, False)

        @displacement.defjvp
        def _jvp(primals, tangents):
            d, *slopes = call(primals, True)
            tangent = slopes[0] * tangents[0]
            for slope, dp in zip(slopes[1:], tangents[1:]):
                tangent = tangent + slope * dp
            return d, tangent

        return displacement


def _from_bits(bits):
    """float64 values from their bits (uint32 pairs along a last axis): the parameter's
    values, passed to the callback as bits, so that an XLA thread does not cast them to
    float32."""
    return np.ascontiguousarray(bits, dtype=np.uint32).view(np.float64)[..., 0]


def _as_bits(arrays):
    """float64 arrays as their bits, uint32 pairs along a last axis: what a JAX callback
    returns intact on any thread (XLA's threads, where a thread-local ``jax.enable_x64``
    does not reach, would cast float64 to float32)."""
    if isinstance(arrays, tuple):
        return tuple(_as_bits(a) for a in arrays)
    return np.ascontiguousarray(arrays, dtype=np.float64).view(np.uint32).reshape(np.shape(arrays) + (2,))


def inferred_parameters(model, priors) -> InferredParameters:
    """The parameters ``priors`` (name -> a distribution for each inferred, a number for
    each held) gives ``model``, checked: at least one distribution, every required
    parameter given, none the model lacks, each inferred one a parameter the model
    differentiates D by, and each prior of positive values (the Laplace approximation is
    normal in their logarithms)."""
    if not isinstance(priors, dict):
        raise ValueError(f"priors must be a dict name -> a distribution (a parameter inferred) or a number (one "
                         f"held fixed), got {priors!r}")
    fixed, uncertain = split_parameters(priors, model)
    if not uncertain:
        raise ValueError(f"back_analysis infers the parameters of the {model.kind} model that priors gives a "
                         "distribution; got none: give each parameter inferred a distribution, the others numbers")
    lacking = [name for name in uncertain if name not in model.differentiable]
    if lacking:
        raise ValueError(f"the {model.kind} model gives no {', '.join('dD/d' + name for name in lacking)}, and "
                         "back_analysis needs it (the maximum a posteriori, its Laplace approximation and NUTS all "
                         "follow the log posterior's gradient); "
                         f"it differentiates D by {list(model.differentiable) or 'no parameter'}. A DesignModel of "
                         "your own gives one through has_derivative (dD/d DESIGN from displacements) or "
                         "differentiable and gradient()")
    for name, prior in uncertain.items():
        low, _ = support(prior)
        if low < 0:
            raise ValueError(f"priors[{name!r}]={prior!r} gives {name} < 0 [{model.PARAMETERS[name]}] a probability; "
                             "truncate it (design.Truncated(..., low=0)) or use a LogNormal")
    return InferredParameters(model, uncertain, fixed)
