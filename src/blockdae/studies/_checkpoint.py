"""Study checkpoints: each finished task saved as it completes; a rerun skips them.

A checkpoint folder holds ``manifest.json``, what the study is (the grid and settings,
the records' names, sample steps [s], sample counts and SHA-256 of their samples, the
records per task, the blockdae version, and the SHA-256 of each task's table once it is
saved), and one table per finished task, ``task-000012.csv`` (written by
:func:`save_study`: atomically, floats to the last bit, a row-count footer). A rerun with
the same study loads the finished tasks and runs the others, so its table is
bit-identical to an uninterrupted run's; a rerun of another study is refused
(:class:`ValueError` naming the folder and what differs), and so is a task's table that
was changed after it was saved (its SHA-256 is not the manifest's: ValueError naming the
file). A table whose hash the manifest lacks (the run was killed between the two
writes) is run again.
"""

import dataclasses
import hashlib
import importlib.metadata
import json
import pathlib
import reprlib

import numpy as np

from ..core import FILES, record_file, recorded, write_manifest
from ._io import load_study, save_study

MANIFEST = "manifest.json"
_BRIEF = reprlib.Repr()  # values in errors: long lists cut, names and strings whole
_BRIEF.maxstring = _BRIEF.maxother = 400
#: the layout of a checkpoint folder; another one is refused
FORMAT = 1


class Checkpoint:
    """A checkpoint folder of one study; :meth:`open` creates or checks it."""

    def __init__(self, folder: pathlib.Path, manifest, tasks, rows_per_record):
        self.folder = folder
        self._manifest = manifest
        self._tasks = tasks
        self._rows_per_record = rows_per_record

    @classmethod
    def open(cls, folder, records, grid, tasks) -> "Checkpoint":
        """The checkpoint of the study (``records``, ``grid``, ``tasks``) in ``folder``:
        a new or empty folder gets the study's manifest; one with a manifest must hold
        the same study (else ValueError naming the folder and what differs)."""
        folder = pathlib.Path(folder)
        manifest = _manifest(records, grid, tasks)
        path = folder / MANIFEST
        if path.is_file():
            saved = _read_manifest(path)
            _check_same_study(folder, saved, manifest)
            manifest = saved
        else:
            _check_new_folder(folder)
            folder.mkdir(parents=True, exist_ok=True)
            write_manifest(path, manifest)
        return cls(folder, manifest, tasks, grid.rows_per_record)

    def path(self, index) -> pathlib.Path:
        """The table of task ``index``."""
        return self.folder / f"task-{index:06d}.csv"

    def finished(self) -> dict:
        """Task index -> columns (as :func:`run_task` returns them) of every saved task
        whose SHA-256 the manifest holds (ValueError naming a file that was changed since)."""
        parts = {}
        for i in range(len(self._tasks)):
            if self.path(i).is_file():
                part = self._load(i)  # its records checked first: the more telling error
                if recorded(self._manifest, self.path(i)):
                    parts[i] = part
        return parts

    def save(self, index, part):
        """Save the columns ``part`` of task ``index``, atomically, then its SHA-256 in the manifest."""
        import pandas as pd

        record_file(self.folder / MANIFEST, self._manifest, save_study(pd.DataFrame(part), self.path(index)))

    def _load(self, index):
        """The columns of task ``index`` as :func:`run_task` returned them (checked: its records, its rows)."""
        path = self.path(index)
        table = load_study(path)
        names = [motion_name(r) for r in self._tasks[index]]
        expected = np.repeat(np.asarray(names), self._rows_per_record)
        got = table.pop("record").fillna("").to_numpy(dtype=str)  # load_study reads "" as NaN
        if not np.array_equal(got, expected):
            raise ValueError(f"{path}: {len(got)} rows of records {_BRIEF.repr(list(dict.fromkeys(got.tolist())))}, "
                             f"expected {self._rows_per_record} rows of each of {_BRIEF.repr(names)}: delete "
                             "the file to run the task again")
        return {"record": expected, **{k: v.to_numpy() for k, v in table.items()}}


