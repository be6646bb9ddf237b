"""Solver backends behind one contract (:class:`AbstractBackend`), by name or as objects.

``simulate(..., backend=...)`` takes a registered name (``available()``) with the
backend's options beside it, or a backend object configured already:
``backend="cvode", rtol=1e-12`` and ``backend=bd.CVODE(rtol=1e-12)`` run the same
backend. :func:`register_backend` adds a name.
"""

import functools
import importlib

from ._backend import AbstractBackend, Horizon

# name -> a class or "module:class", imported on first use so that unused solvers cost nothing
_REGISTRY = {
    "exact": "blockdae.solvers._exact:Exact",
    "exact-jax": "blockdae.solvers._exact:ExactJax",
    "cvode": "blockdae.solvers._cvode:CVODE",
    "ida": "blockdae.solvers._ida:IDA",
    "jax": "blockdae.solvers._jax:JaxTwin",
    "compiled": "blockdae.solvers._compiled:Compiled",
}
#: the names the package registers itself; register_backend does not replace them
BUILT_IN = tuple(_REGISTRY)


def available(model=None) -> tuple[str, ...]:
    """Names accepted by ``simulate(..., backend=...)``; with ``model``, those that run it."""
    return tuple(name for name in _REGISTRY if model is None or make_backend(name).runs(model))


def make_backend(backend, **options) -> AbstractBackend:
    """The backend ``backend`` names, configured with ``options`` (none: its defaults),
    or ``backend`` itself where it is a backend object (options are then an error: an
    object carries its own)."""
    if isinstance(backend, str):
        if backend not in _REGISTRY:
            raise ValueError(f"backend={backend!r} is unknown; choose one of {available()}")
        if not options:
            return _default_backend(backend)
        try:
            return backend_class(backend)(**options)
        except TypeError as err:
            raise TypeError(f"backend {backend!r}: {err}") from None
    if isinstance(backend, AbstractBackend):
        if options:
            names = sorted(options)
            raise TypeError(f"backend={backend!r} carries its own settings: give {', '.join(names)} to it "
                            f"({type(backend).__name__}({names[0]}=...)), not beside it")
        return backend
    raise TypeError(f"backend must be a name from {available()} or a backend object (an AbstractBackend), "
                    f"got {type(backend).__name__}")


def backend_name(backend) -> str:
    """The name of ``backend``: a backend object's ``name``, or ``backend`` as given."""
    return backend.name if isinstance(backend, AbstractBackend) else backend


def register_backend(name: str, backend) -> None:
    """Make ``backend`` available as ``simulate(..., backend=name)``.

    Args:
        name: the name users pass, e.g. "cvode-tight"; not one of :data:`BUILT_IN`.
            Registering a name again replaces its backend.
        backend: a subclass of :class:`AbstractBackend` whose ``name`` is ``name``, or
            "module:Class" naming one, imported on first use (so that registering a
            backend costs nothing until it runs). Its options are its constructor's
            keyword arguments, and it must construct with none (its defaults), for
            :func:`available` and for ``backend=name`` without options.
    """
    if not (isinstance(name, str) and name):
        raise ValueError(f"name must be a non-empty string, got {name!r}")
    if name in BUILT_IN:
        raise ValueError(f"backend {name!r} is built in and cannot be replaced; register another name")
    if isinstance(backend, str):
        if backend.count(":") != 1 or not all(backend.split(":")):
            raise ValueError(f"backend={backend!r}: give a class or 'module:Class'")
    else:
        _check_class(name, backend)
    _REGISTRY[name] = backend
    backend_class.cache_clear()
    _default_backend.cache_clear()


@functools.cache
def backend_class(name: str) -> type:
    """The class registered as ``name`` (imported on first use)."""
    target = _REGISTRY[name]
    if not isinstance(target, str):
        return target
    module, cls = target.split(":")
    return _check_class(name, getattr(importlib.import_module(module), cls))


@functools.cache
def _default_backend(name: str) -> AbstractBackend:
    """The backend called ``name`` with its defaults: one object per name (backends are immutable)."""
    return backend_class(name)()


def _check_class(name, cls) -> type:
    if not (isinstance(cls, type) and issubclass(cls, AbstractBackend)):
        raise TypeError(f"backend {name!r}: {cls!r} is not a subclass of blockdae.backends.AbstractBackend")
    if getattr(cls, "name", None) != name:
        raise ValueError(f"backend {name!r}: {cls.__name__}.name is {getattr(cls, 'name', None)!r}; set it to "
                         f"{name!r} (a backend's results carry its name)")
    return cls


__all__ = ["AbstractBackend", "BUILT_IN", "Horizon", "available", "backend_class", "backend_name", "make_backend",
           "register_backend"]
