"""Model-agnostic solvers: the integrators of the hybrid driver (CVODE, IDA, diffrax), the
compiled engine of linear modes, Runge-Kutta and Rosenbrock steps for compiled engines, and
the backends that run a model's own engine (``exact``, ``exact-jax``, ``jax``, ``compiled``).
No physics here: a model brings its rules through the contract and, where it has one, its
engine (its ``engines``)."""
