"""Numba kernels: located maxima of |f| on an interval and the exact oscillator recurrence.

Imported lazily (numba compiles on the first call and caches to disk), so that
``import blockdae`` stays cheap.

Every response quantity on a piece of the excitation is of the form (local time τ)

    f(τ) = k0 + k1 τ + k2 τ² + k3 τ³ + e^(-α τ) (k4 cos βτ + k5 sin βτ)
           + k6 cos w1 τ + k7 sin w1 τ + k8 cos w2 τ + k9 sin w2 τ,

with α, β >= 0. ``max_abs`` finds max |f| on [0, h] by branch and bound on the bound
|f| <= max(|f(a)|, |f(b)|) + M2 (b - a)² / 8 over [a, b], with M2 >= |f''| there: an
interval is dropped once its bound cannot beat the best value by more than a relative
1e-15, and where f' is certified monotone its root is found by bracketed Newton: the
maximum is located to rounding, never sampled on a grid.
"""

import numpy as np
from numba import njit, prange

RTOL = 1e-15  # relative slack of the branch and bound
_STACK = 256


@njit(cache=True)
def f_eval(k, al, be, w1, w2, t):
    """f(t) for the coefficients k (10,)."""
    e = np.exp(-al * t)
    out = k[0] + t * (k[1] + t * (k[2] + t * k[3])) + e * (k[4] * np.cos(be * t) + k[5] * np.sin(be * t))
    if k[6] != 0.0 or k[7] != 0.0:
        out += k[6] * np.cos(w1 * t) + k[7] * np.sin(w1 * t)
    if k[8] != 0.0 or k[9] != 0.0:
        out += k[8] * np.cos(w2 * t) + k[9] * np.sin(w2 * t)
    return out


@njit(cache=True)
def _derivative(k, al, be, w1, w2, out):
    """Coefficients of f' into ``out``."""
    out[0], out[1], out[2], out[3] = k[1], 2.0 * k[2], 3.0 * k[3], 0.0
    out[4], out[5] = -al * k[4] + be * k[5], -al * k[5] - be * k[4]
    out[6], out[7] = w1 * k[7], -w1 * k[6]
    out[8], out[9] = w2 * k[9], -w2 * k[8]


@njit(cache=True)
def _eval3(k, k1, k2, al, be, w1, w2, t):
    """f, f', f'' at t (the transcendental functions computed once)."""
    e = np.exp(-al * t)
    cb, sb = e * np.cos(be * t), e * np.sin(be * t)
    f = k[0] + t * (k[1] + t * (k[2] + t * k[3])) + k[4] * cb + k[5] * sb
    f1 = k1[0] + t * (k1[1] + t * k1[2]) + k1[4] * cb + k1[5] * sb
    f2 = k2[0] + t * k2[1] + k2[4] * cb + k2[5] * sb
    if k[6] != 0.0 or k[7] != 0.0:
        c1, s1 = np.cos(w1 * t), np.sin(w1 * t)
        f += k[6] * c1 + k[7] * s1
        f1 += k1[6] * c1 + k1[7] * s1
        f2 += k2[6] * c1 + k2[7] * s1
    if k[8] != 0.0 or k[9] != 0.0:
        c2, s2 = np.cos(w2 * t), np.sin(w2 * t)
        f += k[8] * c2 + k[9] * s2
        f1 += k1[8] * c2 + k1[9] * s2
        f2 += k2[8] * c2 + k2[9] * s2
    return f, f1, f2


@njit(cache=True)
def _m2(k, al, be, w1, w2, a, b):
    """An upper bound of |f''| on [a, b] (0 <= a <= b)."""
    poly = max(abs(2 * k[2] + 6 * k[3] * a), abs(2 * k[2] + 6 * k[3] * b))
    damped = (al * al + be * be) * np.sqrt(k[4] * k[4] + k[5] * k[5]) * np.exp(-al * a)
    sines = w1 * w1 * np.sqrt(k[6] * k[6] + k[7] * k[7]) + w2 * w2 * np.sqrt(k[8] * k[8] + k[9] * k[9])
    return poly + damped + sines


