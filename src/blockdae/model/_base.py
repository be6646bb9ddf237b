"""The contract a hybrid model gives to the driver and to the backends."""

import abc


class AbstractHybridModel(abc.ABC):
    """A hybrid automaton: continuous flows in discrete modes, guards, transitions.

    A model is pure physics. Backends integrate ``flow`` in one mode, locate the
    roots of ``guards`` and ask ``mode_after_guard`` which mode follows; none of them
    re-derives these rules. Every method works on NumPy and on JAX arrays: ``xp`` is
    the array namespace (``numpy`` or ``jax.numpy``).
    """

    #: names of the continuous states, in order
    state_names: tuple[str, ...]

    @abc.abstractmethod
    def flow(self, mode, t, y, excitation, xp):
        """dy/dt in ``mode`` at time ``t`` [s], for state ``y`` of shape (n,)."""

    @abc.abstractmethod
    def guards(self, mode, t, y, excitation, xp):
        """Guard functions of ``mode``, shape (n_guards,).

        Each is oriented so that the mode is left when it crosses zero downwards
        (direction -1); this fixes the direction at build time for every backend.
        """

    @abc.abstractmethod
    def mode_at_rest(self, t, excitation, xp):
        """The mode a block at rest relative to its base takes at ``t``."""

    @abc.abstractmethod
    def mode_after_guard(self, mode, guard_index, t, y, excitation, xp, time_tol=0.0):
        """The mode entered when guard ``guard_index`` of ``mode`` is reached; a
        threshold reached within ``time_tol`` [s] of ``t`` counts as reached at ``t``
        (0: within rounding; ODE backends pass the uncertainty of a located root)."""
