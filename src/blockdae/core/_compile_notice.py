"""One line before a compile that makes the user wait: :class:`CompileNotice`, said
once per process per engine (the JAX kernels, each numba engine), naming the user's line.

A numba engine is announced only when a compile is about to happen: the dispatcher has
no compiled signature in this process and numba's disk cache holds no current index for
it (a load from the cache takes under a second and is not announced).
"""

import contextlib
import pathlib
import sys
import warnings

_PACKAGE = str(pathlib.Path(__file__).resolve().parents[1])  # the blockdae folder
_noticed: set[str] = set()  # engines announced, or looked at and found compiled, in this process


class CompileNotice(UserWarning):
    """Said once per process per engine, before blockdae compiles that engine's kernels
    (JAX: up to about 15 s after an install, about 5 s in a later process; numba: 7 to
    14 s per engine after an install or upgrade, then loaded from its disk cache in under
    a second; CPU times measured by ``benchmarks/cold_start.py``). Silence it
    with ``warnings.filterwarnings("ignore", category=blockdae.CompileNotice)``."""


def notice(engine: str, what: str) -> None:
    """Warn once per process for ``engine``: blockdae is compiling ``what`` (a phrase
    ending with the expected pause in parentheses)."""
    if engine in _noticed:
        return
    _noticed.add(engine)
    warnings.warn(f"blockdae: compiling {what}. "
                  "Silence: warnings.filterwarnings('ignore', category=blockdae.CompileNotice)", CompileNotice,
                  stacklevel=_callers_level())


def notice_numba(engine: str, seconds: float, *dispatchers) -> None:
    """:func:`notice` for a numba ``engine`` (its compile takes about ``seconds`` [s])
    whose ``dispatchers`` are about to be called, if one of them will compile (see the
    module's docstring). Looked at once per process: a dispatcher that has loaded or
    compiled its kernel keeps it (asking numba on every call cost a fifth of a warm run)."""
    if engine in _noticed:
        return
    if any(_will_compile(d) for d in dispatchers):
        notice(engine, f"{engine} with numba (its first run after an install or upgrade; about {seconds:g} s, "
                       f"then loaded from numba's disk cache)")
    _noticed.add(engine)


def _will_compile(dispatcher) -> bool:
    """True if ``dispatcher`` has no compiled signature in this process and numba's disk
    cache has no current index for it; False (say nothing) where numba's private cache
    object is not as ``numba/core/caching.py`` keeps it, a notice must never stop a run."""
    if dispatcher.signatures:
        return False
    try:
        return not dispatcher._cache._cache_file._load_index()  # {} if absent, stale or another numba's
    except Exception:  # noqa: BLE001
        return False


def _callers_level() -> int:
    """The ``stacklevel`` that names the first caller outside blockdae and contextlib (the
    user's line), counted from the function that calls this one."""
    frame, level = sys._getframe(2), 2
    while frame.f_back is not None and (frame.f_code.co_filename.startswith(_PACKAGE)
                                        or frame.f_code.co_filename == contextlib.__file__):
        frame, level = frame.f_back, level + 1
    return level
