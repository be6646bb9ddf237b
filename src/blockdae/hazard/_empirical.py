"""The fragility of an empirical regression, with the magnitude fixed or from a
deaggregation table (the weights of magnitudes at each intensity level)."""

import dataclasses
import inspect

import numpy as np
from ..core import compact_repr


@dataclasses.dataclass(frozen=True)
class Deaggregation:
    """Weights of magnitudes at intensity levels (rows summing to 1).

    Attributes: im: increasing intensity levels (n,); magnitudes: (m,) [-];
    weights: (n, m) [-]. Between levels the weights are interpolated linearly in ln im,
    beyond them the nearest level's are used.
    """

    def __repr__(self):
        return compact_repr(self)

    im: np.ndarray
    magnitudes: np.ndarray
    weights: np.ndarray

    def __post_init__(self):
        im, m, w = (np.asarray(a, dtype=float) for a in (self.im, self.magnitudes, self.weights))
        if im.ndim != 1 or np.any(~(im > 0)) or np.any(np.diff(im) <= 0):
            raise ValueError(f"Deaggregation.im must be positive and increasing, got {im!r}")
        if w.shape != (im.size, m.size):
            raise ValueError(f"Deaggregation.weights must have shape (len(im), len(magnitudes)) = "
                             f"{(im.size, m.size)}, got {w.shape}")
        rows = w.sum(axis=1)
        if np.any(w < 0) or not np.allclose(rows, 1.0, atol=1e-6):
            bad = int(np.argmax(np.abs(rows - 1.0)))
            raise ValueError(f"Deaggregation.weights must be >= 0 with rows summing to 1: row {bad} "
                             f"(im={im[bad]:g}) sums to {rows[bad]:g}")
        for name, a in (("im", im), ("magnitudes", m), ("weights", w)):
            object.__setattr__(self, name, a)

    def at(self, x):
        """Weights (…, m) at intensities ``x`` (…)."""
        u = np.log(np.asarray(x, dtype=float))
        return np.stack([np.interp(u, np.log(self.im), w) for w in self.weights.T], axis=-1)


@dataclasses.dataclass(frozen=True)
class EmpiricalFragility:
    """P(D > d | im) of a regression of :mod:`blockdae.empirical`.

    Attributes:
        model: the regression, e.g. ``bd.empirical.jibson_2007``.
        im: the name of its argument that is the intensity, e.g. "pga_g" or "sa_g".
        fixed: its other arguments but the magnitude, e.g. ``{"ky_g": 0.1}``.
        magnitude: a moment magnitude, a :class:`Deaggregation`, or None for a model
            without one.
    """

    def __repr__(self):
        return compact_repr(self)

    model: object
    im: str
    fixed: dict = dataclasses.field(default_factory=dict)
    magnitude: object = None

    def __post_init__(self):
        names = set(inspect.signature(self.model).parameters)
        wanted = {self.im, *self.fixed} | ({"magnitude"} if self.magnitude is not None else set())
        if wanted != names:
            raise ValueError(f"{self.model.__name__} takes {sorted(names)}: give im and fixed (and magnitude) "
                             f"to cover them, got {sorted(wanted)}")

    def exceedance(self, d_m, im):
        """P(D > d | im) for d [m] > 0 and intensities ``im``, broadcast."""
        d, x = np.asarray(d_m, dtype=float), np.asarray(im, dtype=float)
        if not isinstance(self.magnitude, Deaggregation):
            extra = {} if self.magnitude is None else {"magnitude": self.magnitude}
            return self.model(**self.fixed, **extra, **{self.im: x}).exceedance(d)
        deagg = self.magnitude
        w = deagg.at(x)
        p = [self.model(**self.fixed, magnitude=m, **{self.im: x}).exceedance(d) for m in deagg.magnitudes]
        return sum(w[..., j] * p[j] for j in range(len(p)))
