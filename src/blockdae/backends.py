"""The backends by name: the registry (:func:`available`, :func:`make_backend`,
:func:`register_backend`) and the backend contract (:class:`AbstractBackend`, :class:`Horizon`);
the backend classes themselves are ``blockdae.Exact``, ``blockdae.CVODE``, ... ."""

from .core import (BUILT_IN, AbstractBackend, Horizon, available, backend_class, backend_name, make_backend,
                   register_backend, set_compilation_cache)

__all__ = ["BUILT_IN", "AbstractBackend", "Horizon", "available", "backend_class", "backend_name", "make_backend",
           "register_backend", "set_compilation_cache"]
