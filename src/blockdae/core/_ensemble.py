"""The one result of many runs: :class:`Ensemble`, a case per motion x factor x polarity x
parameter set, for every model."""

import dataclasses

import numpy as np

from ..units import STANDARD_GRAVITY
from ._cases import Cases
from ._repr import compact_repr


@dataclasses.dataclass(frozen=True, eq=False)
class Finals:
    """The final numbers of one motion x factor x polarity over the model's parameter sets
    (n of them, 1 for a model of one set).

    Attributes:
        displacement: the displacement states at the end, shape (n, d) (d: the model's
            ``displacement_states``), in the model's ``displacement_unit`` ([m]; [rad] for a
            rotation), as is max_abs_displacement.
        max_abs_displacement: max |displacement| over the run, shape (n,).
        n_events: located events, shape (n,).
        t_end: final time [s], shape (n,).
    """

    displacement: np.ndarray
    max_abs_displacement: np.ndarray
    n_events: np.ndarray
    t_end: np.ndarray

    @classmethod
    def of(cls, solution) -> "Finals":
        """The final numbers of a solution of one parameter set or of a :class:`BatchSolution`."""
        batch = np.ndim(solution.max_abs_displacement) == 1
        n_events = solution.n_events if batch else len(solution.events)
        u = np.asarray(solution.displacement, dtype=float)
        return cls(displacement=u.reshape(np.size(solution.max_abs_displacement), -1),
                   max_abs_displacement=np.atleast_1d(np.asarray(solution.max_abs_displacement, dtype=float)),
                   n_events=np.atleast_1d(np.asarray(n_events, dtype=int)),
                   t_end=np.atleast_1d(np.asarray(solution.t_end, dtype=float)))


