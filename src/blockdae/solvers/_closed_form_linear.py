"""Closed-form steps for models whose every mode is a linear second-order ODE with
affine guards (the :class:`~blockdae.SpringSupportedMass`), on the generic driver.

In a mode the model gives u'' + c u' + k u = b - a(t) (``linear_flow``) and guards
alpha u + beta u' + gamma (``affine_guards``). On a piece of the excitation,
a(tau) = p0 + p1 tau + s sin(w tau + phi), the solution from (u, u') at a restart is

    u(tau) = P(tau) + (A + E tau) sin(w tau + phi) + (B + F tau) cos(w tau + phi)
             + exp(-sigma tau) (C cos(w_d tau) + D sin(w_d tau)),

with P a polynomial (degree <= 1 for k > 0, <= 3 for k = c = 0; E = F = 0 but at
undamped resonance, w² = k, c = 0), and so is every guard
and each of its derivatives (:class:`ClosedForm`). A guard's first downward zero
crossing is found by :func:`first_down_crossing`, which cannot miss one: it keeps an
interval only where bounds of the guard's first three derivatives (from the closed
form) fail to show that it stays positive, is monotone, or is convex/concave (then
its slope's root splits it into monotone parts), bisecting otherwise; every crossing
in a monotone part is then refined by Brent's method to a few ulps.
"""

import dataclasses
import math

import numpy as np

from ..core import AbstractIntegrator, drive, falls, one_sign
from ..excitation import rebase

_EPS = np.finfo(float).eps
#: most intervals one root search may examine (a degenerate touch of zero by the guard
#: and its first two derivatives at once); more raises instead of looping
_MAX_INTERVALS = 10_000
#: sine forcing closer to resonance than this, sqrt((k - w²)² + (c w)²) / k [-], is taken as
#: undamped resonance (the particular solution is then off by about this times (w tau)²)
_AT_RESONANCE = 1e-12
#: between that and this distance from resonance the particular and free parts cancel and
#: the closed form would lose about 2e-16 / distance of its digits: refused
_NEAR_RESONANCE = 1e-6
#: damped frequency / undamped one below which (damping ratio within 5e-9 of 1) the free
#: part's D = (...) / w_d loses about 2e-16 / ratio of its digits: refused
_NEAR_CRITICAL = 1e-4


@dataclasses.dataclass(frozen=True)
class ClosedForm:
    """f(tau) = sum_i poly[i] tau^i + (A + E tau) sin(w tau + phi) + (B + F tau) cos(w tau + phi)
    + exp(-sigma tau) (C cos(w_d tau) + D sin(w_d tau)), tau >= 0 [s]."""

    poly: tuple
    A: float
    B: float
    w: float
    phi: float
    C: float
    D: float
    sigma: float
    w_d: float
    E: float = 0.0
    F: float = 0.0

    def __call__(self, tau):
        value = 0.0
        for coefficient in reversed(self.poly):
            value = value * tau + coefficient
        if self.A or self.B or self.E or self.F:
            theta = self.w * tau + self.phi
            value += (self.A + self.E * tau) * math.sin(theta) + (self.B + self.F * tau) * math.cos(theta)
        if self.C or self.D:
            phase = self.w_d * tau
            value += math.exp(-self.sigma * tau) * (self.C * math.cos(phase) + self.D * math.sin(phase))
        return value

    def derivative(self) -> "ClosedForm":
        poly = tuple(i * c for i, c in enumerate(self.poly))[1:] or (0.0,)
        return dataclasses.replace(self, poly=poly, A=self.E - self.w * self.B, B=self.F + self.w * self.A,
                                   E=-self.w * self.F, F=self.w * self.E,
                                   C=-self.sigma * self.C + self.w_d * self.D,
                                   D=-self.sigma * self.D - self.w_d * self.C)

    def rounding(self, tau) -> float:
        """The rounding error of f(tau): a few ulps of the sum of its terms' sizes."""
        poly = sum(abs(c * tau**i) for i, c in enumerate(self.poly))
        periodic = math.hypot(self.A, self.B) + abs(tau) * math.hypot(self.E, self.F)
        return 8 * _EPS * (poly + periodic + math.exp(-self.sigma * tau) * (abs(self.C) + abs(self.D)))

    def bound(self, a, b) -> float:
        """An upper bound of |f| on [a, b], 0 <= a <= b [s], term by term: loose where the
        terms cancel, which :func:`solve_linear` keeps from happening (it refuses forcing
        near resonance and damping near critical)."""
        poly = sum(abs(c) * b**i for i, c in enumerate(self.poly))
        return (poly + math.hypot(self.A, self.B) + b * math.hypot(self.E, self.F)
                + math.hypot(self.C, self.D) * math.exp(-self.sigma * a)) * (1 + 8 * _EPS)

    def combine(self, alpha, other: "ClosedForm", beta, gamma) -> "ClosedForm":
        """alpha self + beta other + gamma (same w, phi, sigma, w_d)."""
        n = max(len(self.poly), len(other.poly))
        pad = lambda p: tuple(p) + (0.0,) * (n - len(p))
        poly = tuple(alpha * x + beta * y for x, y in zip(pad(self.poly), pad(other.poly)))
        poly = (poly[0] + gamma,) + poly[1:]
        return dataclasses.replace(self, poly=poly, A=alpha * self.A + beta * other.A,
                                   B=alpha * self.B + beta * other.B, C=alpha * self.C + beta * other.C,
                                   E=alpha * self.E + beta * other.E, F=alpha * self.F + beta * other.F,
                                   D=alpha * self.D + beta * other.D)