@njit(cache=True)
def _m3(k, al, be, w1, w2, a):
    """An upper bound of the third derivative's magnitude on [a, inf), 0 <= a."""
    om2 = al * al + be * be
    return (6.0 * abs(k[3]) + om2 * np.sqrt(om2) * np.sqrt(k[4] * k[4] + k[5] * k[5]) * np.exp(-al * a)
            + w1 ** 3 * np.sqrt(k[6] * k[6] + k[7] * k[7]) + w2 ** 3 * np.sqrt(k[8] * k[8] + k[9] * k[9]))


@njit(cache=True)
def _critical(k, k1, k2, al, be, w1, w2, a, b, da):
    """The root of f' in [a, b] where f' is monotone and changes sign (bracketed Newton)."""
    lo, hi = a, b
    x = 0.5 * (a + b)
    for _ in range(100):
        f, f1, f2 = _eval3(k, k1, k2, al, be, w1, w2, x)
        if f1 == 0.0:
            return x
        if (f1 > 0.0) == (da > 0.0):
            lo = x
        else:
            hi = x
        nxt = x - f1 / f2 if f2 != 0.0 else 0.5 * (lo + hi)
        if not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        if abs(nxt - x) <= 4e-16 * max(abs(x), b) or hi - lo <= 4e-16 * max(abs(hi), b):
            return nxt
        x = nxt
    return x


@njit(cache=True)
def max_abs(k, al, be, w1, w2, h, best, t_best):
    """(max(best, max |f| on [0, h]), where): t_best is kept when nothing beats ``best``."""
    return max_abs_ws(k, al, be, w1, w2, h, best, t_best, np.empty(10), np.empty(10), np.empty((_STACK, 6)))


@njit(cache=True)
def max_abs_ws(k, al, be, w1, w2, h, best, t_best, k1, k2, stack):
    """(max(best, max |f| on [0, h]), where): t_best is kept when nothing beats ``best``.

    Branch and bound: an interval [a, b] is dropped when max(|f(a)|, |f(b)|) + M2 (b-a)²/8
    cannot beat ``best``; where f' is certified monotone (|f''(m)| > M3 (b - a) / 2) the
    only candidate inside is the root of f', found by bracketed Newton to rounding.
    """
    _derivative(k, al, be, w1, w2, k1)
    _derivative(k1, al, be, w1, w2, k2)
    fa, da, _ = _eval3(k, k1, k2, al, be, w1, w2, 0.0)
    fb, db, _ = _eval3(k, k1, k2, al, be, w1, w2, h)
    if abs(fa) > best:
        best, t_best = abs(fa), 0.0
    if abs(fb) > best:
        best, t_best = abs(fb), h
    stack[0, 0], stack[0, 1], stack[0, 2], stack[0, 3], stack[0, 4], stack[0, 5] = 0.0, h, fa, fb, da, db
    n = 1
    floor = 4e-16 * h
    while n > 0:
        n -= 1
        a, b, fa, fb, da, db = stack[n, 0], stack[n, 1], stack[n, 2], stack[n, 3], stack[n, 4], stack[n, 5]
        length = b - a
        bound = max(abs(fa), abs(fb)) + 0.125 * _m2(k, al, be, w1, w2, a, b) * length * length
        if bound <= best * (1.0 + RTOL) or length <= floor:
            continue
        m = 0.5 * (a + b)
        fm, dm, d2m = _eval3(k, k1, k2, al, be, w1, w2, m)
        if abs(fm) > best:
            best, t_best = abs(fm), m
        if abs(d2m) > 0.5 * _m3(k, al, be, w1, w2, a) * length:  # f' monotone on [a, b]
            if (da > 0.0) != (db > 0.0) and da != 0.0 and db != 0.0:
                x = _critical(k, k1, k2, al, be, w1, w2, a, b, da)
                fx = f_eval(k, al, be, w1, w2, x)
                if abs(fx) > best:
                    best, t_best = abs(fx), x
            continue
        if n + 2 > _STACK:
            continue
        stack[n, 0], stack[n, 1], stack[n, 2], stack[n, 3], stack[n, 4], stack[n, 5] = m, b, fm, fb, dm, db
        n += 1
        stack[n, 0], stack[n, 1], stack[n, 2], stack[n, 3], stack[n, 4], stack[n, 5] = a, m, fa, fm, da, dm
        n += 1
    return best, t_best


