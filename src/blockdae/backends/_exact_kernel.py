"""The exact backend's compiled kernel.

The excitation is a sequence of monotone closed-form pieces. Before the loop, every
piece is marked where its demand leaves [-mu g, mu g], so that from stick the loop jumps
to the next possible onset at once. In slip an iteration accumulates the closed-form
velocity over a window of ``window`` pieces and finds the first piece where v returns to
zero, or skips the window. Each event is located in closed form (linear pieces: linear
or quadratic equations) or by bracketing a monotone function (sine pieces), to machine
precision. The loop thus runs about (events + sliding pieces / window) times.

Everything is ``jax.numpy``: the kernel compiles, vectorises over parameter sets and
differentiates (forward mode) through the event times.
"""

import functools
from typing import NamedTuple

import jax
import jax.numpy as jnp

from ..excitation._pieces import accel, accel_int1, accel_int2, accel_rate, rebase
from ..model import comes_to_rest, demand, rest_mode, slip_constant, stop_mode
from ._closed_form import onset_delta, slip_motion, stop_delta


class Params(NamedTuple):
    """Scalar parameters of one run (all float64)."""

    mu: jax.Array  # static friction [-]
    f: jax.Array  # kinetic friction [-]
    bias: jax.Array  # R/Q [-]
    g: jax.Array  # [m/s²]
    scale: jax.Array  # factor on a(t) [-]


class EventLog(NamedTuple):
    """Fixed-capacity log of events, shape (capacity,) each."""

    t: jax.Array
    mode_before: jax.Array
    mode_after: jax.Array
    u: jax.Array


class State(NamedTuple):
    k: jax.Array  # index of the current piece
    tau: jax.Array  # time into the current piece [s]
    u: jax.Array  # [m]
    v: jax.Array  # [m/s]
    mode: jax.Array  # int: -1, 0, +1
    max_abs_u: jax.Array  # [m]
    n_events: jax.Array
    n_iterations: jax.Array
    log: EventLog


class _Rules(NamedTuple):
    params: Params
    allow_neg: jax.Array  # bool: slip- allowed
    allow_pos: jax.Array  # bool: slip+ allowed

    def at_rest(self, sigma, rate):
        p = self.params
        return rest_mode(sigma, rate, p.mu, p.g, self.allow_neg, self.allow_pos, jnp)


class _Excitation(NamedTuple):
    """The pieces with a(t) scaled, and where in stick the block may start to slide."""

    t0: jax.Array  # (n,) [s]
    h: jax.Array  # (n,) [s]
    cf: tuple  # coefficients, each (n,) (sine terms None for linear pieces)
    next_onset: jax.Array  # (n + 1,) first piece >= k whose demand leaves [-mu g, mu g]


def _prepare(rules, pieces, is_sine):
    p = rules.params
    cf = (pieces[2] * p.scale, pieces[3] * p.scale)
    cf += (pieces[4] * p.scale, pieces[5], pieces[6]) if is_sine else (None, None, None)
    up, down = _leaves_stick(rules, cf, pieces[1])
    n = pieces[0].shape[0]
    index = jnp.where(up | down, jnp.arange(n), n)
    next_onset = jnp.append(jax.lax.cummin(index, reverse=True), n)
    return _Excitation(pieces[0], pieces[1], cf, next_onset)


def _leaves_stick(rules, cf, rem):
    """Whether the demand exceeds +mu g (-> slip-) / -mu g (-> slip+) on [0, rem]."""
    p = rules.params
    limit = p.mu * p.g
    start = demand(accel(*cf, 0.0, jnp), p.bias, p.g)
    end = demand(accel(*cf, rem, jnp), p.bias, p.g)
    up = rules.allow_neg & ((end > limit) | (start > limit))
    down = rules.allow_pos & ((end < -limit) | (start < -limit))
    return up, down


def _piece(exc, j, tau):
    """Piece j from time ``tau`` into it: (start time [s], remaining length [s], coefficients)."""
    cf = rebase(*(None if c is None else c[j] for c in exc.cf), tau)
    return exc.t0[j] + tau, exc.h[j] - tau, cf


class _Candidate(NamedTuple):
    """The next event (if ``found``) or the state where the search stopped."""

    found: jax.Array
    k: jax.Array  # piece of the event, or where the search continues
    tau: jax.Array  # time into piece k [s]
    t: jax.Array  # event time [s]
    u: jax.Array  # [m]
    v: jax.Array  # [m/s], 0 at an event
    after: jax.Array  # mode after the event


