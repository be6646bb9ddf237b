"""Warnings caught as lines, one catch at a time: ``warnings.catch_warnings`` is process-wide,
and the app reads files and runs analyses on threads of their own."""

import contextlib
import threading
import warnings

from ..core import CompileNotice

_ONE_AT_A_TIME = threading.Lock()


@contextlib.contextmanager
def caught_warnings():
    """A list that holds, after the block, the message of each warning raised in it, once
    each (the notice that the solvers compile left out: it is no remark on the input)."""
    lines = []
    with _ONE_AT_A_TIME, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield lines
    lines.extend(dict.fromkeys(str(w.message) for w in caught if not issubclass(w.category, CompileNotice)))
