"""What the app holds between clicks, for each page open in the browser (a tab): the files
given to it (kept in a folder of its own), the analysis running in the background (its
progress, a way to stop it) and the last results. Each page load opens a session of its
own; a session the page has not been heard from for :data:`SESSION_EXPIRY_S` ends, its
files removed and its runs cancelled."""

import base64
import binascii
import dataclasses
import itertools
import pathlib
import secrets
import shutil
import threading
import time
import unicodedata

from ._analysis import Settings, analyse
from ._design import DesignJob, DesignSettings, InverseSettings
from ._records import LoadedFile, load

#: the largest file the app takes [bytes] (stated in the page's messages and in docs/app.md)
FILE_LIMIT_BYTES = 20_000_000
#: the most bytes of files given at once (a pick, a drop, a folder) [bytes]
BATCH_LIMIT_BYTES = 200_000_000
#: a session ends this long after its page was last heard from [s] (an open page checks in every minute)
SESSION_EXPIRY_S = 3600.0
#: the longest file name taken [bytes of UTF-8] (that of most file systems)
_NAME_BYTES = 255


class SessionEnded(LookupError):
    """The page's session is not (or no longer) held: the app restarted or the page was idle."""


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


def file_label(filename) -> str:
    """The name a file from the browser is kept under: its last part (a folder's files come
    as ``folder/name``); ValueError naming it where it cannot be a file's name (empty, ``.``,
    ``..``, control characters, longer than 255 bytes)."""
    name = str(filename or "").replace("\\", "/").rsplit("/", 1)[-1]
    shown = repr(name) if len(name) <= 60 else f"{name[:40]!r}... ({len(name)} characters)"
    if name in ("", ".", ".."):
        raise ValueError(f"a file named {shown} is not loaded: that is no file name")
    odd = next((c for c in name if unicodedata.category(c) in ("Cc", "Cs")), None)  # control, lone surrogate
    if odd is not None:
        raise ValueError(f"a file named {shown} is not loaded: its name holds U+{ord(odd):04X}, which no file name "
                         "may hold")
    if len(name.encode()) > _NAME_BYTES:
        raise ValueError(f"a file named {shown} is not loaded: a file name is at most {_NAME_BYTES} bytes")
    return name


def _decoded(label, contents) -> bytes:
    """The bytes of a data URL (base64; an empty file's holds none); ValueError naming
    ``label`` where it is not base64 or holds more than :data:`FILE_LIMIT_BYTES`."""
    _, _, data = str(contents or "").partition(",")
    size = len(data) * 3 // 4 - data[-2:].count("=")
    if size > FILE_LIMIT_BYTES:
        raise ValueError(f"{label}: {size / 1e6:.1f} MB is above the app's limit of {FILE_LIMIT_BYTES / 1e6:g} MB "
                         "per file: not loaded")
    try:
        return base64.b64decode(data, validate=True)
    except binascii.Error:
        raise ValueError(f"{label}: what was received is not the file (not base64): give it again") from None