@njit(cache=True)
def max_abs_many(coeffs, params, h, best, t_best):
    """``max_abs`` for each row: coeffs (m, 10), params (m, 4) = α, β, w1, w2, h (m,)."""
    out_best = best.copy()
    out_t = t_best.copy()
    for i in range(h.size):
        out_best[i], out_t[i] = max_abs(coeffs[i], params[i, 0], params[i, 1], params[i, 2], params[i, 3],
                                        h[i], best[i], t_best[i])
    return out_best, out_t


# ---- the linear oscillator ----------------------------------------------------------
# u'' + 2 ζ ω u' + ω² u = -a_g(τ), a_g = p0 + p1 τ + s sin(w τ + φ) on a piece;
# u: relative displacement, v = u', absolute acceleration -2ζω v - ω² u, z = u + x_g.

@njit(cache=True)
def _particular(p0, p1, s, w, phi, om, ze):
    """u_p = A0 + A1 τ + gu cos wτ + eu sin wτ."""
    A1 = -p1 / (om * om)
    A0 = -p0 / (om * om) + 2.0 * ze * p1 / (om * om * om)
    gu = 0.0
    eu = 0.0
    if s != 0.0:
        dd = om * om - w * w
        den = dd * dd + (2.0 * ze * om * w) ** 2
        X = -s * dd / den
        Y = s * 2.0 * ze * om * w / den
        gu = X * np.sin(phi) + Y * np.cos(phi)
        eu = X * np.cos(phi) - Y * np.sin(phi)
    return A0, A1, gu, eu


@njit(cache=True)
def _fill(k, which, A0, A1, gu, eu, c, d, al, be, om, ze, p0, p1, s, w, phi, xg, vg):
    """Coefficients of u (0), v (1), absolute acceleration (2) or z = u + x_g (3) into k."""
    for i in range(10):
        k[i] = 0.0
    if which == 0 or which == 3:
        k[0], k[1], k[4], k[5], k[6], k[7] = A0, A1, c, d, gu, eu
    elif which == 1:
        k[0], k[4], k[5], k[6], k[7] = A1, -al * c + be * d, -al * d - be * c, w * eu, -w * gu
    else:
        kv0, kv4, kv5, kv6, kv7 = A1, -al * c + be * d, -al * d - be * c, w * eu, -w * gu
        q = -2.0 * ze * om
        r = -om * om
        k[0] = q * kv0 + r * A0
        k[1] = r * A1
        k[4] = q * kv4 + r * c
        k[5] = q * kv5 + r * d
        k[6] = q * kv6 + r * gu
        k[7] = q * kv7 + r * eu
    if which == 3:
        k[0] += xg
        k[1] += vg
        k[2] = 0.5 * p0
        k[3] = p1 / 6.0
        if s != 0.0:
            k[0] += s / (w * w) * np.sin(phi)
            k[1] += s / w * np.cos(phi)
            k[6] -= s / (w * w) * np.sin(phi)
            k[7] -= s / (w * w) * np.cos(phi)


@njit(cache=True)
def _step(u0, v0, p0, p1, s, w, phi, hk, om, ze, al, be):
    """(u, v) at the end of a piece of length hk, from (u0, v0) at its start (exact)."""
    A0, A1, gu, eu = _particular(p0, p1, s, w, phi, om, ze)
    c = u0 - A0 - gu
    d = (v0 - A1 - w * eu + al * c) / be
    E, C, S = np.exp(-al * hk), np.cos(be * hk), np.sin(be * hk)
    cw = sw = 0.0
    if s != 0.0:
        cw, sw = np.cos(w * hk), np.sin(w * hk)
    u1 = A0 + A1 * hk + gu * cw + eu * sw + E * (c * C + d * S)
    v1 = A1 + w * (eu * cw - gu * sw) + E * ((-al * c + be * d) * C + (-al * d - be * c) * S)
    return u1, v1


