"""How blockdae runs JAX: float64 inside its own calls, and a persistent compilation
cache so that a kernel compiled once (per shape) is not compiled again in a later process.

The cache folder is ``$BLOCKDAE_CACHE_DIR``, else ``$XDG_CACHE_HOME/blockdae/jax``, else
``~/.cache/blockdae/jax``. Set ``BLOCKDAE_CACHE_DIR=off`` (or call
``set_compilation_cache(None)``) to keep none. A cache folder the user set in JAX's own
configuration is left as it is. Nothing is configured at import: only on the first
compiled call, which a one-line :class:`CompileNotice` announces (once per process).
"""

import contextlib
import os
import pathlib

from ._compile_notice import notice

_OFF = ("", "off", "none", "0")
_DEFAULT = object()  # no folder chosen: the environment's, unless JAX has one set
_state = {"folder": _DEFAULT, "applied": False}


def default_cache_dir() -> pathlib.Path | None:
    """The folder from the environment, or None if the cache is turned off there."""
    folder = os.environ.get("BLOCKDAE_CACHE_DIR")
    if folder is not None:
        return None if folder.strip().lower() in _OFF else pathlib.Path(folder)
    base = os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache"
    return pathlib.Path(base) / "blockdae" / "jax"


def set_compilation_cache(folder: str | os.PathLike | None) -> None:
    """Keep JAX's compiled kernels in ``folder`` (None: keep no cache) for this process;
    takes effect at the next compiled call (JAX is not imported for it)."""
    _state["folder"] = None if folder is None else pathlib.Path(folder)
    if _state["applied"]:
        _apply(_state["folder"])


def _apply(folder):
    import jax

    jax.config.update("jax_compilation_cache_dir", None if folder is None else str(folder))
    # kernels compile in 0.1-1.5 s; JAX's default keeps only those over 1 s
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.1)


@contextlib.contextmanager
def jax_context():
    """float64 for the calls inside; sets the compilation cache on first use."""
    import jax

    notice("JAX", "its JAX kernels (the first JAX call in this process: up to about 15 s after an install, "
                  "about 5 s once JAX's disk cache holds them)")
    if not _state["applied"]:
        if _state["folder"] is not _DEFAULT:
            _apply(_state["folder"])
        elif jax.config.jax_compilation_cache_dir is None:
            _apply(default_cache_dir())
        _state["applied"] = True
    with jax.enable_x64(True):
        yield

