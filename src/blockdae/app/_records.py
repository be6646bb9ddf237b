"""The records of the app: files read by :func:`blockdae.read_record` under its rules (units
and step as the file states them, or as the user gives them; never guessed), what was read
of each, and the figure of each record."""

import dataclasses
import pathlib

import numpy as np

from ..excitation import read_record, unit_factor
from ..units import STANDARD_GRAVITY
from ._caught import caught_warnings

#: the units a user may give a file that does not state them, with their symbols
UNITS = {"g": "g", "m/s2": "m/s²", "cm/s2": "cm/s²"}
#: peaks outside this range [g] are marked implausible beside a units choice (the library's rule)
PLAUSIBLE_PEAK_G = (1e-4, 4.0)
_UNSTATED_UNITS = "units of the accelerations are not stated"
_STEP_NEEDED = "needs the sample step dt"


@dataclasses.dataclass
class LoadedFile:
    """One file given to the app.

    Attributes:
        label: the file's name as the user gave it (unique in the app).
        path: where the app keeps it [a local path].
        record: the record read, or None while the file waits for its units or step.
        units: the units the user gave ("g", "m/s2", "cm/s2"), None: as the file states them.
        dt: the sample step the user gave [s], None: as the file states it.
        needs: "units" or "step" while the file waits for one, else None.
        raw_peak: the file's largest |value| in its own unstated units (while ``needs`` is "units").
        notes: the library's warnings on reading it (one line each).
    """

    label: str
    path: pathlib.Path
    record: object = None
    units: str | None = None
    dt: float | None = None
    needs: str | None = None
    raw_peak: float | None = None
    notes: list = dataclasses.field(default_factory=list)


def load(label, path, units=None, dt=None) -> LoadedFile:
    """``path`` read as a record (``units``, ``dt`` as the user gave them, None: the file's);
    a :class:`LoadedFile` that waits for units or a step where the file states neither;
    ValueError naming the file (and line) for anything else the reader refuses."""
    loaded = LoadedFile(label, pathlib.Path(path), units=units, dt=dt)
    try:
        loaded.record, loaded.notes = _read(path, units, dt)
    except ValueError as err:
        message = str(err)
        if dt is None and _STEP_NEEDED in message:
            loaded.needs = "step"
        elif units is None and _UNSTATED_UNITS in message:
            loaded.needs = "units"
            as_written, _ = _read(path, "m/s2", dt, check_peak=False)  # m/s² keeps the file's numbers
            loaded.raw_peak = as_written.peak_acceleration
        else:
            raise ValueError(_named(message, label, path)) from None
    return loaded


def _read(path, units, dt, check_peak=True):
    """(the record, its reading warnings as lines)."""
    with caught_warnings() as notes:
        record = read_record(path, units=units, dt=dt, check_peak=check_peak)
    return record, notes


def _named(message, label, path):
    """The reader's message with the app's copy of the file named as the user named it."""
    return message.replace(str(path), label)


def unit_choices(raw_peak) -> list[tuple[str, str]]:
    """(units, label) of each unit a file of peak ``raw_peak`` (its own numbers) may be in,
    the label giving the peak in g and marking an implausible one."""
    low, high = PLAUSIBLE_PEAK_G
    choices = []
    for units, symbol in UNITS.items():
        peak_g = raw_peak * unit_factor(units) / STANDARD_GRAVITY
        label = f"{symbol}: peak {raw_peak:.4g} {symbol}" + ("" if units == "g" else f" = {peak_g:.4g} g")
        choices.append((units, label + ("" if low <= peak_g <= high else " (implausible)")))
    return choices


def summary(loaded: LoadedFile) -> dict:
    """What was read of a file: file, record, format, units, dt_s [s], samples, duration_s [s],
    pga_g [g], station, component (empty where the header does not say)."""
    record = loaded.record
    meta = record.metadata
    units = meta.get("units") or loaded.units or ""
    return {"file": loaded.label, "record": record.name, "format": str(meta.get("format", "")),
            "units": f"{UNITS.get(units, units)}" + (" (given)" if loaded.units else ""),
            "dt_s": record.dt, "samples": record.acceleration_samples.size, "duration_s": record.duration,
            "pga_g": record.peak_acceleration / STANDARD_GRAVITY, "station": str(meta.get("station") or ""),
            "component": str(meta.get("component") or "")}


def record_figure(record):
    """a(t) [g] against t [s] of ``record``, its peak marked; a small matplotlib Figure."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.0, 1.7), layout="constrained")
    ax = fig.subplots()
    a = record.acceleration_samples / STANDARD_GRAVITY
    t = record.times + record.start_time
    ax.plot(t, a, color="0.25", lw=0.6)
    k = int(np.argmax(np.abs(a)))
    ax.plot(t[k], a[k], "o", color="C3", ms=4, label=f"peak {abs(a[k]):.3g} g at {t[k]:.2f} s")
    ax.set(xlabel="time t [s]", ylabel="a [g]", title=record.name)
    ax.title.set_fontsize("small")
    ax.legend(loc="upper right", fontsize="x-small")
    ax.grid(True, alpha=0.3)
    return fig
