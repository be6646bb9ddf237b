"""Two horizontal components of a record projected on each cell's dip azimuth.

A cell of dip azimuth β [deg clockwise from north, the downslope direction] is shaken along
its dip by

    a_β(t) = s · (a1(t) cos(θ1 − β) + a2(t) cos(θ2 − β))   [m/s²],

a1, a2 the two orthogonal horizontal components of azimuths θ1, θ2 [deg from north] stated
by the user. The pair is scaled by one factor s so that its larger component's peak |a| is
the cell's PGA (the peak horizontal acceleration that ShakeMap and ground-motion models give
as the larger of the two components): the ratio of the components is kept, and a slope
dipping across the stronger component slides less than one dipping along it. a_β as given
is the "normal" polarity, as for a single record; "inverse" is −a_β.

Each cell's record is then its own, so every cell runs on the exact engine
(:func:`blockdae.newmark`), one batched call over all cells that share a dip azimuth:
D = p · D_β(ky / p) with D_β the displacement under the pair scaled to a larger peak of 1 g.
"""

import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ._tables import POLARITIES

#: |cos(θ2 − θ1)| above which two components are refused as not orthogonal [-]
_ORTHOGONAL = 1e-9


def _cos_deg(angle_deg):
    """cos of angles [deg], exact (0, ±1) at multiples of 90°."""
    angle = np.asarray(angle_deg, float)
    quarter = angle / 90.0
    k = np.round(quarter)
    exact = np.array([1.0, 0.0, -1.0, 0.0])[np.mod(np.nan_to_num(k), 4).astype(int)]
    return np.where(quarter == k, exact, np.cos(np.radians(angle)))


class RecordPair:
    """The two horizontal components of one record, with their azimuths.

    Args:
        first, second: the components (:class:`blockdae.Record`), same step, length and
            start time.
        azimuths_deg: (θ1, θ2), each component's azimuth [deg clockwise from north, in
            [0, 360]], as the record's provider states them (e.g. 0 and 90 for "N-S" and
            "E-W"; never assumed); the two must be orthogonal.
        name: the pair's name in the outputs (default: the first component's name).
    """

    def __init__(self, first, second, azimuths_deg=None, *, name: str | None = None):
        from ..excitation import Record, check_horizontal

        for label, component in (("first", first), ("second", second)):
            if not isinstance(component, Record):
                raise TypeError(f"RecordPair: {label}={component!r:.60} must be a blockdae Record")
            check_horizontal(component)
        self.azimuths_deg = _azimuths(azimuths_deg)
        if first.dt != second.dt or first.acceleration_m_s2.size != second.acceleration_m_s2.size or \
                first.start_time != second.start_time:
            raise ValueError(f"RecordPair: the components differ in step, length or start time ({first!r} against "
                             f"{second!r}); resample them onto one time axis (blockdae.excitation.resample)")
        self.name = name if name is not None else (first.name or "record pair")
        self.dt = float(first.dt)
        self.first, self.second = first, second

    def __repr__(self):
        return (f"RecordPair({self.name!r}, azimuths {self.azimuths_deg[0]:g} and {self.azimuths_deg[1]:g} deg "
                f"from north, {self.first.acceleration_m_s2.size} samples, dt={self.dt} s)")

    @property
    def peak_acceleration(self) -> float:
        """The larger component's peak |a| [m/s²]: the pair's PGA."""
        return max(self.first.peak_acceleration, self.second.peak_acceleration)

    def projected(self, dip_azimuth_deg: float, g: float = STANDARD_GRAVITY):
        """The pair scaled so its larger component's peak is 1 g, projected on the dip
        azimuth [deg from north]: a :class:`blockdae.Record` [m/s²]."""
        (c1, c2), = self._cosines([dip_azimuth_deg])
        return self._projected(self._unit(g), c1, c2, f"{dip_azimuth_deg:g}")

    def _unit(self, g):
        """Both components scaled so that the larger one's peak is 1 g [m/s²]: (a1, a2)."""
        factor = float(g / self.peak_acceleration)
        return self.first.acceleration_m_s2 * factor, self.second.acceleration_m_s2 * factor

    def _cosines(self, dip_azimuths_deg):
        """cos(θ1 − β), cos(θ2 − β) at each dip azimuth β [deg]: shape (n, 2)."""
        beta = np.asarray(dip_azimuths_deg, float)[:, None]
        return _cos_deg(np.asarray(self.azimuths_deg)[None, :] - beta)

    def _projected(self, unit, c1, c2, label):
        from ..excitation import Record

        return Record(c1 * unit[0] + c2 * unit[1], self.dt, f"{self.name} at {label} deg", check_peak=False)


