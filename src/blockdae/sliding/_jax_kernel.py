"""The JAX twin's compiled kernel: diffrax integration of the hybrid automaton.

A ``lax.scan`` runs over the monotone pieces of a(t), so every breakpoint of a
record is stepped onto exactly. Within a piece a bounded ``lax.while_loop`` runs
segments: each integrates one mode with a diffrax solver and a PID controller until
the piece ends or the mode's single guard (a ``diffrax.Event``) crosses zero
downwards; the root is bracketed by ``optimistix.Bisection`` on the solver's dense
output, then polished by one Newton step that also carries derivatives (the
implicit function theorem at the guard). The flow, guards and transitions come
from :mod:`blockdae.sliding` (``relative_acceleration``, ``stick_guards``, ``demand``,
``slip_constant``; the stop rule through the exact kernel's ``_mode_after_stop``).
Derivatives: forward mode (``jax.jvp``/``jax.jacfwd``), via ``diffrax.ForwardMode``.
"""

import functools
from typing import NamedTuple

import diffrax
import jax
import jax.numpy as jnp
import optimistix as optx

from ..excitation import accel, accel_rate, monotone_rate, piece_direction, rebase
from ..solvers.diffrax_solvers import SOLVERS
from ._model import comes_to_rest, demand, relative_acceleration, slip_constant, stick_guards
from ._exact_kernel import Params, _mode_after_stop, _Rules, onset_delta

# guards decrease through their roots (flip=True): no bracket check, which under vmap
# would also run on members without an event
_ROOT_FINDER = optx.Bisection(rtol=1e-14, atol=1e-12, flip=True)


class State(NamedTuple):
    u: jax.Array  # [m]
    v: jax.Array  # [m/s]
    mode: jax.Array  # int: -1, 0, +1
    max_abs_u: jax.Array  # [m]
    n_events: jax.Array


class Knot(NamedTuple):
    """Rows emitted per piece: a mode change at its start, its segments, its end."""

    valid: jax.Array
    is_event: jax.Array
    t: jax.Array  # [s]
    mode_before: jax.Array
    mode_after: jax.Array
    u: jax.Array  # [m]
    v: jax.Array  # [m/s]


class Config(NamedTuple):
    """Static settings of one compiled kernel (hashable)."""

    allow_neg: bool
    allow_pos: bool
    is_sine: bool  # whether a(t) has sine pieces
    solver: str
    rtol: float
    atol: float
    max_segments: int  # segments per piece; events per piece <= max_segments - 1
    max_steps: int  # solver steps per segment


class Flags(NamedTuple):
    """Diagnostics accumulated over a run."""

    n_overflow: jax.Array  # pieces that needed more than max_segments segments
    n_failed: jax.Array  # segments whose solve failed (e.g. max_steps reached)
    n_steps: jax.Array  # accepted solver steps


def _rhs(tau, y, args):
    """dy/dtau = (v, dv/dtau) by the model's flow [m/s, m/s²]."""
    cf, _, mode, (p, _, _), _ = args
    return y[1], relative_acceleration(mode, accel(*cf, tau, jnp), p.bias, p.f, p.g, jnp)


def _stick_guards(tau, args):
    """(mu g - sigma, mu g + sigma) [m/s²]; a disallowed direction's guard is 1."""
    cf, _, _, (p, allow_neg, allow_pos), _ = args
    return stick_guards(demand(accel(*cf, tau, jnp), p.bias, p.g), p.mu, p.g, allow_neg, allow_pos, jnp)


def _guard(t, y, args, **_):
    """The one guard of the current mode, left when it crosses zero downwards.

    Stick: the threshold a(t) moves towards (a is monotone on a piece, so at most that
    one can be reached; a demand that starts on the other one, a touch, leaves it);
    the nearer one on a flat piece; slip: mode * v [m/s].
    """
    _, _, mode, _, direction = args
    to_neg, to_pos = _stick_guards(t, args)  # t: local time [s]
    stick = jnp.where(direction > 0, to_neg, jnp.where(direction < 0, to_pos, jnp.minimum(to_neg, to_pos)))
    return jnp.where(mode == 0, stick, mode * y[1])