@dataclasses.dataclass(frozen=True, eq=False)
class Ensemble:
    """Results of one model over many cases: motions x scales (or target PGAs) x polarities
    x parameter sets, what :func:`blockdae.simulate` returns for many motions or factors.

    A case is a row of :meth:`to_dataframe`; ``ensemble[i]`` is the full solution (events,
    dense output) of row ``i``, run again where only the final numbers were kept;
    ``len(ensemble)`` is the number of rows. Arrays (``displacement``,
    ``max_abs_displacement``, ``n_events``, ``t_end``) have :attr:`shape`.

    Attributes:
        model: the model as given (a batch of parameter sets where its parameters are arrays).
        cases: the motions, their factors and polarities.
        finals: the final numbers per (motion, factor, polarity), nested in that order.
        solutions: the full solution per (motion, factor, polarity), nested likewise, where
            they were kept (a model of one parameter set, ``final_only=False``); else None.
        run: ``run(model, motion)`` -> the solution of one case (how the ensemble was run:
            its ``t_end`` and backend).
    """

    def __repr__(self):
        largest = np.nanmax(self.max_abs_displacement) if len(self) else float("nan")
        n_motions, n_scales, n_polarities = self.cases.shape
        states = self.model.displacement_states
        name = self.model.state_names[states[0]] if len(states) == 1 else "u"
        return compact_repr(self, f"{n_motions} motions x {n_scales} {self.cases.by} x {n_polarities} polarities x "
                                  f"{self._n_sets} parameter sets, largest max |{name}| {largest:.4g} "
                                  f"{self.model.displacement_unit}; .to_dataframe()")

    model: object
    cases: Cases
    finals: tuple
    solutions: tuple | None = dataclasses.field(default=None, repr=False)
    run: object = dataclasses.field(default=None, repr=False)

    @property
    def _n_sets(self) -> int:
        return int(np.prod(self.model.batch_shape)) if self.model.batch_shape else 1

    @property
    def shape(self) -> tuple[int, ...]:
        """(n_motions, n_scales, n_polarities) + the model's batch shape."""
        return self.cases.shape + tuple(self.model.batch_shape)

    def __len__(self) -> int:
        return int(np.prod(self.cases.shape)) * self._n_sets

    def _stack(self, name) -> np.ndarray:
        """One of the finals' arrays, (n_motions, n_scales, n_polarities, n_sets) + its own trailing shape."""
        return np.array([[[getattr(f, name) for f in row] for row in motion] for motion in self.finals])

    def _shaped(self, values):
        return values.reshape(self.shape + values.shape[4:])

    @property
    def displacement(self) -> np.ndarray:
        """The displacement at the end, :attr:`shape` (+ (d,) for a model of d
        displacement states, e.g. (u_x, u_y)); signed, in the model's own convention and
        its ``displacement_unit`` ([m]; [rad] for a rotation)."""
        values = self._stack("displacement")
        return self._shaped(values[..., 0] if values.shape[-1] == 1 else values)

    @property
    def max_abs_displacement(self) -> np.ndarray:
        """max |displacement| over each run, :attr:`shape`, in the model's ``displacement_unit``."""
        return self._shaped(self._stack("max_abs_displacement"))

    @property
    def n_events(self) -> np.ndarray:
        """Located events of each run, :attr:`shape`."""
        return self._shaped(self._stack("n_events"))

    @property
    def t_end(self) -> np.ndarray:
        """Final time of each run [s], :attr:`shape`."""
        return self._shaped(self._stack("t_end"))

    def _case(self, row: int) -> tuple[int, int, int, int]:
        if not -len(self) <= row < len(self):
            raise IndexError(f"row {row} is out of range for {len(self)} cases")
        return tuple(int(i) for i in np.unravel_index(row % len(self), self.cases.shape + (self._n_sets,)))

    def __getitem__(self, row: int):
        """The full solution (events, dense output) of row ``row`` of :meth:`to_dataframe`."""
        if not isinstance(row, (int, np.integer)):
            raise TypeError(f"an ensemble is indexed by the row of its table (an int), got {type(row).__name__}")
        i, k, p, j = self._case(row)
        if self.solutions is not None:
            return self.solutions[i][k][p]
        model = self.model.item(j) if self.model.batch_shape else self.model
        return self.run(model, self.cases.motion(i, k, p))

    def to_dataframe(self, metadata: bool = True):
        """One row per case (pandas): record (the motion's label), the record set's metadata
        columns (if ``metadata`` and the motions came as a :class:`RecordSet`), scale (the
        factor on a(t) [-], polarity aside), pga_g (the scaled motion's peak [g]),
        polarity ("normal", or "inverse": a(t) times -1), the parameter set's columns
        (``set`` and the model's batch parameters, for a batch), then the displacement
        states at the end (``<state>_end_<unit>``, signed, in the model's
        ``displacement_unit``: ``u_end_m``, ``theta_end_rad``), ``max_abs_displacement_<unit>``,
        n_events, t_end_s [s], then the model's own columns (its ``final_quantities``: a
        rocking block's ``overturned`` and ``max_theta_over_alpha``)."""
        import pandas as pd

        from ..excitation import with_metadata

        i, k, p, j = np.indices(self.cases.shape + (self._n_sets,)).reshape(4, -1)
        g = float(getattr(self.model, "g", STANDARD_GRAVITY))
        columns = {"record": np.asarray(self.cases.names, dtype=object)[i], "scale": self.cases.factors[i, k],
                   "pga_g": self.cases.peak_g(g)[i, k], "polarity": np.asarray(self.cases.polarities, dtype=object)[p]}
        if self.model.batch_shape:
            columns["set"] = j
            columns |= {name: np.broadcast_to(value, self.model.batch_shape).reshape(-1)[j]
                        for name, value in self.model.batch_parameters().items()}
        table = pd.DataFrame(columns | self.final_columns())
        return with_metadata(table, self.cases.metadata) if metadata else table

    def final_columns(self) -> dict:
        """The columns of :meth:`to_dataframe` after the case's, name -> one value per row
        in its order: the displacement states at the end (``<state>_end_<unit>``, in the
        model's ``displacement_unit``), ``max_abs_displacement_<unit>``, n_events, t_end_s
        [s], then the model's own (its ``final_quantities``)."""
        u = self._stack("displacement").reshape(len(self), -1)
        largest = self._stack("max_abs_displacement").reshape(-1)
        names, unit = [self.model.state_names[s] for s in self.model.displacement_states], self.model.displacement_unit
        columns = {f"{name}_end_{unit}": u[:, s] for s, name in enumerate(names)}
        columns |= {f"max_abs_displacement_{unit}": largest,
                    "n_events": self._stack("n_events").reshape(-1), "t_end_s": self._stack("t_end").reshape(-1)}
        return columns | self.model.final_quantities(u, largest)

    def figure(self, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
        """max |displacement| [m] of every case against the scaled motion's peak [g]: a line
        per (motion, polarity, parameter set) across the factors, a marker per case (the
        other arguments are unused); a matplotlib Figure."""
        from ._figures import ensemble_figure

        return ensemble_figure(self, title=title)

    def plot(self, *, title: str | None = None):
        """:meth:`figure` (a matplotlib Figure)."""
        return self.figure(title=title)