@njit(cache=True)
def _refine(k, q, us, vs, t0, h, p0, p1, s, w, phi, xg, vg, om, ze, al, be, kk, best, when, ws1, ws2, stack):
    """Branch and bound for quantity q on piece k; updates best[q], when[q]."""
    A0, A1, gu, eu = _particular(p0[k], p1[k], s[k], w[k], phi[k], om, ze)
    c = us[k] - A0 - gu
    d = (vs[k] - A1 - w[k] * eu + al * c) / be
    _fill(kk, q, A0, A1, gu, eu, c, d, al, be, om, ze, p0[k], p1[k], s[k], w[k], phi[k], xg[k], vg[k])
    b, tb = max_abs_ws(kk, al, be, w[k], 0.0, h[k], best[q], -1.0, ws1, ws2, stack)
    if tb >= 0.0:
        best[q] = b
        when[q] = t0[k] + tb


@njit(cache=True)
def history(h, p0, p1, s, w, phi, om, ze, us, vs):
    """The exact response at the ends of the pieces, from rest at the start.

    Fills us, vs (shape (n + 1,), n = h.size) with u, u' at t0[0] (zero) and at the
    end of every piece: the Nigam-Jennings recurrence for linear pieces of the common
    length h[0], the exact step of ``_step`` for the others.
    """
    al = ze * om
    be = om * np.sqrt(1.0 - ze * ze)
    # the Nigam-Jennings matrix of a linear piece of the common length h[0]:
    # (u1, v1) = M (u0, v0, p0, p1), from the exact step applied to unit inputs
    href = h[0]
    M = np.empty((2, 4))
    for j in range(4):
        e = np.zeros(4)
        e[j] = 1.0
        M[0, j], M[1, j] = _step(e[0], e[1], e[2], e[3], 0.0, 0.0, 0.0, href, om, ze, al, be)
    m00, m01, m02, m03 = M[0, 0], M[0, 1], M[0, 2], M[0, 3]
    m10, m11, m12, m13 = M[1, 0], M[1, 1], M[1, 2], M[1, 3]
    u = v = 0.0
    us[0] = vs[0] = 0.0
    for k in range(h.size):
        if s[k] == 0.0 and h[k] == href:
            u, v = m00 * u + m01 * v + m02 * p0[k] + m03 * p1[k], m10 * u + m11 * v + m12 * p0[k] + m13 * p1[k]
        else:
            u, v = _step(u, v, p0[k], p1[k], s[k], w[k], phi[k], h[k], om, ze, al, be)
        us[k + 1] = u
        vs[k + 1] = v