def _segment_end(cfg, args, tau, h):
    """Local time [s] where the segment from ``tau`` must end at the latest.

    In slip, the turning point of v (dv/dt = c - a = 0) if it lies inside: v is then
    monotone on every segment, so no guard root can hide between two steps.
    """
    cf, c, mode, _, _ = args
    rate_start, rate_end = _rhs(tau, (0.0, 0.0), args)[1], _rhs(h, (0.0, 0.0), args)[1]
    d_turn = onset_delta(rebase(*cf, tau), h - tau, c, cfg.is_sine)
    turns = (mode != 0) & (rate_start * rate_end < 0) & (tau < tau + d_turn) & (tau + d_turn < h)
    return jax.lax.stop_gradient(jnp.where(turns, tau + d_turn, h))


def _solve_segment(cfg, args, tau, h, y0):
    """Integrate from local time ``tau`` to ``h`` [s], stopping at the guard."""
    solver = SOLVERS[cfg.solver]()
    return diffrax.diffeqsolve(
        diffrax.ODETerm(_rhs), solver, t0=tau, t1=h, dt0=jnp.maximum(h - tau, 1e-12), y0=y0, args=args,
        saveat=diffrax.SaveAt(t1=True),
        stepsize_controller=diffrax.PIDController(rtol=cfg.rtol, atol=cfg.atol),
        event=diffrax.Event(_guard, root_finder=_ROOT_FINDER, direction=False),
        adjoint=diffrax.ForwardMode(), max_steps=cfg.max_steps, throw=False)


def _polish_onset(args, tau_root):
    """Newton step on the reached stick guard; returns (tau [s], mode after)."""
    cf, _, _, (p, _, _), _ = args
    sigma = demand(accel(*cf, tau_root, jnp), p.bias, p.g)
    to_neg = sigma > 0  # guard 0 (mu g - sigma) -> slip-, guard 1 (mu g + sigma) -> slip+
    active = lambda t: _stick_guards(t, args)[jnp.where(to_neg, 0, 1)]
    value, slope = jax.jvp(active, (tau_root,), (jnp.ones_like(tau_root),))
    step = jnp.where(slope != 0, value / jnp.where(slope != 0, slope, 1.0), 0.0)
    return _newton(tau_root, step), jnp.where(to_neg, -1, 1)


def _polish_stop(args, tau_root, u, v):
    """Newton step on v = 0 along the flow; returns (tau [s], u [m])."""
    _, rate = _rhs(tau_root, (u, v), args)
    step = jnp.where(rate != 0, v / jnp.where(rate != 0, rate, 1.0), 0.0)
    return _newton(tau_root, step), u - 0.5 * v * step


def _newton(tau_root, step):
    """``tau_root`` [s] moved by the Newton ``step`` [s], its value kept within the
    bisection's tolerance (at a graze the slope vanishes and a full step would leave
    the bracket: 1.6e-7 s off at a demand one ulp over mu g) and its derivative (the
    implicit function theorem at the guard) whole."""
    bracket = _ROOT_FINDER.atol + _ROOT_FINDER.rtol * jnp.abs(tau_root)
    value = jnp.clip(jax.lax.stop_gradient(step), -bracket, bracket)
    return tau_root - value - (step - jax.lax.stop_gradient(step))


