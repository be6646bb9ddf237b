"""The exact backend's compiled kernel.

The excitation is a sequence of monotone closed-form pieces. Once per excitation (on the
host, independently of the parameters) the range of a(t) is bounded over blocks of
``window`` pieces, so that from stick an iteration skips to the first block where the
demand may leave [-mu g, mu g] and checks its pieces one by one. In slip an iteration
accumulates the closed-form velocity over a window of ``window`` pieces and finds the
first piece where v returns to zero, or skips the window. Each event is located in
closed form (linear pieces: linear or quadratic equations) or by bracketing a monotone
function (sine pieces), to machine precision. The loop thus runs about (events +
sliding pieces / window) times.

Everything is ``jax.numpy``: the kernel compiles, maps over parameter sets and
differentiates (forward mode) through the event times.
"""

import functools
from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np

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


class State(NamedTuple):
    k: jax.Array  # index of the current piece
    tau: jax.Array  # time into the current piece [s]
    u: jax.Array  # [m]
    v: jax.Array  # [m/s]
    mode: jax.Array  # int: -1, 0, +1
    max_abs_u: jax.Array  # [m]
    n_events: jax.Array
    n_iterations: jax.Array
    log: jax.Array  # (capacity, 4): t [s], mode before, mode after, u [m] per event


def _logged(log, n_events, logged, t, before, after, u):
    """``log`` with (t, before, after, u) in row n_events; it counts only if ``logged``.

    An unconditional row update stays in place (a masked scatter copies the log every
    iteration); a row not logged is overwritten by the next event, and at n_events =
    capacity the last row is: the caller then reruns with a larger log.
    """
    if log.shape[0] == 0:
        return log, n_events + logged
    row = jnp.stack([jnp.asarray(x, log.dtype) for x in (t, before, after, u)])[None]
    slot = jnp.minimum(n_events, log.shape[0] - 1)
    return jax.lax.dynamic_update_slice(log, row, (slot, 0)), n_events + logged


class _Rules(NamedTuple):
    params: Params
    allow_neg: jax.Array  # bool: slip- allowed
    allow_pos: jax.Array  # bool: slip+ allowed

    def at_rest(self, sigma, rate):
        p = self.params
        return rest_mode(sigma, rate, p.mu, p.g, self.allow_neg, self.allow_pos, jnp)


class Excitation(NamedTuple):
    """The kernel's input: the pieces (a(t) not yet scaled) and bounds of a(t) per
    block of ``window`` pieces. Built on the host by :func:`prepare`."""

    t0: jax.Array  # (n,) [s]
    h: jax.Array  # (n,) [s]
    cf: tuple  # coefficients, each (n,) (sine terms None for linear pieces)
    a_max: jax.Array  # (n // window,) max of a over the pieces of each block [m/s²]
    a_min: jax.Array  # (n // window,) min of a over the pieces of each block [m/s²]


def prepare(pieces, window, is_sine) -> Excitation:
    """NumPy, once per excitation (independent of the parameters): ``pieces`` are the
    7 fields of :class:`~blockdae.excitation.Pieces`, each (n,), ending with at least
    ``window`` empty pieces after the last one simulated."""
    cf = (pieces[2], pieces[3]) + ((pieces[4], pieces[5], pieces[6]) if is_sine else (None, None, None))
    ends = (accel(*cf, 0.0), accel(*cf, pieces[1]))  # monotone pieces: extrema at their ends
    n_blocks = len(pieces[0]) // window
    per_block = lambda x: x[: n_blocks * window].reshape(n_blocks, window)
    return Excitation(pieces[0], pieces[1], cf, per_block(np.maximum(*ends)).max(axis=1),
                      per_block(np.minimum(*ends)).min(axis=1))


def _scaled(cf, scale):
    """Coefficients of ``scale`` a(t)."""
    p0, p1, s, w, phi = cf
    return p0 * scale, p1 * scale, (None if s is None else s * scale), w, phi


