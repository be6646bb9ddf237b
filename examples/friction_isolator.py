"""A friction pendulum isolator written outside blockdae, against its public contract only.

A mass on a spherical sliding surface of radius R [m] with friction coefficient mu [-].
With u [m] its displacement relative to the base and a(t) [m/s²] the base acceleration,
the mass sticks while the friction it needs, |a(t) + (g/R) u|, is at most mu g, and slides
otherwise:

    STICK:       u' = 0,  u'' = 0
    SLIDE_POS:   u'' = -a(t) - (g/R) u - mu g       (u' > 0)
    SLIDE_NEG:   u'' = -a(t) - (g/R) u + mu g       (u' < 0)

STICK has two guards, mu g + a + (g/R) u (a slide to +u starts where it falls through 0)
and mu g - a - (g/R) u (a slide to -u); each slide one, its velocity (signed so that it
is positive in the slide): the mass stops where it falls through 0. Nothing in
``src/blockdae`` names this model: it runs on every generic backend, in batches of
records, in process pools, in ``bd.study`` (over its mu: it declares no study hook), in
design studies through ``blockdae.design.Simulated`` (``design.exceedance`` and the
inverses on mu), and from the command line (``blockdae run --model
friction_isolator:FrictionIsolator``).
Run: ``python examples/friction_isolator.py``.
"""

import dataclasses
import enum
import math

import numpy as np

import blockdae as bd
from blockdae import design
from blockdae.core.contract import DifferentiableModel


class IsolatorMode(enum.IntEnum):
    STICK = 0
    SLIDE_POS = 1
    SLIDE_NEG = 2


#: the direction of each mode's slide (0: none)
_SIDE = {IsolatorMode.STICK: 0.0, IsolatorMode.SLIDE_POS: 1.0, IsolatorMode.SLIDE_NEG: -1.0}


