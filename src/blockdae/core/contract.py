"""The model contract: everything blockdae asks of a model, grouped by capability.

A model is a subclass of :class:`AbstractHybridModel` (the hybrid automaton: what every
backend and the driver ask). What more it can do it declares by also subclassing a
capability, and the package chooses by these declarations (``isinstance``), never by a
model's class or name:

* :class:`BatchedModel`: array parameters, one model for a batch of parameter sets;
* :class:`DifferentiableModel`: :func:`blockdae.sensitivities` and
  :func:`blockdae.crosscheck`'s derivatives (the generic trajectory method by
  default, or the model's own);
* :class:`LinearModesModel`: linear flows and affine guards, run in closed form by the
  compiled linear engine (``engines = {"exact": "linear"}``);
* :class:`EngineModel`: the packed parameters of a compiled engine the model ships;
* :class:`StudyModel`: what :func:`blockdae.study` sweeps and tabulates.

Units are SI (m, s, m/s²) unless stated; ``g`` [m/s²] is the model's gravity.
"""

import abc
from collections.abc import Mapping
import enum
import math
import types

import numpy as np

from ..units import STANDARD_GRAVITY
from ._linear_modes import LinearModes
from ._solution import DriverSolution, HybridEvent
from ..excitation import AbstractExcitation, check_horizontal

__all__ = ["AbstractHybridModel", "BatchedModel", "DifferentiableModel", "EngineModel", "ExplicitForm", "LinearModes",
           "LinearModesModel", "SCALAR", "StudyBatch", "StudyModel"]

#: the array namespace of the model's xp-generic rules on Python floats (the driver's
#: and IDA's callbacks): the names of ``numpy``/``jax.numpy`` a rule may call
SCALAR = types.SimpleNamespace(
    stack=tuple, where=lambda cond, a, b: a if cond else b, pi=math.pi,
    abs=abs, sign=lambda x: float(x > 0) - float(x < 0), minimum=min, maximum=max, hypot=math.hypot,
    sqrt=math.sqrt, exp=math.exp, log=math.log, sin=math.sin, cos=math.cos, tan=math.tan,
    arcsin=math.asin, arccos=math.acos, arctan=math.atan, arctan2=math.atan2, sinh=math.sinh,
    cosh=math.cosh, tanh=math.tanh)
#: dense-output knots per radian of an oscillation, of a(t) on sine pieces or of a
#: model's own: cubic Hermite's error is then near 1e-9 of the amplitude
#: (h^4 w^4 / 384 with h = 1 / (32 w))
KNOTS_PER_RADIAN = 32


