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
differentiates (forward mode) through the event times. The closed forms and rules come
from :mod:`._closed_form` and :mod:`blockdae.sliding`, which the numba engine
(:mod:`._exact_numba`) compiles too; only the loop and the bisection are this kernel's own.
"""

import functools
from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np

from ..excitation import accel, accel_int1, accel_int2, rebase
from ._model import demand, rest_mode, slip_constant
from ._closed_form import (BISECTIONS, block_may_leave_stick, crosses_zero, departure_rate, leaves_stick,
                           mode_after_stop, onset_delta_linear, onset_gap, onset_side, onset_target, onset_within,
                           rate_turns, sine_stop_bracket, slip_motion, slip_rate, slip_velocity,
                           stop_delta_linear, tail_to_rest)


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
    """Per block: whether the demand may leave [-mu g, mu g] there."""
    p = rules.params
    return block_may_leave_stick(exc.a_max, exc.a_min, p.scale, p.bias, p.g, p.mu * p.g,
                                 rules.allow_neg, rules.allow_pos, jnp)


def _leaves_stick(rules, cf, rem):
    """Whether the demand exceeds +mu g (-> slip-) / -mu g (-> slip+) on [0, rem]."""
    p = rules.params
    start = demand(accel(*cf, 0.0, jnp), p.bias, p.g)
    end = demand(accel(*cf, rem, jnp), p.bias, p.g)
    return leaves_stick(start, end, p.mu * p.g, rules.allow_neg, rules.allow_pos)


def _piece(exc, scale, j, tau):
    """Piece j from time ``tau`` into it: (start time [s], remaining length [s], coefficients)."""
    cf = rebase(*_scaled(tuple(None if c is None else c[j] for c in exc.cf), scale), tau)
    return exc.t0[j] + tau, exc.h[j] - tau, cf


def _bisect(fun, lo, hi):
    """Bracketed root of ``fun``, monotone on [lo, hi]; returns the upper end.

    The value is the bisection's; its derivative with respect to parameters that
    ``fun`` closes over is the implicit function theorem's, -dF/dp / dF/dt.
    Twin of ``_exact_numba._bisect`` (same halvings, no derivative): keep them alike.
    """
    flo_sign = jnp.sign(fun(lo))

    def halve(_, bracket):
        lo, hi = bracket
        mid = 0.5 * (lo + hi)
        keep_lo = jnp.sign(fun(mid)) == flo_sign
        return jnp.where(keep_lo, mid, lo), jnp.where(keep_lo, hi, mid)

    _, root = jax.lax.fori_loop(0, BISECTIONS, halve, jax.lax.stop_gradient((lo, hi)))
    root = jax.lax.stop_gradient(root)
    value, slope = jax.jvp(fun, (root,), (jnp.ones_like(root),))
    step = jnp.where(slope != 0, value / jnp.where(slope != 0, slope, 1.0), 0.0)
    return root - (step - jax.lax.stop_gradient(step))


def onset_delta(cf, rem, target, is_sine):
    """Time [s] until a(d) reaches ``target`` [m/s²] on [0, rem] (a monotone).
    Twin of ``_exact_numba._onset_delta``."""
    linear = onset_delta_linear(cf, target, jnp)
    if not is_sine:
        return linear
    sine = _bisect(lambda d: onset_gap(cf, d, target, jnp), jnp.zeros_like(rem), rem)
    return jnp.where(cf[2] != 0, sine, linear)


def stop_delta(cf, rem, v, c, mode, is_sine):
    """First time d in (0, rem] where v(d) returns to 0 in slip ``mode`` (= sign of v):
    (d [s], found). Twin of ``_exact_numba._stop_delta``."""
    d_lin, found_lin = stop_delta_linear(cf, rem, v, c, mode, jnp)
    if not is_sine:
        return d_lin, found_lin
    r0 = departure_rate(cf, v, c, mode, jnp)
    rate = lambda d: slip_rate(cf, d, c, jnp)
    vel = lambda d: slip_velocity(cf, d, v, c, jnp)
    turns = rate_turns(r0, rate(rem), jnp)
    d_turn = jnp.where(turns, _bisect(rate, jnp.zeros_like(rem), rem), rem)
    lo, hi = sine_stop_bracket(r0, turns, d_turn, rem, mode, jnp)
    found_sin = crosses_zero(vel(lo), vel(hi), mode)
    d_sin = jnp.where(found_sin, _bisect(vel, lo, hi), rem)
    sine = cf[2] != 0
    return jnp.where(sine, d_sin, d_lin), jnp.where(sine, found_sin, found_lin)


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
    going_up, at_once = onset_side(sigma_j, up_j, limit, rules.allow_neg, rules.allow_pos)
    target = onset_target(going_up, p.bias, p.g, limit, jnp)
    d = onset_within(onset_delta(cf_j, rem_j, target, is_sine), rem_j, at_once, jnp)
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
    u_event, _ = slip_motion(cf_i, d, u_start[i], v_start[i], c, jnp)
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
    return mode_after_stop(cf, d, c, mode, t_stop, p.mu, p.f, p.g, rules.allow_neg, rules.allow_pos, jnp)


def _tail_to_rest(rules, state, t_start):
    """After the excitation (a = 0): slide until v = 0, then stick for good.

    Returns the final state, its time [s] and whether the block comes to rest.
    """
    p = rules.params
    d, u, rests = tail_to_rest(state.u, state.v, state.mode, p.bias, p.f, p.g, jnp)
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
