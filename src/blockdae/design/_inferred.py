"""The parameter a back-analysis infers: one of a design model's parameters with a prior,
the others held at given values, and the model's D [m] as a function of it, in NumPy
and in JAX (differentiable through the model's own dD/dp: :meth:`DesignModel.gradient`,
called back from JAX with ``jax.pure_callback`` inside a ``jax.custom_jvp``, its float64
arguments and values passed as their bits so that JAX's float64 is needed only on the
calling thread)."""

import dataclasses

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


@dataclasses.dataclass(frozen=True)
class InferredParameter:
    """``name`` of ``model`` with its ``prior``; ``fixed`` (name -> number) the values
    of the model's other parameters."""

    model: DesignModel
    name: str
    prior: object
    fixed: dict

    @property
    def unit(self) -> str:
        """The parameter's unit (the model's)."""
        return self.model.PARAMETERS[self.name]

    @property
    def column(self) -> str:
        """Its column in tables (``ky_g``, ``vs_m_s``, the plane's ``mu``)."""
        return column_name(self.name, self.model)

    def displacements(self, record, pga_g, value, derivative=False):
        """D [m] of ``record`` scaled to ``pga_g`` [g] at each ``value`` of the parameter
        (an array, any shape), and with ``derivative`` dD/d(parameter) [m per its unit]:
        one batched call of the model. Where the parameter is the model's design
        parameter, D = 0 and dD/dp = 0 from the model's sliding limit on (the model is run
        at half the limit there, so that every call has the batch's shape)."""
        value = np.asarray(value, dtype=float)
        flat = value.reshape(-1)
        values = {name: np.full(flat.shape, v) for name, v in self.fixed.items()} | {self.name: flat}
        slides = np.ones(flat.shape, dtype=bool)
        if self.name == self.model.DESIGN:
            limit = self.model.sliding_limit(record, pga_g, values)
            slides = flat < limit
            values[self.name] = np.where(slides, flat, 0.5 * limit)
        if not derivative:
            d = self.model.displacements(record, pga_g, values)
            return np.where(slides, d, 0.0).reshape(value.shape)
        d, slopes = self.model.gradient(record, pga_g, values, (self.name,))
        return (np.where(slides, d, 0.0).reshape(value.shape),
                np.where(slides, slopes[self.name], 0.0).reshape(value.shape))

    def displacement_function(self, record, pga_g):
        """D [m] of ``record`` scaled to ``pga_g`` [g] as a JAX function of the parameter's
        value (any shape): the model's D, and in a derivative its dD/dp (a
        ``jax.custom_jvp`` around ``jax.pure_callback``; batches under ``jax.vmap`` into one
        model call)."""
        import jax
        import jax.numpy as jnp

        def call(value, derivative):
            if jax.dtypes.canonicalize_dtype(np.float64) != np.float64:
                raise ValueError("the model's D is passed to JAX in float64, and JAX is in float32 here: evaluate "
                                 "the log posterior inside `with jax.enable_x64(True):`")
            bits = jax.ShapeDtypeStruct(jnp.shape(value) + (2,), jnp.uint32)
            out = jax.pure_callback(lambda v: _as_bits(self.displacements(record, pga_g, _from_bits(v), derivative)),
                                    (bits, bits) if derivative else bits,
                                    jax.lax.bitcast_convert_type(jnp.asarray(value, jnp.float64), jnp.uint32),
                                    vmap_method="broadcast_all")
            return jax.tree.map(lambda b: jax.lax.bitcast_convert_type(b, jnp.float64), out)

        @jax.custom_jvp
        def displacement(value):
            return call(value, False)

        @displacement.defjvp
        def _jvp(primals, tangents):
            d, slope = call(primals[0], True)
            return d, slope * tangents[0]

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


def inferred_parameter(model, priors) -> InferredParameter:
    """The parameter ``priors`` (name -> a distribution for the one inferred, a number
    for each held) gives ``model``, checked: one distribution, every required parameter
    given, none the model lacks, a parameter the model differentiates D by, a prior
    of positive values (the Laplace approximation is normal in its logarithm)."""
    if not isinstance(priors, dict):
        raise ValueError(f"priors must be a dict name -> a distribution (the parameter inferred) or a number (one "
                         f"held fixed), got {priors!r}")
    fixed, uncertain = split_parameters(priors, model)
    if len(uncertain) != 1:
        raise ValueError(f"back_analysis infers one parameter of the {model.kind} model: give it a distribution and "
                         f"the others numbers; got distributions for {list(uncertain) or 'none'}")
    (name, prior), = uncertain.items()
    unit = model.PARAMETERS[name]
    if name not in model.differentiable:
        raise ValueError(f"the {model.kind} model gives no dD/d{name}, and back_analysis needs it (the maximum a "
                         "posteriori, its Laplace approximation and NUTS all follow the log posterior's gradient); "
                         f"it differentiates D by {list(model.differentiable) or 'no parameter'}. A DesignModel of "
                         "your own gives one through has_derivative (dD/d DESIGN from displacements) or "
                         "differentiable and gradient()")
    low, _ = support(prior)
    if low < 0:
        raise ValueError(f"priors[{name!r}]={prior!r} gives {name} < 0 [{unit}] a probability; truncate it "
                         "(design.Truncated(..., low=0)) or use a LogNormal")
    return InferredParameter(model, name, prior, fixed)
