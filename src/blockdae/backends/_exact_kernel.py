"""The exact backend's compiled kernel: a scan over the monotone pieces of a(t).

Within a piece every guard root is closed form (linear pieces: linear or quadratic
equations) or bracketed on a monotone function (sine pieces), so each event is located
to machine precision. A piece holds at most ``max_events`` events; more is reported as
overflow. Everything is ``jax.numpy`` so that the kernel compiles, vectorises over
parameter sets and differentiates through the event times.
"""

import functools
from typing import NamedTuple

import jax
import jax.numpy as jnp

from ..excitation._pieces import accel, accel_rate, rebase
from ..model import demand, rest_mode, slip_constant, stop_mode
from ._closed_form import onset_delta, slip_motion, stop_delta


class Params(NamedTuple):
    """Scalar parameters of one run (all float64)."""

    mu: jax.Array  # static friction [-]
    f: jax.Array  # kinetic friction [-]
    bias: jax.Array  # R/Q [-]
    g: jax.Array  # [m/s²]
    scale: jax.Array  # factor on a(t) [-]


class State(NamedTuple):
    u: jax.Array  # [m]
    v: jax.Array  # [m/s]
    mode: jax.Array  # int: -1, 0, +1
    max_abs_u: jax.Array  # [m]
    n_events: jax.Array
    n_overflow: jax.Array  # pieces that needed more than max_events events


class Knot(NamedTuple):
    """Rows the scan emits per piece: events, then the piece end."""

    valid: jax.Array
    is_event: jax.Array
    t: jax.Array
    mode_before: jax.Array
    mode_after: jax.Array
    u: jax.Array
    v: jax.Array


def _knot(valid, is_event, t, before, after, u, v):
    return Knot(valid, is_event, t, before, after, u, v)


class _Rules(NamedTuple):
    params: Params
    allow_neg: bool
    allow_pos: bool

    def at_rest(self, sigma, rate):
        p = self.params
        return rest_mode(sigma, rate, p.mu, p.g, self.allow_neg, self.allow_pos, jnp)


def _advance_piece(rules, state, piece, max_events, is_sine):
    """Advance through one piece; returns the new state and its knots."""
    p = rules.params
    t0, h = piece[0], piece[1]
    cf0 = tuple(x * p.scale for x in piece[2:5]) + tuple(piece[5:7])
    knots = []

    # At the piece start a block at rest takes the mode the right-hand limits of a give.
    sigma0 = demand(accel(*cf0, 0.0, jnp), p.bias, p.g)
    at_rest = (state.mode == 0) | (state.v == 0)
    mode = jnp.where(at_rest, rules.at_rest(sigma0, accel_rate(*cf0, 0.0, jnp)), state.mode)
    changed = mode != state.mode
    knots.append(_knot(changed, changed, t0, state.mode, mode, state.u, state.v))
    tau, u, v, done = jnp.zeros_like(h), state.u, state.v, jnp.zeros((), bool)
    n_events = state.n_events + changed

    for _ in range(max_events + 1):  # the last pass must find no further event
        cf = rebase(*cf0, tau)
        rem = h - tau
        # stick: onset where the demand reaches a threshold (a is monotone on the piece)
        sigma_end = demand(accel(*cf, rem, jnp), p.bias, p.g)
        limit = p.mu * p.g
        up = rules.allow_neg & (mode == 0) & (sigma_end > limit)
        down = rules.allow_pos & (mode == 0) & (sigma_end < -limit)
        target = p.bias * p.g + jnp.where(up, limit, -limit)
        d_on = jnp.clip(onset_delta(cf, rem, target, is_sine), 0.0, rem)
        # slip: stop where v returns to zero
        c = slip_constant(mode, p.bias, p.f, p.g)
        d_stop, stops = stop_delta(cf, rem, v, c, mode, is_sine)
        stops = stops & (mode != 0)

        d = jnp.where(up | down, d_on, jnp.where(stops, d_stop, rem))
        u_new, v_new = slip_motion(cf, d, u, v, c)
        u_new, v_new = jnp.where(mode == 0, u, u_new), jnp.where(mode == 0, 0.0, v_new)
        t_event = t0 + tau + d
        after_stop = _mode_after_stop(rules, cf, d, c, mode, t_event)
        mode_new = jnp.where(up, -1, jnp.where(down, 1, jnp.where(stops, after_stop, mode)))
        hit = (up | down | stops) & ~done
        logged = hit & (mode_new != mode)
        knots.append(_knot(logged, logged, t_event, mode, mode_new, u_new, jnp.where(hit, 0.0, v_new)))

        keep = done
        u, v = jnp.where(keep, u, u_new), jnp.where(keep, v, jnp.where(hit, 0.0, v_new))
        tau = jnp.where(keep, tau, jnp.where(hit, tau + d, h))
        n_events = n_events + logged
        mode = jnp.where(keep, mode, mode_new)
        done = done | ~hit

    knots.append(_knot(jnp.ones((), bool), jnp.zeros((), bool), t0 + h, mode, mode, u, v))
    max_abs_u = jnp.maximum(state.max_abs_u, jnp.max(jnp.abs(jnp.stack([k.u for k in knots]))))
    new_state = State(u, v, mode, max_abs_u, n_events, state.n_overflow + ~done)
    return new_state, Knot(*(jnp.stack(field) for field in zip(*knots)))