@njit(cache=True)
def _one(t0, h, p0, p1, s, w, phi, xg, vg, om, ze, best, when):
    """Located max |u|, |v|, |a_abs|, |z| over the pieces (best, when: shape (4,))."""
    n = h.size
    al = ze * om
    be = om * np.sqrt(1.0 - ze * ze)
    om2 = om * om
    tz = 2.0 * ze * om
    us = np.empty(n + 1)
    vs = np.empty(n + 1)
    history(h, p0, p1, s, w, phi, om, ze, us, vs)  # pass 1: the exact recurrence
    b0 = b1 = b2 = b3 = 0.0  # the sample maxima
    i0 = i1 = i2 = i3 = 0
    for i in range(1, n + 1):
        u = us[i]
        v = vs[i]
        x = abs(u)
        if x > b0:
            b0, i0 = x, i
        x = abs(v)
        if x > b1:
            b1, i1 = x, i
        x = abs(tz * v + om2 * u)
        if x > b2:
            b2, i2 = x, i
        x = abs(u + xg[i])
        if x > b3:
            b3, i3 = x, i
    t_end = t0[n - 1] + h[n - 1]
    best[0], best[1], best[2], best[3] = b0, b1, b2, b3
    when[0] = t0[i0] if i0 < n else t_end
    when[1] = t0[i1] if i1 < n else t_end
    when[2] = t0[i2] if i2 < n else t_end
    when[3] = t0[i3] if i3 < n else t_end
    kk = np.empty(10)
    ws1 = np.empty(10)
    ws2 = np.empty(10)
    stack = np.empty((_STACK, 6))
    inv_be = 1.0 / be
    flag = np.empty(n, dtype=np.bool_)
    _screen(h, p0, p1, s, us, vs, xg, vg, om, ze, best, flag)
    for k in range(n):  # pass 2: pieces whose bound can beat the running maxima
        if not flag[k]:
            continue
        hk = h[k]
        if s[k] != 0.0:  # sine pieces: bounds from the coefficients, then refine
            for q in range(4):
                A0, A1, gu, eu = _particular(p0[k], p1[k], s[k], w[k], phi[k], om, ze)
                c = us[k] - A0 - gu
                d = (vs[k] - A1 - w[k] * eu + al * c) * inv_be
                _fill(kk, q, A0, A1, gu, eu, c, d, al, be, om, ze, p0[k], p1[k], s[k], w[k], phi[k], xg[k], vg[k])
                if _bound(kk, al, be, w[k], hk) > best[q] * (1.0 + 1e-15):
                    _refine(k, q, us, vs, t0, h, p0, p1, s, w, phi, xg, vg, om, ze, al, be, kk, best, when,
                    ws1, ws2, stack)
            continue
        R2, thr0, thr1, thr2, thr3 = _linear_thresholds(hk, p0[k], p1[k], us[k], us[k + 1], vs[k], vs[k + 1],
                                                        xg[k], xg[k + 1], vg[k], om, ze, best)
        for q, thr in ((0, thr0), (1, thr1), (2, thr2), (3, thr3)):
            if thr < 0.0 or R2 > thr * thr:
                _refine(k, q, us, vs, t0, h, p0, p1, s, w, phi, xg, vg, om, ze, al, be, kk, best, when,
                        ws1, ws2, stack)


@njit(cache=True, error_model="numpy")  # no zero-division branch: vectorises
def _screen(h, p0, p1, s, us, vs, xg, vg, om, ze, best, flag):
    """flag[k]: piece k passes any of the four tests of ``_one``'s pass 2 against ``best``.

    The same arithmetic as there, branch-free so that it vectorises; the maxima only grow
    during pass 2 and every test is monotone in them, so the flagged pieces include all
    that pass 2 refines, which stays exact by re-testing them with the running maxima.
    Sine pieces are always flagged.
    """
    for k in range(h.size):
        R2, t0, t1, t2, t3 = _linear_thresholds(h[k], p0[k], p1[k], us[k], us[k + 1], vs[k], vs[k + 1],
                                                xg[k], xg[k + 1], vg[k], om, ze, best)
        flag[k] = ((s[k] != 0.0) | (t0 < 0.0) | (R2 > t0 * t0) | (t1 < 0.0) | (R2 > t1 * t1)
                   | (t2 < 0.0) | (R2 > t2 * t2) | (t3 < 0.0) | (R2 > t3 * t3))


