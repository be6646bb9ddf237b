"""The SHA-256 of each file a checkpoint saved, kept in its manifest: a file changed after
it was saved (one digit edited, its footer intact) is refused, never read as a result."""

import hashlib
import json

from ._atomic import atomic_path

#: the manifest's key of the files' hashes: file name -> SHA-256 of its bytes
FILES = "files"


def file_sha256(path) -> str:
    """The SHA-256 of the bytes of the file at ``path`` (hex)."""
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def write_manifest(path, manifest: dict) -> None:
    """Write ``manifest`` (JSON values) to ``path``, atomically."""
    with atomic_path(path) as temporary:
        temporary.write_text(json.dumps(manifest, indent=1) + "\n")


def record_file(manifest_path, manifest: dict, path) -> None:
    """Add the SHA-256 of the file at ``path`` (just saved beside the manifest) to
    ``manifest`` and write the manifest again, atomically."""
    manifest.setdefault(FILES, {})[path.name] = file_sha256(path)
    write_manifest(manifest_path, manifest)


def recorded(manifest: dict, path) -> bool:
    """Whether the file at ``path`` is the one saved: True where its SHA-256 is the one
    ``manifest`` holds, False where the manifest holds none (a save interrupted before its
    hash was written: the work is to be done again). Raises ValueError naming the file
    where the hashes differ (the file was changed after it was saved)."""
    saved = manifest.get(FILES, {}).get(path.name)
    if saved is None:
        return False
    if file_sha256(path) != saved:
        raise ValueError(f"{path}: its SHA-256 differs from the one the checkpoint's manifest recorded when it was "
                         "saved, so the file was changed since; delete it to run its part again")
    return True
