"""What the solutions of the driver's models share: knots, events and dense output."""

import dataclasses
from typing import Callable

import numpy as np


@dataclasses.dataclass(frozen=True, eq=False)
class DriverSolution:
    """Knots and located events of a model run by the hybrid driver.

    Attributes:
        t: knot times [s], shape (n,).
        state: the model's state at the knots, shape (n, k).
        mode: mode right after each knot, shape (n,) of int (the model's modes).
        events: located events, in time order.
        backend: name of the backend that produced it.
        dense: ``dense(t)`` -> the k states at times ``t`` [s] (tuple of arrays).
        stats: counters.
        block, motion: the model and the base motion (set by :func:`blockdae.simulate`).
    """

    t: np.ndarray
    state: np.ndarray
    mode: np.ndarray
    events: tuple
    backend: str
    dense: Callable = dataclasses.field(repr=False)
    stats: dict = dataclasses.field(default_factory=dict)
    block: object = dataclasses.field(default=None, repr=False)
    motion: object = dataclasses.field(default=None, repr=False)

    @property
    def t_end(self) -> float:
        """Final time [s]."""
        return float(self.t[-1])

    @property
    def t_events(self) -> np.ndarray:
        """Event times [s], shape (n_events,)."""
        return np.array([e.t for e in self.events])

    def dense_state(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(state of shape t.shape + (k,), mode of shape t.shape) at times ``t`` in
        [0, t_end] [s]."""
        t = np.asarray(t, dtype=float)
        if np.any((t < self.t[0]) | (t > self.t[-1])):
            raise ValueError(f"t must lie in [{self.t[0]}, {self.t[-1]}] s")
        mode = self.mode[np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, len(self.t) - 1)]
        return np.stack(self.dense(t), axis=-1), mode
