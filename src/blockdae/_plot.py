"""``bd.plot``: the figure of any solution (each solution draws itself: ``figure``), of a
response spectrum or of a two-point relative motion; matplotlib on demand."""

from .motions import RelativeMotion, ResponseSpectrum, plot_relative_motion, plot_spectrum


def plot(solution, excitation=None, block=None, *, n_points: int = 2000, title: str | None = None):
    """Draw a solution: absolute and relative motion, and the phase plane.

    A :class:`ResponseSpectrum` is drawn as PSa [m/s²] against the period (log-log; see
    :func:`blockdae.motions.plot_spectrum` for the other quantities), a
    :class:`RelativeMotion` as R(tau) with Christian's (1973) estimates. A
    :class:`BatchSolution` is drawn as u(t_end) and max |u| [m] against the one
    parameter that varies across its grid (mu_kinetic counts only when the grid sets
    it), or against the parameter-set index when none or several vary (the x label
    then names those that vary). A :class:`PlanarSolution` is drawn as the path
    (u_x, u_y) [m] of the block relative to the base, u_x and u_y [m] and the relative
    speed |v| [m/s] against time, events marked (``excitation`` and ``block`` unused);
    an :class:`UpthrowSolution` as its flight history (ground and mass, gap, support
    force; liftoffs and landings marked); any other model's :class:`DriverSolution` as
    its states against time.

    Left column (only with ``excitation``): base (solid) and block (dashed)
    acceleration [m/s²], velocity [m/s] and displacement [m]; the block's
    acceleration needs ``block`` (its flow gives it). Right column: relative
    velocity v [m/s], relative displacement u [m] and the phase plane (u, v).
    Located events are marked with circles on every panel.

    Args:
        solution: a single run, or a batch (``excitation``, ``block``, ``n_points``
            are then unused).
        excitation: the base motion the solution was computed for.
        block: the block, for the block-acceleration curve.
        n_points: samples of the time grid; the solution's knots are added to it.
        title: figure title.

    Returns:
        The matplotlib Figure.
    """
    if isinstance(solution, ResponseSpectrum):
        return plot_spectrum(solution, title=title)
    if isinstance(solution, RelativeMotion):
        return plot_relative_motion(solution, title=title)
    figure = getattr(solution, "figure", None)
    if figure is None:
        raise TypeError("solution must be a Solution, BatchSolution, PlanarSolution, UpthrowSolution, "
                        f"DriverSolution, ResponseSpectrum or RelativeMotion, got {type(solution).__name__}")
    return figure(excitation, block, n_points=n_points, title=title)
