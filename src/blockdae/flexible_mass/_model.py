"""The flexible sliding mass as a hybrid automaton (Rathje & Bray 2000; the equations in
docs/flexible-mass.md, "The model").

The sliding mass is the first mode of a uniform shear column (:class:`ShearColumn`):
u is the modal coordinate (the top relative to the base of the mass), omega its
circular frequency and xi its total damping ratio. On a base acceleration a(t) [m/s²]
(downslope = the +ky direction) its average acceleration is HEA = a + (2/pi) u''. With
the sliding displacement s and velocity w = s' of the base (one-way: downslope only):

    STICK:            u'' = -(4/pi) a - 2 xi omega u' - omega² u;    s' = w' = 0
    SLIP, decoupled:  u'' as in STICK;                               s' = w,  w' = HEA - ky g
    SLIP, coupled:    d1 u'' = -(4/pi) ky g - 2 xi omega u' - omega² u;  s' = w,  w' = a - ky g + (2/pi) u''

with d1 = 1 - 8/pi² (ky may be a table of s: :class:`KyTable`). STICK is left when
ky g - HEA falls through 0 (onset), SLIP when w falls through 0 (stop, w := 0). Every
mode is linear in (u, u', s, w) with a forcing linear in t on each piece of a record:
the exact backend (:mod:`._exact`; :mod:`._table_engine` for a ky table) steps closed
forms and locates every event to adjacent floats.
"""

import dataclasses
import math

import numpy as np

from ..core import set_batch_fields, set_real_fields
from ..core.contract import KNOTS_PER_RADIAN, BatchedModel, DifferentiableModel, StudyModel, scale_factor_units
from ..excitation import MAX_KY_G, ky_not_reached
from ..units import STANDARD_GRAVITY
from ._column import MASS_PARTICIPATION, MODE_PARTICIPATION, SLIP_MASS_FRACTION, ShearColumn
from ._exact import ExactEngine
from ._ky_table import KyTable, next_breakpoint, piece_ky, piecewise_ky
from ._modes import EVENT_KINDS, FlexibleMode
from ._solution import FlexibleEvent, FlexibleSolution

#: the slip equations: "coupled" (Rathje & Bray 1999) or "decoupled" (Bray & Rathje 1998)
METHODS = ("coupled", "decoupled")
#: a ky table's parameters: breakpoint_j [m], ky_intercept_j [g], ky_slope_j [g/m]
_TABLE_PARAMETERS = ("breakpoint", "ky_intercept", "ky_slope")
_U, _V, _S, _W, _PASSED = range(5)
#: the next breakpoint once all are passed [m]: a guard that is never reached
_BEYOND = 1e30


