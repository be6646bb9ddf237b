"""Derivatives of a spring-supported mass's flights: the first liftoff velocity, the
largest flight height and the total flight time.

Each is read at located events of the trajectory the JAX twin locates, and is
differentiated by the chain rule through the event times
(:func:`blockdae.core.derivatives.trajectory_sensitivities`): a state component q read at
an event at t_e(p) has dq/dp = S-[q] + f-[q] dt_e/dp, the total derivative of the
located state, and a time t_e has dt_e/dp.
"""

import numpy as np

from ..core import Horizon, backend_name, make_backend
from ..core.derivatives import Sensitivities, by_parameter, checked_wrt, jax_context, largest_peak, \
    parameter_names, trajectory_sensitivities

#: quantity -> its unit
QUANTITIES = {"liftoff_velocity": "m/s", "height": "m", "flight_time": "s"}
_U, _V = range(2)


def flight_sensitivities(mass, motion, t_end, wrt, backend, of, options) -> Sensitivities:
    """d(quantity)/dp for each quantity in ``of`` (names of :data:`QUANTITIES`; None: all)
    and parameter in ``wrt``, along the JAX twin's trajectory (``backend`` "jax" or None),
    in the quantity's unit per the parameter's."""
    backend = "jax" if backend is None else backend
    if backend_name(backend) != "jax":
        raise ValueError(f"backend={backend!r} has no derivatives for a SpringSupportedMass; use 'jax'")
    of = tuple(QUANTITIES) if of is None else ((of,) if isinstance(of, str) else tuple(of))
    unknown = [name for name in of if name not in QUANTITIES]
    if unknown or not of:
        raise ValueError(f"of={of!r}: choose among {tuple(QUANTITIES)}")
    wrt = checked_wrt(mass, wrt)
    peak = largest_peak(motion) if "A" in wrt else None
    horizon = Horizon.resolve(motion, t_end)
    solution, _, events = trajectory_sensitivities(mass, motion, horizon, make_backend(backend, **options))
    with jax_context():
        rows = flight_quantity_jacobians(mass, solution, events, of)
    derivatives = {quantity: {name: float(value) for name, value in by_parameter(mass, row, wrt, peak).items()}
                   for quantity, row in rows.items()}
    return Sensitivities.make(mass, derivatives, quantity_units=[QUANTITIES[q] for q in of], backend=backend)


def flight_quantity_jacobians(mass, solution, events, of):
    """name -> d(quantity)/dp, shape (n_p,) over the parameters of
    :func:`blockdae.core.derivatives.parameter_names`, for each quantity in ``of``.

    Args:
        mass: the :class:`~blockdae.SpringSupportedMass`.
        solution: its :class:`~blockdae.upthrow.UpthrowSolution`.
        events: one :class:`~blockdae.core.derivatives.EventSensitivity` per event of it.
        of: names from :data:`QUANTITIES`.
    """
    rows = {"liftoff_velocity": _liftoff_velocity, "height": _height, "flight_time": _flight_time}
    return {name: rows[name](mass, solution, events) for name in of}


def _liftoff_velocity(mass, solution, events):
    """u' at the first liftoff [m/s]."""
    for event, derivative in zip(solution.events, events):
        if event.kind == "liftoff":
            return derivative.dy_dp_before[_V]
    raise ValueError(f"the mass never lifts off before t_end = {solution.t_end:.6g} s: it has no liftoff velocity "
                     "(a larger motion, a lower frequency or a later t_end may make it fly)")


def _height(mass, solution, events):
    """The largest u - u0 over the flights [m], as :attr:`~blockdae.upthrow.UpthrowSolution.flights`
    has it: at a top (u' = 0), or at the liftoff or landing of a flight that lands still
    rising; a flight still rising at t_end has no height yet."""
    candidates, liftoff = [], None
    for i, event in enumerate(solution.events):
        if event.kind == "liftoff":
            liftoff = i
        elif event.kind == "top":
            candidates.append((event.height, i))
        elif event.kind == "landing" and liftoff is not None:
            candidates += [(solution.events[liftoff].height, liftoff), (event.height, i)]
            liftoff = None
    if not candidates:
        raise ValueError(f"no flight reaches its top or lands before t_end = {solution.t_end:.6g} s: there is no "
                         "flight height (a later t_end may give one)")
    _, i = max(candidates)
    return events[i].dy_dp_after[_U] - _static_deflection_gradient(mass)


def _flight_time(mass, solution, events):
    """The sum of landing - liftoff over the flights [s]; a flight not landed by t_end
    counts to t_end (fixed)."""
    total = np.zeros(len(parameter_names(mass)))
    for event, derivative in zip(solution.events, events):
        if event.kind == "liftoff":
            total = total - derivative.dt_dp
        elif event.kind == "landing":
            total = total + derivative.dt_dp
    return total


def _static_deflection_gradient(mass):
    """d u0 / dp [m per unit] from the model's own u0, by forward-mode JAX; 0 for the
    excitation's scale factors."""
    import jax

    names = tuple(mass.parameters())
    u0 = lambda theta: mass.with_parameters(dict(zip(names, theta))).static_deflection
    gradient = np.asarray(jax.jacfwd(u0)(np.array([*mass.parameters().values()])))
    return np.concatenate([gradient, np.zeros(len(parameter_names(mass)) - len(names))])
