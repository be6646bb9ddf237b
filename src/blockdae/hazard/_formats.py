"""Hazard curves in the formats that hazard programs export: OpenQuake's hazard-curve CSV
and the JSON of the USGS NSHMP hazard web service. Each reader returns (im, rate, where):
the levels [g], their annual rates [1/yr] and, for each level, the place in the file it
came from (for the curve's checks to name)."""

import json
import math
import re

import numpy as np

_POE = re.compile(r"poe-(.+)")
_COMMENT_FIELD = re.compile(r"(\w+)=('[^']*'|[^,\"]*)")
SITE_TOLERANCE_DEG = 1e-5  # OpenQuake prints lon and lat to 5 decimals


def openquake_csv(path, site, imt):
    """(im, rate, where) of one site of an OpenQuake hazard-curve CSV (see
    :meth:`HazardCurve.from_openquake_csv`)."""
    lines = path.read_text().splitlines()
    if len(lines) < 3 or not lines[0].startswith("#"):
        raise ValueError(f"{path}: not an OpenQuake hazard-curve CSV (a '#' comment line with "
                         f"investigation_time, a header lon,lat,depth,poe-..., then a line per site)")
    meta = {k: v.strip("'") for k, v in _COMMENT_FIELD.findall(lines[0])}
    if "investigation_time" not in meta:
        raise ValueError(f"{path}, line 1: no investigation_time=... in the comment {lines[0][:120]!r}")
    years = _number(meta["investigation_time"], f"{path}, line 1, field investigation_time")
    if not (math.isfinite(years) and years > 0):
        raise ValueError(f"{path}, line 1, field investigation_time: {years!r} must be a positive number of years")
    if imt is not None and meta.get("imt", imt) != imt:
        raise ValueError(f"{path}, line 1, field imt: the file holds imt={meta['imt']!r}, not {imt!r}")
    header = [h.strip() for h in lines[1].split(",")]
    if header[:3] != ["lon", "lat", "depth"]:
        raise ValueError(f"{path}, line 2: the header must begin lon,lat,depth, got {','.join(header[:3])!r}")
    levels = []
    for column, name in enumerate(header[3:], 4):
        match = _POE.fullmatch(name)
        if not match:
            raise ValueError(f"{path}, line 2, field {column}: {name!r} is not poe-<level>")
        levels.append(_number(match.group(1), f"{path}, line 2, field {column} ({name!r})"))
    rows = [(n, line.split(",")) for n, line in enumerate(lines[2:], 3) if line.strip()]
    n, fields = _site_row(path, rows, site)
    if len(fields) != len(header):
        raise ValueError(f"{path}, line {n}: {len(fields)} fields, the header has {len(header)}")
    poe = np.array([_number(v, f"{path}, line {n}, field {header[i]!r}") for i, v in enumerate(fields[3:], 3)])
    bad = np.flatnonzero(~((poe >= 0) & (poe <= 1)))
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"{path}, line {n}, field {header[i + 3]!r}: poe={float(poe[i])!r} is no probability")
    keep = (poe > 0) & (poe < 1)  # poe 1: a rate without bound; poe 0: none
    with np.errstate(divide="ignore"):
        rate = -np.log1p(-poe) / years
    where = [f"{path}, line {n}, field {name!r}" for name in header[3:]]
    return _kept(np.array(levels), rate, where, keep, f"{path}, line {n}: fewer than two levels with 0 < poe < 1")


def _site_row(path, rows, site):
    """(line number, fields) of the site: None (the only one), a row index or (lon, lat)."""
    if site is None:
        if len(rows) != 1:
            raise ValueError(f"{path}: {len(rows)} sites; choose one with site=<row index> or site=(lon, lat)")
        return rows[0]
    if isinstance(site, (int, np.integer)) and not isinstance(site, bool):
        if not 0 <= site < len(rows):
            raise ValueError(f"{path}: site={site} is no row index (the file has {len(rows)} sites, 0-based)")
        return rows[site]
    try:
        lon, lat = (float(v) for v in site)
    except (TypeError, ValueError):
        raise ValueError(f"site must be None, a row index or (lon, lat) [deg], got {site!r}") from None
    for n, fields in rows:
        coordinates = [_number(v, f"{path}, line {n}, field {name}") for v, name in zip(fields[:2], ("lon", "lat"))]
        if np.allclose(coordinates, (lon, lat), rtol=0, atol=SITE_TOLERANCE_DEG):
            return n, fields
    listed = ", ".join(f"({f[0]}, {f[1]})" for _, f in rows[:5])
    raise ValueError(f"{path}: no site at (lon, lat) = ({lon:g}, {lat:g}) within {SITE_TOLERANCE_DEG:g} deg; "
                     f"sites: {listed}{' ...' if len(rows) > 5 else ''}")


