"""Atomic file writes: a reader sees the old file or the new one, never a part.

Every file the package writes goes through :func:`atomic_path`: the writer fills a
temporary file beside the target (same folder, so the same file system), which is
flushed to disk and renamed onto the target (``os.replace``, atomic on POSIX and
Windows) only once the writer returned. A writer that raises, or is interrupted, leaves
the target as it was and removes the temporary file; only a killed process (SIGKILL,
power loss before the rename) can leave one behind, named ``.NAME.XXXXXXXX.tmpSUFFIX``.
"""

import contextlib
import os
import pathlib
import secrets


@contextlib.contextmanager
def atomic_path(path):
    """A temporary path beside ``path`` to write to; renamed onto ``path`` when the block
    ends without an error, removed when it raises.

    The temporary name keeps the target's suffix (``.png``, ``.csv``, ...), for writers
    that choose a format by it; it is created empty with the usual permissions
    (0o666 less the umask), which the target then has.
    """
    path = pathlib.Path(path)
    temporary = path.with_name(f".{path.stem}.{secrets.token_hex(4)}.tmp{path.suffix}")
    try:
        os.close(os.open(temporary, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))
    except FileNotFoundError:
        raise FileNotFoundError(f"{path}: no such folder, {path.parent}") from None
    try:
        yield temporary
        _flush_to_disk(temporary)
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def _flush_to_disk(path):
    """fsync the file at ``path``: its bytes reach the disk before the rename does."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
