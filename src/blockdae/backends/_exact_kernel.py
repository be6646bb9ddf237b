"""The exact backend's compiled kernel.

The excitation is a sequence of monotone closed-form pieces. Each loop iteration looks
at a window of ``window`` pieces at once: in stick it finds the first piece where the
demand leaves [-mu g, mu g], in slip it accumulates the closed-form velocity over the
window and finds the first piece where v returns to zero. The first such event is
located in closed form (linear pieces: linear or quadratic equations) or by bracketing
a monotone function (sine pieces), to machine precision; without one the whole window
is skipped. The loop thus runs about (events + pieces / window) times, vectorised over
the window.

Everything is ``jax.numpy``: the kernel compiles, vectorises over parameter sets and
differentiates (forward mode) through the event times.
"""

import functools
from typing import NamedTuple

import jax
import jax.numpy as jnp

from ..excitation._pieces import accel, accel_int1, accel_int2, accel_rate, rebase
from ..model import demand, rest_mode, slip_constant
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


def _window(pieces, k, tau, scale, window, is_sine):
    """The ``window`` pieces from piece k, the first one starting at ``tau``."""
    take = lambda x: jax.lax.dynamic_slice_in_dim(x, k, window)
    t0, h = take(pieces[0]), take(pieces[1])
    cf = (take(pieces[2]) * scale, take(pieces[3]) * scale)
    cf += (take(pieces[4]) * scale, take(pieces[5]), take(pieces[6])) if is_sine else (None, None, None)
    offset = jnp.where(jnp.arange(window) == 0, tau, 0.0)
    return t0 + offset, h - offset, rebase(*cf, offset)


def _pick(cf, i):
    return tuple(None if c is None else c[i] for c in cf)


def _step(rules, pieces, state, *, window, is_sine, log_events):
    """One iteration: the first event in the window, or the whole window."""
    p = rules.params
    t_start, rem, cf = _window(pieces, state.k, state.tau, p.scale, window, is_sine)
    limit = p.mu * p.g
    mode = state.mode

    # stick: the first piece whose demand leaves [-mu g, mu g] (a is monotone on a piece)
    sigma_start = demand(accel(*cf, 0.0, jnp), p.bias, p.g)
    sigma_end = demand(accel(*cf, rem, jnp), p.bias, p.g)
    up = rules.allow_neg & ((sigma_end > limit) | (sigma_start > limit))
    down = rules.allow_pos & ((sigma_end < -limit) | (sigma_start < -limit))
    onset = (mode == 0) & (up | down)

    # slip: v at every piece start of the window, and the first piece where v returns to 0
    c = slip_constant(mode, p.bias, p.f, p.g)
    dv = c * rem - accel_int1(*cf, rem, jnp)
    v_start = state.v + jnp.cumsum(dv) - dv
    du = v_start * rem + 0.5 * c * rem**2 - accel_int2(*cf, rem, jnp)
    u_start = state.u + jnp.cumsum(du) - du
    d_stop, stop = stop_delta(cf, rem, v_start, c, mode, is_sine)
    stop = (mode != 0) & stop

    hit = onset | stop
    found = jnp.any(hit)
    i = jnp.argmax(hit)
    cf_i, rem_i = _pick(cf, i), rem[i]
    going_up = up[i]
    target = p.bias * p.g + jnp.where(going_up, limit, -limit)
    starts_beyond = jnp.where(going_up, sigma_start[i] > limit, sigma_start[i] < -limit)
    d_on = jnp.where(starts_beyond, 0.0, jnp.clip(onset_delta(cf_i, rem_i, target, is_sine), 0.0, rem_i))
    d = jnp.where(mode == 0, d_on, d_stop[i])
    t_event = t_start[i] + d
    u_event, _ = slip_motion(cf_i, d, u_start[i], v_start[i], c)
    u_event = jnp.where(mode == 0, state.u, u_event)
    after = jnp.where(mode == 0, jnp.where(going_up, -1, 1),
                      _mode_after_stop(rules, cf_i, d, c, mode, t_event))
    logged = found & (after != mode)

    u_end = jnp.where(mode == 0, state.u, u_start[-1] + du[-1])
    v_end = jnp.where(mode == 0, 0.0, v_start[-1] + dv[-1])
    log = state.log
    if log_events:
        slot = jnp.where(logged, state.n_events, log.t.shape[0])  # out of range: dropped
        log = EventLog(log.t.at[slot].set(t_event, mode="drop"),
                       log.mode_before.at[slot].set(mode, mode="drop"),
                       log.mode_after.at[slot].set(after, mode="drop"),
                       log.u.at[slot].set(u_event, mode="drop"))
    return State(
        k=jnp.where(found, state.k + i, state.k + window),
        tau=jnp.where(found, jnp.where(i == 0, state.tau, 0.0) + d, 0.0),
        u=jnp.where(found, u_event, u_end),
        v=jnp.where(found, 0.0, v_end),
        mode=jnp.where(found, after, mode),
        max_abs_u=jnp.maximum(state.max_abs_u, jnp.abs(jnp.where(found, u_event, u_end))),
        n_events=state.n_events + logged,
        n_iterations=state.n_iterations + 1,
        log=log,
    )