def _mode_after_stop(rules, cf, d, c, mode, t_stop):
    """Mode after v returns to zero in ``mode`` (the model's :func:`stop_mode`)."""
    p = rules.params
    return stop_mode(mode, c - accel(*cf, d, jnp), accel_rate(*cf, d, jnp), t_stop, p.mu, p.f, p.g,
                     rules.allow_neg, rules.allow_pos, jnp)


def _tail_to_rest(rules, state, t_start):
    """After the excitation (a = 0): slide until v = 0, then stick for good.

    Returns the final state, the stop knot and whether the block ever comes to rest.
    """
    p = rules.params
    sliding = state.v != 0
    c = slip_constant(state.mode, p.bias, p.f, p.g)
    rests = ~sliding | (state.v * c < 0)
    d = jnp.where(sliding & rests, -state.v / jnp.where(c != 0, c, 1.0), 0.0)
    u = state.u + 0.5 * state.v * d
    after = rules.at_rest(-p.bias * p.g, 0.0)
    changed = rests & (after != state.mode)
    knot = _knot(changed, changed, t_start + d, state.mode, after, u, 0.0)
    final = state._replace(u=u, v=jnp.where(rests, 0.0, state.v), mode=jnp.where(rests, after, state.mode),
                           max_abs_u=jnp.maximum(state.max_abs_u, jnp.abs(u)),
                           n_events=state.n_events + changed)
    return final, knot, rests


_STATIC = ("allow_neg", "allow_pos", "max_events", "is_sine", "full_output")


def _run(params, pieces, until_rest, *, allow_neg, allow_pos, max_events, is_sine, full_output):
    """Integrate the block through ``pieces`` (a tuple of (n,) arrays).

    Returns (final State, t_final [s], rests (bool), knots or None) where knots is a
    Knot of arrays of shape (n_pieces + 1, max_events + 3) when ``full_output``.
    """
    rules = _Rules(Params(*params), allow_neg, allow_pos)
    zero = jnp.zeros_like(params[0])
    init = State(zero, zero, jnp.zeros((), int), zero, jnp.zeros((), int), jnp.zeros((), int))

    def body(state, piece):
        new, knots = _advance_piece(rules, state, piece, max_events, is_sine)
        return new, (knots if full_output else None)

    state, knots = jax.lax.scan(body, init, pieces)
    t_excitation_end = pieces[0][-1] + pieces[1][-1]
    final, tail_knot, rests = _tail_to_rest(rules, state, t_excitation_end)
    final = jax.tree.map(lambda a, b: jnp.where(until_rest, a, b), final, state)
    t_final = jnp.where(until_rest, tail_knot.t, t_excitation_end)
    rests = rests | ~until_rest
    if full_output:
        tail = tail_knot._replace(valid=tail_knot.valid & until_rest,
                                  is_event=tail_knot.is_event & until_rest)
        first_only = jnp.arange(max_events + 3) == 0
        row = Knot(*(jnp.where(first_only, x, jnp.zeros_like(x)) for x in tail))
        knots = jax.tree.map(lambda x, y: jnp.concatenate([x, y[None]]), knots, row)
    return final, t_final, rests, knots


#: one parameter set
run = jax.jit(_run, static_argnames=_STATIC)


@functools.partial(jax.jit, static_argnames=_STATIC)
def run_batch(params, pieces, until_rest, **static):
    """``run`` vectorised over the leading axis of every entry of ``params``."""
    return jax.vmap(functools.partial(_run, **static), in_axes=(0, None, None))(params, pieces, until_rest)
