"""A model written outside blockdae, against its public abstract API only.

A single-degree-of-freedom oscillator (natural circular frequency omega [rad/s], damping
ratio zeta [-]) whose mass may strike a unilateral elastic stop a gap [m] below its rest
position: in CONTACT the stop adds a stiffness omega_c² per unit mass [1/s²]. Under a
base acceleration a(t) [m/s²], with u [m] the displacement relative to the base,

    FREE:     u'' = -2 zeta omega u' - omega² u - a(t)
    CONTACT:  u'' = -2 zeta omega u' - omega² u - omega_c² (u + gap) - a(t)

and one guard per mode: FREE is left when u + gap falls through 0, CONTACT when it rises
through 0. Nothing in ``src/blockdae`` names this model: ``bd.simulate`` runs it on CVODE
(its default), IDA (as the explicit ODE) and the JAX twin, and ``bd.crosscheck``
compares them. Run: ``python examples/custom_model.py``.
"""

import dataclasses
import enum
import math

import numpy as np

import blockdae as bd
from blockdae.core.contract import DifferentiableModel


class StopMode(enum.IntEnum):
    FREE = 0
    CONTACT = 1


@dataclasses.dataclass(frozen=True)
class OscillatorOnStop(DifferentiableModel):
    """Args: omega [rad/s], zeta [-], omega_c [rad/s] (the stop's stiffness per unit
    mass is omega_c²), gap [m] > 0 between the rest position and the stop."""

    omega: float
    zeta: float
    omega_c: float
    gap: float

    state_names = ("u", "u_rate")
    modes = StopMode
    initial_mode = StopMode.FREE

    # ---- the automaton ---------------------------------------------------------
    def flow(self, mode, t, y, excitation, xp=np):
        """(u', u'') [m/s, m/s²]; works on floats, NumPy and JAX (``xp``)."""
        u, v = y[0], y[1]
        accel = -2 * self.zeta * self.omega * v - self.omega**2 * u - excitation.acceleration(t)
        if mode == StopMode.CONTACT:
            accel = accel - self.omega_c**2 * (u + self.gap)
        return xp.stack([v, accel])

    def guards(self, mode, t, y, excitation, xp=np):
        """FREE: u + gap (contact as it falls through 0); CONTACT: -(u + gap)."""
        clearance = y[0] + self.gap
        return xp.stack([clearance if mode == StopMode.FREE else -clearance])

    def mode_at_rest(self, t, excitation, xp=np, y=None):
        return StopMode.FREE if y is None or y[0] + self.gap > 0 else StopMode.CONTACT

    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp=np, time_tol=0.0):
        return StopMode.CONTACT if mode == StopMode.FREE else StopMode.FREE

    # ---- what the driver asks ----------------------------------------------------
    def is_static(self, mode):
        return False  # it always moves

    def at_rest(self, mode, y):
        return False  # an oscillator never re-takes a mode from the excitation alone

    def rest_state(self, y):
        return np.array([y[0], 0.0])

    def state_at_guard(self, mode, guard_index, y, xp=np):
        """At either guard the mass is exactly at the stop."""
        return xp.stack([-self.gap, y[1]])

    def turn_rate(self, mode, t, y, excitation, xp=np):
        return None  # the solvers' steps resolve the oscillation

    def guard_rates(self, mode, guard_index, t, y, excitation):
        """(d/dt, d²/dt²) of the guard [m/s, m/s²]."""
        side = 1.0 if mode == StopMode.FREE else -1.0
        return side * y[1], side * float(self.flow(mode, t, y, excitation, np)[1])

    def output_step(self):
        """Dense-output knots every 1 / (32 omega_max) [s]."""
        return 1.0 / (32 * math.hypot(self.omega, self.omega_c))

    def speed(self, y):
        return abs(float(y[1]))

    def time_to_rest(self, mode, y):
        raise ValueError("an oscillator never comes to rest exactly: give t_end [s]")

    # ---- for the JAX twin and derivatives ----------------------------------------
    def parameters(self):
        return {"omega": self.omega, "zeta": self.zeta, "omega_c": self.omega_c, "gap": self.gap}

    def parameter_units(self):
        """Units of the parameters and of the motion's scale factors (A [g], A_x [-])."""
        return {"omega": "rad/s", "zeta": "-", "omega_c": "rad/s", "gap": "m", "A": "g", "A_x": "-"}

    def with_parameters(self, values):
        return dataclasses.replace(self, **values)

    def replace(self, **changes):
        """A copy with ``changes`` (parameter name -> value in its unit)."""
        return dataclasses.replace(self, **changes)


def record(duration=6.0, dt=0.01):
    """A decaying 1.5 Hz shake sampled at ``dt`` [s], peak about 0.5 g, as a bd.Record."""
    t = np.arange(0.0, duration, dt)
    return bd.Record(0.5 * 9.81 * np.exp(-0.4 * t) * np.sin(2 * np.pi * 1.5 * t), dt, name="decaying 1.5 Hz",
                     units="m/s2")


def main():
    model = OscillatorOnStop(omega=2 * np.pi * 2.0, zeta=0.2, omega_c=2 * np.pi * 8.0, gap=0.005)
    check = bd.crosscheck(model, record(), t_end=6.0, backends=("cvode", "ida", "jax"), rtol=1e-10)
    print(check)
    worst = max(row["max_dt"] for row in check.rows)
    print(f"largest event-time disagreement between backends: {worst:.2e} s "
          f"over {check.rows[0]['n_events']} events")
    return check


if __name__ == "__main__":
    main()