@dataclasses.dataclass(frozen=True, eq=False)
class FlexibleSlidingMass(DifferentiableModel, StudyModel, BatchedModel):
    """A flexible sliding mass: a shear column on a slip surface of yield acceleration ky.

    Args:
        column: the sliding mass (:class:`ShearColumn`: height [m], vs, vr [m/s],
            damping ratios).
        ky: yield acceleration [g], >= 0; the base slides downslope (the +ky
            direction) while it transmits ky g. A :class:`KyTable` makes it a function
            of the sliding displacement s (linear between breakpoints; a one-row table
            is its constant ky): the state then has a fifth entry, the breakpoints
            passed, and SLIP a second guard, the next breakpoint minus s, whose
            crossing is a "breakpoint" event (SLIP to SLIP).
        method: "coupled" (the column's response feels the sliding) or "decoupled"
            (the stick response drives a rigid block).
        g: the value of one g [m/s²].

    ``ky`` may be a 1-D array of yield accelerations [g]: a batch of parameter sets, which
    :func:`blockdae.simulate` runs into a :class:`~blockdae.core.BatchSolution`
    (``item(i)``: set i as a model of its own).

    The excitation's component 0 is the ground acceleration along the slope [m/s²].
    State y = (u [m], u' [m/s], s [m], w [m/s]); the displacement is s, downslope positive.
    """

    column: ShearColumn
    ky: float | KyTable
    method: str = "coupled"
    g: float = STANDARD_GRAVITY

    state_names = ("u", "u_rate", "s", "w")
    state_units = ("m", "m/s", "m", "m/s")
    modes = FlexibleMode
    initial_mode = FlexibleMode.STICK
    displacement_states = (_S,)
    default_backend = "exact"
    engines = {"exact": ExactEngine()}
    #: the share of the column's u'' in HEA, the sliding mass's average acceleration
    mass_participation = MASS_PARTICIPATION
    #: HEA at rest as a share of a: u'' = -(4/pi) a there, so HEA = a + (2/pi) u'' = (1 - 8/pi²) a
    hea_share_at_rest = SLIP_MASS_FRACTION

    def __post_init__(self):
        if _is_batch(self.ky):
            return _check_batch(self)
        if not isinstance(self.column, ShearColumn):
            raise TypeError(f"column must be a ShearColumn(height, vs, ...), got {type(self.column).__name__}")
        if isinstance(self.ky, KyTable) and self.ky.constant:
            object.__setattr__(self, "ky", self.ky.ky_g[0])
        if isinstance(self.ky, KyTable):
            from ._table_engine import TableEngine

            set_real_fields(self, ("g",))
            object.__setattr__(self, "table", self.ky.segments())
            object.__setattr__(self, "state_names", FlexibleSlidingMass.state_names + ("breakpoints_passed",))
            object.__setattr__(self, "state_units", FlexibleSlidingMass.state_units + ("-",))
            object.__setattr__(self, "engines", {"exact": TableEngine()})
        else:
            set_real_fields(self, ("ky", "g"))
            object.__setattr__(self, "table", None)
        if self.table is None and self.ky < 0:
            raise ValueError(f"ky={self.ky!r} must be a yield acceleration >= 0 [g]")
        if self.g <= 0:
            raise ValueError(f"g={self.g!r} must be > 0 [m/s²]")
        if self.method not in METHODS:
            raise ValueError(f"method={self.method!r} is unknown; choose one of {METHODS}")
        object.__setattr__(self, "omega", self.column.omega)
        object.__setattr__(self, "damping", self.column.total_damping)
        object.__setattr__(self, "slip_mass_fraction", SLIP_MASS_FRACTION)

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """() for one parameter set, (n,) for a batch of n yield accelerations."""
        return np.shape(self.ky) if isinstance(self.ky, np.ndarray) else ()

    def item(self, index: int) -> "FlexibleSlidingMass":
        """Parameter set ``index`` of a batch (its ky), as a model of one set."""
        return dataclasses.replace(self, ky=float(self.ky[index]))

    parameter_labels = {"ky": "yield acceleration ky [g]"}

    def batch_parameters(self) -> dict:
        """ky [g], of shape ``batch_shape``."""
        return {"ky": np.broadcast_to(np.asarray(self.ky, dtype=float), self.batch_shape)}

    @property
    def coupled(self) -> bool:
        """Whether the slip equations are the coupled ones."""
        return self.method == "coupled"

    @property
    def yield_acceleration(self) -> float:
        """ky g [m/s²] (of a table: at s = 0)."""
        return self.ky_at(0.0) * self.g

    def ky_at(self, s, xp=np):
        """ky [g] at the sliding displacement ``s`` [m]."""
        if self.table is None:
            return self.ky + 0.0 * s
        return piecewise_ky(s, *self.table, xp)

    def _friction(self, y, xp=np):
        """ky(s) g [m/s²] in state ``y``; of a table, on the piece that the breakpoints
        passed select (the events switch pieces: the flow is smooth between them, also
        for its derivatives, whatever side of a breakpoint rounding puts s on)."""
        if self.table is None:
            return self.ky_at(y[_S], xp) * self.g
        return piece_ky(y[_PASSED], y[_S], *self.table, xp) * self.g

    def _friction_rate(self, y):
        """d(ky(s) g)/dt = ky'(s) g w [m/s³] (0 for a constant ky; w = 0 in STICK)."""
        if self.table is None:
            return 0.0
        return float(self.table[2][int(round(float(y[_PASSED])))]) * self.g * y[_W]

    def _more(self, y):
        """The states beyond (u, u', s, w): the breakpoints passed, for a table."""
        return () if self.table is None else (y[_PASSED],)

    def replace(self, **changes) -> "FlexibleSlidingMass":
        """A copy with some of column, ky, method, g changed (validated again)."""
        return dataclasses.replace(self, **changes)

    # ---- the physics ------------------------------------------------------------
    def modal_acceleration(self, mode, a, y, xp=np):
        """u'' [m/s²] in ``mode`` at ground acceleration ``a`` [m/s²] in state ``y``."""
        elastic = 2 * self.damping * self.omega * y[_V] + self.omega**2 * y[_U]
        if mode == FlexibleMode.SLIP and self.coupled:
            return (-MODE_PARTICIPATION * self._friction(y, xp) - elastic) / self.slip_mass_fraction
        return -MODE_PARTICIPATION * a - elastic

    def modal_jerk(self, mode, a_rate, y, accel):
        """u''' [m/s³] from u'' = ``accel`` and a' = ``a_rate`` [m/s³] (a'' = 0)."""
        elastic = 2 * self.damping * self.omega * accel + self.omega**2 * y[_V]
        if mode == FlexibleMode.SLIP and self.coupled:
            return -(elastic + MODE_PARTICIPATION * self._friction_rate(y)) / self.slip_mass_fraction
        return -MODE_PARTICIPATION * a_rate - elastic

    def hea(self, mode, a, y, xp=np):
        """The column's average acceleration a + (2/pi) u'' [m/s²] (the base shear per unit mass)."""
        return a + MASS_PARTICIPATION * self.modal_acceleration(mode, a, y, xp)

    # ---- hybrid automaton ------------------------------------------------------
    def flow(self, mode, t, y, excitation, xp=np):
        """(u', u'', s', w') in ``mode``."""
        a = excitation.acceleration(t)
        accel = self.modal_acceleration(mode, a, y, xp)
        more = tuple(0.0 * y[_W] for _ in self._more(y))
        if mode == FlexibleMode.STICK:
            return xp.stack([y[_V], accel, 0.0 * y[_W], 0.0 * y[_W], *more])
        return xp.stack([y[_V], accel, y[_W], a - self._friction(y, xp) + MASS_PARTICIPATION * accel, *more])

    def guards(self, mode, t, y, excitation, xp=np):
        """STICK: ky g - HEA (onset as it falls through 0); SLIP: w (stop) and, with a
        ky table, the next breakpoint minus s (a breakpoint crossed)."""
        if mode == FlexibleMode.STICK:
            return xp.stack([self._friction(y, xp) - self.hea(mode, excitation.acceleration(t), y, xp)])
        if self.table is None:
            return xp.stack([y[_W]])
        return xp.stack([y[_W], next_breakpoint(y[_PASSED], self.table[0], xp, _BEYOND) - y[_S]])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        """At rest HEA = d1 a: SLIP where it exceeds ky g (or reaches it rising)."""
        excess = SLIP_MASS_FRACTION * excitation.acceleration(t) - self.yield_acceleration
        if excess > 0 or (excess == 0 and excitation.acceleration_rate(t) > 0):
            return FlexibleMode.SLIP
        return FlexibleMode.STICK

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        """STICK -> SLIP at an onset, SLIP -> STICK at a stop; a breakpoint stays in SLIP."""
        if mode == FlexibleMode.SLIP and guard_index == 1:
            return FlexibleMode.SLIP
        return FlexibleMode.SLIP if mode == FlexibleMode.STICK else FlexibleMode.STICK

    def guard_restarts(self, mode, guard_index):
        """A breakpoint crossed is an event (ky's slope changes) though SLIP stays."""
        return mode == FlexibleMode.SLIP and guard_index == 1

    def state_on_entry(self, before, after, t, y, excitation, xp=np):
        """Past a breakpoint (SLIP to SLIP) the count of breakpoints passed grows by one."""
        if self.table is not None and before == after == FlexibleMode.SLIP:
            return xp.stack([y[_U], y[_V], y[_S], y[_W], y[_PASSED] + 1.0])
        return y

    # ---- what the hybrid driver asks --------------------------------------------
    def is_static(self, mode):
        return False  # the column oscillates in both modes

    def at_rest(self, mode, y):
        """Only the initial state: nothing has moved yet."""
        return mode == FlexibleMode.STICK and not np.any(np.asarray(y, dtype=float))

    def rest_state(self, y):
        return np.array([y[_U], 0.0, y[_S], 0.0, *self._more(y)])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """w = 0 exactly at a stop (it is 0 in STICK); a breakpoint keeps the state."""
        if mode == FlexibleMode.SLIP and guard_index == 1:
            return y
        return xp.stack([y[_U], y[_V], y[_S], 0.0 * y[_W], *self._more(y)])

    def turn_rate(self, mode, t, y, excitation, xp=np):
        return None  # the solvers' steps and the driver's knots resolve the oscillation

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(rate, curvature) of the guard [m/s³, m/s⁴ at STICK; m/s², m/s³ at SLIP] on a
        linear piece of a(t)."""
        a, a_rate = excitation.acceleration(t), excitation.acceleration_rate(t)
        accel = self.modal_acceleration(mode, a, y)
        jerk = self.modal_jerk(mode, a_rate, y, accel)
        if mode == FlexibleMode.STICK:  # -(a + (2/pi) u'')
            snap = -2 * self.damping * self.omega * jerk - self.omega**2 * accel
            return -a_rate - MASS_PARTICIPATION * jerk, -MASS_PARTICIPATION * snap
        w_rate = a - self._friction(y) + MASS_PARTICIPATION * accel
        if guard_index == 1:  # the next breakpoint minus s
            return -y[_W], -w_rate
        return w_rate, a_rate - self._friction_rate(y) + MASS_PARTICIPATION * jerk

    def contradiction(self, mode, y, velocity_error):
        """A slide moving upslope: w [m/s] below zero."""
        if mode == FlexibleMode.SLIP and y[_W] < -velocity_error:
            return f"w = {y[_W]:+.6g} m/s points upslope"
        return None

    def output_step(self):
        """Largest gap between dense-output knots [s]: 1 / (32 omega) of the fastest mode."""
        fastest = self.omega / math.sqrt(SLIP_MASS_FRACTION) if self.coupled else self.omega
        return 1.0 / (KNOTS_PER_RADIAN * fastest)

    def speed(self, y):
        return max(abs(float(y[_V])), abs(float(y[_W])))

    def time_to_rest(self, mode, y):
        raise ValueError("the column oscillates on after the record: give t_end [s]")

    # ---- parameters, for JAX ------------------------------------------------------
    def parameters(self):
        """omega [rad/s], damping (total ratio) [-], ky [g], g [m/s²]; coupled also d1 =
        slip_mass_fraction [-], which only its slip reads (so that the compiled rules of
        the two methods, cached by parameter names, differ)."""
        named = {"omega": self.omega, "damping": self.damping, "g": self.g}
        if self.table is None:
            named["ky"] = self.ky
        else:  # a ky table: its reachable breakpoints [m], its pieces' intercepts [g] and slopes [g/m]
            for label, values in zip(_TABLE_PARAMETERS, self.table):
                named |= {f"{label}_{j}": float(v) for j, v in enumerate(values)}
        return named | ({"slip_mass_fraction": self.slip_mass_fraction} if self.coupled else {})

    def parameter_units(self) -> dict:
        """Units of :meth:`parameters` (omega [rad/s], ky and intercepts [g], breakpoints
        [m], slopes [g/m], ...) and of the motion's scale factors (A [g])."""
        units = {"omega": "rad/s", "damping": "-", "g": "m/s²", "ky": "g", "breakpoint": "m",
                 "ky_intercept": "g", "ky_slope": "g/m", "slip_mass_fraction": "-"}
        return {name: units[name.rstrip("0123456789").rstrip("_")] for name in self.parameters()} \
            | scale_factor_units(self)

    def with_parameters(self, values):
        model = object.__new__(FlexibleSlidingMass)
        for name in ("column", "method", "table", "state_names", "state_units", "ky"):
            object.__setattr__(model, name, getattr(self, name))
        if self.table is not None:
            object.__setattr__(model, "engines", self.engines)
        named = {**self.parameters(), **values}
        for name, value in named.items():
            object.__setattr__(model, name, value)
        if self.table is not None:
            object.__setattr__(model, "table", tuple([named[f"{label}_{j}"] for j in range(len(part))]
                                                     for label, part in zip(_TABLE_PARAMETERS, self.table)))
        return model

    def event(self, t, mode_before, mode_after, y):
        return FlexibleEvent(float(t), mode_before, mode_after, EVENT_KINDS[(mode_before, mode_after)],
                             *(float(v) for v in y[:4]))

    def solution(self, *, t, y, mode, events, backend, dense, stats):
        return FlexibleSolution(t=t, state=y, mode=mode, events=events, backend=backend, dense=dense, stats=stats)

    def check_solution(self, solution):
        """The ky rule of ``bd.flexible`` on a run of :func:`blockdae.simulate` (a
        :class:`FlexibleSolution`, or a batch's :class:`~blockdae.core.BatchSolution`): a
        ValueError (:func:`~blockdae.excitation.ky_not_reached`) where the mass did not slide
        and its ky [g] is above :data:`~blockdae.excitation.MAX_KY_G` (likely m/s²), naming
        the peak of the mass's average acceleration HEA at the knots [g]."""
        ky = np.atleast_1d(np.asarray(self.batch_parameters()["ky"] if self.batch_shape else self.ky_at(0.0)))
        if not np.any(ky > MAX_KY_G):  # the common case: nothing to look at
            return
        still = np.atleast_1d(solution.max_abs_displacement) == 0
        for j in np.flatnonzero(still & (ky > MAX_KY_G)):  # rare: an error follows
            run = solution[int(j)] if self.batch_shape else solution
            peak = float(np.max(run.hea(run.t))) / self.g
            where = f"parameter set {j} of {self.batch_shape[0]}: " if self.batch_shape else ""
            ky_not_reached(ky[j], peak, where, "the peak of the mass's average acceleration HEA")

    # ---- bd.study ------------------------------------------------------------------
    #: what :func:`bd.study` sweeps: its keyword, the table's column, the unit (the
    #: mass's ``study_batch`` and ``study_sweep``, which run ``bd.flexible``'s rows, are in
    #: :mod:`._study`, attached by the package)
    study_parameter = ("ky", "ky_g", "g")


def _is_batch(ky) -> bool:
    """Whether ``ky`` is a batch of yield accelerations (a sequence, not a KyTable)."""
    return not isinstance(ky, KyTable) and np.ndim(ky) > 0


def _check_batch(model) -> None:
    """A batch of yield accelerations: ``model.ky`` set to a read-only 1-D array [g], each
    value (and the other settings) checked as one set's (ValueError naming the set)."""
    set_batch_fields(model, ("ky",))
    for i, ky in enumerate(model.ky):
        try:
            one = FlexibleSlidingMass(model.column, float(ky), model.method, model.g)
        except ValueError as error:
            raise ValueError(f"ky[{i}]: {error}") from None
    for name in ("g", "table", "omega", "damping", "slip_mass_fraction"):
        object.__setattr__(model, name, getattr(one, name))
