"""Derivatives of a hybrid model's final state and events along its located trajectory.

The JAX twin (:mod:`blockdae.solvers._diffrax`) runs the generic driver once and
keeps its trace (every integrated stretch, guard root and mode change). The trace is
then replayed with the sensitivity matrix S = dy/dp of the state y to the parameters
p (the model's :meth:`~blockdae.AbstractHybridModel.parameters`, then one scale
factor per excitation component, at 1):

* on a stretch in a mode, S' = f_y S + f_p (the variational equation, by forward-mode
  JAX through ``model.flow``), integrated with diffrax alongside y from the driver's
  state at its start;
* at a guard root the event time moves by dt/dp = -(g_y S + g_p) / (g_t + g_y f-), and
  the state jumps by the model's maps h (``state_at_guard`` then ``state_on_entry``):
  S+ = h_y (S- + f- dt/dp) + h_t dt/dp + h_p - f+ dt/dp (the saltation matrix);
* a mode change at a piece start (a block at rest re-taking a mode) has a fixed time.

At every event the replay keeps dt/dp and the total derivatives of the located state
before and after the event's maps (:class:`EventSensitivity`), from which quantities
read at events (a liftoff velocity, a flight's height or duration) are differentiated.

Nothing here knows the model: flows, guards and maps come from the model, evaluated
on ``jax.numpy``.
"""

import dataclasses
import functools

import diffrax
import jax
import jax.numpy as jnp
import numpy as np
import optimistix as optx

from ..core import drive, jax_context
from ._diffrax import JaxPieceExcitation, ModelTemplate, Settings
from .diffrax_solvers import SOLVERS


@dataclasses.dataclass(frozen=True)
class EventSensitivity:
    """Derivatives at one located event, by the parameters of :func:`~blockdae.core.contract.parameter_names`
    (n_p of them) and the n_y states.

    Attributes:
        t: event time [s]; mode_before, mode_after: the modes on either side.
        dt_dp: d t_event / dp [s per unit], shape (n_p,).
        dy_dp_before: d y(t_event) / dp of the located state before the event's maps,
            S- + f- dt/dp [state unit per unit], shape (n_y, n_p).
        dy_dp_after: the same after them (``state_at_guard``, ``state_on_entry``),
            shape (n_y, n_p).
    """

    t: float
    mode_before: object
    mode_after: object
    dt_dp: np.ndarray
    dy_dp_before: np.ndarray
    dy_dp_after: np.ndarray


def displacement_jacobian(model, motion, horizon, backend):
    """d(final displacement)/dp [m per unit], shape (len(displacement_states),
    len(parameter_names(model))), along the trajectory the JAX twin ``backend`` locates."""
    _, S, _ = trajectory_sensitivities(model, motion, horizon, backend)
    return S[list(model.displacement_states)]


def trajectory_sensitivities(model, motion, horizon, backend):
    """The trajectory the JAX twin ``backend`` locates and its derivatives by the
    parameters of :func:`~blockdae.core.contract.parameter_names`: (solution, dy(t_end)/dp of shape (n_y, n_p),
    one :class:`EventSensitivity` per mode change of the run, in its order: one per event
    of the solution, unless the model merges some (an impact through an instant mode is
    two changes and one event))."""
    trace = []
    solution = drive(model, motion, horizon, backend.integrator, backend.name, backend.max_events_at_one_instant,
                     backend.event_resolution, (backend.rtol, backend.atol), trace=trace)
    settings = Settings(backend.solver or "dopri8", float(backend.rtol), float(backend.atol), backend.max_steps)
    theta = np.array([*model.parameters().values()] + [1.0] * len(model.component_names))
    template = ModelTemplate(model)
    events = []
    with jax_context():
        S = _replay(model, template, settings, theta, trace, events)
    changes = solution.stats["n_events"]  # the run's mode changes, before a model merges any
    if len(events) != changes:
        raise RuntimeError(f"the replay found {len(events)} events, the run {changes}")
    return solution, S, events