def _mode_after_stop(rules, cf, d, c, mode, t_stop):
    """Mode after v returns to zero in ``mode``, with grazes kept sliding.

    At a stop dv/dt = c - a cannot point away from rest, so the demand is
    sigma = -mode f g - r with mode * r <= 0 (rounding is projected out). If the
    block would stick but the same threshold is crossed outwards at the same
    instant (a graze: f = mu and v touches zero at the threshold), it keeps sliding.
    """
    p = rules.params
    r = c - accel(*cf, d, jnp)
    r = jnp.where(mode * r > 0, 0.0, r)
    sigma = -mode * p.f * p.g - r
    rate = accel_rate(*cf, d, jnp)
    after = rules.at_rest(sigma, rate)
    threshold = -mode * p.mu * p.g
    outward = -mode * rate > 0
    wait = (threshold - sigma) / jnp.where(outward, rate, 1.0)
    graze = (after == 0) & outward & (t_stop + wait == t_stop)
    graze = graze & jnp.where(mode < 0, rules.allow_neg, rules.allow_pos)
    return jnp.where(graze, mode, after)


def _tail_to_rest(rules, state, t_start, log_events):
    """After the excitation (a = 0): slide until v = 0, then stick for good.

    Returns the final state, its time [s] and whether the block comes to rest.
    """
    p = rules.params
    sliding = state.v != 0
    c = slip_constant(state.mode, p.bias, p.f, p.g)
    rests = ~sliding | (state.v * c < 0)
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

    step = functools.partial(_step, rules, pieces, window=window, is_sine=is_sine, log_events=log_capacity > 0)
    state = jax.lax.while_loop(running, step, init)
    finished = state.k >= n_pieces
    t_excitation_end = pieces[0][n_pieces - 1] + pieces[1][n_pieces - 1]
    final, t_rest, rests = _tail_to_rest(rules, state, t_excitation_end, log_capacity > 0)
    final = jax.tree.map(lambda a, b: jnp.where(until_rest, a, b), final, state)
    return final, jnp.where(until_rest, t_rest, t_excitation_end), rests | ~until_rest, finished


#: one parameter set
run = jax.jit(_run, static_argnames=_STATIC)


@functools.partial(jax.jit, static_argnames=_STATIC)
def run_batch(params, allowed, pieces, n_pieces, until_rest, **static):
    """``run`` vectorised over the leading axis of every entry of ``params``."""
    return jax.vmap(functools.partial(_run, **static), in_axes=(0, None, None, None, None))(
        params, allowed, pieces, n_pieces, until_rest)