def _manifest(records, grid, tasks) -> dict:
    """What a study is, as JSON values (floats by their repr: exact)."""
    settings = {f.name: _plain(getattr(grid, f.name)) for f in dataclasses.fields(grid)
                if f.name not in ("by", "parameter", "column", "values")}
    settings[grid.by] = settings.pop("factors")  # "pga" or "scale", as study names them
    settings[grid.parameter] = settings.pop("sweep")  # "mu" or "ky" as study names them: numbers, or ky tables
    manifest = {"format": FORMAT, "blockdae": _version(), **settings,
                "records_per_task": len(tasks[0]), "records": [_fingerprint(r) for r in records]}
    return json.loads(json.dumps(manifest, default=_number))  # tuples as lists, as read back


def _number(value):
    """A NumPy scalar (e.g. ``refine=np.int64(4)``) as the Python number json writes."""
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"{value!r} ({type(value).__name__}) has no JSON form")


def _plain(value):
    """``value`` as JSON values: arrays as lists, floors and ky tables as their fields."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    if dataclasses.is_dataclass(value):
        return dataclasses.asdict(value)
    return value


def motion_name(motion) -> str:
    """A record's name; a three-component motion's: its components' names joined by " + "."""
    if hasattr(motion, "components"):
        return " + ".join(c.name for c in motion.components if c is not None)
    return motion.name


def _fingerprint(record) -> dict:
    """A record's name, sample step [s], sample count and the SHA-256 of its samples (a
    three-component motion's: those of its components)."""
    if hasattr(record, "components"):
        return {"name": motion_name(record),
                "components": [None if c is None else _fingerprint(c) for c in record.components]}
    samples = np.ascontiguousarray(record.acceleration_samples, dtype=np.float64)
    return {"name": record.name, "dt": record.dt, "samples": int(samples.size),
            "sha256": hashlib.sha256(samples.tobytes()).hexdigest()}


def _version():
    try:
        return importlib.metadata.version("blockdae")
    except importlib.metadata.PackageNotFoundError:  # run from a source tree
        return "unknown"


def _read_manifest(path) -> dict:
    """The manifest at ``path``; ValueError naming it if it is not one."""
    try:
        saved = json.loads(path.read_text())
    except ValueError as err:  # JSONDecodeError, UnicodeDecodeError
        raise ValueError(f"{path}: not a study checkpoint's manifest ({err})") from None
    if not isinstance(saved, dict):
        raise ValueError(f"{path}: not a study checkpoint's manifest (a JSON object)")
    return saved


def _check_new_folder(folder):
    """A folder for a new checkpoint: absent, or an empty folder."""
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"checkpoint {folder}: not a folder")
    if folder.is_dir() and any(folder.iterdir()):
        raise ValueError(f"checkpoint {folder}: the folder holds files but no {MANIFEST}, so it is no study's "
                         "checkpoint; give a new or an empty folder")


def _check_same_study(folder, saved, now):
    """Raise ValueError naming ``folder`` and what differs if the ``saved`` manifest is not ``now``'s."""
    keys = [key for key in saved if key != FILES] + [key for key in now if key not in saved]
    differences = [_difference(key, saved.get(key), now.get(key)) for key in keys if saved.get(key) != now.get(key)]
    if differences:
        raise ValueError(f"checkpoint {folder} holds another study: {'; '.join(differences)}. Rerun with the "
                         "same arguments to resume it, or give a new or an empty folder")


def _difference(key, saved, now):
    """One difference of two manifests, said briefly."""
    if key != "records" or saved is None or now is None:
        return f"{key} was {_BRIEF.repr(saved)}, now {_BRIEF.repr(now)}"
    old, new = {r["name"]: r for r in saved}, {r["name"]: r for r in now}
    parts = [f"{what} {_BRIEF.repr(names)}" for what, names in (
        ("new records", [n for n in new if n not in old]), ("records left out", [n for n in old if n not in new]),
        ("records with other samples", [n for n in new if n in old and new[n] != old[n]])) if names]
    return "records: " + (", ".join(parts) or "another order")