def _replay(model, template, settings, theta, trace, events):
    """S at the end of ``trace`` (see the module's docstring); appends an
    :class:`EventSensitivity` to ``events`` at every mode change."""
    S = np.zeros((len(model.state_names), len(theta)))
    pending = None  # (S- + f- dt/dp mapped so far, dt/dp, mode, t, y, piece) at an event
    located = None  # S- + f- dt/dp at the last guard, before its map
    for step in _joined(trace):
        kind = step[0]
        if kind == "flow":
            _, mode, t_from, y_from, t_to, piece = step
            if pending is not None:
                S, pending = _finish(template, pending, theta), None
            if not model.is_static(mode) and t_to > t_from:
                S, result = _variational(template, mode, settings)(theta, *_arrays(piece), t_from, t_to, y_from, S)
                if int(result) != diffrax.RESULTS.successful._value:
                    raise RuntimeError(f"the variational equation failed in {mode.name} on [{t_from:.12g}, "
                                       f"{t_to:.12g}] s (diffrax result {int(result)}); raise max_steps")
                S = np.asarray(S)
        elif kind == "guard":
            _, mode, index, t, y, piece = step
            if pending is not None and mode in model.instant_modes:
                # left at the instant it was entered: the event's time moves as the one
                # that entered it (its dt/dp kept), and the flow after it is f+
                S_bar, tau = pending[:2]
                S_bar, _, y, located = _guard_jump(template, mode, index)(theta, *_arrays(piece), t, y, S_bar)
                pending = (S_bar, tau, mode, t, y, piece)
                continue
            if pending is not None:
                S, pending = _finish(template, pending, theta), None
            S_bar, tau, y, located = _guard_jump(template, mode, index)(theta, *_arrays(piece), t, y, S)
            pending = (S_bar, tau, mode, t, y, piece)
        else:
            _, before, after, t, y, piece = step
            if pending is None:
                S_bar, tau, located = S, np.zeros(len(theta)), S
            else:
                S_bar, tau = pending[:2]
            S_bar, y = _entry_jump(template, before, after)(theta, *_arrays(piece), t, y, S_bar, tau)
            pending = (S_bar, tau, after, t, y, piece)
            events.append(EventSensitivity(t, before, after, *(np.asarray(a) for a in (tau, located, S_bar))))
            located = S_bar  # a further event at this instant starts from this one's state
    return np.asarray(S if pending is None else _finish(template, pending, theta))


def _joined(trace):
    """``trace`` with consecutive "flow" steps of one mode on one piece (the driver's
    dense-output knots) joined into one, integrated from the first one's state."""
    joined = []
    for step in trace:
        last = joined[-1] if joined else None
        if (step[0] == "flow" and last is not None and last[0] == "flow" and last[1] == step[1]
                and last[4] == step[2] and _same_piece(last[5], step[5])):
            joined[-1] = (*last[:4], step[4], last[5])
        else:
            joined.append(step)
    return joined


def _same_piece(a, b):
    return a[0] == b[0] and np.array_equal(a[1], b[1])


def _finish(template, pending, theta):
    """S just after the event: the mapped S- + f- dt/dp less f+ dt/dp."""
    S_bar, tau, mode, t, y, piece = pending
    return np.asarray(_flow_jump(template, mode)(theta, *_arrays(piece), t, y, S_bar, tau))


def _arrays(piece):
    t0, coefficients = piece
    return np.float64(t0), np.asarray(coefficients, dtype=float)


def _rules(template, theta, t0, coefficients):
    """The model and the piece's excitation with the parameters ``theta``."""
    names = tuple(template.parameters())
    model = template.with_parameters(dict(zip(names, theta[:len(names)])))
    return model, JaxPieceExcitation(t0, coefficients, theta[len(names):])