def _segment(cfg, rules, cf, t0, h, tau, u, v, mode):
    """One segment in ``mode`` from local time ``tau``.

    Returns (hit, tau, u, v, mode after, ok, steps): the guard was reached at the
    new ``tau`` [s] (else the segment's end), with the state there.
    """
    p = rules.params
    c = slip_constant(mode, p.bias, p.f, p.g)
    args = (cf, c, mode, (p, rules.allow_neg, rules.allow_pos), piece_direction(cf, h, jnp))
    t_stop = _segment_end(cfg, args, tau, h)
    sol = _solve_segment(cfg, args, tau, t_stop, (u, v))
    tau_e, u_e, v_e = sol.ts[-1], sol.ys[0][-1], sol.ys[1][-1]
    # a threshold merely reached at the segment's end is no onset: the rest rule at
    # the next piece's start decides, from the right-hand rate of a
    hit = sol.event_mask & ((mode != 0) | (_guard(t_stop, (u, v), args) < 0))
    ok = (sol.result == diffrax.RESULTS.successful) | (sol.result == diffrax.RESULTS.event_occurred)
    # keep only the derivative at fixed time: d/dp y(tau_root), then the IFT step
    tau_root = jax.lax.stop_gradient(tau_e)
    du, dv = _rhs(tau_e, (u_e, v_e), args)
    u_e, v_e = u_e + du * (tau_root - tau_e), v_e + dv * (tau_root - tau_e)
    tau_on, mode_on = _polish_onset(args, tau_root)
    tau_stop, u_stop = _polish_stop(args, tau_root, u_e, v_e)
    stick = mode == 0
    tau_new = jnp.where(stick, tau_on, tau_stop)
    # keep it in [tau, h]; jnp.clip would halve the derivative of a root on a bound
    tau_new = jnp.where(tau_new < tau, tau, jnp.where(tau_new > h, h, tau_new))
    u_new = jnp.where(stick, u_e, u_stop)
    after_stop = _mode_after_stop(rules, cf, tau_new, c, mode, t0 + tau_new)
    mode_new = jnp.where(stick, mode_on, after_stop)
    tau_new = jnp.where(hit, tau_new, t_stop)
    return (hit, tau_new, jnp.where(hit, u_new, u_e), jnp.where(hit, 0.0, v_e), jnp.where(hit, mode_new, mode),
            ok, sol.stats["num_accepted_steps"])


def _onset_on_threshold(p, sigma, rate, onset, mode):
    """Time [s] of an onset at a piece start: 0, with the derivative of the guard's
    root when the demand starts exactly on the threshold (a sample equal to mu g)."""
    guard = p.mu * p.g + mode * sigma  # the reached stick guard: mode -1 -> mu g - sigma
    slope = mode * rate  # its right-hand rate [m/s³]
    shift = guard / jnp.where(slope != 0, slope, 1.0)
    on_threshold = onset & (guard == 0) & (slope < 0)
    return jnp.where(on_threshold, jax.lax.stop_gradient(shift) - shift, 0.0)


def _advance_piece(cfg, rules, carry, piece, emit_end=True):
    """Advance through one piece; returns the new (State, Flags) and its knots."""
    state, flags = carry
    p = rules.params
    t0, h = piece[0], piece[1]
    cf = tuple(x * p.scale for x in piece[2:5]) + tuple(piece[5:7])
    # at the piece start a block at rest takes the mode the right-hand limits of a give
    sigma0 = demand(accel(*cf, 0.0, jnp), p.bias, p.g)
    rate0 = monotone_rate(accel_rate(*cf, 0.0, jnp), piece_direction(cf, h, jnp), jnp)
    at_rest = (state.mode == 0) | (state.v == 0)
    mode = jnp.where(at_rest, rules.at_rest(sigma0, rate0), state.mode)
    changed = mode != state.mode
    tau_start = _onset_on_threshold(p, sigma0, rate0, changed & (state.mode == 0), mode)
    start = Knot(changed, changed, t0 + tau_start, state.mode, mode, state.u, state.v)

    k = cfg.max_segments
    empty = Knot(jnp.zeros(k, bool), jnp.zeros(k, bool), *(jnp.zeros(k, x.dtype) for x in
                                                          (t0, state.mode, state.mode, state.u, state.v)))

    def cond(loop):
        i, done = loop[0], loop[5]
        return (i < k) & ~done

    def body(loop):
        i, tau, u, v, mode, _, knots, failed, steps = loop
        hit, tau, u, v, mode_new, ok, n = _segment(cfg, rules, cf, t0, h, tau, u, v, mode)
        logged = hit & (mode_new != mode)
        row = Knot(logged, logged, t0 + tau, mode, mode_new, u, v)
        knots = Knot(*(buf.at[i].set(x) for buf, x in zip(knots, row)))
        return i + 1, tau, u, v, mode_new, ~hit & (tau >= h), knots, failed + ~ok, steps + n

    zero = jnp.zeros((), int)
    loop = (zero, tau_start, state.u, state.v, mode, jnp.zeros((), bool), empty, zero, zero)
    _, _, u, v, mode, done, knots, failed, steps = jax.lax.while_loop(cond, body, loop)

    end = Knot(jnp.asarray(emit_end), jnp.zeros((), bool), t0 + h, mode, mode, u, v)
    knots = Knot(*(jnp.concatenate([a[None], b, c[None]]) for a, b, c in zip(start, knots, end)))
    n_events = state.n_events + jnp.sum(knots.is_event)
    max_abs_u = jnp.maximum(state.max_abs_u, jnp.max(jnp.where(knots.valid, jnp.abs(knots.u), 0.0)))
    new_state = State(u, v, mode, max_abs_u, n_events)
    new_flags = Flags(flags.n_overflow + ~done, flags.n_failed + failed, flags.n_steps + steps)
    return (new_state, new_flags), knots