@njit(cache=True, inline="always")
def _linear_thresholds(hk, p0, p1, u0, u1, v0, v1, xg0, xg1, vg0, om, ze, best):
    """Pass 2's tests on a linear piece of length ``hk`` [s]: (R², thr_u, thr_v, thr_a,
    thr_z); quantity q can beat ``best[q]`` only if thr_q < 0 or R² > thr_q².

    On the piece u = A0 + A1 τ + e^(-ατ)(c cos βτ + d sin βτ), R = sqrt(c² + d²), and
    |f| <= min(max|poly| + k1 R, max|f(ends)| + (m2poly + k2 R) h²/8), so f can beat
    best only if R > max((best - max|poly|) / k1, (best - ends - m2poly h²/8) / k2).
    Branch-free (selects only), so that ``_screen`` vectorises.
    """
    al = ze * om
    be = om * np.sqrt(1.0 - ze * ze)
    om2 = om * om
    tz = 2.0 * ze * om
    inv_om = 1.0 / om
    inv_om2 = 1.0 / om2
    h8 = 0.125 * hk * hk
    k2u = 1.0 / (om2 * h8)  # 1 / (ω² h²/8): |u''| <= ω² R
    k2v = k2u * inv_om
    k2a = k2u * inv_om2
    A1 = -p1 * inv_om2
    A0 = -p0 * inv_om2 - 2.0 * ze * A1 * inv_om
    c = u0 - A0
    d = (v0 - A1 + al * c) * (1.0 / be)
    R2 = c * c + d * d
    thr_u = _max(best[0] - _max(abs(A0), abs(A0 + A1 * hk)), (best[0] - _max(abs(u0), abs(u1))) * k2u)
    thr_v = _max((best[1] - abs(A1)) * inv_om, (best[1] - _max(abs(v0), abs(v1))) * k2v)
    # absolute acceleration: poly p0 + p1 τ, damped amplitude ω² R
    pa = _max(abs(p0), abs(p0 + p1 * hk))
    ends = _max(abs(tz * v0 + om2 * u0), abs(tz * v1 + om2 * u1))
    thr_a = _max((best[2] - pa) * inv_om2, (best[2] - ends) * k2a)
    # absolute displacement: poly A0 + xg + (A1 + vg) τ + p0 τ²/2 + p1 τ³/6
    poly = abs(A0 + xg0) + hk * (abs(A1 + vg0) + hk * (0.5 * abs(p0) + hk * abs(p1) / 6.0))
    ends = _max(abs(u0 + xg0), abs(u1 + xg1))
    thr_z = _max(best[3] - poly, (best[3] - ends - pa * h8) * k2u)
    return R2, thr_u, thr_v, thr_a, thr_z


@njit(cache=True, inline="always")
def _max(a, b):
    """max(a, b) as a select (vectorisable); the same value as ``max`` for numbers."""
    return a if a > b else b


@njit(cache=True)
def _bound(k, al, be, w1, h):
    """An upper bound of |f| on [0, h] (w2 = 0)."""
    poly = abs(k[0]) + h * (abs(k[1]) + h * (abs(k[2]) + h * abs(k[3])))
    damped = np.sqrt(k[4] * k[4] + k[5] * k[5])
    sine = np.sqrt(k[6] * k[6] + k[7] * k[7])
    ends = max(abs(f_eval(k, al, be, w1, 0.0, 0.0)), abs(f_eval(k, al, be, w1, 0.0, h)))
    return min(poly + damped + sine, ends + 0.125 * _m2(k, al, be, w1, 0.0, 0.0, h) * h * h)


@njit(cache=True, parallel=True)
def spectra(t0, h, p0, p1, s, w, phi, xg, vg, starts, omegas, zetas, best, when):
    """Batch: records r (pieces starts[r]:starts[r+1]; xg, vg with one more entry per record),
    dampings j, frequencies i -> best[r, j, i, q], when[r, j, i, q], q = u, v, a_abs, z."""
    n_r = starts.size - 1
    n_z = zetas.size
    n_p = omegas.size
    for idx in prange(n_r * n_z * n_p):
        r = idx // (n_z * n_p)
        j = (idx // n_p) % n_z
        i = idx % n_p
        lo, hi = starts[r], starts[r + 1]
        _one(t0[lo:hi], h[lo:hi], p0[lo:hi], p1[lo:hi], s[lo:hi], w[lo:hi], phi[lo:hi],
             xg[lo + r:hi + r + 1], vg[lo + r:hi + r + 1], omegas[i], zetas[j], best[r, j, i], when[r, j, i])
