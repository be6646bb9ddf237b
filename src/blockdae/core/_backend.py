"""The contract every backend fulfils."""

import abc
import dataclasses
import functools
import math

import numpy as np

from ._solution import BatchSolution, of_run
from ..excitation import AbstractExcitation
from .contract import AbstractHybridModel


@dataclasses.dataclass(frozen=True)
class Horizon:
    """Where a run ends: at ``t_end`` [s], or (``t_end`` None) when the block has come
    to rest after the excitation ends."""

    t_end: float | None

    @classmethod
    def resolve(cls, excitation: AbstractExcitation, t_end) -> "Horizon":
        if t_end is None:
            if not math.isfinite(excitation.duration):
                raise ValueError(f"{type(excitation).__name__} never ends: give t_end [s]")
            return _UNTIL_REST
        t_end = float(t_end)
        if not (math.isfinite(t_end) and t_end > 0):
            raise ValueError(f"t_end must be a positive finite time [s], got {t_end!r}")
        return cls(t_end)

    @property
    def until_rest(self) -> bool:
        return self.t_end is None

    def integration_end(self, excitation: AbstractExcitation) -> float:
        """End of the part driven by a(t) [s]; a rest-seeking tail may follow."""
        return excitation.duration if self.t_end is None else self.t_end


_UNTIL_REST = Horizon(None)


def cached_per_excitation(build):
    """``build(excitation, t_end, window)`` kept for the last few excitations, which are
    immutable; an unhashable (user-defined) excitation is built afresh every call."""
    cached = functools.lru_cache(maxsize=16)(build)

    @functools.wraps(build)
    def get(excitation, t_end, window):
        try:
            return cached(excitation, t_end, window)
        except TypeError:  # an unhashable user-defined excitation
            return build(excitation, t_end, window)

    return get


def check_window(window) -> None:
    """The exact backends' ``window`` (pieces per block of a(t) bounds): an integer >= 1."""
    if not (isinstance(window, int) and window >= 1):
        raise ValueError(f"window must be an integer >= 1, got {window!r}")


class AbstractBackend(abc.ABC):
    """Integrates a hybrid model under an excitation to its solution.

    Backends are immutable settings objects; ``solve`` takes one parameter set,
    ``solve_batch`` a batch (by default one ``solve`` per set). A backend knows engines,
    never models: a model names the engine it runs on with each backend (its
    ``engines``); a generic backend (``generic``) runs any other model on the hybrid
    driver.
    """

    name: str
    #: whether models without an engine of this backend run on the generic driver
    generic: bool = True

    def runs(self, model) -> bool:
        """Whether this backend runs ``model``."""
        return isinstance(model, AbstractHybridModel) and (self.generic or self.name in model.engines)

    def engine(self, model) -> str | None:
        """The engine ``model`` runs on here (its ``engines``), None: the generic driver."""
        return model.engines.get(self.name)

    @abc.abstractmethod
    def solve(self, block, excitation: AbstractExcitation, horizon: Horizon):
        """One parameter set."""

    def solve_batch(self, block, excitation: AbstractExcitation, horizon: Horizon) -> BatchSolution:
        """A batch of parameter sets (``block.batch_shape == (n,)``)."""
        n = block.batch_shape[0]
        items = [block.item(i) for i in range(n)]
        sols = [of_run(self.solve(item, excitation, horizon), item, excitation) for item in items]
        return BatchSolution(
            displacement=np.array([s.displacement for s in sols]),
            max_abs_displacement=np.array([s.max_abs_displacement for s in sols]),
            n_events=np.array([len(s.events) for s in sols]),
            t_end=np.array([s.t_end for s in sols]),
            backend=self.name,
            solve_one=sols.__getitem__,
        )
