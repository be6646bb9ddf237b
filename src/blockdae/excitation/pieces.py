"""Piecewise closed forms of the base acceleration.

On piece k, with local time tau in [0, h_k],

    a(tau) = p0 + p1 tau + s sin(w tau + phi)              [m/s²],

and a is monotone on every piece (pieces are split at extrema). Records have s = 0
(linear pieces); harmonic motion and sine pulses have p1 = 0. Every function here
works on NumPy and on JAX arrays (``xp`` is the namespace); passing ``s=None`` (with
``w``, ``phi`` None) drops the sine terms, for kernels compiled for linear pieces only.
"""

from typing import NamedTuple

import numpy as np


class Pieces(NamedTuple):
    """Monotone pieces of a(t); each field has shape (n_pieces,)."""

    t0: np.ndarray  # start time [s]
    h: np.ndarray  # length [s]
    p0: np.ndarray  # [m/s²]
    p1: np.ndarray  # [m/s³]
    s: np.ndarray  # sine amplitude [m/s²]
    w: np.ndarray  # angular frequency [rad/s]
    phi: np.ndarray  # phase at tau = 0 [rad]

    @classmethod
    def linear(cls, t0, h, p0, p1):
        zeros = np.zeros_like(np.asarray(t0, dtype=float))
        return cls(*(np.asarray(x, dtype=float) + zeros for x in (t0, h, p0, p1)), zeros, zeros, zeros)

    @property
    def has_sine(self) -> bool:
        return bool(np.any(np.asarray(self.s) != 0))

    @property
    def t_end(self) -> float:
        return float(self.t0[-1] + self.h[-1])

    def scaled(self, k):
        """a(t) multiplied by ``k``."""
        return self._replace(p0=self.p0 * k, p1=self.p1 * k, s=self.s * k)

    @staticmethod
    def concatenate(parts: "list[Pieces]") -> "Pieces":
        return Pieces(*(np.concatenate([np.atleast_1d(getattr(p, f)) for p in parts]) for f in Pieces._fields))


def _safe_w(w, xp):
    return xp.where(w == 0, 1.0, w)


def accel(p0, p1, s, w, phi, tau, xp=np):
    """a(tau) [m/s²]."""
    linear = p0 + p1 * tau
    return linear if s is None else linear + s * xp.sin(w * tau + phi)


def accel_rate(p0, p1, s, w, phi, tau, xp=np):
    """da/dtau [m/s³]."""
    return p1 if s is None else p1 + s * w * xp.cos(w * tau + phi)


def piece_direction(coefficients, h, xp=np):
    """Which way a, monotone on a piece of length ``h`` [s], moves: the sign of
    a(h) - a(0) [-] (0: flat, or a change below rounding)."""
    return xp.sign(accel(*coefficients, h, xp) - accel(*coefficients, 0.0, xp))


def monotone_rate(rate, direction, xp=np):
    """``rate`` [m/s³] of a monotone a with rounding projected out: zero where it points
    against the piece's ``direction`` (:func:`piece_direction`), e.g. the cosine of a
    sine piece at its extremum, which rounds to ±6e-17 instead of 0."""
    return xp.where(rate * direction < 0, 0.0 * rate, rate)


def accel_int1(p0, p1, s, w, phi, tau, xp=np):
    """Integral of a over [0, tau] [m/s]."""
    linear = (p0 + 0.5 * p1 * tau) * tau
    if s is None:
        return linear
    ws = _safe_w(w, xp)
    return linear + (s / ws) * 2.0 * xp.sin(phi + 0.5 * w * tau) * xp.sin(0.5 * w * tau)


def accel_int2(p0, p1, s, w, phi, tau, xp=np):
    """Double integral of a over [0, tau] (zero value and slope at 0) [m]."""
    linear = (0.5 * p0 + p1 * tau / 6.0) * tau**2
    if s is None:
        return linear
    ws = _safe_w(w, xp)
    return linear + (s / ws) * (tau * xp.cos(phi)
                                - 2.0 * xp.cos(phi + 0.5 * w * tau) * xp.sin(0.5 * w * tau) / ws)


def rebase(p0, p1, s, w, phi, tau):
    """Coefficients of the same piece with its origin moved to ``tau``."""
    return p0 + p1 * tau, p1, s, w, (None if phi is None else phi + w * tau)


def evaluate(pieces: Pieces, t, v0=0.0, x0=0.0):
    """a, da/dt (right-hand), v and x of the base at times ``t`` [s] (NumPy).

    ``v0``, ``x0``: base velocity [m/s] and displacement [m] at t = pieces.t0[0].
    Beyond the last piece the base keeps the end velocity (a = 0).
    """
    t = np.asarray(t, dtype=float)
    coeffs = (pieces.p0, pieces.p1, pieces.s, pieces.w, pieces.phi)
    h = pieces.h
    dv = accel_int1(*coeffs, h)
    dx = accel_int2(*coeffs, h)
    v_start = v0 + np.concatenate([[0.0], np.cumsum(dv)])
    x_start = x0 + np.concatenate([[0.0], np.cumsum(dx + v_start[:-1] * h)])
    k = np.clip(np.searchsorted(pieces.t0, t, side="right") - 1, 0, len(h) - 1)
    inside = t < pieces.t_end
    tau = np.where(inside, t - pieces.t0[k], 0.0)
    ck = tuple(c[k] for c in coeffs)
    a = np.where(inside, accel(*ck, tau), 0.0)
    rate = np.where(inside, accel_rate(*ck, tau), 0.0)
    v = np.where(inside, v_start[k] + accel_int1(*ck, tau), v_start[-1])
    x = np.where(inside, x_start[k] + v_start[k] * tau + accel_int2(*ck, tau),
                 x_start[-1] + v_start[-1] * (t - pieces.t_end))
    return a, rate, v, x