def _blocks_may_leave_stick(rules, exc):
    """Per block: whether the demand may leave [-mu g, mu g] there. Conservative by a
    relative 1e-9 (the pieces are checked one by one after), never missing an onset."""
    p = rules.params
    limit = p.mu * p.g
    highest = jnp.maximum(p.scale * exc.a_max, p.scale * exc.a_min)
    lowest = jnp.minimum(p.scale * exc.a_max, p.scale * exc.a_min)
    slack = 1e-9 * (jnp.maximum(highest, -lowest) + jnp.abs(p.bias * p.g) + limit)
    up = rules.allow_neg & (demand(highest, p.bias, p.g) > limit - slack)
    down = rules.allow_pos & (demand(lowest, p.bias, p.g) < -limit + slack)
    return up | down


def _leaves_stick(rules, cf, rem):
    """Whether the demand exceeds +mu g (-> slip-) / -mu g (-> slip+) on [0, rem]."""
    p = rules.params
    limit = p.mu * p.g
    start = demand(accel(*cf, 0.0, jnp), p.bias, p.g)
    end = demand(accel(*cf, rem, jnp), p.bias, p.g)
    up = rules.allow_neg & ((end > limit) | (start > limit))
    down = rules.allow_pos & ((end < -limit) | (start < -limit))
    return up, down


def _piece(exc, scale, j, tau):
    """Piece j from time ``tau`` into it: (start time [s], remaining length [s], coefficients)."""
    cf = rebase(*_scaled(tuple(None if c is None else c[j] for c in exc.cf), scale), tau)
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
    """Stick: the onset in the rest of piece k, else in the first block of pieces after
    it that may hold one; a block that holds none after all is skipped."""
    p = rules.params
    limit = p.mu * p.g
    _, rem_k, cf_k = _piece(exc, p.scale, state.k, state.tau)
    up_k, down_k = _leaves_stick(rules, cf_k, rem_k)
    here = up_k | down_k
    block_start = jnp.arange(exc.a_max.shape[0]) * window
    after_k = (block_start + window > state.k + 1) & (block_start < n_pieces)
    candidate = _blocks_may_leave_stick(rules, exc) & after_k
    start = block_start[jnp.argmax(candidate)]
    take = lambda x: jax.lax.dynamic_slice_in_dim(x, start, window)
    cf_b = _scaled(tuple(None if c is None else take(c) for c in exc.cf), p.scale)
    up_b, down_b = _leaves_stick(rules, cf_b, take(exc.h))
    index = start + jnp.arange(window)
    in_block = (up_b | down_b) & (index > state.k) & (index < n_pieces)
    found = here | jnp.any(in_block)
    j = jnp.where(here, state.k, start + jnp.argmax(in_block))
    tau = jnp.where(here, state.tau, 0.0)
    t_j, rem_j, cf_j = _piece(exc, p.scale, j, tau)
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
    skip_to = jnp.where(jnp.any(candidate), start + window, n_pieces)
    return _Candidate(found, jnp.where(found, j, skip_to), jnp.where(found, tau + d, 0.0), t_j + d,
                      state.u, 0.0 * state.v, jnp.where(found, jnp.where(going_up, -1, 1), state.mode))


def _next_stop(rules, exc, state, n_pieces, *, window, is_sine):
    """Slip: v accumulated over a window of pieces; the first piece where it returns to 0."""
    p = rules.params
    take = lambda x: jax.lax.dynamic_slice_in_dim(x, state.k, window)
    offset = jnp.where(jnp.arange(window) == 0, state.tau, 0.0)
    cf = rebase(*_scaled(tuple(None if c is None else take(c) for c in exc.cf), p.scale), offset)
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


def _step(rules, exc, n_pieces, state, *, window, is_sine):
    """One iteration: to the next event, or as far as the search went without one."""
    static = dict(window=window, is_sine=is_sine)
    nxt = jax.lax.cond(state.mode == 0, functools.partial(_next_onset, **static),
                       functools.partial(_next_stop, **static), rules, exc, state, n_pieces)
    logged = nxt.found & (nxt.after != state.mode)
    log, n_events = _logged(state.log, state.n_events, logged, nxt.t, state.mode, nxt.after, nxt.u)
    return State(k=nxt.k, tau=nxt.tau, u=nxt.u, v=nxt.v, mode=nxt.after,
                 max_abs_u=jnp.maximum(state.max_abs_u, jnp.abs(nxt.u)),
                 n_events=n_events, n_iterations=state.n_iterations + 1, log=log)


