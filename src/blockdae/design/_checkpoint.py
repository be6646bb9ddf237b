"""Design-study checkpoints: each finished block of runs saved as it completes (by
:func:`blockdae.save_study`: atomically, floats to the last bit); a rerun of the same
study reads them back, checks that its samplers draw the very parameter sets saved, and
runs only the blocks still missing, so its result is bit-identical to an uninterrupted
run's. A rerun of another study is refused (ValueError naming the folder and what differs).

A folder holds ``manifest.json`` (what the study is: the model, the parameters, the
target PGAs, the sampling, the seed, the correlation, the blocks, each record's name,
sample step [s], sample count and SHA-256 of its samples, and the SHA-256 of each block's
table once it is saved) and ``block-000003.csv`` per finished block. A block's table
changed after it was saved (its SHA-256 is not the manifest's) is refused (ValueError
naming the file); one whose hash the manifest lacks (the run was killed between the two
writes) is run again."""

import hashlib
import json
import pathlib

import numpy as np

from ..core import FILES, record_file, recorded, write_manifest
from ..studies import load_study, save_study

MANIFEST = "manifest.json"
#: the layout of a checkpoint folder; another one is refused
FORMAT = 1


def manifest(entries, model, parameters, sampling, seed, correlation, runs_per_block) -> dict:
    """What a design study is, as JSON values (floats and distributions by their repr)."""
    records = [{"name": name, "pga_g": pga} | _fingerprint(record) for name, record, pga in entries]
    return {"format": FORMAT, "model": repr(model), "parameters": {k: repr(v) for k, v in parameters.items()},
            "sampling": sampling, "seed": repr(seed), "correlation": repr(correlation),
            "runs_per_block": runs_per_block, "records": records}


def _fingerprint(record) -> dict:
    """A Record's sample step [s], sample count and SHA-256 of its samples; a
    BaseMotion's of each of its components (x, y, z) present."""
    components = getattr(record, "components", None)
    if components is not None:
        return {axis: _fingerprint(c) for axis, c in zip("xyz", components) if c is not None}
    samples = np.ascontiguousarray(record.acceleration_samples, dtype=np.float64)
    return {"dt": record.dt, "samples": int(samples.size), "sha256": hashlib.sha256(samples.tobytes()).hexdigest()}


class Checkpoint:
    """The checkpoint folder of one design study."""

    def __init__(self, folder, study):
        self.folder = pathlib.Path(folder)
        self._path = path = self.folder / MANIFEST
        self._manifest = study
        if path.is_file():
            try:
                saved = json.loads(path.read_text())
            except ValueError as err:
                raise ValueError(f"{path}: not a design checkpoint's manifest ({err})") from None
            differences = [key for key in sorted((set(saved) | set(study)) - {FILES})
                           if saved.get(key) != study.get(key)]
            if differences:
                raise ValueError(f"checkpoint {self.folder} holds another study: its "
                                 f"{', '.join(differences)} differ. Rerun with the same arguments to resume it, or "
                                 "give a new or an empty folder")
            self._manifest = saved
        else:
            if self.folder.exists() and (not self.folder.is_dir() or any(self.folder.iterdir())):
                raise ValueError(f"checkpoint {self.folder}: not a new or an empty folder, and no {MANIFEST} in it")
            self.folder.mkdir(parents=True, exist_ok=True)
            write_manifest(path, study)

    def path(self, index) -> pathlib.Path:
        """The table of block ``index``."""
        return self.folder / f"block-{index:06d}.csv"

    def load(self, index):
        """The saved table of block ``index``, or None (none saved, or its SHA-256 not in the
        manifest); ValueError naming a file changed since it was saved."""
        path = self.path(index)
        return load_study(path) if path.is_file() and recorded(self._manifest, path) else None

    def save(self, index, table):
        """Save block ``index``'s table, atomically, then its SHA-256 in the manifest."""
        record_file(self._path, self._manifest, save_study(table, self.path(index)))
