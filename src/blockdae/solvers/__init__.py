"""Model-agnostic solvers: the integrators of the hybrid driver (CVODE, IDA, diffrax), the
compiled engine of linear modes, Runge-Kutta and Rosenbrock steps for compiled engines, and
the backends that run a model's own engine (``exact``, ``exact-jax``, ``jax``, ``compiled``).
No physics here: a model brings its rules through the contract and, where it has one, its
engine (its ``engines``). Its public function: :func:`simulate_linear_final`, the final numbers
of many linear-mode models (e.g. spring-supported masses) under many records in one compiled call."""

from ._linear_solution import simulate_linear_final

__all__ = ["simulate_linear_final"]

# what the other packages of blockdae use
from ._exact import Exact
from ._linear import (CHATTER, EVENT_RESOLUTION, FINISHED, LOG_FULL, MAX_EVENTS_AT_ONE_INSTANT, MAX_INTERVALS,
                      STACK_DEPTH, UNSETTLED, combine_forms, evaluate_form, evaluate_form_at, form_bound,
                      form_derivative, form_rounding, piece_form)
from ._linear_solution import linear_pieces
