"""What a model declares to run on the compiled linear engine
(:mod:`blockdae.solvers._linear`): its modes as tables."""

import dataclasses

import numpy as np


@dataclasses.dataclass(frozen=True)
class LinearModes:
    """A model's modes as the linear engine's tables.

    Attributes:
        stiffness, damping, offset: (m,) k [1/s²], c [1/s], b [m/s²] of
            u'' + c u' + k u = b - a(t) in each mode; k > 0 with c² < 4 k, or k = c = 0.
        guards: (m, g, 3) rows (alpha, beta, gamma) of the guard alpha u + beta u' +
            gamma; a mode with fewer guards pads with (0, 0, 1) (never reached).
        next_mode: (m, g) the mode entered at each guard.
        resets: (m, g, 2, 3): the state after guard j of mode m is R @ (u, u') + r, with
            [R | r] the 2 x 3 block.
        initial_mode: the mode at t = 0, from rest (u = u' = 0).
    """

    stiffness: np.ndarray
    damping: np.ndarray
    offset: np.ndarray
    guards: np.ndarray
    next_mode: np.ndarray
    resets: np.ndarray
    initial_mode: int

    def __post_init__(self):
        fields = {name: np.asarray(getattr(self, name), dtype=float)
                  for name in ("stiffness", "damping", "offset", "guards", "resets")}
        m = fields["stiffness"].shape[0] if fields["stiffness"].ndim == 1 else -1
        shapes = {"stiffness": (m,), "damping": (m,), "offset": (m,)}
        g = fields["guards"].shape[1] if fields["guards"].ndim == 3 else -1
        shapes |= {"guards": (m, g, 3), "resets": (m, g, 2, 3)}
        for name, array in fields.items():
            if m < 1 or g < 1 or array.shape != shapes[name]:
                raise ValueError(f"LinearModes.{name} must have shape {shapes[name]} (modes, guards), "
                                 f"got {array.shape}")
            if not np.all(np.isfinite(array)):
                raise ValueError(f"LinearModes.{name} must be finite, got {array!r}")
            object.__setattr__(self, name, array)
        next_mode = np.asarray(self.next_mode)
        if next_mode.shape != (m, g) or not np.issubdtype(next_mode.dtype, np.integer) or \
                np.any((next_mode < 0) | (next_mode >= m)):
            raise ValueError(f"LinearModes.next_mode must be ({m}, {g}) integers in [0, {m}), got {next_mode!r}")
        object.__setattr__(self, "next_mode", next_mode.astype(np.int64))
        if not (isinstance(self.initial_mode, (int, np.integer)) and 0 <= self.initial_mode < m):
            raise ValueError(f"LinearModes.initial_mode must be an integer in [0, {m}), got {self.initial_mode!r}")
        k, c = fields["stiffness"], fields["damping"]
        free = (k == 0) & (c == 0)
        under = (k > 0) & (c**2 < 4 * k * (1 - 1e-8))  # damping within 5e-9 of critical loses digits
        if not np.all(free | under):
            bad = int(np.flatnonzero(~(free | under))[0])
            ratio = c[bad] / (2 * np.sqrt(k[bad])) if k[bad] > 0 else np.inf
            raise ValueError(f"mode {bad}: k={float(k[bad])!r} 1/s², c={float(c[bad])!r} 1/s (damping ratio "
                             f"{float(ratio)!r}) has no closed form here: an underdamped oscillator (damping "
                             "ratio below 1 - 5e-9 of critical) or free flight (k = c = 0); use backend 'cvode' "
                             "or 'ida'")

    def arrays(self):
        """The tables as the kernels take them."""
        return self.stiffness, self.damping, self.offset, self.guards, self.next_mode, self.resets
