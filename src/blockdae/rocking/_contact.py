"""The contact force at the pivot of a rocking block against its limits: where N falls to 0
(the pivot would lift: a flight) and where |F| reaches mu N (the pivot would slip), located
on a solution's dense output. Housner's model goes on through them (its pivot holds, as
the literature's overturning spectra assume); they are reported."""

import numpy as np

from ._modes import side

#: bisection steps on the dense output: [t_i, t_i+1] of at most 1 / (32 p) to below 1e-15 s
BISECTIONS = 60
#: the kinds of a contact event and the guard each is the zero of
KINDS = ("lift_limit", "slip_limit")


class MotionAt:
    """A base motion as the model's rules read an excitation: a_x and a_z [m/s²] and
    their rates [m/s³] at any times (a 1-D excitation: a_x alone)."""

    def __init__(self, motion):
        components = getattr(motion, "components", None)
        self.x, self.z = (motion, None) if components is None else (components[0], components[2])

    def component(self, index, t):
        source = self.x if index == 0 else self.z
        return 0.0 * np.asarray(t) if source is None else source.acceleration(t)

    def component_rate(self, index, t):
        source = self.x if index == 0 else self.z
        return 0.0 * np.asarray(t) if source is None else source.acceleration_rate(t)


def contact_margins(block, excitation, s, t, theta, rate):
    """(N [m/s²], mu N - |F| [m/s²]) rocking about side ``s`` at times ``t`` [s] in the
    states (theta [rad], theta' [rad/s]) (arrays of one shape)."""
    force, normal = block.contact_force(s, theta, rate, t, excitation, np)
    return normal, block.mu * normal - np.abs(force)


def locate_contact_events(solution):
    """[(t [s], kind, theta [rad], theta' [rad/s], F [m/s²], N [m/s²])]: each time the
    contact force leaves its limits while the block rocks (N falls through 0, or mu N -
    |F| does), located by bisection on the dense output; a limit already broken as a
    rocking episode starts is reported at its start."""
    block, excitation = solution.block, MotionAt(solution.motion)
    rocking = np.array([abs(int(m)) in (2, 3, 4) for m in solution.mode])
    found = []
    for i in np.flatnonzero(rocking[:-1]):
        a, b = solution.t[i], solution.t[i + 1]
        if b <= a:
            continue
        s = side(solution.mode[i])
        times = np.array([a, 0.5 * (a + b), b])
        theta, rate = solution.dense(times)
        theta[0], rate[0] = solution.state[i]
        margins = contact_margins(block, excitation, s, times, theta, rate)
        episode_start = i == 0 or not rocking[i - 1]
        for kind, values in zip(KINDS, margins):
            if episode_start and values[0] <= 0:
                found.append((a, kind))
                continue
            crossing = np.flatnonzero((values[:-1] > 0) & (values[1:] <= 0))
            if crossing.size:
                k = crossing[0]
                found.append((_bisect(solution, block, excitation, s, kind, times[k], times[k + 1]), kind))
    rows = []
    for t, kind in sorted(found):
        s = side(solution.mode[np.searchsorted(solution.t, t, side="right") - 1])
        theta, rate = (float(v[0]) for v in solution.dense(np.array([t])))
        force, normal = block.contact_force(s, theta, rate, t, excitation, np)
        rows.append((float(t), kind, theta, rate, float(force), float(normal)))
    return rows


def _bisect(solution, block, excitation, s, kind, a, b):
    index = KINDS.index(kind)
    for _ in range(BISECTIONS):
        mid = 0.5 * (a + b)
        theta, rate = solution.dense(np.array([mid]))
        if contact_margins(block, excitation, s, np.array([mid]), theta, rate)[index][0] > 0:
            a = mid
        else:
            b = mid
    return b
