"""What a model's own derivative method builds on (its package overrides
:meth:`~blockdae.core.contract.DifferentiableModel.sensitivities` from these): the
located trajectory's sensitivities, the names it is differentiated by, central
differences, the JAX context and :func:`simulate` (for differences). JAX loads on the
first call that needs it, not on import."""

from ._jax_config import jax_context
from .contract import parameter_names
from ._sensitivities import (by_parameter, checked_wrt, derivative_unit, largest_peak, parameter_differences,
                             step_difference, trajectory_displacement_sensitivities,
                             trajectory_quantity_sensitivities)
from ._sensitivity_result import Sensitivities
from ._simulate import simulate


def trajectory_sensitivities(model, motion, horizon, backend):
    """The trajectory the JAX twin ``backend`` locates and its derivatives by the names
    of :func:`parameter_names`: (solution, dy(t_end)/dp of shape (n_y, n_p), one
    ``EventSensitivity`` per event: t, dt_dp (n_p,), dy_dp_before and dy_dp_after
    (n_y, n_p), the located state's total derivatives before and after the event's maps)."""
    return backend.trajectory_sensitivities(model, motion, horizon)


__all__ = ["Sensitivities", "by_parameter", "checked_wrt", "derivative_unit", "jax_context", "largest_peak",
           "parameter_differences", "parameter_names", "simulate", "step_difference",
           "trajectory_displacement_sensitivities", "trajectory_quantity_sensitivities", "trajectory_sensitivities"]