class Session:
    """The files, the running jobs (an analysis, a design study) and the last results of
    one page; files are written under ``folder`` (made on the first file).

    Attributes:
        thumbnails: file label -> the PNG data URL of its record's figure.
        seen: when the page was last heard from [s, time.monotonic()].
    """

    def __init__(self, folder):
        self.folder = pathlib.Path(folder)
        self.files: dict[str, LoadedFile] = {}
        self.thumbnails: dict[str, str] = {}
        self.job: Job | None = None
        self.results: Results | None = None
        self.design_job: DesignJob | None = None
        self.design = None  # the last design study that finished (an Exceedance)
        self.seen = time.monotonic()
        self._closed = False
        self._uploads = itertools.count()
        self._lock = threading.Lock()

    def add_upload(self, filename: str, contents: str) -> LoadedFile:
        """A file from the browser (``contents``: a data URL, base64) read and kept under its
        name (a file of the same name is replaced); ValueError naming it if it cannot be taken
        (its name, its size: :data:`FILE_LIMIT_BYTES`) or read, nothing kept then."""
        label = file_label(filename)
        data = _decoded(label, contents)
        with self._lock:
            if self._closed:
                raise SessionEnded("this page's session has ended")
            path = self.folder / f"{next(self._uploads)}" / label
            path.parent.mkdir(parents=True)
        try:
            path.write_bytes(data)
        except OSError as err:
            raise ValueError(f"{label}: the app could not keep a copy ({err.strerror}): not loaded") from None
        try:
            loaded = load(label, path)
        except ValueError:
            shutil.rmtree(path.parent, ignore_errors=True)
            raise
        with self._lock:
            replaced = self.files.get(label)
            self.files[label] = loaded
        if replaced is not None:
            shutil.rmtree(replaced.path.parent, ignore_errors=True)
        return loaded

    def give(self, label: str, units: str | None = None, dt: float | None = None) -> LoadedFile:
        """The file ``label`` read again with the units or step the user gave it; ValueError
        naming it where it is not (or no longer) loaded."""
        old = self.files.get(label)
        if old is None:
            raise ValueError(f"{label}: this file is not loaded (removed meanwhile?): give it again")
        loaded = load(label, old.path, units or old.units, dt or old.dt)
        with self._lock:
            self.files[label] = loaded
        return loaded

    def remove(self, label: str):
        """Forget the file ``label`` and remove the app's copy."""
        with self._lock:
            removed = self.files.pop(label, None)
            self.thumbnails.pop(label, None)
        if removed is not None:
            shutil.rmtree(removed.path.parent, ignore_errors=True)

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

    def close(self):
        """Cancel its runs and remove its files."""
        with self._lock:
            self._closed = True
            self.files.clear()
            self.thumbnails.clear()
            self.results = self.design = None
        for job in (self.job, self.design_job):
            if job is not None:
                job.cancelled.set()
        shutil.rmtree(self.folder, ignore_errors=True)


class Sessions:
    """The sessions of one app, each under a folder of its own in ``folder``, by a key
    each page holds (unguessable, made for each page load); a session not heard from for
    ``expiry_s`` [s] is closed (checked every ``expiry_s / 4`` s, at most every minute)."""

    def __init__(self, folder, expiry_s: float = SESSION_EXPIRY_S):
        self.folder, self.expiry_s = pathlib.Path(folder), expiry_s
        self._sessions: dict[str, Session] = {}
        self._numbers = itertools.count()
        self._lock = threading.Lock()
        self._stopped = threading.Event()
        threading.Thread(target=self._sweep_until_stopped, name="blockdae-app-sessions", daemon=True).start()

    def new(self) -> str:
        """The key of a new session."""
        key = secrets.token_urlsafe(24)
        with self._lock:
            self._sessions[key] = Session(self.folder / f"session-{next(self._numbers)}")
        return key

    def __getitem__(self, key) -> Session:
        """The session ``key``, marked as heard from; :class:`SessionEnded` where none is held."""
        return self.heard_from(key)

    def heard_from(self, key) -> Session:
        """Mark the session ``key`` as heard from (its page is open); returns it, or raises
        :class:`SessionEnded` where none is held."""
        with self._lock:
            session = self._sessions.get(key) if isinstance(key, str) else None
        if session is None:
            raise SessionEnded("this page's session has ended")
        session.seen = time.monotonic()
        return session

    def sweep(self):
        """Close the sessions not heard from for ``expiry_s``."""
        now = time.monotonic()
        with self._lock:
            ended = [key for key, session in self._sessions.items() if now - session.seen > self.expiry_s]
            closed = [self._sessions.pop(key) for key in ended]
        for session in closed:
            session.close()

    def _sweep_until_stopped(self):
        while not self._stopped.wait(min(60.0, self.expiry_s / 4)):
            self.sweep()

    def close(self):
        """Close every session and stop checking."""
        self._stopped.set()
        with self._lock:
            closed = list(self._sessions.values())
            self._sessions.clear()
        for session in closed:
            session.close()
