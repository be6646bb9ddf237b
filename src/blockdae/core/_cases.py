"""The cases of a run over many motions: which motions (a list, a mapping, a record set, a
folder), at which factors on a(t) (scales or target PGAs) and in which polarities."""

import dataclasses
import os
import pathlib
from collections.abc import Mapping

import numpy as np

from ..excitation import (BaseMotion, RecordSet, check_pga, check_pga_rounding, pga_factor,
                          read_record, record_files)

POLARITIES = ("normal", "inverse", "both")
#: the factor on a(t) of each polarity [-]
_SIGN = {"normal": 1.0, "inverse": -1.0}


def is_many(motions) -> bool:
    """Whether ``motions`` holds many motions (a list, tuple, mapping, :class:`RecordSet`,
    or a path to a record file or a folder), else it is one."""
    return isinstance(motions, (list, tuple, Mapping, RecordSet, str, os.PathLike))


@dataclasses.dataclass(frozen=True, eq=False)
class Cases:
    """Motions x factors x polarities, in that order.

    Attributes:
        names: each motion's label, length n_motions.
        motions: the motions as given (unscaled), length n_motions.
        factors: the factor on each motion's a(t) [-] (polarity aside), shape (n_motions, n_scales).
        by: "scale" or "pga": what was given.
        targets: the given scales [-] or target PGAs [g], shape (n_scales,).
        polarities: ("normal",), ("inverse",) or ("normal", "inverse").
        metadata: a record set's metadata (pandas, indexed by name), or None.
    """

    names: tuple
    motions: tuple
    factors: np.ndarray
    by: str
    targets: np.ndarray
    polarities: tuple
    metadata: object = None

    @property
    def shape(self) -> tuple[int, int, int]:
        """(n_motions, n_scales, n_polarities)."""
        return self.factors.shape + (len(self.polarities),)

    def scaled(self, i: int, k: int):
        """Motion ``i`` at factor ``k``, polarity aside: a scaled copy (the motion itself at factor 1)."""
        factor = self.factors[i, k]
        return self.motions[i] if factor == 1.0 else self.motions[i].scaled(float(factor))

    def motion(self, i: int, k: int, p: int):
        """Motion ``i`` at factor ``k`` in polarity ``p``: a scaled copy (the motion itself
        at factor 1 in the normal polarity)."""
        factor = self.factors[i, k] * _SIGN[self.polarities[p]]
        return self.motions[i] if factor == 1.0 else self.motions[i].scaled(float(factor))

    def check(self, check_one) -> None:
        """``check_one(motion)`` on each motion as given; an error it raises names the motion
        in its note."""
        for name, motion in zip(self.names, self.motions):
            try:
                check_one(motion)
            except Exception as err:
                err.add_note(f"in the motion {name}")
                raise

    def peak_g(self, g: float) -> np.ndarray:
        """Peak |a| of each scaled motion [g] (one g = ``g`` [m/s²]), shape (n_motions,
        n_scales); the largest component's of a multi-component motion."""
        own = np.array([_peak(m) for m in self.motions])
        return own[:, None] * self.factors / g


def cases(motions, *, scale=None, pga=None, polarity="normal", g: float, pga_rounding="exact",
          check_peak=True) -> Cases:
    """The cases of ``motions`` (one excitation, a sequence, a mapping name -> excitation, a
    :class:`RecordSet`, or a path to a record file or a folder of them, read with one g =
    ``g`` [m/s²]) at factors ``scale`` [-] or target peaks ``pga`` [g] (a number or a 1-D
    sequence each) in ``polarity`` ("normal", "inverse" or "both")."""
    if polarity not in POLARITIES:
        raise ValueError(f"polarity must be one of {POLARITIES}, got {polarity!r}")
    names, motions, metadata = labelled_motions(motions, g)
    if scale is not None and pga is not None:
        raise ValueError("give scale or pga, not both")
    if pga is None:
        targets = _values("scale", 1.0 if scale is None else scale)
        factors = np.tile(targets, (len(motions), 1))
    else:
        targets = check_pga(pga, check_peak=check_peak)
        check_pga_rounding(pga_rounding)
        factors = np.array([_pga_factors(name, motion, targets, g, pga_rounding, check_peak)
                            for name, motion in zip(names, motions)])
    polarities = ("normal", "inverse") if polarity == "both" else (polarity,)
    return Cases(names, tuple(motions), factors, "scale" if pga is None else "pga", targets, polarities, metadata)


def labelled_motions(motions, g: float):
    """(labels, motions, a record set's metadata or None) of one motion, a sequence, a
    mapping name -> motion, a :class:`RecordSet`, or a path to a record file or a folder of
    them (read with one g = ``g`` [m/s²]); a sequence is labelled by each record's name."""
    metadata = motions.metadata if isinstance(motions, RecordSet) else None
    return *_labelled(_read(motions, g)), metadata


def _read(motions, g):
    """Excitations from a record file or a folder of them, else ``motions`` (one: a list of it)."""
    if not is_many(motions):
        return [motions]
    if isinstance(motions, RecordSet):
        return list(motions)
    if not isinstance(motions, (str, os.PathLike)):
        return motions
    path = pathlib.Path(motions)
    return [read_record(p, g=g) for p in (record_files(path) if path.is_dir() else [path])]


def _labelled(motions):
    """(labels, excitations) of a sequence or mapping of excitations; a sequence is
    labelled by each record's ``name`` (else "motion i", i its position)."""
    items = list(motions.items()) if isinstance(motions, Mapping) else \
        [(getattr(m, "name", "") or f"motion {i}", m) for i, m in enumerate(motions)]
    if not items:
        raise ValueError("motions is empty: give at least one excitation")
    for name, motion in items:
        if is_many(motion):
            raise TypeError(f"motions must be excitations (Record, Harmonic, BaseMotion, ...); {name!r} is a "
                            f"{type(motion).__name__}")
    return tuple(str(name) for name, _ in items), [m for _, m in items]


def _pga_factors(name, motion, targets, g, rounding, check_peak):
    if isinstance(motion, BaseMotion):
        raise ValueError(f"{name}: pga scales a motion of one component; for a BaseMotion give scale [-]")
    try:
        return np.atleast_1d(pga_factor(motion.peak_acceleration, targets, g, rounding, name=f"pga ({name})",
                                        check_peak=check_peak))
    except ValueError as err:  # a motion of zeros
        raise ValueError(f"{name}: {err}") from None


def _peak(motion) -> float:
    peak = getattr(motion, "peak_acceleration", np.nan)
    return float(max(peak)) if isinstance(peak, tuple) else float(peak)


def _values(name, values) -> np.ndarray:
    array = np.atleast_1d(np.asarray(values, dtype=float))
    if array.ndim != 1 or array.size == 0 or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be a finite number or a non-empty 1-D sequence, got {values!r}")
    return array
