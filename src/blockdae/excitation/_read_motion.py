"""Reading a three-component base motion: one file per component, or one table."""

import pathlib

from ..core._units import STANDARD_GRAVITY
from ._motion import BaseMotion
from ._readers import read_record, read_samples, record_name
from ._record import Record
from ._resample import resample

_AXES = ("x", "y", "z")
# a table read_motion reads: one column of a_x (with dt), or time [s] and up to three components
_COMPONENTS = (4, "1 to 4 columns (time [s], a_x[, a_y[, a_z]])")


def read_motion(x, y=None, z=None, *, units=None, dt=None, g=STANDARD_GRAVITY, name=None,
                check_peak=True, resample_dt=None) -> BaseMotion:
    """Read a base motion (a_x, a_y, a_z) [m/s²] from files.

    Either one file per component, ``x`` and optionally ``y``, ``z``, each read by
    :func:`read_record` with the options below (components named after their files);
    or, with ``x`` alone, one file: a table with columns time [s], a_x, a_y[, a_z]
    (read as read_record reads two columns: separators, header line, '#' comments;
    components named "<name> x", ...), or a file read_record reads, giving a_x alone.

    Args:
        x, y, z: file paths; y, z None: absent.
        units, dt, g, check_peak: as for :func:`read_record`; one unit for all columns
            of a table, whose peak check covers them all.
        name: label of the components; by default the files' names less their suffixes
            (:func:`~blockdae.excitation._readers.record_name`).
        resample_dt: None (default): the files' own steps; else every component is
            resampled to this step [s] (see :func:`blockdae.resample`) before the
            components are joined, so that files of mixed steps make one motion.

    Records of different lengths are fine (a component is zero after its last
    sample); different sample steps raise ValueError (see :class:`BaseMotion`)
    unless ``resample_dt`` is given.
    """
    options = dict(units=units, dt=dt, g=g, check_peak=check_peak)
    if y is None and z is None:
        path = pathlib.Path(x)
        samples, step, start_time = read_samples(path, columns=_COMPONENTS, **options)
        label = record_name(path) if name is None else name
        records = [Record(a, step, f"{label} {axis}", start_time, units="m/s2", check_peak=False)
                   for a, axis in zip(samples.T, _AXES)]
    else:
        labels = (None,) * 3 if name is None else tuple(f"{name} {axis}" for axis in _AXES)
        records = [None if path is None else read_record(path, name=label, **options)
                   for path, label in zip((x, y, z), labels)]
    if resample_dt is not None:
        records = [None if r is None else resample(r, resample_dt) for r in records]
    return BaseMotion(*records)
