"""The rest -> mode map of the free-standing block (Shenton 1996, with the vertical
acceleration through g_e): what a block at rest does first under a base acceleration."""

import numpy as np

from . import _slide_rock_laws as laws

#: the mode names, indexed by the laws' kind codes (REST = 0, ... FLIGHT = 4)
MODE_NAMES = ("rest", "slide", "rock", "slide-rock", "flight")
_NAMES = np.array(MODE_NAMES)


def _checked(name, value, low, strict):
    """``value`` as a float array, every element finite and > ``low`` (>= unless ``strict``)."""
    array = np.asarray(value, dtype=float)
    bad = ~np.isfinite(array) | ((array <= low) if strict else (array < low))
    if np.any(bad):
        raise ValueError(f"{name} must be finite and {'>' if strict else '>='} {low}, got {array[bad].ravel()[0]!r}")
    return array


def mode_codes(b_over_h, mu_s, a_over_g, mu_k=None, av_over_g=0.0):
    """:func:`mode_map` as the laws' kind codes (int array; :data:`MODE_NAMES` names them)."""
    b_over_h = _checked("b_over_h", b_over_h, 0.0, True)
    mu_s = _checked("mu_s", mu_s, 0.0, False)
    mu_k = mu_s if mu_k is None else _checked("mu_k", mu_k, 0.0, False)
    a_over_g = _checked("a_over_g", a_over_g, -np.inf, True)
    av_over_g = _checked("av_over_g", av_over_g, -np.inf, True)
    if np.any(mu_k > mu_s):
        raise ValueError(f"mu_k must be <= mu_s, got mu_k = {np.max(mu_k)!r} with mu_s = {np.min(mu_s)!r}")
    kind = np.vectorize(lambda lam, ms, a, mk, av: laws.rest_mode(a, 1.0 + av, lam, ms, mk)[0], otypes=[int])
    return kind(b_over_h, mu_s, a_over_g, mu_k, av_over_g)


def mode_map(b_over_h, mu_s, a_over_g, mu_k=None, av_over_g=0.0):
    """The mode a block at rest takes under a base acceleration: "rest", "slide", "rock",
    "slide-rock" (rocking on a slipping corner) or "flight" (Shenton 1996, with g + a_z for g).

    Args:
        b_over_h: the block's aspect ratio b/h = tan(alpha) [-] (> 0).
        mu_s: static friction coefficient [-].
        a_over_g: the horizontal base acceleration a_x / g [-]; its sign only picks the side.
        mu_k: kinetic friction coefficient [-] (<= mu_s); None: mu_s.
        av_over_g: the vertical base acceleration a_z / g [-] (upward positive).

    The arguments broadcast; returns a str array of their broadcast shape. On a threshold
    the block stays as it is (at rest, or on a sticking pivot)."""
    return _NAMES[mode_codes(b_over_h, mu_s, a_over_g, mu_k, av_over_g)]
