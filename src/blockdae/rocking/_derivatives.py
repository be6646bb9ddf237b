"""The derivatives of a free-standing block's largest rotation, max |theta| / alpha [-],
through its impacts (what overturning spectra and fragility read); those of the complete
block's (:class:`FreeStandingDerivatives`) also of its slip and overturning time.

The largest |theta| is reached where theta' = 0 (an apex, or the release from a tilt), at
the overturn (|theta| = pi/2, fixed), or at t_end while the block still turns out; at
each of these d|theta|/dp is the located state's derivative (theta' = 0 at an apex, so
the event time's own derivative adds nothing), and

    d(m / alpha)/dp = sign(theta) (d theta/dp) / alpha - m / alpha² d alpha/dp,

alpha = atan(b/h): d alpha/db = h / R², d alpha/dh = -b / R². An overturned block has
m / alpha = (pi/2) / alpha, which moves with b and h alone.
"""

import numpy as np

from ..core.contract import DifferentiableModel, parameter_names, scale_factor_units
from ..core.derivatives import Sensitivities, trajectory_quantity_sensitivities
from ._free_modes import OVERTURNED, SLIDE_ROCK_KINDS, kind_of, side

FLIGHT = 9  # the kind of a flight (:func:`._free_modes.kind_of`)

#: the events at which |theta| may be largest: theta' = 0 there, or theta = pi/2
EXTREMES = ("release", "apex", "overturn")


def max_theta_jacobian(block, solution, final, events) -> np.ndarray:
    """d(max |theta| / alpha)/dp [-], shape (n_p,), by the names of
    :func:`~blockdae.core.contract.parameter_names` (see the module's docstring);
    ``final`` is d(theta, theta')(t_end)/dp (2, n_p), ``events`` one derivative per event
    of ``solution`` (its ``dy_dp_after``: the located state's after the event's maps)."""
    names = parameter_names(block)
    if block.slides:
        return np.zeros(len(names))
    candidates = [(float(solution.state[-1, 0]), np.asarray(final[0]))]
    candidates += [(event.q, np.asarray(derivative.dy_dp_after[0]))
                   for event, derivative in zip(solution.events, events) if event.kind in EXTREMES]
    theta, d_theta = max(candidates, key=lambda candidate: abs(candidate[0]))
    alpha, r2 = block.alpha, block.b ** 2 + block.h ** 2
    d_alpha = np.array([{"b": block.h / r2, "h": -block.b / r2}.get(name, 0.0) for name in names])
    return np.sign(theta) * d_theta / alpha - abs(theta) / alpha ** 2 * d_alpha


# ---- the complete free-standing block -------------------------------------------------
class FreeStandingDerivatives(DifferentiableModel):
    """What :func:`blockdae.sensitivities` differentiates of a
    :class:`~blockdae.rocking.FreeStandingBlock`, along the JAX twin's located trajectory
    (the variational equation in every mode, the saltation jump at every guard and every
    impact's or landing's velocity jump on the branch it took): by its parameters b, h
    [m], mu, mu_kinetic (where given; else mu moves both) [-], g [m/s²] and the motion's
    scale factors ("A" [g], "A_x", "A_z" [-]).

    Quantities (``of=``): "max_theta_over_alpha" [-], "slip" [m] (the base's slip at
    t_end, :func:`._slide_rock_laws.base_slip`) and "overturn_time" [s]; without ``of``, the
    centroid's x(t_end) relative to the base [m]."""

    def parameter_units(self) -> dict:
        return {"b": "m", "h": "m", "mu": "-", "mu_kinetic": "-", "g": "m/s²", **scale_factor_units(self)}

    def default_wrt(self) -> tuple:
        return tuple(name for name in self.parameters() if name != "g") + ("A",)

    def scalar_quantities(self) -> dict:
        return {"max_theta_over_alpha": "-", "slip": "m", "overturn_time": "s"}

    def sensitivities(self, motion, t_end, wrt, backend, of, options):
        """The core's along the twin's trajectory (NotImplemented), except where the
        largest rotation is reached at an apex inside a slide-rock (theta' = 0 there, no
        mode change): max |theta| / alpha is then differentiated on the trajectory that
        ends at that apex, located on the run's dense output, where d theta/dp is its
        derivative (theta' = 0: the apex's time adds nothing), the other quantities on
        the whole one."""
        names = (of,) if isinstance(of, str) else tuple(of or ())
        if "max_theta_over_alpha" not in names:
            return NotImplemented
        try:
            return trajectory_quantity_sensitivities(self, motion, t_end, wrt, backend, of, options)
        except ApexInSlideRock as apex:
            largest = trajectory_quantity_sensitivities(self, motion, apex.t, wrt, backend,
                                                        ("max_theta_over_alpha",), options)
        others = tuple(name for name in names if name != "max_theta_over_alpha")
        if not others:
            return largest
        rest = trajectory_quantity_sensitivities(self, motion, t_end, wrt, backend, others, options)
        rows = [(largest, 0) if name == "max_theta_over_alpha" else (rest, others.index(name)) for name in names]
        return Sensitivities(names, [r.quantity_units[i] for r, i in rows], rest.parameters,
                             np.stack([r.array[i] for r, i in rows]), [r.units[i] for r, i in rows], self,
                             rest.backend)

    def scalar_quantity_jacobian(self, name, solution, final, events):
        """d ``name`` / dp (:func:`free_max_theta_jacobian`, :func:`free_slip_jacobian`,
        :func:`free_overturn_time_jacobian`)."""
        return {"max_theta_over_alpha": free_max_theta_jacobian, "slip": free_slip_jacobian,
                "overturn_time": free_overturn_time_jacobian}[name](self, solution, final, events)


