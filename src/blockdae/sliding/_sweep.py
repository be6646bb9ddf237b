"""A parameter grid over several motions and amplitude scales in one call: ``simulate_many``."""

import dataclasses
import warnings
from collections.abc import Mapping

import numpy as np

from ..core import BatchSolution, compact_repr, simulate
from ..excitation import AbstractExcitation, check_horizontal, check_pga, check_pga_rounding, pga_factor
from ._model import SlidingBlock


@dataclasses.dataclass(frozen=True, eq=False)
class SweepSolution:
    """Results of a parameter grid under several motions, each at several amplitude scales.

    Attributes:
        names: label of each motion, length n_motions.
        scale: factor on a(t) of each (motion, scale) [-], shape (n_motions, n_scales).
        batches: the :class:`BatchSolution` of each (motion, scale), ``batches[i][j]``;
            each keeps its grid (``.block``) and its scaled motion (``.motion``).

    Result arrays (``displacement`` [m], ``max_abs_displacement`` [m], ``n_events``,
    ``t_end`` [s]) have shape (n_motions, n_scales, n_sets).
    """

    def __repr__(self):
        return compact_repr(self)

    names: tuple[str, ...]
    scale: np.ndarray
    batches: tuple[tuple[BatchSolution, ...], ...]

    @property
    def shape(self) -> tuple[int, int, int]:
        """(n_motions, n_scales, n_sets)."""
        return self.scale.shape + (len(self.batches[0][0]),)

    def __getitem__(self, index: tuple[int, int]) -> BatchSolution:
        """The batch of motion ``i`` at scale ``j``: ``sweep[i, j]``."""
        i, j = index
        return self.batches[i][j]

    def _stack(self, name):
        return np.array([[getattr(batch, name) for batch in row] for row in self.batches])

    @property
    def displacement(self) -> np.ndarray:
        """u(t_end) [m], shape (n_motions, n_scales, n_sets)."""
        return self._stack("displacement")

    @property
    def max_abs_displacement(self) -> np.ndarray:
        """max |u| [m], shape (n_motions, n_scales, n_sets)."""
        return self._stack("max_abs_displacement")

    @property
    def n_events(self) -> np.ndarray:
        """Number of events, shape (n_motions, n_scales, n_sets)."""
        return self._stack("n_events")

    @property
    def t_end(self) -> np.ndarray:
        """Final time [s], shape (n_motions, n_scales, n_sets)."""
        return self._stack("t_end")

    def to_dataframe(self):
        """A tidy pandas DataFrame, one row per (motion, scale, parameter set): record
        (the motion's label), scale [-], pga_m_s2 (peak of the scaled a(t) [m/s²]) and
        the columns of :meth:`BatchSolution.to_dataframe`."""
        import pandas as pd

        frames = []
        for name, scales, row in zip(self.names, self.scale, self.batches):
            for k, batch in zip(scales, row):
                frame = batch.to_dataframe()
                frame.insert(0, "pga_m_s2", batch.motion.peak_acceleration)
                frame.insert(0, "scale", float(k))
                frame.insert(0, "record", name)
                frames.append(frame)
        return pd.concat(frames, ignore_index=True)


def simulate_many(block: SlidingBlock, motions, t_end: float | None = None, backend: str = "exact", *,
                  scale=None, pga=None, pga_rounding: str = "exact", check_peak=True, **options) -> SweepSolution:
    """Slide every parameter set of ``block`` under every motion, at every amplitude scale.

    Args:
        block: the block; a grid of parameter sets if its parameters are 1-D arrays
            (a single set is a grid of one).
        motions: base excitations, a sequence or a mapping label -> excitation; a
            sequence is labelled by each :class:`Record`'s ``name`` (else its repr).
        t_end: final time [s]; None: until the block rests after each motion ends.
        backend, **options: as for :func:`blockdae.simulate`.
        scale: factor(s) on a(t) [-], a number or a 1-D sequence (default 1; -1 inverts).
        pga: instead of ``scale``, target peak ground acceleration(s) [g], a number or a
            1-D sequence: each motion is scaled so that max |a(t)| is each value times the
            block's g (see :func:`blockdae.excitation.pga_factor`; values above 2, likely m/s², are refused).
        pga_rounding: "exact" (default) or "slammer": each motion's own peak rounded to
            0.001 g before scaling, as SLAMMER scales.
        check_peak: False accepts a ``pga`` above 2 g.

    Returns:
        A :class:`SweepSolution` of shape (n_motions, n_scales, n_sets).

    Deprecated: :func:`blockdae.simulate` with many motions runs every model, in
    both polarities where asked, into one :class:`blockdae.Ensemble`.
    """
    warnings.warn("blockdae.sliding.simulate_many is deprecated; use bd.simulate(block, motions, scale=..., pga=...), "
                  "which runs every model and returns a bd.Ensemble", DeprecationWarning, stacklevel=2)
    if not isinstance(block, SlidingBlock):
        raise TypeError(f"block must be a SlidingBlock, got {type(block).__name__}")
    names, motions = _labelled(motions)
    factors = _factors(motions, scale, pga, block.g, pga_rounding, check_peak)
    grid = block if block.batch_shape else block.replace(mu=np.atleast_1d(block.mu))
    batches = tuple(tuple(simulate(grid, motion.scaled(k), t_end, backend, **options) for k in row)
                    for motion, row in zip(motions, factors))
    return SweepSolution(names=names, scale=factors, batches=batches)


def _labelled(motions):
    """(labels, excitations) of a sequence or mapping of excitations."""
    if isinstance(motions, AbstractExcitation):
        raise TypeError("motions must be a sequence of excitations; for one, use simulate or [motion]")
    items = list(motions.items()) if isinstance(motions, Mapping) else \
        [(getattr(m, "name", "") or repr(m), m) for m in motions]
    if not items:
        raise ValueError("motions is empty: give at least one excitation")
    for name, motion in items:
        if not isinstance(motion, AbstractExcitation):
            raise TypeError(f"motions must be excitations (Record, Harmonic, ...); {name!r} is "
                            f"a {type(motion).__name__}")
        check_horizontal(motion)
    return tuple(str(name) for name, _ in items), [m for _, m in items]


def _factors(motions, scale, pga, g, rounding, check_peak) -> np.ndarray:
    """Factor on a(t) per (motion, scale) [-], shape (n_motions, n_scales); ``pga`` [g], one g = ``g`` [m/s²]."""
    if scale is not None and pga is not None:
        raise ValueError("give scale or pga, not both")
    if pga is None:
        k = _values("scale", 1.0 if scale is None else scale)
        return np.tile(k, (len(motions), 1))
    check_pga(pga, check_peak=check_peak), check_pga_rounding(rounding)  # before any motion
    rows = []
    for i, motion in enumerate(motions):
        try:
            rows.append(pga_factor(motion.peak_acceleration, np.atleast_1d(pga), float(g), rounding,
                                   check_peak=check_peak))
        except ValueError as err:  # a motion of zeros
            raise ValueError(f"motion {i}: {err}") from None
    return np.array(rows)


def _values(name, values) -> np.ndarray:
    array = np.atleast_1d(np.asarray(values, dtype=float))
    if array.ndim != 1 or array.size == 0 or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be a finite number or a non-empty 1-D sequence, got {values!r}")
    return array
