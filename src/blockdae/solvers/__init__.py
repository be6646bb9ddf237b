"""Model-agnostic solvers: the integrators of the hybrid driver (CVODE, IDA, diffrax), the
compiled engine of linear modes, Runge-Kutta and Rosenbrock steps for compiled engines, and
the backends that run a model's own engine (``exact``, ``exact-jax``, ``jax``, ``compiled``).
No physics here: a model brings its rules through the contract and, where it has one, its
engine (its ``engines``)."""

# what the other packages of blockdae use
from ._diffrax import SOLVERS
from ._linear import CHATTER, FINISHED, MAX_INTERVALS, UNSETTLED
from ._linear_solution import linear_pieces, simulate_linear_final