def _tail(cfg, rules, carry, t_start):
    """After the excitation (a = 0): slide until the guard v = 0, then stick.

    The window is bounded by twice the stopping time under the slip constant; a
    block whose kinetic friction cannot stop it (v c >= 0) never rests.
    """
    state, _ = carry
    p = rules.params
    c = slip_constant(state.mode, p.bias, p.f, p.g)
    sliding = state.v != 0
    rests = comes_to_rest(state.v, state.mode, p.bias, p.f, p.g)
    window = jnp.where(sliding & rests, 2.0 * jnp.abs(state.v) / jnp.where(c != 0, jnp.abs(c), 1.0) + 1.0, 0.0)
    zero = jnp.zeros_like(t_start)
    piece = (t_start, window, zero, zero, zero, zero, zero)
    carry, knots = _advance_piece(cfg, rules, carry, piece, emit_end=False)
    last = jnp.max(jnp.where(knots.is_event, knots.t, t_start))
    return carry, knots, rests, last


_STATIC = ("cfg", "until_rest", "full_output")


def _run(params, pieces, *, cfg, until_rest, full_output):
    """Integrate the block through ``pieces`` (a tuple of (n,) arrays).

    Returns (final State, t_final [s], rests (bool), Flags, knots or None), knots
    being a Knot of arrays of shape (n_pieces [+ 1], max_segments + 2).
    """
    rules = _Rules(Params(*params), cfg.allow_neg, cfg.allow_pos)
    zero = jnp.zeros_like(params[0])
    izero = jnp.zeros((), int)
    init = (State(zero, zero, izero, zero, izero), Flags(izero, izero, izero))

    def body(carry, piece):
        carry, knots = _advance_piece(cfg, rules, carry, piece)
        return carry, (knots if full_output else None)

    carry, knots = jax.lax.scan(body, init, pieces)
    t_final = pieces[0][-1] + pieces[1][-1]
    rests = jnp.ones((), bool)
    if until_rest:
        carry, tail_knots, rests, t_final = _tail(cfg, rules, carry, t_final)
        if full_output:
            knots = jax.tree.map(lambda x, y: jnp.concatenate([x, y[None]]), knots, tail_knots)
    state, flags = carry
    return state, t_final, rests, flags, knots


#: one parameter set
run = jax.jit(_run, static_argnames=_STATIC)


@functools.partial(jax.jit, static_argnames=_STATIC)
def run_batch(params, pieces, **static):
    """``run`` vectorised over the leading axis of every entry of ``params``. Unlike the
    exact kernel's, the twin's loop (a scan over pieces) has the same shape for every
    parameter set, so ``vmap`` pays: 16 sets on Kobe take 0.16 s, 0.6 s one by one."""
    return jax.vmap(functools.partial(_run, **static), in_axes=(0, None))(params, pieces)
