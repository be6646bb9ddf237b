"""The events of Newmark's mass on a compliant support (upthrow) from closed forms, in
50 significant digits (mpmath), as references for the exact engine.

The ground acceleration y''(t) [m/s²] is given in pieces, each
``a(t) = p0 + p1 tau + s sin(W tau + phi)`` with tau = t - start: a piecewise-linear
record, a rectangular pulse or a sine train is exact in these terms. On each piece both
phases have closed forms:
  contact  u'' + 2 z w u' + w² u = -a(t)   (a damped linear oscillator; 0 <= z < 1);
  flight   u'' = -g - a(t)                  (a cubic plus the sine's double integral).
The rules are the paper's, as the engine states them: liftoff where the support's force
n = w² (u0 - u) - 2 z w u' falls through 0; in flight a top where u' falls through 0, a
bottom where it rises through 0, a landing where u falls through u0 (falling) or where n
rises through 0 (rising). A guard's first crossing after an event is bracketed on a grid
of ``GRID`` [s] and then found to 50 digits: two crossings closer than the grid would be
missed, which shows as a different sequence of kinds (the tests compare the kinds first).
"""

from dataclasses import dataclass

import mpmath as mp

DIGITS = 50
GRID = 2e-4  # [s], bracketing grid of the guards


@dataclass(frozen=True)
class Piece:
    """y''(t) = p0 + p1 (t - start) + s sin(W (t - start) + phi) [m/s²] on [start, end) [s]."""
    start: object
    end: object
    p0: object = 0
    p1: object = 0
    s: object = 0
    W: object = 0
    phi: object = 0


def linear_pieces(times, values):
    """Pieces of the record interpolated linearly between samples ``values`` [m/s²] at
    ``times`` [s] (floats, taken exactly)."""
    with mp.workdps(DIGITS):
        t, a = [mp.mpf(float(x)) for x in times], [mp.mpf(float(x)) for x in values]
        return [Piece(t[k], t[k + 1], a[k], (a[k + 1] - a[k]) / (t[k + 1] - t[k])) for k in range(len(t) - 1)]


def sine_train_pieces(amplitude, period, cycles):
    """A sin(2 pi t / T) [m/s²] for n cycles of period T [s], then 0."""
    with mp.workdps(DIGITS):
        end = mp.mpf(float(cycles)) * mp.mpf(float(period))
        W = 2 * mp.pi / mp.mpf(float(period))
        return [Piece(mp.mpf(0), end, s=mp.mpf(float(amplitude)), W=W), Piece(end, mp.inf)]


def pulse_pieces(amplitude, duration):
    """A constant ``amplitude`` [m/s²] for ``duration`` [s], then 0."""
    with mp.workdps(DIGITS):
        end = mp.mpf(float(duration))
        return [Piece(mp.mpf(0), end, p0=mp.mpf(float(amplitude))), Piece(end, mp.inf)]


def _contact(w, z, piece):
    """The contact phase u'' + 2 z w u' + w² u = -a on ``piece``: (particular solution
    (u, v)(tau), free motion (u, v) after ``dt`` [s] from (u, v))."""
    q = -piece.p1 / w**2
    p = (-piece.p0 - 2 * z * w * q) / w**2
    det = (w**2 - piece.W**2) ** 2 + (2 * z * w * piece.W) ** 2
    x = -piece.s * (w**2 - piece.W**2) / det if piece.s else 0
    y = 2 * z * w * piece.W * piece.s / det if piece.s else 0
    wd = w * mp.sqrt(1 - z**2)

    def particular(tau):
        angle = piece.W * tau + piece.phi
        return (p + q * tau + x * mp.sin(angle) + y * mp.cos(angle),
                q + piece.W * (x * mp.cos(angle) - y * mp.sin(angle)))

    def free(u, v, dt):
        c2 = (v + z * w * u) / wd
        decay, c, s = mp.exp(-z * w * dt), mp.cos(wd * dt), mp.sin(wd * dt)
        return decay * (u * c + c2 * s), decay * ((c2 * wd - z * w * u) * c - (u * wd + z * w * c2) * s)
    return particular, free


def _flight(g, piece):
    """The flight u'' = -g - a on ``piece``: (particular solution (u, v)(tau), free motion
    (u, v) after ``dt`` [s] from (u, v))."""
    W, phi, s = piece.W, piece.phi, piece.s

    def particular(tau):
        sine_u, sine_v = (s / W**2 * mp.sin(W * tau + phi), s / W * mp.cos(W * tau + phi)) if s else (0, 0)
        return (-(g + piece.p0) * tau**2 / 2 - piece.p1 * tau**3 / 6 + sine_u,
                -(g + piece.p0) * tau - piece.p1 * tau**2 / 2 + sine_v)
    return particular, lambda u, v, dt: (u + v * dt, v)


def _propagator(phase, piece, t, u, v):
    """(u, v)(time) on ``piece`` [s] from (u, v) at time t [s] in the given phase."""
    particular, free = phase
    up0, vp0 = particular(t - piece.start)

    def state(time):
        uh, vh = free(u - up0, v - vp0, time - t)
        up, vp = particular(time - piece.start)
        return up + uh, vp + vh
    return state


def _first_fall(guard, a, b):
    """The first t in (a, b] where ``guard`` falls through 0 from above, or None."""
    n = max(1, int(mp.ceil((b - a) / GRID)))
    left, f_left = a, guard(a)
    for k in range(1, n + 1):
        right = a + (b - a) * k / n
        f_right = guard(right)
        if f_left > 0 >= f_right:
            return mp.findroot(guard, (left, right), solver="anderson")
        left, f_left = right, f_right
    return None


def upthrow_events(block, pieces, t_end, n_events):
    """The first ``n_events`` events [(kind, t [s] as mpf)] of ``block`` (a
    bd.SpringSupportedMass: omega [rad/s], damping, static_deflection [m], g [m/s²]) from
    rest in contact at t = 0, until ``t_end`` [s]."""
    with mp.workdps(DIGITS):
        w, z = mp.mpf(block.omega), mp.mpf(block.damping)
        u0, g = mp.mpf(block.static_deflection), mp.mpf(block.g)
        guards = {  # mode: [(guard(u, v), next mode, kind)], each an event where it falls through 0
            "contact": [(lambda u, v: w**2 * (u0 - u) - 2 * z * w * v, "up", "liftoff")],
            "up": [(lambda u, v: v, "down", "top"), (lambda u, v: u - u0 + 2 * z * v / w, "contact", "landing")],
            "down": [(lambda u, v: u - u0, "contact", "landing"), (lambda u, v: -v, "up", "bottom")]}
        t, u, v, mode, events = mp.mpf(0), mp.mpf(0), mp.mpf(0), "contact", []
        t_end = mp.mpf(float(t_end))
        while len(events) < n_events and t < t_end:
            piece = next(p for p in pieces if p.start <= t < p.end)
            end = min(piece.end, t_end)
            phase = _contact(w, z, piece) if mode == "contact" else _flight(g, piece)
            state = _propagator(phase, piece, t, u, v)
            hits = []
            for guard, after, kind in guards[mode]:
                time = _first_fall(lambda s: guard(*state(s)), t, end)  # noqa: B023
                if time is not None:
                    hits.append((time, after, kind))
            if hits:
                t, mode, kind = min(hits, key=lambda hit: hit[0])
                events.append((kind, t))
            else:
                t = end
            u, v = state(t)
        return events