def solve_linear(k, c, b, coefficients, u, u_rate) -> ClosedForm:
    """u(tau) of u'' + c u' + k u = b - a(tau) from (u, u') at tau = 0, a(tau) =
    p0 + p1 tau + s sin(w tau + phi) (``coefficients``); k > 0 with c² < 4 k (an
    underdamped oscillator) or k = c = 0 (free flight). Raises ValueError where the
    parts of the solution would cancel to lose digits: sine forcing within
    ``_NEAR_RESONANCE`` of resonance but not within ``_AT_RESONANCE`` of it (taken as
    resonance), and damping within ``_NEAR_CRITICAL`` of critical (as w_d / omega)."""
    p0, p1, s, w, phi = coefficients
    if s != 0 and w == 0:
        p0, s = p0 + s * math.sin(phi), 0.0
    if k > 0:
        A = B = E = F = 0.0
        sigma = 0.5 * c
        w_d = math.sqrt(k - sigma**2)
        if w_d < _NEAR_CRITICAL * math.sqrt(k):
            raise ValueError(f"damping ratio {sigma / math.sqrt(k)!r} is within 5e-9 of critical: the exact "
                             "backend's closed form loses digits there; use backend 'cvode' or 'ida'")
        det = (k - w**2) ** 2 + (c * w) ** 2
        distance = math.sqrt(det) / k
        if s != 0 and distance <= _AT_RESONANCE:  # undamped resonance: u = s tau cos(w tau + phi) / (2 w)
            F = s / (2 * w)
        elif s != 0 and distance < _NEAR_RESONANCE:
            raise ValueError(f"sine forcing at {w!r} rad/s is within {distance:.1e} of the resonance at "
                             f"{math.sqrt(k)!r} rad/s: the exact backend's closed form loses digits there; "
                             "use backend 'cvode' or 'ida'")
        elif s != 0:
            A, B = -s * (k - w**2) / det, s * c * w / det
        a1 = -p1 / k
        a0 = (b - p0 - c * a1) / k
        C = u - (a0 + A * math.sin(phi) + B * math.cos(phi))
        D = (u_rate - (a1 + F * math.cos(phi) + w * (A * math.cos(phi) - B * math.sin(phi))) + sigma * C) / w_d
        return ClosedForm((a0, a1), A, B, w, phi, C, D, sigma, w_d, E, F)
    if k == 0 and c == 0:
        A = s / w**2 if s != 0 else 0.0
        poly = (u - A * math.sin(phi), u_rate - A * w * math.cos(phi), 0.5 * (b - p0), -p1 / 6.0)
        return ClosedForm(poly, A, 0.0, w, phi, 0.0, 0.0, 0.0, 0.0)
    raise ValueError(f"no closed form for k={k!r} 1/s², c={c!r} 1/s (overdamped or damped without stiffness)")


class _Guard:
    """One guard along the closed form: f and its first three derivatives."""

    def __init__(self, form):
        self.f = [form]
        for _ in range(3):
            self.f.append(self.f[-1].derivative())