def _next_onset(rules, exc, state, n_pieces, *, window, is_sine):
    """Stick: the onset in the rest of piece k, else in the first piece that allows one."""
    p = rules.params
    limit = p.mu * p.g
    _, rem_k, cf_k = _piece(exc, state.k, state.tau)
    up_k, down_k = _leaves_stick(rules, cf_k, rem_k)
    here = up_k | down_k
    j = jnp.where(here, state.k, exc.next_onset[jnp.minimum(state.k + 1, n_pieces)])
    found = here | (j < n_pieces)
    j = jnp.minimum(j, n_pieces - 1)
    tau = jnp.where(here, state.tau, 0.0)
    t_j, rem_j, cf_j = _piece(exc, j, tau)
    up_j, _ = _leaves_stick(rules, cf_j, rem_j)
    sigma_j = demand(accel(*cf_j, 0.0, jnp), p.bias, p.g)
    starts_up = rules.allow_neg & (sigma_j > limit)
    starts_down = rules.allow_pos & (sigma_j < -limit)
    # beyond a threshold at the start: onset there; else a (monotone) crosses one of them
    going_up = starts_up | (~starts_down & up_j)
    target = p.bias * p.g + jnp.where(going_up, limit, -limit)
    d = onset_delta(cf_j, rem_j, target, is_sine)
    # keep d in [0, rem]; jnp.clip would halve the derivative of a root on a bound
    d = jnp.where(starts_up | starts_down | (d < 0), 0.0, jnp.where(d > rem_j, rem_j, d))
    return _Candidate(found, jnp.where(found, j, n_pieces), jnp.where(found, tau + d, 0.0), t_j + d,
                      state.u, 0.0 * state.v, jnp.where(found, jnp.where(going_up, -1, 1), state.mode))


def _next_stop(rules, exc, state, n_pieces, *, window, is_sine):
    """Slip: v accumulated over a window of pieces; the first piece where it returns to 0."""
    p = rules.params
    take = lambda x: jax.lax.dynamic_slice_in_dim(x, state.k, window)
    offset = jnp.where(jnp.arange(window) == 0, state.tau, 0.0)
    cf = rebase(*(None if c is None else take(c) for c in exc.cf), offset)
    rem = take(exc.h) - offset
    c = slip_constant(state.mode, p.bias, p.f, p.g)
    dv = c * rem - accel_int1(*cf, rem, jnp)
    v_start = state.v + jnp.cumsum(dv) - dv
    du = v_start * rem + 0.5 * c * rem**2 - accel_int2(*cf, rem, jnp)
    u_start = state.u + jnp.cumsum(du) - du
    d_stop, stop = stop_delta(cf, rem, v_start, c, state.mode, is_sine)
    found = jnp.any(stop)
    i = jnp.argmax(stop)
    cf_i = tuple(None if x is None else x[i] for x in cf)
    d = d_stop[i]
    t_event = take(exc.t0)[i] + offset[i] + d
    u_event, _ = slip_motion(cf_i, d, u_start[i], v_start[i], c)
    after = _mode_after_stop(rules, cf_i, d, c, state.mode, t_event)
    return _Candidate(found, jnp.where(found, state.k + i, state.k + window),
                      jnp.where(found, offset[i] + d, 0.0), t_event,
                      jnp.where(found, u_event, u_start[-1] + du[-1]),
                      jnp.where(found, 0.0, v_start[-1] + dv[-1]), jnp.where(found, after, state.mode))


def _step(rules, exc, n_pieces, state, *, window, is_sine, log_events):
    """One iteration: to the next event, or as far as the search went without one."""
    static = dict(window=window, is_sine=is_sine)
    nxt = jax.lax.cond(state.mode == 0, functools.partial(_next_onset, **static),
                       functools.partial(_next_stop, **static), rules, exc, state, n_pieces)
    logged = nxt.found & (nxt.after != state.mode)
    log = state.log
    if log_events:
        slot = jnp.where(logged, state.n_events, log.t.shape[0])  # out of range: dropped
        log = EventLog(*(x.at[slot].set(y, mode="drop") for x, y in
                         zip(log, (nxt.t, state.mode, nxt.after, nxt.u))))
    return State(k=nxt.k, tau=nxt.tau, u=nxt.u, v=nxt.v, mode=nxt.after,
                 max_abs_u=jnp.maximum(state.max_abs_u, jnp.abs(nxt.u)),
                 n_events=state.n_events + logged, n_iterations=state.n_iterations + 1, log=log)


def _mode_after_stop(rules, cf, d, c, mode, t_stop):
    """Mode after v returns to zero in ``mode`` (the model's :func:`stop_mode`)."""
    p = rules.params
    return stop_mode(mode, c - accel(*cf, d, jnp), accel_rate(*cf, d, jnp), t_stop, p.mu, p.f, p.g,
                     rules.allow_neg, rules.allow_pos, jnp)


