"""The diffrax solvers the JAX twins take by name (importing this module loads diffrax and JAX)."""

import diffrax

#: solver name -> diffrax solver class: explicit Runge-Kutta pairs and one implicit method
SOLVERS = {"tsit5": diffrax.Tsit5, "dopri5": diffrax.Dopri5, "dopri8": diffrax.Dopri8, "kvaerno5": diffrax.Kvaerno5}
