"""A hazard curve λ(IM > x): annual rates of exceedance at increasing intensity levels."""

import dataclasses
import pathlib

import numpy as np


@dataclasses.dataclass(frozen=True)
class HazardCurve:
    """λ(IM > x) at levels x.

    Attributes: im: intensity levels, positive and increasing (n >= 2);
    rate: annual rates of exceedance [1/yr], positive and decreasing (n,).
    """

    im: np.ndarray
    rate: np.ndarray

    def __post_init__(self):
        x, lam = np.asarray(self.im, dtype=float), np.asarray(self.rate, dtype=float)
        _check(x, lam, [f"point {i}" for i in range(x.size)] if x.ndim == 1 else [])
        object.__setattr__(self, "im", x)
        object.__setattr__(self, "rate", lam)

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