@functools.cache
def _variational(key, mode, settings):
    """(theta, t0, coefficients, t_from, t_to, y0, S0) -> (S(t_to), diffrax result)."""
    template = key.model

    def rhs(t, state, args):
        theta, t0, coefficients = args
        y, S = state
        flow = lambda y, theta: (lambda m, e: m.flow(mode, t, y, e, jnp))(*_rules(template, theta, t0, coefficients))
        tangent = lambda column, unit: jax.jvp(flow, (y, theta), (column, unit))[1]
        return flow(y, theta), jax.vmap(tangent, in_axes=(1, 0), out_axes=1)(S, jnp.eye(theta.shape[0]))

    def run(theta, t0, coefficients, t_from, t_to, y0, S0):
        sol = diffrax.diffeqsolve(
            diffrax.ODETerm(rhs), SOLVERS[settings.solver](), t0=t_from, t1=t_to, dt0=None, y0=(y0, S0),
            args=(theta, t0, coefficients), saveat=diffrax.SaveAt(t1=True),
            stepsize_controller=diffrax.PIDController(rtol=settings.rtol, atol=settings.atol, norm=_state_norm),
            max_steps=settings.max_steps, throw=False)
        return sol.ys[1][-1], sol.result._value

    return jax.jit(run)


def _state_norm(error):
    """The step-size controller's error norm on the state alone: S follows the same
    linearised dynamics, and its components near zero would otherwise force steps
    far below the state's (as CVODES without sensitivities in the error test)."""
    return optx.rms_norm(error[0])


@functools.cache
def _guard_jump(key, mode, index):
    """(theta, t0, coefficients, t, y, S) -> (h_y (S + f dt/dp) + h_p, dt/dp, h(y),
    S + f dt/dp) at the root of guard ``index``, h = ``state_at_guard``."""
    template = key.model

    def run(theta, t0, coefficients, t, y, S):
        def guard(t, y, theta):
            model, excitation = _rules(template, theta, t0, coefficients)
            return model.guards(mode, t, y, excitation, jnp)[index]

        model, excitation = _rules(template, theta, t0, coefficients)
        rate = model.flow(mode, t, y, excitation, jnp)
        g_t, g_y, g_p = jax.jacfwd(guard, argnums=(0, 1, 2))(t, y, theta)
        tau = -(g_y @ S + g_p) / (g_t + g_y @ rate)
        located = S + jnp.outer(rate, tau)
        at_guard = lambda y, theta: _rules(template, theta, t0, coefficients)[0].state_at_guard(mode, index, y, jnp)
        h_y, h_p = jax.jacfwd(at_guard, argnums=(0, 1))(y, theta)
        return h_y @ located + h_p, tau, at_guard(y, theta), located

    return jax.jit(run)


@functools.cache
def _entry_jump(key, before, after):
    """(theta, t0, coefficients, t, y, S_bar, dt/dp) -> (h_y S_bar + h_t dt/dp + h_p,
    h(y)), h = ``state_on_entry`` from ``before`` to ``after``."""
    template = key.model

    def run(theta, t0, coefficients, t, y, S_bar, tau):
        def entry(t, y, theta):
            model, excitation = _rules(template, theta, t0, coefficients)
            return model.state_on_entry(before, after, t, y, excitation, jnp)

        h_t, h_y, h_p = jax.jacfwd(entry, argnums=(0, 1, 2))(t, y, theta)
        return h_y @ S_bar + jnp.outer(h_t, tau) + h_p, entry(t, y, theta)

    return jax.jit(run)


@functools.cache
def _flow_jump(key, mode):
    """(theta, t0, coefficients, t, y, S_bar, dt/dp) -> S_bar - f dt/dp in ``mode``."""
    template = key.model

    def run(theta, t0, coefficients, t, y, S_bar, tau):
        model, excitation = _rules(template, theta, t0, coefficients)
        return S_bar - jnp.outer(model.flow(mode, t, y, excitation, jnp), tau)

    return jax.jit(run)
