"""A hazard curve λ(IM > x): annual rates of exceedance at increasing intensity levels."""

import dataclasses
import pathlib

import numpy as np

from . import _formats
from ..core import compact_repr


@dataclasses.dataclass(frozen=True)
class HazardCurve:
    """λ(IM > x) at levels x.

    Attributes: im: intensity levels, positive and increasing (n >= 2);
    rate: annual rates of exceedance [1/yr], positive and decreasing (n,).
    """

    def __repr__(self):
        return compact_repr(self)

    im: np.ndarray
    rate: np.ndarray

    def __post_init__(self):
        x, lam = np.asarray(self.im, dtype=float), np.asarray(self.rate, dtype=float)
        _check(x, lam, [f"point {i}" for i in range(x.size)] if x.ndim == 1 else [])
        object.__setattr__(self, "im", x)
        object.__setattr__(self, "rate", lam)

    @classmethod
    def from_openquake_csv(cls, path, site=None, imt=None):
        """One site's curve from an OpenQuake engine hazard-curve CSV export.

        The format (``oq export hcurves``, e.g. hazard_curve-mean-PGA_<calc>.csv; written by
        openquake/calculators/export/hazard.py, ``export_hcurves_csv``): line 1 a comment
        ``#,,,"generated_by=..., kind='mean', investigation_time=50.0, imt='PGA'"``; line 2
        the header ``lon,lat,depth,poe-<level>,...`` (levels in g for PGA and SA); then one
        line per site of probabilities of exceedance in the investigation time T [yr].

        Conversion (Poisson occurrence): λ = -ln(1 - poe) / T [1/yr]. Levels with poe = 1
        (a rate without bound) or poe = 0 (none) are left out.

        Args:
            path: the CSV file.
            site: None (the file holds one site), the site's row (0-based), or its
                (lon, lat) [deg], matched to within 1e-5 deg.
            imt: None, or the intensity measure expected, e.g. "PGA" or "SA(0.2)":
                checked against the comment's imt.

        A malformed file, a probability outside [0, 1] or a curve that does not decrease
        raises a ValueError naming the file, the line and the field.
        """
        return cls._checked(*_formats.openquake_csv(pathlib.Path(path), site, imt))

    @classmethod
    def from_usgs_json(cls, path, imt=None, component="Total"):
        """A curve from a USGS NSHMP hazard web-service response (JSON), rates annual.

        The format (usgs/nshmp-haz-ws, ``HazardService``): ``{"status", "date", "url",
        "server", "response": [{"metadata": {"imt": {"value": "PGA", ...}, "xlabel":
        "Ground Motion (g)", "ylabel": "Annual Frequency of Exceedence", "xvalues": [...],
        ...}, "data": [{"component": "Total", "yvalues": [...]}, {"component":
        "Fault", ...}, ...]}, ...]}``, one response per IMT; also the older static-curve
        service of the Unified Hazard Tool (usgs/earthquake-hazard-tool,
        etc/curve/data.json): ``xvals`` and one data entry with ``yvals``. Levels in g;
        levels of rate 0 are left out.

        Args:
            path: the JSON file.
            imt: None (the file holds one curve) or its imt value, e.g. "PGA", "SA0P2".
            component: the curve of ``data`` by its component, "Total" by default.

        A malformed file (with its line for a JSON syntax error) or a curve that does not
        decrease raises a ValueError naming the file and the field.
        """
        return cls._checked(*_formats.usgs_json(pathlib.Path(path), imt, component))

    @classmethod
    def _checked(cls, im, rate, where):
        _check(np.asarray(im, dtype=float), np.asarray(rate, dtype=float), where)
        return cls(im, rate)

    @classmethod
    def read_csv(cls, path, im_column=0, rate_column=1):
        """A curve from a CSV file: a header naming the columns, then one level a line
        (``#`` lines skipped); the columns by position or name. A line whose level or
        rate does not continue the curve (increasing levels, decreasing rates) is named."""
        path = pathlib.Path(path)
        lines = [(n, line) for n, line in enumerate(path.read_text().splitlines(), 1)
                 if line.strip() and not line.lstrip().startswith("#")]
        if len(lines) < 3:
            raise ValueError(f"{path}: a header and at least two levels are needed")
        header = [h.strip() for h in lines[0][1].split(",")]
        cols = [c if isinstance(c, int) else _column(path, header, c) for c in (im_column, rate_column)]
        values, where = [], []
        for n, line in lines[1:]:
            fields = line.split(",")
            try:
                values.append([float(fields[c]) for c in cols])
            except (ValueError, IndexError):
                raise ValueError(f"{path}, line {n}: not two numbers in columns {cols}: {line!r}") from None
            where.append(f"{path}, line {n}")
        x, lam = np.array(values).T
        _check(x, lam, where)
        return cls(x, lam)


def _column(path, header, name):
    if name not in header:
        raise ValueError(f"{path}: no column {name!r} in the header {header}")
    return header.index(name)


def _check(x, lam, where):
    if x.ndim != 1 or x.shape != lam.shape or x.size < 2:
        raise ValueError(f"a hazard curve needs im and rate of one shape (n >= 2,), got {x.shape} and {lam.shape}")
    for name, a in (("im", x), ("rate", lam)):
        bad = np.flatnonzero(~(np.isfinite(a) & (a > 0)))
        if bad.size:
            raise ValueError(f"{where[bad[0]]}: {name}={float(a[bad[0]])!r} must be positive and finite")
    up = np.flatnonzero(np.diff(x) <= 0)
    if up.size:
        i = up[0] + 1
        raise ValueError(f"{where[i]}: im={x[i]:g} does not increase (previous {x[i - 1]:g})")
    flat = np.flatnonzero(np.diff(lam) >= 0)
    if flat.size:
        i = flat[0] + 1
        raise ValueError(f"{where[i]}: the hazard curve is not decreasing: rate={lam[i]:g} at im={x[i]:g} "
                         f"after rate={lam[i - 1]:g} at im={x[i - 1]:g}")
