"""Closed forms shared by the tests' references: a damped linear oscillator under a
piecewise-linear excitation (a record, linear between its samples).

u'' + 2 zeta omega u' + omega² u = -a(t), a(t) linear on each sample interval, 0 <= zeta < 1:
on each interval u is the particular solution A + B t plus the free vibration
e^(-zeta omega t) (C cos wd t + D sin(wd t) / wd), wd = omega sqrt(1 - zeta²). The states at
the samples are carried in mpmath (``DPS`` digits), so the reference does not accumulate
rounding over a record; between samples the same closed form is evaluated in float64 from
the exact state at the sample before (a few ulps of the response).
"""

import mpmath as mp
import numpy as np
from scipy.optimize import brentq

DPS = 30  # decimal digits of the states at the samples


def _coefficients(u, v, a0, slope, omega, zeta, sqrt):
    """(A, B, C, D, sigma, wd) of the closed form on one interval from (u, v) at its start."""
    b = -slope / omega**2
    a = (-a0 - 2 * zeta * omega * b) / omega**2
    sigma = zeta * omega
    c = u - a
    return a, b, c, v - b + sigma * c, sigma, omega * sqrt((1 - zeta) * (1 + zeta))


def oscillator_samples(samples, dt, omega, zeta, n_steps=None):
    """States (u [m], u' [m/s]) at the samples, shape (n_steps + 1, 2), float64 rounded from
    mpmath: the oscillator from rest at t = 0 under ``samples`` [m/s²] at k dt [s],
    linear between them."""
    n_steps = len(samples) - 1 if n_steps is None else n_steps
    with mp.workdps(DPS):
        omega, zeta, dt = mp.mpf(omega), mp.mpf(zeta), mp.mpf(dt)
        u, v = mp.mpf(0), mp.mpf(0)
        states = [(0.0, 0.0)]
        for k in range(n_steps):
            a0 = mp.mpf(samples[k])
            slope = (mp.mpf(samples[k + 1]) - a0) / dt
            a, b, c, d, sigma, wd = _coefficients(u, v, a0, slope, omega, zeta, mp.sqrt)
            decay, cos, sin = mp.exp(-sigma * dt), mp.cos(wd * dt), mp.sin(wd * dt) / wd
            free, free_rate = c * cos + d * sin, -c * wd**2 * sin + d * cos
            u, v = a + b * dt + decay * free, b + decay * (free_rate - sigma * free)
            states.append((float(u), float(v)))
    return np.array(states)


def oscillator_piece(state, a0, slope, omega, zeta, t):
    """(u, u', u'') at times ``t`` [s] after a sample, from its ``state`` (u, u') under
    a = a0 + slope t [m/s²] (float64; sin(wd t) / wd as t sinc, so zeta next to 1 keeps its digits)."""
    t = np.asarray(t, dtype=float)
    a, b, c, d, sigma, wd = _coefficients(state[0], state[1], a0, slope, omega, zeta, np.sqrt)
    decay, cos, sin = np.exp(-sigma * t), np.cos(wd * t), t * np.sinc(wd * t / np.pi)
    free, free_rate = c * cos + d * sin, -c * wd**2 * sin + d * cos
    u, v = a + b * t + decay * free, b + decay * (free_rate - sigma * free)
    return u, v, -(a0 + slope * t) - 2 * zeta * omega * v - omega**2 * u


def sup_abs(value, rate, t0, t1, grid=65):
    """sup |value| over [t0, t1] [s]: the ends and the roots of ``rate`` (sign changes on a
    grid of ``grid`` points, refined by brentq). ``value``, ``rate``: float functions of t,
    element-wise on arrays."""
    times = np.linspace(t0, t1, grid)
    rates = rate(times)
    best = max(abs(value(t0)), abs(value(t1)))
    for j in np.flatnonzero(rates[:-1] * rates[1:] < 0):
        best = max(best, abs(value(brentq(rate, times[j], times[j + 1], xtol=1e-15, rtol=1e-15))))
    return best