def _alpha_rates(block, names):
    """d alpha / dp [rad per unit], alpha = atan(b/h), shape (n_p,)."""
    r2 = block.b ** 2 + block.h ** 2
    return np.array([{"b": block.h / r2, "h": -block.b / r2}.get(name, 0.0) for name in names])


def _located(solution, events):
    """(theta [rad] before it, d theta/dp before it (n_p,)) at each event of ``solution``:
    the first of the run's mode changes at its time from its mode (an impact is two)."""
    located = []
    for event in solution.events:
        change = next((c for c in events if c.t == event.t and c.mode_before == event.mode_before), None)
        if change is None:
            raise RuntimeError(f"no derivative found for the event {event.kind} at t = {event.t!r} s")
        located.append((event.state[2], np.asarray(change.dy_dp_before[2])))
    return located


class ApexInSlideRock(ValueError):
    """The largest rotation is reached at an apex inside a slide-rock, at ``t`` [s]: no
    event of the run (:meth:`FreeStandingDerivatives.sensitivities` differentiates it on
    the trajectory that ends there)."""

    def __init__(self, largest, at_events, t):
        super().__init__(f"the largest rotation (|theta| = {largest:.9g} rad) is reached inside a slide-rock at "
                         f"t = {t:.9g} s, at no located event (the largest at an event or t_end: {at_events:.9g} "
                         "rad): differentiate it with t_end at that apex")
        self.t = t


def _apex_time(solution) -> float:
    """The time [s] where theta' = 0 next to the knot of the largest |theta|, by bisection
    on the run's dense output (its Hermite cubic of theta' between the knots)."""
    t, state = solution.t, solution.state
    k = int(np.argmax(np.abs(state[:, 2])))
    s = np.sign(state[k, 2])
    lo, hi = t[max(k - 1, 0)], t[min(k + 1, len(t) - 1)]

    def turning(time):  # s theta' [rad/s] at ``time``
        return s * float(solution.dense(np.array([time]))[5][0])

    if turning(lo) < 0 or turning(hi) > 0:  # the apex is at a knot itself
        return float(t[k])
    while lo < 0.5 * (lo + hi) < hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if turning(mid) > 0 else (lo, mid)
    return float(hi)


def free_max_theta_jacobian(block, solution, final, events) -> np.ndarray:
    """d(max |theta| / alpha)/dp [-/unit], shape (n_p,): the largest |theta| at an event
    (an apex, where theta' = 0; a landing or lift-off, reached from flight where theta'' =
    0; the overturn at pi/2) or at t_end, differentiated as the located state there
    (its total derivative, the event time's included). :class:`ApexInSlideRock` where the
    largest rotation lies inside a slide-rock (its apex is no event of the model)."""
    names = parameter_names(block)
    candidates = [(float(solution.state[-1, 2]), np.asarray(final[2]))] + _located(solution, events)
    theta, d_theta = max(candidates, key=lambda candidate: abs(candidate[0]))
    largest = float(np.max(np.abs(solution.state[:, 2])))
    if largest > abs(theta) + 1e-12 * max(block.alpha, largest):
        raise ApexInSlideRock(largest, abs(theta), _apex_time(solution))
    alpha = block.alpha
    return np.sign(theta) * d_theta / alpha - abs(theta) / alpha ** 2 * _alpha_rates(block, names)


def free_slip_jacobian(block, solution, final, events) -> np.ndarray:
    """d slip(t_end)/dp [m/unit], shape (n_p,), slip = x - h sin theta - sgn(theta) b (1 -
    cos theta) (:func:`._slide_rock_laws.base_slip`), from the centroid's state at t_end
    (ValueError where the block is in flight then: its state is a corner's)."""
    if kind_of(solution.mode[-1]) == FLIGHT:
        raise ValueError(f"the block is in flight at t_end = {solution.t_end:.6g} s: its slip is that of no corner "
                         "on the base; choose a t_end where it stands on the base")
    names = parameter_names(block)
    if kind_of(solution.mode[-1]) in SLIDE_ROCK_KINDS:  # the state holds the pivot's u: slip = u - s b
        s = float(side(solution.mode[-1]))
        return np.asarray(final[0]) - s * np.array([name == "b" for name in names], dtype=float)
    theta = float(solution.state[-1, 2])
    s = float(np.sign(theta))
    d_slip = np.asarray(final[0]) - (block.h * np.cos(theta) + s * block.b * np.sin(theta)) * np.asarray(final[2])
    explicit = {"h": -np.sin(theta), "b": -s * (1.0 - np.cos(theta))}
    return d_slip + np.array([explicit.get(name, 0.0) for name in names])


def free_overturn_time_jacobian(block, solution, final, events) -> np.ndarray:
    """d t_overturn/dp [s/unit], shape (n_p,): the located event's dt/dp. ValueError where
    the block did not overturn by t_end."""
    change = next((c for c in events if kind_of(c.mode_after) == OVERTURNED), None)
    if change is None:
        raise ValueError(f"the block did not overturn by t_end = {solution.t_end:.6g} s: no overturning time to "
                         "differentiate")
    return np.asarray(change.dt_dp)