def _mode_after_stop(rules, cf, d, c, mode, t_stop):
    """Mode after v returns to zero in ``mode`` (the model's :func:`stop_mode`)."""
    p = rules.params
    return stop_mode(mode, c - accel(*cf, d, jnp), accel_rate(*cf, d, jnp), t_stop, p.mu, p.f, p.g,
                     rules.allow_neg, rules.allow_pos, jnp)


def _tail_to_rest(rules, state, t_start):
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
    log, n_events = _logged(state.log, state.n_events, logged, t_start + d, state.mode, after, u)
    final = state._replace(u=u, v=jnp.where(rests, 0.0, state.v), mode=jnp.where(rests, after, state.mode),
                           max_abs_u=jnp.maximum(state.max_abs_u, jnp.abs(u)), n_events=n_events, log=log)
    return final, t_start + d, rests


_STATIC = ("window", "log_capacity", "is_sine")


def _run(params, allowed, exc, n_pieces, until_rest, *, window, log_capacity, is_sine):
    """Integrate the block through the first ``n_pieces`` pieces of ``exc``.

    ``params``: (mu, f, bias, g, scale); ``allowed``: (slip- allowed, slip+ allowed);
    ``exc``: from :func:`prepare` with the same ``window`` and ``is_sine``. Returns
    (final State, t_final [s], rests (bool), finished (bool)). ``log_capacity`` events
    are logged (0: none, for batches).
    """
    rules = _Rules(Params(*params), *allowed)
    zero = jnp.zeros_like(params[0])
    zero_int = jnp.zeros((), int)
    init = State(zero_int, zero, zero, zero, zero_int, zero, zero_int, zero_int, jnp.zeros((log_capacity, 4)))
    max_iterations = n_pieces // window + 2 + 4 * exc.t0.shape[0]

    def running(state):
        return (state.k < n_pieces) & (state.n_iterations < max_iterations)

    step = functools.partial(_step, rules, exc, n_pieces, window=window, is_sine=is_sine)
    state = jax.lax.while_loop(running, step, init)
    finished = state.k >= n_pieces
    t_excitation_end = exc.t0[n_pieces - 1] + exc.h[n_pieces - 1]
    final, t_rest, rests = _tail_to_rest(rules, state, t_excitation_end)
    final = jax.tree.map(lambda a, b: jnp.where(until_rest, a, b), final, state)
    return final, jnp.where(until_rest, t_rest, t_excitation_end), rests | ~until_rest, finished


class Summary(NamedTuple):
    """A run's outcome, packed into two arrays so that it crosses to the host at once."""

    scalars: jax.Array  # (..., 8): u [m], v [m/s], mode, max |u| [m], n_events, t_final [s], rests, finished
    log: jax.Array  # (..., capacity, 4): t [s], mode_before, mode_after, u [m] per event

    @staticmethod
    def pack(final, t_final, rests, finished):
        scalars = (final.u, final.v, final.mode, final.max_abs_u, final.n_events, t_final, rests, finished)
        return Summary(jnp.stack([jnp.asarray(x, float) for x in scalars], axis=-1), final.log)


def _packed(params, allowed, exc, n_pieces, until_rest, **static):
    return Summary.pack(*_run(params, allowed, exc, n_pieces, until_rest, **static))


#: one parameter set
run = jax.jit(_packed, static_argnames=_STATIC)


@functools.partial(jax.jit, static_argnames=_STATIC)
def run_batch(params, allowed, exc, n_pieces, until_rest, **static):
    """``run`` over the leading axis of every entry of ``params``, one parameter set
    after another in one compiled loop: each set takes only its own loop iterations
    and branches, where ``vmap`` would run every set in step with the slowest one and
    evaluate both branches of each mode test (3-5 times slower per analysis)."""
    return jax.lax.map(lambda p: _packed(p, allowed, exc, n_pieces, until_rest, **static), params)