def first_down_crossing(guard: _Guard, a: float, b: float, origin: float = 0.0) -> float | None:
    """The first tau in [a, b] [s] where the guard reaches <= 0 from > 0; None if it
    does not. A touch of zero at a minimum that does not go below it (by more than
    rounding) is no crossing; a guard already <= 0 at a and heading down (f' < 0, or f'
    = 0 and f'' < 0; not turning back within the search's resolution) crosses at a.
    ``origin``: the time [s] at tau = 0, which sets the resolution of the search."""
    from scipy.optimize import brentq  # on use: importing scipy.optimize takes about half a second

    f, f1, f2, f3 = guard.f
    budget = [_MAX_INTERVALS]
    resolution = 4 * _EPS * max(abs(origin) + abs(b), 1.0)  # [s]: a few ulps of the time
    if f(a) <= 0 and falls(f1(a), f2(a), resolution):  # heading down, not turning back within rounding
        return a

    def monotone_part(lo, f_lo, hi, f_hi, decreasing):
        """The crossing on [lo, hi] where f is monotone: f must fall below zero by more
        than its rounding (a touch computed an ulp low is none; a crossing that goes on
        falls past hi, where the next window finds it at once)."""
        if not decreasing or not (f_lo > 0 > f_hi) or f_hi >= -f.rounding(hi):
            return None
        root = brentq(f, lo, hi, xtol=1e-300, rtol=4 * _EPS)
        while f(root) > 0 and root < hi:  # the first point past the crossing
            root = min(np.nextafter(root, math.inf), hi)
        return root

    def search(lo, f_lo, hi, f_hi):
        budget[0] -= 1
        if budget[0] < 0:
            raise RuntimeError(f"the root search of a guard did not settle on [{a}, {b}] s")
        length = hi - lo
        if one_sign(f_lo, f_hi, f1.bound(lo, hi), length):
            return None  # one sign strictly inside: no crossing in (lo, hi)
        d_lo, d_hi = f1(lo), f1(hi)
        slope_sign = one_sign(d_lo, d_hi, f2.bound(lo, hi), length)
        if slope_sign:
            return monotone_part(lo, f_lo, hi, f_hi, slope_sign < 0)
        if one_sign(f2(lo), f2(hi), f3.bound(lo, hi), length):  # f' monotone
            if d_lo * d_hi >= 0:  # f' of one sign inside: f monotone
                return monotone_part(lo, f_lo, hi, f_hi, d_lo + d_hi < 0)
            turn = brentq(f1, lo, hi, xtol=1e-300, rtol=4 * _EPS)
            f_turn = f(turn)
            first = monotone_part(lo, f_lo, turn, f_turn, d_lo < 0)
            return first if first is not None else monotone_part(turn, f_turn, hi, f_hi, d_hi < 0)
        if length <= resolution:
            return hi if f_lo > 0 > f_hi and f_hi < -f.rounding(hi) else None
        mid = lo + 0.5 * length
        f_mid = f(mid)
        first = search(lo, f_lo, mid, f_mid)
        return first if first is not None else search(mid, f_mid, hi, f_hi)

    return search(a, f(a), b, f(b))


class ClosedFormIntegrator(AbstractIntegrator):
    """Steps the driver's runs in closed form: between restarts the state is the
    closed form from the restart; a step returns at ``t_out`` or at the first guard
    crossing, located by :func:`first_down_crossing`."""

    def __init__(self, model, piece):
        self.model, self.piece = model, piece
        self.counts = {"n_restarts": 0, "n_calls": 0}

    def restart(self, mode, t, y):
        model, piece = self.model, self.piece
        self.mode, self.t_start, self.t = mode, float(t), float(t)
        k, c, b = model.linear_flow(mode)
        coefficients = rebase(*piece.coefficients[0], self.t_start - piece.t0)
        self.u = solve_linear(k, c, b, coefficients, float(y[0]), float(y[1]))
        self.u_rate = self.u.derivative()
        self.guards = [_Guard(self.u.combine(alpha, self.u_rate, beta, gamma))
                       for alpha, beta, gamma in model.affine_guards(mode)]
        self.counts["n_restarts"] += 1

    def step(self, t_out, t_stop):
        self.counts["n_calls"] += 1
        a, b = self.t - self.t_start, t_out - self.t_start
        best, index = None, None
        for i, guard in enumerate(self.guards):
            root = first_down_crossing(guard, a, b if best is None else best, self.t_start)
            if root is not None and (best is None or root < best):
                best, index = root, i
        tau = b if best is None else best
        self.t = t_out if best is None else self.t_start + tau
        return self.t, np.array([self.u(tau), self.u_rate(tau)]), index

    @property
    def stats(self):
        return dict(self.counts)


def solve_closed_form(model, excitation, horizon, name, max_events_at_one_instant=5, event_resolution=1e-12):
    """Run ``model`` on the driver with :class:`ClosedFormIntegrator`."""
    return drive(model, excitation, horizon, ClosedFormIntegrator, name, max_events_at_one_instant,
                 event_resolution, (0.0, 0.0))
