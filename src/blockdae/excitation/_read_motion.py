"""Reading a three-component base motion: one file per component, one table, or the
channels of one station (COSMOS, K-NET/KiK-net, ESM, SAC, miniSEED) by their orientation."""

import pathlib
import warnings

from ..units import STANDARD_GRAVITY
from ._motion import BaseMotion
from ._formats import FORMAT_OPTIONS, read_channels
from ._read_record import read_record
from ._readers import read_samples, record_name
from ._record import Record
from ._resample import resample

_AXES = ("x", "y", "z")
# a table read_motion reads: one column of a_x (with dt), or time [s] and up to three components
_COMPONENTS = (4, "1 to 4 columns (time [s], a_x[, a_y[, a_z]])")


def read_motion(x, y=None, z=None, *, units=None, dt=None, g=STANDARD_GRAVITY, name=None,
                check_peak=True, check_step=True, remove_mean=None, resample_dt=None, **options) -> BaseMotion:
    """Read a base motion (a_x, a_y, a_z) [m/s²] from files.

    Either one file per component, ``x`` and optionally ``y``, ``z``, each read by
    :func:`read_record` with the options below (components named after their files);
    or, with ``x`` alone, one file: a table with columns time [s], a_x, a_y[, a_z]
    (read as read_record reads two columns: separators, header line, '#' comments;
    components named "<name> x", ...), or a file read_record reads, giving a_x alone.

    Files of one station in a format with a header (COSMOS, K-NET/KiK-net, ESM, SAC,
    miniSEED: the three files of a station, in any order, or one file of several
    channels) are placed by their own orientation: the vertical (U-D, Up, HNZ) is z; of the
    horizontals, the one nearer north-south (N-S, azimuth 0 or 180, HNN) is x, the other
    (E-W, HNE) y; horizontals of unknown azimuth (H1, H2) keep their order. Channels of
    different steps are resampled to the smallest (:func:`blockdae.excitation.resample`, with a
    warning) unless ``resample_dt`` is given; a channel pointing down, two verticals,
    three horizontals or two stations are refused.

    Args:
        x, y, z: file paths; y, z None: absent.
        units, dt, g, check_peak, check_step, remove_mean: as for :func:`read_record`; one
            unit for all columns of a table, whose peak check covers them all.
        name: label of the components; by default the files' names less their suffixes
            (:func:`~blockdae.excitation._readers.record_name`).
        resample_dt: None (default): the files' own steps; else every component is
            resampled to this step [s] (see :func:`blockdae.excitation.resample`) before the
            components are joined, so that files of mixed steps make one motion.
        options: ``gain``: as for :func:`read_record`, for the formats that take it.

    Records of different lengths are fine (a component is zero after its last
    sample); different sample steps raise ValueError (see :class:`BaseMotion`)
    unless ``resample_dt`` is given.
    """
    options = dict(units=units, dt=dt, g=g, check_peak=check_peak, check_step=check_step, remove_mean=remove_mean,
                   **options)
    if y is None and z is None:
        path = pathlib.Path(x)
        records, _ = read_channels(path, units, dt, g, check_peak, name, _format_options(options),
                                   check_step=check_step, remove_mean=remove_mean)
        if records is not None:
            return _station_motion(records, resample_dt, path)
        samples, step, start_time = read_samples(path, units, dt, g, check_peak, _COMPONENTS, check_step=check_step,
                                                 remove_mean=bool(remove_mean))
        label = record_name(path) if name is None else name
        records = [Record(a, step, f"{label} {axis}", start_time, units="m/s2", check_peak=False)
                   for a, axis in zip(samples.T, _AXES)]
    else:
        labels = (None,) * 3 if name is None else tuple(f"{name} {axis}" for axis in _AXES)
        records = [None if path is None else read_record(path, name=label, **options)
                   for path, label in zip((x, y, z), labels)]
        given = [r for r in records if r is not None]
        if all("vertical" in r.metadata for r in given):
            return _station_motion(given, resample_dt, ", ".join(str(p) for p in (x, y, z) if p is not None))
    if resample_dt is not None:
        records = [None if r is None else resample(r, resample_dt) for r in records]
    return BaseMotion(*records)


def _format_options(options):
    """The options of ``options`` that only some formats take, set to other than their defaults."""
    return {key: options[key] for key in FORMAT_OPTIONS if options.get(key) not in (None, False)}


def _station_motion(records, resample_dt, source):
    """The BaseMotion of one station's channels, placed by their orientation (see read_motion)."""
    stations = sorted({r.metadata.get("station", "") for r in records})
    if len(stations) > 1:
        raise ValueError(f"{source}: channels of different stations ({', '.join(map(repr, stations))}); "
                         "a motion is one station's")
    vertical = [r for r in records if r.metadata.get("vertical")]
    horizontal = [r for r in records if not r.metadata.get("vertical")]
    down = [r for r in records if r.metadata.get("component") == "Down"]
    if down or len(vertical) > 1 or len(horizontal) > 2:
        names = ", ".join(repr(r.metadata.get("component")) for r in records)
        raise ValueError(f"{source}: channels {names}: expected up to two horizontals and one vertical pointing "
                         "up (read the others one by one with read_record)")
    horizontal.sort(key=lambda r: _north_first(r.metadata.get("azimuth_deg")))
    placed = (horizontal + [None, None])[:2] + (vertical or [None])
    if resample_dt is None:
        steps = {r.dt for r in records}
        if len(steps) > 1:
            resample_dt = min(steps)
            warnings.warn(f"{source}: channels of steps {', '.join(f'{s:g}' for s in sorted(steps))} s resampled "
                          f"to {resample_dt:g} s (blockdae.excitation.resample: linear a(t), exact at the new samples)",
                          UserWarning, stacklevel=3)
    if resample_dt is not None:
        placed = [None if r is None else resample(r, resample_dt) for r in placed]
    return BaseMotion(*placed)


def _north_first(azimuth):
    """Sort key of a horizontal: nearer north-south first; unknown azimuths after, in file order."""
    if azimuth is None:
        return 2.0
    angle = azimuth % 180.0
    return min(angle, 180.0 - angle) / 90.0