def usgs_json(path, imt, component):
    """(im, rate, where) of one curve of a USGS hazard web-service response (see
    :meth:`HazardCurve.from_usgs_json`)."""
    try:
        document = json.loads(path.read_text())
    except json.JSONDecodeError as error:
        raise ValueError(f"{path}, line {error.lineno}: not JSON ({error.msg})") from None
    responses = document.get("response") if isinstance(document, dict) else None
    if not isinstance(responses, list) or not responses:
        raise ValueError(f"{path}: no 'response' list of curves (a USGS hazard web-service response has "
                         f"response[i].metadata.xvalues and response[i].data[j].yvalues)")
    imts = [_imt_of(path, i, r) for i, r in enumerate(responses)]
    if imt is None:
        if len(responses) != 1:
            raise ValueError(f"{path}: {len(responses)} curves (imt {imts}); choose one with imt=...")
        index = 0
    elif imt in imts:
        index = imts.index(imt)
    else:
        raise ValueError(f"{path}: no curve of imt={imt!r} (the file has {imts})")
    response, at = responses[index], f"{path}: response[{index}]"
    metadata = response["metadata"]
    x_key = "xvalues" if "xvalues" in metadata else "xvals"
    x = _numbers(metadata.get(x_key), f"{at}.metadata.{x_key}")
    data = response.get("data")
    if not isinstance(data, list) or not data:
        raise ValueError(f"{at}.data: no curves")
    if any("component" in d for d in data):
        names = [d.get("component") for d in data]
        if component not in names:
            raise ValueError(f"{at}.data: no component {component!r} (components: {names})")
        j = names.index(component)
    elif len(data) == 1:
        j = 0
    else:
        raise ValueError(f"{at}.data: {len(data)} curves with no component named")
    y_key = "yvalues" if "yvalues" in data[j] else "yvals"
    y = _numbers(data[j].get(y_key), f"{at}.data[{j}].{y_key}")
    if y.size != x.size:
        raise ValueError(f"{at}.data[{j}].{y_key}: {y.size} rates for {x.size} levels in metadata.{x_key}")
    negative = np.flatnonzero(y < 0)
    if negative.size:
        i = int(negative[0])
        raise ValueError(f"{at}.data[{j}].{y_key}[{i}]: rate={float(y[i])!r} is negative")
    keep = y > 0  # a rate of 0: the curve ends below
    where = [f"{at}.data[{j}].{y_key}[{i}]" for i in range(y.size)]
    return _kept(x, y, where, keep, f"{at}.data[{j}].{y_key}: fewer than two levels with a rate > 0")


def _kept(im, rate, where, keep, too_few):
    """The levels ``keep`` selects, at least two (else ValueError ``too_few``)."""
    if np.count_nonzero(keep) < 2:
        raise ValueError(too_few)
    return im[keep], rate[keep], [w for w, k in zip(where, keep) if k]


def _imt_of(path, index, response):
    metadata = response.get("metadata") if isinstance(response, dict) else None
    if not isinstance(metadata, dict) or "imt" not in metadata:
        raise ValueError(f"{path}: response[{index}].metadata.imt is missing")
    imt = metadata["imt"]
    return imt.get("value") if isinstance(imt, dict) else imt


def _numbers(values, where):
    if not isinstance(values, list) or not values:
        raise ValueError(f"{where}: not a list of numbers")
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"{where}[{i}]: {v!r} is not a finite number")
        out.append(float(v))
    return np.array(out)


def _number(text, where):
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"{where}: {text.strip()!r} is not a number") from None
