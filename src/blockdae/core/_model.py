"""The contract a hybrid model gives to the driver and to the backends."""

import abc
import enum
import math
import types

import numpy as np

from ._solution import DriverSolution, HybridEvent
from ..excitation import AbstractExcitation
from ..excitation._record import check_horizontal

#: the array namespace of the model's xp-generic rules on Python floats (the driver's)
SCALAR = types.SimpleNamespace(stack=tuple, sqrt=math.sqrt, where=lambda cond, a, b: a if cond else b)
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
    """

    #: names of the continuous states, in order
    state_names: tuple[str, ...]
    #: the mode enumeration (an IntEnum)
    modes: type[enum.IntEnum]
    #: the mode at t = 0 (the model starts at rest relative to its base)
    initial_mode: enum.IntEnum
    #: names of the excitation's components, in the order of ``excitation_pieces``
    component_names: tuple[str, ...] = ("x",)
    #: whether the motion shakes the model along its base (a record whose header says it is
    #: a vertical component is then refused); False for a model shaken vertically
    horizontal_motion: bool = True
    #: indices of the states that make up the displacement the solution reports
    displacement_states: tuple[int, ...] = (0,)
    #: the backend :func:`blockdae.simulate` uses when none is named
    default_backend: str = "cvode"
    #: backend name -> the engine it runs this model on (see :mod:`._engines`: an object
    #: with ``solve``, and ``solve_batch``/``solve_final`` where it batches), or "linear"
    #: (the compiled engine of linear modes, for a model that declares its
    #: ``linear_modes``); a backend not named here runs the model on the generic driver
    #: ("cvode", "ida", "jax") or not at all ("exact", "exact-jax", "compiled")
    engines: dict = {}
    #: backends whose kernels differentiate the model (others: finite differences)
    differentiated_backends: tuple[str, ...] = ("jax",)
    #: how :func:`blockdae.sensitivities` differentiates it: "trajectory" (u(t_end)
    #: along the JAX twin's trajectory, variational equation and saltation jumps),
    #: "sliding" (the 1-D block's compiled kernels) or "flights" (a spring-supported
    #: mass's flight quantities)
    derivatives: str = "trajectory"

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """() for one parameter set (models with array parameters override it)."""
        return ()

    def check_motion(self, motion) -> None:
        """Raise TypeError unless ``motion`` is a base motion this model runs under (an
        excitation, by default); ValueError for a vertical component where the model takes
        horizontal motion (:attr:`horizontal_motion`)."""
        if not isinstance(motion, AbstractExcitation):
            raise TypeError(f"motion must be an excitation (Harmonic, Record, ...), got {type(motion).__name__}")
        if self.horizontal_motion:
            check_horizontal(motion)

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

    @abc.abstractmethod
    def is_static(self, mode) -> bool:
        """Whether the state is constant in ``mode`` (no integration needed)."""

    @abc.abstractmethod
    def at_rest(self, mode, y) -> bool:
        """Whether the block is at rest relative to its base (it re-takes
        ``mode_at_rest`` when a new piece of the excitation begins)."""

    @abc.abstractmethod
    def rest_state(self, y):
        """``y`` with the relative velocities set to zero."""

    @abc.abstractmethod
    def state_at_guard(self, mode, guard_index, y, xp=np):
        """The state where guard ``guard_index`` of ``mode`` is zero (e.g. v = 0 at a
        stop, exactly), from the located ``y``."""

    def state_on_entry(self, before, after, t, y, excitation, xp):
        """The state on entering ``after`` from ``before`` at ``t`` (unchanged by default)."""
        return y

    # ---- parameters, for JAX (compiled rules, derivatives) ------------------
    def parameters(self) -> dict:
        """The model's real parameters by name [their units]: every value that ``flow``,
        ``guards``, ``state_at_guard`` and ``state_on_entry`` read (what compiled
        backends pass as arguments and :func:`blockdae.sensitivities` differentiates)."""
        raise NotImplementedError(f"{type(self).__name__} does not list its parameters")

    def with_parameters(self, values: dict) -> "AbstractHybridModel":
        """This model with the parameters ``values`` (name -> number or traced JAX
        scalar, names from :meth:`parameters`), not validated: for compiled rules."""
        raise NotImplementedError(f"{type(self).__name__} does not take traced parameters")

    def replace_parameter(self, name: str, value: float) -> "AbstractHybridModel":
        """A validated copy with parameter ``name`` (from :meth:`parameters`) set to
        ``value``; raises ValueError where that is no valid model."""
        return self.replace(**{name: value})

    #: parameter name -> words for axis labels and tables ("static friction coefficient
    #: mu"); a name not here is shown as it is
    parameter_words: dict = {}

    def parameter_units(self) -> dict:
        """Parameter name -> its unit ("-" for a dimensionless one); a name not here is
        dimensionless."""
        return {}

    def tied_parameters(self) -> dict:
        """name -> the parameters that move with it as ``replace(name=...)`` moves them
        (e.g. a kinetic friction that defaults to the static one); none by default."""
        return {}

    def output_step(self) -> float:
        """Largest gap between dense-output knots [s] the model's own motion needs
        (inf: the excitation alone sets it)."""
        return math.inf

    def guard_restarts(self, mode, guard_index) -> bool:
        """Whether reaching the guard is an event even if the mode stays (False)."""
        return False

    @abc.abstractmethod
    def turn_rate(self, mode, t, y, excitation, xp):
        """A quantity, monotone on a piece of the excitation, whose sign change marks
        where a guard of ``mode`` may turn; None: the guards cannot turn."""

    @abc.abstractmethod
    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(rate, curvature) of the guard in time near ``t`` [unit/s, unit/s²], with
        their signs (a guard at zero that falls, by its rate or, at a zero rate, by its
        curvature, is left at once); a model that knows only a bound on the curvature
        gives it as a non-negative number (the uncertainty of a located root needs
        only its size)."""

    def contradiction(self, mode, y, velocity_error) -> str | None:
        """Why the state ``y`` cannot be in ``mode`` (a slide moving against its
        direction, a rising flight falling, ...) by more than ``velocity_error`` [m/s],
        as a phrase with values and units; None where it can (the default: no check).
        The driver raises :class:`~blockdae.InconsistentStateError` on it."""
        return None

    @abc.abstractmethod
    def speed(self, y) -> float:
        """Size of the relative velocity [m/s] (sets the velocity error scale)."""

    @abc.abstractmethod
    def time_to_rest(self, mode, y) -> float:
        """After the excitation ends: a time [s] within which the block comes to rest
        from ``y`` in ``mode``; raises ValueError if it never does."""

    def event(self, t, mode_before, mode_after, y):
        """The event record of a mode change at ``t`` [s] in state ``y`` (a
        :class:`~blockdae.HybridEvent` by default)."""
        return HybridEvent(float(t), mode_before, mode_after, tuple(float(v) for v in y))

    def solution(self, *, t, y, mode, events, backend, dense, stats):
        """The model's solution from the driver's knots: ``t`` (n,), ``y`` (n, k),
        ``mode`` (n,), ``dense(t)`` -> k arrays (a :class:`~blockdae.DriverSolution` by
        default)."""
        return DriverSolution(t=t, state=y, mode=mode, events=events, backend=backend, dense=dense, stats=stats)

    def dae_form(self, piece):
        """The model as a DAE for IDA on the driver's excitation ``piece``: by default
        the explicit ODE y' = flow (:class:`ExplicitForm`); a model with algebraic
        variables (a friction force) returns its own form of the same interface."""
        return ExplicitForm(self, piece)


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
