"""Files in the formats users download, written here to their published descriptions: COSMOS
Strong-Motion Data Format v1.20 (CESMD's V1/V2 "Volume" files), NIED's K-NET/KiK-net ASCII
and ESM's ASCII. Each writer takes the header fields as arguments, so that a test can make
one of them contradict the data."""

import numpy as np

#: samples of the fixtures: 200 samples of a sine with a peak of 100 (cm/s², 0.1 g), 2 decimals
SAMPLES = np.round(100.0 * np.sin(2 * np.pi * np.arange(200) / 50.0), 2)
COUNTS = np.round(SAMPLES / (3920.0 / 6182761.0) + 1000.0)  # K-NET counts, an offset of 1000 counts


def _fixed(values, per_line, fmt):
    values = list(values)
    return ["".join(format(v, fmt) for v in values[k:k + per_line]) for k in range(0, len(values), per_line)]


def cosmos_block(values=SAMPLES, *, kind="acceleration", title="Corrected acceleration", parameter=1,
                 units_code=4, units_text="cm/sec2", header_units=None, dt_ms=10.0, count=None, approx=None,
                 orientation=360, peak=None, stage=2, station="CE-12345"):
    """One channel of a COSMOS V1/V2 file (text, integer and real headers, a comment, data)."""
    ints = [-999] * 100
    ints[0], ints[1], ints[2], ints[53] = stage, parameter, units_code if header_units is None else header_units, \
        orientation
    reals = [-999.0] * 100
    reals[61] = dt_ms
    reals[63] = float(np.max(np.abs(values))) if peak is None else peak
    count = len(values) if count is None else count
    approx = round(count * dt_ms / 1000.0) if approx is None else approx
    text = [f"{title:<25}(Format v01.20 with 13 text lines) Src: test.v2",
            "Test Earthquake            January 1, 2000 00:00 UTC",
            "Hypocenter: 34.000  -118.000  H= 10km  Mw=6.0",
            "Origin: 01/01/2000, 00:00:00.0 UTC",
            f"Statn No: 05- 12345  Code:{station}  CSMIP   Test Station",
            "Coords: 34.100  -118.100   Site geology: alluvium",
            "Recorder: test  s/n 1 ( 3 Chns of 3 at Sta) Sensor: test",
            "Rcrd start time: 1/ 1/2000, 00:00:10.0 UTC (Q=5) RcrdId: test",
            f"Sta Chan   1: {orientation} deg (Rcrdr Chan  1)",
            "Raw record length = 2.000 sec",
            "Processed: 01/02/00",
            "Record filtered below  0.10 Hz and above 25.0 Hz",
            "Values used when parameter or data value is unknown/unspecified:   -999, -999.0"]
    return "\n".join(
        text + ["100 Integer-header values follow on  10 lines, Format= (10I8)"] + _fixed(ints, 10, "8d")
        + ["100 Real-header values follow on  17 lines, Format= (6F13.6)"] + _fixed(reals, 6, "13.6f")
        + ['  1 Comment line(s) follow, each starting with a "|":', "| a test fixture"]
        + [f"{count:8d} {kind} pts, approx {approx:4d} secs, units={units_text}({units_code:02d}), Format=(8F10.5)"]
        + _fixed(values, 8, "10.5f") + [f"End-of-data for Chan  1 {kind}"]) + "\n"


def cosmos_v2(**fields):
    """A V2 file: acceleration, then velocity and displacement (made-up values, as the spec lays them out)."""
    return (cosmos_block(**fields) + cosmos_block(SAMPLES / 10, kind="velocity", title="Velocity data", parameter=2,
                                                  units_code=5, units_text="cm/sec")
            + cosmos_block(SAMPLES / 100, kind="displacement", title="Displacement data", parameter=3,
                           units_code=6, units_text="cm"))


def knet(counts=COUNTS, *, direction="N-S", frequency="100Hz", duration="2", scale="3920(gal)/6182761",
         max_acc=None, station="MYG004"):
    """A K-NET (or, with a direction 1-6, KiK-net) ASCII file; Max. Acc. as NIED states it (mean removed)."""
    if max_acc is None:
        a = counts * 3920.0 / 6182761.0
        max_acc = f"{np.max(np.abs(a - a.mean())):.3f}"
    header = [("Origin Time", "2011/03/11 14:46:00"), ("Lat.", "38.103"), ("Long.", "142.860"),
              ("Depth. (km)", "24"), ("Mag.", "9.0"), ("Station Code", station), ("Station Lat.", "38.7312"),
              ("Station Long.", "141.0214"), ("Station Height(m)", "193"), ("Record Time", "2011/03/11 14:46:59"),
              ("Sampling Freq(Hz)", frequency), ("Duration Time(s)", duration), ("Dir.", direction),
              ("Scale Factor", scale), ("Max. Acc. (gal)", max_acc), ("Last Correction", "2011/03/11 14:46:44"),
              ("Memo.", "")]
    return "\n".join([f"{k:<18}{v}" for k, v in header] + _fixed(counts, 8, "9.0f")) + "\n"


def esm(values=SAMPLES, *, units="cm/s^2", dt="0.010000", ndata=None, duration=None, pga=None, stream="HNE",
        data_type="ACCELERATION"):
    """An ESM ASCII file (a shortened header of the format's keys)."""
    ndata = len(values) if ndata is None else ndata
    duration = f"{len(values) * 0.01:.3f}" if duration is None else duration
    pga = f"{values[np.argmax(np.abs(values))]:.6f}" if pga is None else pga
    header = [("EVENT_NAME", "CENTRAL_ITALY"), ("EVENT_ID", "EMSC-20161030_0000029"),
              ("EVENT_DATE_YYYYMMDD", "20161030"), ("MAGNITUDE_W", "6.5"), ("MAGNITUDE_L", "6.1"),
              ("NETWORK", "IT"), ("STATION_CODE", "NRC"), ("STATION_NAME", "NORCIA"), ("VS30_M/S", "498"),
              ("EPICENTRAL_DISTANCE_KM", "4.6"), ("DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS", "20161030_064012.000"),
              ("SAMPLING_INTERVAL_S", dt), ("NDATA", str(ndata)), ("DURATION_S", duration), ("STREAM", stream),
              ("UNITS", units), ("PGA_CM/S^2", pga), ("DATA_TYPE", data_type), ("USER5", "")]
    return "\n".join([f"{k}: {v}" for k, v in header] + [f"{v:.6f}" for v in values]) + "\n"
