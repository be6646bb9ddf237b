"""What the app holds between clicks: the files given to it (kept in a folder of its own),
the analysis running in the background (its progress, a way to stop it) and the last
results. One app serves one user on this computer: one session per app."""

import base64
import dataclasses
import pathlib
import threading
import time

from ._analysis import Settings, analyse
from ._design import DesignJob, DesignSettings, InverseSettings
from ._records import LoadedFile, load


class Job:
    """An analysis of ``records`` (name -> Record) under ``settings`` on a thread of its own,
    one record at a time: progress is counted, and a cancel honoured, between records.

    Attributes (read while it runs): done and total (records), rows (the table so far),
    notes (warnings, one line each), errors (records the library refused, one line each),
    cancelled and finished (threading.Event), seconds (its wall time when finished [s]).
    """

    def __init__(self, records: dict, settings: Settings):
        self.records, self.settings = dict(records), settings
        self.total, self.done = len(self.records), 0
        self.rows, self.notes, self.errors = [], [], []
        self.cancelled, self.finished = threading.Event(), threading.Event()
        self.seconds = None
        self._start = time.perf_counter()
        threading.Thread(target=self._run, name="blockdae-app-analysis", daemon=True).start()

    def _run(self):
        try:
            for name, record in self.records.items():
                if self.cancelled.is_set():
                    break
                try:
                    rows, notes = analyse(name, record, self.settings)
                except ValueError as err:
                    self.errors.append(str(err))
                else:
                    self.rows += rows
                    self.notes += [note for note in notes if note not in self.notes]
                self.done += 1
        except Exception as err:  # shown in the page; the app keeps running
            self.errors.append(f"the analysis stopped: {type(err).__name__}: {err}")
        finally:
            self.seconds = time.perf_counter() - self._start
            self.finished.set()


@dataclasses.dataclass
class Results:
    """The last analysis that finished: its settings, the records it ran (name -> Record) and its rows."""

    settings: Settings
    records: dict
    rows: list


class Session:
    """The files, the running jobs (an analysis, a design study) and the last results of
    one app; files are written under ``folder``."""

    def __init__(self, folder):
        self.folder = pathlib.Path(folder)
        self.files: dict[str, LoadedFile] = {}
        self.job: Job | None = None
        self.results: Results | None = None
        self.design_job: DesignJob | None = None
        self.design = None  # the last design study that finished (an Exceedance)
        self._lock = threading.Lock()

    def add_upload(self, filename: str, contents: str) -> LoadedFile:
        """A file from the browser (``contents``: a data URL, base64) read and kept under its
        name (a file of the same name is replaced); ValueError naming it if it cannot be read,
        nothing kept then."""
        label = pathlib.PurePath(filename).name
        _, _, data = contents.partition(",")
        path = self.folder / f"{len(self.files)}-{time.monotonic_ns()}" / label
        path.parent.mkdir(parents=True)
        path.write_bytes(base64.b64decode(data))
        loaded = load(label, path)
        with self._lock:
            self.files[label] = loaded
        return loaded

    def give(self, label: str, units: str | None = None, dt: float | None = None) -> LoadedFile:
        """The file ``label`` read again with the units or step the user gave it."""
        old = self.files[label]
        loaded = load(label, old.path, units or old.units, dt or old.dt)
        with self._lock:
            self.files[label] = loaded
        return loaded

    def remove(self, label: str):
        with self._lock:
            self.files.pop(label, None)

    def ready(self) -> dict:
        """The records ready to analyse, name -> Record (a name two files share gets the file's)."""
        loaded = [f for f in self.files.values() if f.record is not None]
        names = [f.record.name for f in loaded]
        return {(f.record.name if names.count(f.record.name) == 1 else f.label): f.record for f in loaded}

    def start(self, settings: Settings) -> Job:
        """A job over the ready records; ValueError if none is ready or one is running."""
        if self.job is not None and not self.job.finished.is_set():
            raise ValueError("an analysis is running: wait for it or cancel it")
        records = self.ready()
        if not records:
            raise ValueError("no record is loaded (or every file still waits for its units): load a record first")
        self.job = Job(records, settings)
        return self.job

    def finish(self, job: Job) -> Results | None:
        """Keep the rows of a finished ``job`` as the results (None where it gave none: the
        earlier results stay)."""
        if job.rows:
            self.results = Results(job.settings, job.records, job.rows)
        return self.results if job.rows else None

    def start_design(self, settings: DesignSettings, kind: str, inverse: InverseSettings | None = None) -> DesignJob:
        """A design study (``kind``: "exceedance" or "inverse") over the ready records;
        ValueError if none is ready or a study is running."""
        if self.design_job is not None and not self.design_job.finished.is_set():
            raise ValueError("a design study is running: wait for it or cancel it")
        records = self.ready()
        if not records:
            raise ValueError("no record is loaded (or every file still waits for its units): load a record first")
        self.design_job = DesignJob(records, settings, kind, inverse)
        return self.design_job