def _tail_to_rest(rules, state, t_start, log_events):
    """After the excitation (a = 0): slide until v = 0, then stick for good.

    Returns the final state, its time [s] and whether the block comes to rest.
    """
    p = rules.params
    sliding = state.v != 0
    c = slip_constant(state.mode, p.bias, p.f, p.g)
    rests = comes_to_rest(state.v, state.mode, p.bias, p.f, p.g)
    d = jnp.where(sliding & rests, -state.v / jnp.where(c != 0, c, 1.0), 0.0)
    u = state.u + 0.5 * state.v * d
    after = rules.at_rest(-p.bias * p.g, 0.0)
    logged = rests & (after != state.mode)
    log = state.log
    if log_events:
        slot = jnp.where(logged, state.n_events, log.t.shape[0])
        log = EventLog(*(x.at[slot].set(y, mode="drop") for x, y in
                         zip(log, (t_start + d, state.mode, after, u))))
    final = state._replace(u=u, v=jnp.where(rests, 0.0, state.v), mode=jnp.where(rests, after, state.mode),
                           max_abs_u=jnp.maximum(state.max_abs_u, jnp.abs(u)),
                           n_events=state.n_events + logged, log=log)
    return final, t_start + d, rests


_STATIC = ("window", "log_capacity", "is_sine")


def _run(params, allowed, pieces, n_pieces, until_rest, *, window, log_capacity, is_sine):
    """Integrate the block through the first ``n_pieces`` of ``pieces``.

    ``params``: (mu, f, bias, g, scale); ``allowed``: (slip- allowed, slip+ allowed).
    ``pieces``: tuple of (n,) arrays (see :class:`blockdae.excitation.Pieces`), with at
    least ``window`` empty pieces after the first ``n_pieces``. Returns
    (final State, t_final [s], rests (bool), finished (bool)). ``log_capacity`` events
    are logged (0: none, for batches).
    """
    rules = _Rules(Params(*params), *allowed)
    zero = jnp.zeros_like(params[0])
    zero_int = jnp.zeros((), int)
    capacity = max(log_capacity, 1)
    log = EventLog(jnp.zeros(capacity), jnp.zeros(capacity, int), jnp.zeros(capacity, int), jnp.zeros(capacity))
    init = State(zero_int, zero, zero, zero, zero_int, zero, zero_int, zero_int, log)
    max_iterations = n_pieces // window + 2 + 4 * pieces[0].shape[0]

    def running(state):
        return (state.k < n_pieces) & (state.n_iterations < max_iterations)

    exc = _prepare(rules, pieces, is_sine)
    step = functools.partial(_step, rules, exc, n_pieces, window=window, is_sine=is_sine,
                             log_events=log_capacity > 0)
    state = jax.lax.while_loop(running, step, init)
    finished = state.k >= n_pieces
    t_excitation_end = pieces[0][n_pieces - 1] + pieces[1][n_pieces - 1]
    final, t_rest, rests = _tail_to_rest(rules, state, t_excitation_end, log_capacity > 0)
    final = jax.tree.map(lambda a, b: jnp.where(until_rest, a, b), final, state)
    return final, jnp.where(until_rest, t_rest, t_excitation_end), rests | ~until_rest, finished


class Summary(NamedTuple):
    """A run's outcome, packed into two arrays so that it crosses to the host at once."""

    scalars: jax.Array  # (..., 8): u [m], v [m/s], mode, max |u| [m], n_events, t_final [s], rests, finished
    log: jax.Array  # (..., capacity, 4): t [s], mode_before, mode_after, u [m] per event

    @staticmethod
    def pack(final, t_final, rests, finished):
        scalars = (final.u, final.v, final.mode, final.max_abs_u, final.n_events, t_final, rests, finished)
        return Summary(jnp.stack([jnp.asarray(x, float) for x in scalars], axis=-1),
                       jnp.stack([jnp.asarray(x, float) for x in final.log], axis=-1))


def _packed(params, allowed, pieces, n_pieces, until_rest, **static):
    return Summary.pack(*_run(params, allowed, pieces, n_pieces, until_rest, **static))


#: one parameter set
run = jax.jit(_packed, static_argnames=_STATIC)


@functools.partial(jax.jit, static_argnames=_STATIC)
def run_batch(params, allowed, pieces, n_pieces, until_rest, **static):
    """``run`` vectorised over the leading axis of every entry of ``params``."""
    return jax.vmap(functools.partial(_packed, **static), in_axes=(0, None, None, None, None))(
        params, allowed, pieces, n_pieces, until_rest)