def _azimuths(azimuths_deg):
    if azimuths_deg is None:
        raise ValueError("RecordPair: azimuths_deg is required: each component's azimuth [deg clockwise from north] "
                         "as the record's provider states it (e.g. (0, 90) for N-S and E-W); it is never assumed")
    try:
        values = tuple(float(a) for a in azimuths_deg)
    except (TypeError, ValueError):
        raise ValueError(f"RecordPair: azimuths_deg={azimuths_deg!r} must be two azimuths [deg from north]") from None
    if len(values) != 2:
        raise ValueError(f"RecordPair: azimuths_deg={azimuths_deg!r} must be two azimuths [deg from north], "
                         f"one per component; got {len(values)}")
    for a in values:
        if not (np.isfinite(a) and 0 <= a <= 360):
            raise ValueError(f"RecordPair: azimuth {a!r} must lie in [0, 360] deg clockwise from north")
    if abs(_cos_deg(values[1] - values[0])) > _ORTHOGONAL:
        raise ValueError(f"RecordPair: azimuths_deg={values} are not orthogonal: two horizontal components are "
                         "90 deg apart (e.g. 0 and 90, 45 and 315)")
    return values


class ProjectedPairs:
    """Record pairs run exact on each cell's projected motion (see the module), with the
    interface the map takes from :class:`DisplacementTables`: ``members`` (pair name,
    polarity) and :meth:`exact`."""

    def __init__(self, pairs, polarity: str = "both", g: float = STANDARD_GRAVITY):
        pairs = [pairs] if isinstance(pairs, RecordPair) else list(pairs)
        if not pairs or not all(isinstance(p, RecordPair) for p in pairs):
            raise ValueError("record pairs: give a RecordPair or a non-empty sequence of them")
        if polarity not in ("both",) + POLARITIES:
            raise ValueError(f"polarity must be one of ('both', 'normal', 'inverse'), got {polarity!r}")
        self.pairs, self.polarity, self.g = tuple(pairs), polarity, float(g)
        self.polarities = POLARITIES if polarity == "both" else (polarity,)
        self.members = tuple((p.name, pol) for p in self.pairs for pol in self.polarities)

    def exact(self, ky_g, pga_g, dip_azimuth_deg) -> np.ndarray:
        """D [m] of every member at each cell (1-D ky [g], PGA [g] of the larger component,
        dip azimuth [deg]), shape (n_members, n): NaN where any of them is NaN."""
        from ..sliding import newmark

        ky, pga, azimuth = (np.asarray(v, float) for v in (ky_g, pga_g, dip_azimuth_deg))
        out = np.full((len(self.members), ky.size), np.nan)
        valid = np.isfinite(ky) & np.isfinite(pga) & np.isfinite(azimuth)
        out[:, valid] = 0.0
        slides = np.flatnonzero(valid & (pga > 0))
        azimuths, group = np.unique(azimuth[slides], return_inverse=True)
        order = np.argsort(group, kind="stable")
        bounds = np.searchsorted(group[order], np.arange(azimuths.size + 1))
        units = [pair._unit(self.g) for pair in self.pairs]
        cosines = [pair._cosines(azimuths) for pair in self.pairs]
        for k, beta in enumerate(azimuths):
            at = slides[order[bounds[k]:bounds[k + 1]]]
            for j, pair in enumerate(self.pairs):
                motion = pair._projected(units[j], *cosines[j][k], f"{beta:g}")
                cells = at[ky[at] < pga[at] * motion.peak_acceleration / self.g]  # elsewhere D = 0
                if cells.size == 0:
                    continue
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")  # r above the peak in one polarity: D = 0 there, as wanted
                    result = newmark(motion, ky[cells] / pga[cells], polarity=self.polarity, g=self.g)
                for i, pol in enumerate(self.polarities):
                    out[j * len(self.polarities) + i, cells] = pga[cells] * np.asarray(getattr(result, pol), float)
        return out