@dataclasses.dataclass(frozen=True)
class FrictionIsolator(DifferentiableModel):
    """Args: mu, the friction coefficient [-] (> 0); radius, the surface's radius R [m]
    (> 0); g [m/s²]; u0 [m], v0 [m/s]: the state at t = 0 (at rest at the centre by
    default; v0 != 0: already sliding). State y = (u [m], u' [m/s])."""

    mu: float = 0.06
    radius: float = 2.0
    g: float = bd.STANDARD_GRAVITY
    u0: float = 0.0
    v0: float = 0.0

    state_names = ("u", "u_rate")
    state_units = ("m", "m/s")  # tables: u_m, u_rate_m_s; figures: u [m], u_rate [m/s]
    modes = IsolatorMode

    def __post_init__(self):
        for name in ("mu", "radius", "g"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"{name}={value!r} must be a positive finite number")
        for name in ("u0", "v0"):
            if not (isinstance(getattr(self, name), (int, float)) and math.isfinite(getattr(self, name))):
                raise ValueError(f"{name}={getattr(self, name)!r} must be a finite number")
        if self.v0 == 0 and self.g / self.radius * abs(self.u0) > self.mu * self.g:
            raise ValueError(f"u0={self.u0!r} m: at rest there the surface pulls harder than friction holds "
                             f"(|u0| / R = {abs(self.u0) / self.radius:.4g} > mu = {self.mu}); give v0 or a smaller u0")

    # ---- where it starts ------------------------------------------------------------
    @property
    def initial_mode(self):
        """STICK at rest, else the slide of v0's sign."""
        return IsolatorMode.STICK if self.v0 == 0 else (IsolatorMode.SLIDE_POS if self.v0 > 0
                                                         else IsolatorMode.SLIDE_NEG)

    def initial_state(self):
        return np.array([self.u0, self.v0])

    # ---- the automaton: flow, guards, transitions (floats, NumPy and JAX via xp) ----
    def demand(self, t, y, excitation):
        """-(a + (g/R) u) [m/s²]: the relative acceleration before friction."""
        return -excitation.acceleration(t) - self.g / self.radius * y[0]

    def flow(self, mode, t, y, excitation, xp=np):
        """(u', u'') [m/s, m/s²]."""
        side = _SIDE[IsolatorMode(int(mode))]
        if side == 0:
            return xp.stack([0.0 * y[1], 0.0 * y[1]])
        return xp.stack([y[1], self.demand(t, y, excitation) - side * self.mu * self.g])

    def guards(self, mode, t, y, excitation, xp=np):
        """STICK: (mu g - demand, mu g + demand) [m/s²]; a slide: its signed velocity [m/s]."""
        side = _SIDE[IsolatorMode(int(mode))]
        if side == 0:
            demand = self.demand(t, y, excitation)
            return xp.stack([self.mu * self.g - demand, self.mu * self.g + demand])
        return xp.stack([side * y[1]])

    def _mode_for(self, demand, margin=0.0):
        """The mode the demand [m/s²] asks for: a slide where it exceeds the friction mu g,
        or comes within ``margin`` [m/s²] of it."""
        if demand > self.mu * self.g - margin:
            return IsolatorMode.SLIDE_POS
        if demand < -self.mu * self.g + margin:
            return IsolatorMode.SLIDE_NEG
        return IsolatorMode.STICK

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        return self._mode_for(self.demand(t, np.zeros(2) if y is None else y, excitation))

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        """From STICK the slide of the guard reached; at a stop STICK, or the other slide
        where the demand exceeds the friction the other way, or reaches it within
        ``time_tol`` [s] of ``t`` (u' = 0 there: the demand changes at the rate -a'(t))."""
        if mode == IsolatorMode.STICK:
            return IsolatorMode.SLIDE_POS if guard_index == 0 else IsolatorMode.SLIDE_NEG
        margin = abs(excitation.acceleration_rate(t)) * time_tol
        after = self._mode_for(self.demand(t, y, excitation), margin)
        return IsolatorMode.STICK if after == mode else after

    # ---- what the driver asks ----------------------------------------------------------
    def is_static(self, mode):
        return mode == IsolatorMode.STICK

    def at_rest(self, mode, y):
        return mode == IsolatorMode.STICK

    def rest_state(self, y):
        return np.array([y[0], 0.0])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """At a stop u' = 0 exactly; an onset keeps the state."""
        if mode == IsolatorMode.STICK:
            return y
        return xp.stack([y[0], 0.0 * y[1]])

    def turn_rate(self, mode, t, y, excitation, xp=np):
        """STICK: the guards are linear in t on a piece (u is constant); a slide: None (the
        integrators' steps resolve the pendulum's slow swing)."""
        return None

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(rate, curvature) of the guard [per s, per s²] on a linear piece of a(t)."""
        side = _SIDE[IsolatorMode(int(mode))]
        a_rate = excitation.acceleration_rate(t)
        if side == 0:
            sign = 1.0 if guard_index == 0 else -1.0  # guard 0 is mu g - demand
            return sign * a_rate, 0.0
        accel = self.demand(t, y, excitation) - side * self.mu * self.g
        return side * accel, side * (-a_rate - self.g / self.radius * y[1])

    def contradiction(self, mode, y, velocity_error):
        side = _SIDE[IsolatorMode(int(mode))]
        if side * y[1] < -velocity_error:
            return f"u' = {y[1]:+.6g} m/s points against {mode.name}"
        return None

    def speed(self, y):
        return abs(float(y[1]))

    def time_to_rest(self, mode, y):
        """Each half swing of the free pendulum (pi sqrt(R/g) [s]) loses 2 mu R of amplitude."""
        amplitude = math.hypot(float(y[0]), float(y[1]) * math.sqrt(self.radius / self.g))
        return (amplitude / (2 * self.mu * self.radius) + 2) * math.pi * math.sqrt(self.radius / self.g)

    def output_step(self):
        """Dense-output knots every 1 / (32 omega) [s] of the pendulum, omega = sqrt(g/R)."""
        return 1.0 / (32 * math.sqrt(self.g / self.radius))

    # ---- parameters: the JAX twin, derivatives, design studies -----------------------
    def parameters(self):
        return {"mu": self.mu, "radius": self.radius, "g": self.g}  # u0, v0: not differentiated

    def parameter_units(self):
        return {"mu": "-", "radius": "m", "g": "m/s²", "A": "g", "A_x": "-"}

    def default_wrt(self):
        return ("mu", "radius", "A")

    def with_parameters(self, values):
        """Not validated: the values may be traced JAX scalars."""
        model = object.__new__(FrictionIsolator)
        for name, value in {**self.parameters(), **values}.items():
            object.__setattr__(model, name, value)
        return model

    def replace(self, **changes):
        return dataclasses.replace(self, **changes)


def record(duration=4.0, dt=0.01, peak_g=0.4):
    """A decaying 1 Hz shake sampled at ``dt`` [s], peak about ``peak_g`` [g], as a bd.Record."""
    t = np.arange(0.0, duration, dt)
    return bd.Record(peak_g * bd.STANDARD_GRAVITY * np.exp(-0.5 * t) * np.sin(2 * np.pi * t), dt,
                     name="decaying 1 Hz", units="m/s2")


def design_model(**options):
    """The isolator as a design model: D [m] = its peak |u| (what the bearing must
    accommodate), the inverses solving for mu."""
    return design.Simulated(FrictionIsolator(), parameters={"mu": "-", "radius": "m"}, design="mu", measure="peak",
                            **options)


def main():
    isolator, motion = FrictionIsolator(mu=0.06, radius=2.0), record()
    check = bd.crosscheck(isolator, motion, backends=("cvode", "ida"), rtol=1e-10)
    print(check)
    table = bd.study([motion], mu=[0.04, 0.06, 0.08], scale=[0.5, 1.0], block=isolator)
    print(table[["mu", "scale", "pga_g", "max_abs_displacement_m", "n_events"]].to_string(index=False))
    study = design.exceedance(motion, design_model(), {"mu": design.LogNormal(0.06, 0.2), "radius": 2.0},
                              threshold=0.05, runs=16)
    print(f"P(D > 0.05 m) = {study.probability:.3f} over {len(study.table)} runs")
    mu = design.ky_for_displacement(motion, design_model(), {"radius": 2.0}, allowable=0.05)
    print(f"mu for a peak displacement of 0.05 m: {mu:.5f}")
    return check, table, study, mu


if __name__ == "__main__":
    main()
