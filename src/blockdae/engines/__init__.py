"""Compiled and closed-form engines, and the backends that run them: the 1-D block's
kernels (numba: "exact"; JAX: "exact-jax" and the twin's), closed-form steps of linear
modes on the driver. A model picks an engine by name (its ``engines``)."""
