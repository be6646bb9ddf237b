"""Solver backends behind one contract; see :class:`AbstractBackend`."""

import functools
import importlib

from ._base import AbstractBackend, Horizon

# name -> "module:class", imported on first use so that unused solvers cost nothing
_REGISTRY = {
    "exact": "blockdae.solvers._exact:ExactBackend",
    "exact-jax": "blockdae.solvers._exact:ExactJaxBackend",
    "cvode": "blockdae.integrators._cvode:CVODEBackend",
    "ida": "blockdae.integrators._ida:IDABackend",
    "jax": "blockdae.integrators._jax:JaxBackend",
    "compiled": "blockdae.solvers._compiled:CompiledBackend",
}


def available(model=None) -> tuple[str, ...]:
    """Names accepted by ``simulate(..., backend=...)``; with ``model``, those that run it."""
    return tuple(name for name in _REGISTRY if model is None or make_backend(name).runs(model))


def make_backend(name: str, **options) -> AbstractBackend:
    """The backend called ``name``, configured with ``options``."""
    if name not in _REGISTRY:
        raise ValueError(f"backend={name!r} is unknown; choose one of {available()}")
    return _configured(name, options) if options else _with_defaults(name)


@functools.cache
def _with_defaults(name: str) -> AbstractBackend:
    """The backend called ``name`` with its default settings: one object, as backends are immutable."""
    return _configured(name, {})


def _configured(name: str, options: dict) -> AbstractBackend:
    try:
        return _backend_class(name)(**options)
    except TypeError as err:
        raise TypeError(f"backend {name!r}: {err}") from None


@functools.cache
def _backend_class(name: str) -> type:
    module, cls = _REGISTRY[name].split(":")
    return getattr(importlib.import_module(module), cls)


__all__ = ["AbstractBackend", "Horizon", "available", "make_backend"]
