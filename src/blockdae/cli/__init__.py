"""The ``blockdae`` command: one entry point (:func:`main`), a module per system or tool."""

from ._main import main

__all__ = ["main"]