class AbstractHybridModel(abc.ABC):
    """A hybrid automaton: continuous flows in discrete modes, guards, transitions.

    A model is pure physics. Backends integrate ``flow`` in one mode, locate the
    roots of ``guards`` and ask ``mode_after_guard`` which mode follows; none of them
    re-derives these rules. Every method that takes ``xp`` works on NumPy and on JAX
    arrays (``xp`` is the array namespace: ``numpy`` or ``jax.numpy``) and on Python
    floats (the driver's scalar namespace). ``excitation`` is the base motion, or the
    driver's one piece of it, with ``component(i, t)``/``component_rate(i, t)``
    (``acceleration``/``acceleration_rate``: component 0).

    Required: the class attributes ``state_names``, ``modes``, ``initial_mode`` and the
    abstract methods. Everything else has a default that fits a model without it. What
    more a model can do it declares by subclassing a capability below
    (:class:`BatchedModel`, :class:`DifferentiableModel`, :class:`LinearModesModel`,
    :class:`EngineModel`, :class:`StudyModel`).
    """

    # ---- what the model is -----------------------------------------------------

    #: names of the continuous states, in order
    state_names: tuple[str, ...]
    #: the unit of each state, in order ("m", "m/s", "rad", ...), which tables
    #: (``history()``, ``to_dataframe()``) put in their column names and figures on their
    #: axes; None: not declared (the names alone)
    state_units: tuple[str, ...] | None = None
    #: the mode enumeration (an IntEnum)
    modes: type[enum.IntEnum]
    #: the mode at t = 0 (the model starts at rest relative to its base)
    initial_mode: enum.IntEnum
    #: modes that last an instant: entered with a guard already below zero on purpose,
    #: left at once (a block released from a tilt); the driver's check that a mode is
    #: entered with its guards at or above zero skips them
    instant_modes: tuple = ()
    #: names of the excitation's components, in the order of ``excitation_pieces``
    component_names: tuple[str, ...] = ("x",)
    #: whether the motion shakes the model along its base (a record whose header says it is
    #: a vertical component is then refused); False for a model shaken vertically
    horizontal_motion: bool = True
    #: indices of the states that make up the displacement the solution reports
    displacement_states: tuple[int, ...] = (0,)

    # ---- which backend runs it ---------------------------------------------------
    #: the backend :func:`blockdae.simulate` uses when none is named
    default_backend: str = "cvode"
    #: backend name -> the engine it runs this model on: an object with ``solve`` (and
    #: ``solve_batch``/``solve_final`` where it batches; the contract of an engine is
    #: :mod:`blockdae.core._engines`, :class:`~blockdae.core._engines.LazyEngine` imports
    #: one on first use), or "linear": closed-form steps of linear modes
    #: (:class:`LinearModesModel`); a backend not named here runs the model on the generic
    #: driver ("cvode", "ida", "jax") or not at all ("exact", "exact-jax", "compiled")
    engines: dict = {}

    @property
    def displacement_unit(self) -> str:
        """The unit of the displacement states ("rad" for a rotation), in the names of an
        ensemble's columns: theirs in :attr:`state_units`, "m" where those are not declared."""
        return self.state_units[self.displacement_states[0]] if self.state_units else "m"

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """() : one parameter set (a :class:`BatchedModel` may hold several)."""
        return ()

    def initial_state(self):
        """The state at t = 0 in :attr:`initial_mode`, shape (n,) [the units of
        :attr:`state_names`]: at rest relative to the base (zeros) by default. A model that
        starts elsewhere (a static offset, a block already sliding) returns its own,
        checked by the model where it is built (the driver checks that every guard of
        :attr:`initial_mode` is at or above zero there, as on entering any mode). The
        derivatives along the trajectory take it as independent of the parameters."""
        return np.zeros(len(self.state_names))

    def check_motion(self, motion) -> None:
        """Raise TypeError unless ``motion`` is a base motion this model runs under (an
        excitation, by default); ValueError for a vertical component where the model takes
        horizontal motion (:attr:`horizontal_motion`)."""
        if not isinstance(motion, AbstractExcitation):
            raise TypeError(f"motion must be an excitation (Harmonic, Record, ...), got {type(motion).__name__}")
        if self.horizontal_motion:
            check_horizontal(motion)

    def final_quantities(self, displacement, max_abs_displacement) -> dict:
        """Column name -> values of the model's own columns in an ensemble's table (e.g.
        whether a rocking block overturned), from the final numbers of n runs: the
        displacement states at the end, shape (n, d), and max |displacement|, shape (n,),
        in :attr:`displacement_unit`; none by default."""
        return {}

    # ---- the automaton -------------------------------------------------------
    @abc.abstractmethod
    def flow(self, mode, t, y, excitation, xp):
        """dy/dt in ``mode`` at time ``t`` [s], for state ``y`` of shape (n,)."""

    @abc.abstractmethod
    def guards(self, mode, t, y, excitation, xp):
        """Guard functions of ``mode``, shape (n_guards,).

        Each is oriented so that the mode is left when it crosses zero downwards
        (direction -1); this fixes the direction at build time for every backend.
        """

    @abc.abstractmethod
    def mode_at_rest(self, t, excitation, xp, y=None):
        """The mode a block at rest relative to its base takes at ``t`` (in state ``y``,
        where the mode depends on more than the excitation: a compliant support)."""

    @abc.abstractmethod
    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp, time_tol=0.0):
        """The mode entered when guard ``guard_index`` of ``mode`` is reached; a
        threshold reached within ``time_tol`` [s] of ``t`` counts as reached at ``t``
        (0: within rounding; ODE backends pass the uncertainty of a located root)."""

    # ---- what the hybrid driver asks (state bookkeeping) ---------------------
    def excitation_pieces(self, excitation, t_end):
        """The excitation's components as :class:`~blockdae.excitation.Pieces` on one
        partition of [0, t_end] [s] (one component by default)."""
        return (excitation.pieces(t_end),)

    # The hooks below have defaults that follow from the automaton alone; a model
    # overrides them where it knows more (exact values, a static mode: speed).
    def is_static(self, mode) -> bool:
        """Whether the state is constant in ``mode`` (no integration needed); False by
        default (every mode is integrated: a zero flow stays put)."""
        return False

    def at_rest(self, mode, y) -> bool:
        """Whether the block is at rest relative to its base (it re-takes
        ``mode_at_rest`` when a new piece of the excitation begins); False by default (the
        mode changes at guards only)."""
        return False

    def rest_state(self, y):
        """``y`` with the relative velocities set to zero (by default the states that are
        not :attr:`displacement_states`, as in (u, u'))."""
        return np.array([v if i in self.displacement_states else 0.0 for i, v in enumerate(y)], dtype=float)

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """The state where guard ``guard_index`` of ``mode`` is zero (e.g. v = 0 at a
        stop, exactly), from the located ``y`` (``y`` itself by default)."""
        return y

    def state_on_entry(self, before, after, t, y, excitation, xp):
        """The state on entering ``after`` from ``before`` at ``t`` (unchanged by default)."""
        return y

    # ---- parameters, for the JAX twin's compiled rules -----------------------------
    def parameters(self) -> dict:
        """The model's real parameters by name [their units]: every value that ``flow``,
        ``guards``, ``state_at_guard`` and ``state_on_entry`` read (what the JAX twin
        passes its compiled rules as arguments and :class:`DifferentiableModel`
        differentiates). Needed by the "jax" backend."""
        raise NotImplementedError(f"{type(self).__name__} does not list its parameters")

    def with_parameters(self, values: dict) -> "AbstractHybridModel":
        """This model with the parameters ``values`` (name -> number or traced JAX
        scalar, names from :meth:`parameters`), not validated: for compiled rules."""
        raise NotImplementedError(f"{type(self).__name__} does not take traced parameters")

    # ---- the driver's hooks: dense output, turning points, consistency --------------
    def output_step(self) -> float:
        """Largest gap between dense-output knots [s] the model's own motion needs
        (inf: the excitation alone sets it)."""
        return math.inf

    def guard_restarts(self, mode, guard_index) -> bool:
        """Whether reaching the guard is an event even if the mode stays (False)."""
        return False

    def turn_rate(self, mode, t, y, excitation, xp):
        """A quantity, monotone on a piece of the excitation, whose sign change marks
        where a guard of ``mode`` may turn: the driver stops the integrator there, so
        that each guard is monotone between stops and no step hides two of its roots.
        None (the default): the guards of ``mode`` cannot turn within a piece (or the
        integrators' steps resolve them); a guard that starts at zero is still judged by
        its rate and curvature (:meth:`guard_rates`)."""
        return None

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(rate, curvature) of the guard in time near ``t`` [unit/s, unit/s²], with
        their signs (a guard at zero that falls, by its rate or, at a zero rate, by its
        curvature, is left at once); a model that knows only a bound on the curvature
        gives it as a non-negative number (the uncertainty of a located root needs
        only its size).

        By default from ``guards`` and ``flow`` by backward differences along the flow
        (right-hand limits on the piece: its closed form extends before ``t``), with the
        step :data:`RATE_STEP` [s]: rate to O(h²), curvature to O(h) and rounding of
        about 1e-16 |g| / h²; a model that knows them exactly gives them (a graze whose
        curvature is of rounding size is decided by its sign)."""
        return difference_rates(self, mode, guard_index, t, y, excitation)

    def contradiction(self, mode, y, velocity_error) -> str | None:
        """Why the state ``y`` cannot be in ``mode`` (a slide moving against its
        direction, a rising flight falling, ...) by more than ``velocity_error`` [m/s],
        as a phrase with values and units; None where it can (the default: no check).
        The driver raises :class:`~blockdae.InconsistentStateError` on it."""
        return None

    def speed(self, y) -> float:
        """Size of the relative velocity [m/s] (sets the velocity error scale): by default
        the largest |y_i| of the states that are not :attr:`displacement_states`."""
        return max((abs(float(v)) for i, v in enumerate(y) if i not in self.displacement_states), default=0.0)

    def time_to_rest(self, mode, y) -> float:
        """After the excitation ends: a time [s] within which the block comes to rest
        from ``y`` in ``mode``; raises ValueError if it never does (the default: the
        model gives no bound, so a run needs ``t_end``)."""
        raise ValueError(f"{type(self).__name__} gives no time to come to rest after the motion: give t_end [s]")

    def event(self, t, mode_before, mode_after, y):
        """The event record of a mode change at ``t`` [s] in state ``y`` (a
        :class:`~blockdae.core.HybridEvent` by default)."""
        return HybridEvent(float(t), mode_before, mode_after, tuple(float(v) for v in y))

    # ---- what the driver returns ---------------------------------------------------
    def solution(self, *, t, y, mode, events, backend, dense, stats):
        """The model's solution from the driver's knots: ``t`` (n,), ``y`` (n, k),
        ``mode`` (n,), ``dense(t)`` -> k arrays (a :class:`~blockdae.core.DriverSolution` by
        default; any :class:`~blockdae.core.AbstractSolution`)."""
        return DriverSolution(t=t, state=y, mode=mode, events=events, backend=backend, dense=dense, stats=stats)

    def check_solution(self, solution) -> None:
        """Called by :func:`blockdae.simulate` with every solution of this model, on every
        backend, for one motion or many (its ``block`` and ``motion`` set; a batch's
        :class:`~blockdae.core.BatchSolution`; not the final numbers that ``final_only``
        takes from one compiled call): warn, or raise, where the run left what the model
        assumes (a free-standing block's contact force leaving its limits) and only the
        whole solution shows it. Nothing by default."""

    # ---- for IDA ---------------------------------------------------------------------
    def dae_form(self, piece):
        """The model as a DAE for IDA on the driver's excitation ``piece``: by default
        the explicit ODE y' = flow (:class:`ExplicitForm`); a model with algebraic
        variables (a friction force) returns its own form of the same interface."""
        return ExplicitForm(self, piece)


#: the step [s] of the default :meth:`AbstractHybridModel.guard_rates`' differences
RATE_STEP = 1e-5


def difference_rates(model, mode, guard_index, t, y, excitation, h=RATE_STEP):
    """(rate [unit/s], curvature [unit/s²]) of guard ``guard_index`` of ``mode`` at ``t``
    [s] in state ``y``, from backward differences of ``model.guards`` along ``model.flow``
    (the state at t - k h from its Taylor series to second order)."""
    guard = lambda s, x: float(model.guards(mode, s, x, excitation, SCALAR)[guard_index])
    y = np.asarray(y, dtype=float)
    rate = np.array(model.flow(mode, t, y, excitation, SCALAR), dtype=float)
    back = y - h * rate
    rate_back = np.array(model.flow(mode, t - h, back, excitation, SCALAR), dtype=float)
    accel = (rate - rate_back) / h
    g0 = guard(t, y)
    g1 = guard(t - h, y - h * rate + 0.5 * h**2 * accel)
    g2 = guard(t - 2 * h, y - 2 * h * rate + 2 * h**2 * accel)
    return (3 * g0 - 4 * g1 + g2) / (2 * h), (g0 - 2 * g1 + g2) / h**2


class BatchedModel(AbstractHybridModel):
    """A model whose parameters may be 1-D arrays: a batch of parameter sets, run by
    ``solve_batch`` (one compiled call where its engine has one) into a
    :class:`~blockdae.core.BatchSolution`."""

    #: gravity [m/s²] (a batch's table states it)
    g: float

    @property
    @abc.abstractmethod
    def batch_shape(self) -> tuple[int, ...]:
        """() for one parameter set, (n,) for a batch of n."""

    @abc.abstractmethod
    def item(self, index: int) -> "BatchedModel":
        """The ``index``-th parameter set of a batch, as a model of one set."""

    @abc.abstractmethod
    def replace(self, **changes) -> "BatchedModel":
        """A copy with some parameters changed (validated again; raises ValueError)."""

    #: parameter name -> a figure's axis label, with its unit ("static friction
    #: coefficient mu [-]"); a name not here is shown as it is
    parameter_labels: dict = {}

    @abc.abstractmethod
    def batch_parameters(self) -> dict:
        """The grid: name -> values of shape ``batch_shape`` (what a batch's table and
        figure show)."""


class DifferentiableModel(AbstractHybridModel):
    """A model :func:`blockdae.sensitivities` differentiates, and whose derivatives
    :func:`blockdae.crosscheck` compares.

    Names it is differentiated by (``wrt``): its :meth:`parameters`, "A_<component>"
    (one component's scale factor [-], at 1) and "A" (every component scaled so that the
    largest peak is A g [g]), unless :meth:`sensitivities` is the model's own. By default
    the derivatives are those of the displacement at t_end along the trajectory the JAX
    twin locates (the variational equation and the saltation jump at every event), and
    with ``of`` those of the scalar quantities it declares (:meth:`scalar_quantities`).
    """

    #: gravity [m/s²]: "A" is in units of it (standard gravity unless the model has a g of
    #: its own)
    g: float = STANDARD_GRAVITY
    #: backends whose kernels differentiate the model (others: finite differences)
    differentiated_backends: tuple[str, ...] = ("jax",)
    #: whether :meth:`sensitivities` gives derivatives of the displacement at t_end
    #: (what :func:`blockdae.crosscheck` compares); False: of other quantities
    differentiates_displacement: bool = True

    def default_wrt(self) -> tuple[str, ...]:
        """The names :func:`blockdae.sensitivities` differentiates by when given none
        (every parameter by default)."""
        return tuple(self.parameters())

    @abc.abstractmethod
    def parameter_units(self) -> dict:
        """name -> unit of each name ``wrt`` may hold ("-": none; "g" for "A"; see
        :func:`scale_factor_units`); a derivative is in the displacement's
        unit per this one."""

    def replace_parameter(self, name: str, value: float) -> "DifferentiableModel":
        """A validated copy with parameter ``name`` (from :meth:`parameters`) set to
        ``value``; raises ValueError where that is no valid model (finite differences
        step from the valid side). By default through the model's ``replace(**changes)``."""
        return self.replace(**{name: value})

    def tied_parameters(self) -> dict:
        """name -> the parameters that move with it as ``replace_parameter(name, ...)``
        moves them (e.g. a kinetic friction that defaults to the static one); none by
        default."""
        return {}

    def sensitivities(self, motion, t_end, wrt, backend, of, options) -> Mapping:
        """The model's own derivative method: d displacement(t_end) / d p for p in
        ``wrt`` (a tuple of names), on ``backend`` (None: the model's default) with the
        backend's ``options`` (a dict); ``of``: what is differentiated, for a model with
        more than its displacement (None). Returns a :class:`~blockdae.Sensitivities`
        (``Sensitivities.make(self, derivatives, ...)``), or name -> a float or an array
        (a vector displacement, a batch: one row per set) [displacement unit per unit of
        the parameter], which :func:`blockdae.sensitivities` makes one of.
        NotImplemented (the default): :func:`blockdae.sensitivities` takes the
        core's, along the JAX twin's trajectory
        (:func:`blockdae.core.derivatives.trajectory_displacement_sensitivities`)."""
        return NotImplemented

    def scalar_quantities(self) -> dict:
        """name -> unit of the model's scalar quantities besides its displacement (a peak
        read at located events: the largest rotation of a rocking block) that
        :func:`blockdae.sensitivities` differentiates with ``of=name`` along the JAX
        twin's trajectory, by :meth:`scalar_quantity_jacobian`; none by default."""
        return {}

    def scalar_quantity_jacobian(self, name, solution, final, events) -> np.ndarray:
        """d quantity ``name`` / dp [its unit per unit of p], shape (n_p,), by the names of
        :func:`parameter_names` (the parameters, then each component's scale factor), from
        the trajectory the JAX twin located: ``solution`` (its run, with ``block`` and
        ``motion``), ``final`` dy(t_end)/dp (n_y, n_p) and ``events``, one per event of
        the solution with ``t``, ``dt_dp`` (n_p,), ``dy_dp_before`` and ``dy_dp_after``
        (n_y, n_p): the located state's total derivatives before and after the event's
        maps. Required where :meth:`scalar_quantities` names any."""
        raise NotImplementedError(f"{type(self).__name__} does not differentiate {name!r}")

    def finite_differences(self, motion, t_end, wrt, backend, step, options) -> dict:
        """The model's own finite differences of what :meth:`sensitivities` gives (same
        names and units) on ``backend``, with the relative ``step`` [-]. NotImplemented
        (the default): the core's central differences
        (:func:`blockdae.core.derivatives.parameter_differences`: each parameter moved
        by ``step`` times its value, or by ``step`` where it is 0, each component's scale
        by ``step``; one-sided, second order, from the valid side at a bound)."""
        return NotImplemented


def parameter_names(model) -> tuple[str, ...]:
    """The names the trajectory's sensitivities are by: the model's parameters, then
    "A_<component>" for each component's scale factor [-]."""
    return tuple(model.parameters()) + tuple(f"A_{name}" for name in model.component_names)


def scale_factor_units(model) -> dict:
    """The units of the excitation's scale factors a :class:`DifferentiableModel` is
    differentiated by: "A" [g] and each "A_<component>" [-] (to merge into its
    ``parameter_units()``)."""
    return {"A": "g", **{f"A_{name}": "-" for name in model.component_names}}


class LinearModesModel(AbstractHybridModel):
    """A model whose modes are linear, u'' + c u' + k u = b - a(t) on the state (u, u'),
    with affine guards and resets: the compiled linear engine (``engines = {"exact":
    "linear"}``) steps it in closed form from :meth:`linear_modes`."""

    @abc.abstractmethod
    def linear_flow(self, mode) -> tuple:
        """(k [1/s²], c [1/s], b [m/s²]) of u'' + c u' + k u = b - a(t) in ``mode``."""

    @abc.abstractmethod
    def affine_guards(self, mode) -> tuple:
        """The guards of ``mode`` as rows (alpha, beta, gamma) of alpha u + beta u' +
        gamma, in the order of :meth:`guards`."""

    def linear_modes(self) -> LinearModes:
        """The engine's tables: the flows of :meth:`linear_flow`, the guards of
        :meth:`affine_guards`, the transitions of :meth:`mode_after_guard` (which must
        not read t, y or the excitation) and the resets of :meth:`state_at_guard`
        (affine in y); the modes' values (0, 1, ...) index the tables."""
        modes = list(self.modes)
        flows = np.array([self.linear_flow(mode) for mode in modes])
        n_guards = max(len(self.affine_guards(mode)) for mode in modes)
        guards = np.tile([0.0, 0.0, 1.0], (len(modes), n_guards, 1))
        next_mode = np.zeros((len(modes), n_guards), dtype=np.int64)
        resets = np.tile([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], (len(modes), n_guards, 1, 1))
        for mode in modes:
            for j, row in enumerate(self.affine_guards(mode)):
                guards[mode, j] = row
                next_mode[mode, j] = self.mode_after_guard(mode, j, 0.0, None, None)
                # state_at_guard is affine in y: its map from the images of 0 and the unit vectors
                offset = np.asarray(self.state_at_guard(mode, j, np.zeros(2)), dtype=float)
                columns = [np.asarray(self.state_at_guard(mode, j, e), dtype=float) - offset for e in np.eye(2)]
                resets[mode, j] = np.column_stack([*columns, offset])
        return LinearModes(flows[:, 0], flows[:, 1], flows[:, 2], guards, next_mode, resets, int(self.initial_mode))


class EngineModel(AbstractHybridModel):
    """A model that runs on a compiled engine of its own system (its ``engines``: the 1-D
    block's kernels, the plane's); the engine reads its parameters packed by
    :meth:`engine_parameters` (and may read more of its own model: the 1-D block's
    direction flags, the plane's support)."""

    @abc.abstractmethod
    def engine_parameters(self, scale=(1.0,)) -> np.ndarray:
        """The engine's parameter rows, (m * s, p): the m parameter sets (1 for one set)
        each at the s factors of ``scale`` on a(t) [-]; set j at factor k is row j * s + k."""


class StudyBatch(abc.ABC):
    """What :func:`blockdae.study` asks of a model's ``study_batch``: the columns of its
    table (a study model may be its own batch)."""

    @abc.abstractmethod
    def study_columns(self, motions, t_end, scale, rtol=None) -> dict:
        """Columns of the study's table for this batch (m values of the swept parameter)
        on ``motions`` to ``t_end`` [s] (None: until rest) at the factors ``scale`` on
        a(t) [-]: name (with its unit) -> array of one row per motion x value x factor, in
        that order; ``rtol`` [-]: the integrators' tolerance where the model integrates
        (None: the model's own)."""

    def check_motions(self, motions, t_end) -> None:
        """Raise ValueError for motions (``t_end`` [s] or None) the batch cannot run (by
        default it runs every one)."""


class StudyModel(AbstractHybridModel, StudyBatch):
    """What :func:`blockdae.study` may ask of a model it sweeps over records, intensities
    and one of its parameters. :func:`blockdae.study` takes every model: each hook here is
    optional (a model need not subclass this class to declare one), and where a model
    declares none the study sweeps the keyword it is given (``mu=`` or ``ky=``) as the
    model's own parameter of that name, one model per value through its ``replace`` (or
    :func:`dataclasses.replace`), each motion x factor run by :func:`blockdae.simulate`
    on the model's default backend, with the columns of an ensemble's table."""

    #: gravity [m/s²] (the study's pga targets are in g)
    g: float
    #: what the study sweeps: (its keyword, the table's column, its unit); None (default):
    #: the keyword given to the study, the model's parameter of that name, in the column
    #: of that name (with its unit from ``parameter_units()`` where the model declares one)
    study_parameter: tuple[str, str, str] | None = None
    #: the polarities the study runs each motion in, a column of its table ("normal": the
    #: motion as given, "inverse": times -1); () (default): no polarity column (the
    #: motion as given, or the model's own columns cover both polarities)
    study_polarities: tuple[str, ...] = ()

    def study_parameter_for(self, given: dict) -> tuple[str, str, str] | None:
        """What the study sweeps given what the user gave (keyword -> values, None where
        not given): :attr:`study_parameter` by default; a model that takes another
        keyword for the same values (the rigid block's ky for its mu) returns it."""
        return self.study_parameter

    def study_batch(self, values) -> StudyBatch:
        """This model at every value of the swept parameter (what :meth:`study_sweep`
        made of the given values, else a 1-D array in its unit), checked against its
        other parameters: a batch whose ``study_columns`` run them together (one compiled
        call). NotImplemented (the default): the study runs one model per value through
        :func:`blockdae.simulate`."""
        return NotImplemented

    def study_sweep(self, given):
        """(values for the table (n,), what :meth:`study_batch` takes) from what the user
        gave, where the model takes more than numbers (a table per value); None: numbers,
        checked by the study (the default)."""
        return None

    def study_columns(self, motions, t_end, scale, rtol=None) -> dict:
        """:meth:`StudyBatch.study_columns`, for a model that is its own batch."""
        raise NotImplementedError(f"{type(self).__name__}'s study_batch tabulates the study")


class ExplicitForm:
    """A model's flow as the residual 0 = y' - flow(mode, t, y), no algebraic variable:
    what IDA runs for a model without a DAE form of its own. ``force_scale`` [-] sets
    the algebraic variables' tolerance (none here)."""

    n_friction, force_scale = 0, 1.0

    def __init__(self, model, piece):
        self.block, self.piece = model, piece
        self.n_states = len(model.state_names)

    def residual(self, mode):
        block, piece = self.block, self.piece

        def residual(t, y, yp, res):
            res[:] = yp - np.array(block.flow(mode, t, y, piece, SCALAR), dtype=float)

        return residual

    def guards(self, mode, t, y, out):
        out[:] = self.block.guards(mode, t, y, self.piece, SCALAR)

    def consistent(self, mode, t, y):
        """(y, y') at ``t`` from the flow."""
        return np.asarray(y, dtype=float), np.array(self.block.flow(mode, t, y, self.piece, SCALAR), dtype=float)
