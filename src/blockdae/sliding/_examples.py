"""The worked examples of Sawicki & Chybicki 2005 in one place, for the CLI, tests, notebooks and benchmarks.

The paper's values are transcribed as printed (rounded to its digits), so that our
exact answers can be shown beside them.
"""

import dataclasses

from ..excitation import AbstractExcitation, Harmonic, RectangularPulse, SinePulse, TriangularPulse
from ._model import SlidingBlock

#: gravitational acceleration the paper uses [m/s²]
SEED_G = 9.81


@dataclasses.dataclass(frozen=True)
class SeedExample:
    """One example of Sawicki & Chybicki 2005.

    Attributes:
        name: "Example 1", ..., "Example 6" ("Example 3a"/"3b" for its two frictions).
        description: the setting in words, with units.
        block: the block.
        motion: the base excitation.
        t_end: final time [s]; None runs until the block rests after a pulse.
        paper_event_times: event times the paper prints [s], in order (may be fewer
            than ours, e.g. only the first cycle); empty if it gives none.
        paper_displacement: the permanent relative displacement the paper prints [m],
            or None.
        note: how the paper's numbers relate to the exact ones, if worth saying.
    """

    name: str
    description: str
    block: SlidingBlock
    motion: AbstractExcitation
    t_end: float | None
    paper_event_times: tuple[float, ...] = ()
    paper_displacement: float | None = None
    note: str = ""


def example_solution(example: SeedExample):
    """The :class:`~blockdae.sliding.Solution` of ``example`` on the exact engine, as
    ``bd.simulate(example.block, example.motion, t_end=example.t_end)`` gives it, with the
    engine's source run by the Python interpreter: the same numbers in milliseconds (each
    example has at most five pieces), where compiling the engine takes seconds on its first
    run after an install."""
    from ..core import simulate
    from ._exact import Uncompiled

    return simulate(example.block, example.motion, t_end=example.t_end, backend=Uncompiled())


def rectangular_pulse_displacement(amplitude, duration, mu, g=SEED_G):
    """Relative displacement after a rectangular pulse, Sawicki & Chybicki 2005 Eq. 14 [m].

    u = (A g t0² / 2) (1 - A / mu) with the non-dimensional pulse A = amplitude / g;
    Newmark (1965, Eq. 23) prints the same magnitude with the opposite sign.

    Args:
        amplitude: pulse acceleration [m/s²], above mu g.
        duration: pulse length t0 [s].
        mu: friction coefficient [-].
        g: gravitational acceleration [m/s²].
    """
    a = amplitude / g
    return a * g * duration**2 / 2 * (1 - a / mu)


def seed_examples() -> tuple[SeedExample, ...]:
    """Examples 1-6 of Sawicki & Chybicki 2005 (A = 9 or 7 m/s², T = 1 s, pulses t0 = 0.5 s, g = 9.81 m/s²)."""
    harmonic, harmonic_7 = Harmonic(amplitude=9.0, period=1.0), Harmonic(amplitude=7.0, period=1.0)
    pulse = dict(amplitude=9.0, duration=0.5)
    block = SlidingBlock(mu=0.6, g=SEED_G)
    return (
        SeedExample(
            "Example 1", "harmonic A = 9 m/s², T = 1 s; mu = f = 0.6", block, harmonic, 2.0,
            paper_event_times=(0.1125, 0.535, 0.614, 1.035),
            note="the paper's text gives t* = 0.1125 s (its Table 1: 0.113 s); exact "
                 "t* = arcsin(mu g / A) T / (2 pi) = 0.113455 s"),
        SeedExample(
            "Example 2", "harmonic A = 9 m/s², T = 1 s; mu = 0.6, f = 0.3",
            block.replace(mu_kinetic=0.3), harmonic, 2.0),
        SeedExample(
            "Example 3a", "harmonic A = 7 m/s², T = 1 s; R/Q = 0.3, mu = f = 0.6",
            block.replace(bias=0.3), harmonic_7, 2.0),
        SeedExample(
            "Example 3b", "harmonic A = 7 m/s², T = 1 s; R/Q = 0.3, mu = 0.6, f = 0.4",
            block.replace(bias=0.3, mu_kinetic=0.4), harmonic_7, 2.0),
        SeedExample(
            "Example 4", "rectangular pulse A = 9 m/s², t0 = 0.5 s; mu = 0.6", block,
            RectangularPulse(**pulse), None, paper_displacement=-0.595,
            note=f"Eq. 14 gives {rectangular_pulse_displacement(9.0, 0.5, 0.6):.4f} m; "
                 "Newmark (1965) prints the opposite sign"),
        SeedExample(
            "Example 5", "triangular pulse A = 9 m/s², t0 = 0.5 s; mu = 0.6", block,
            TriangularPulse(**pulse), None, paper_event_times=(0.1635, 0.4588),
            paper_displacement=-0.0453),
        SeedExample(
            "Example 6", "sine pulse A = 9 m/s², t0 = 0.5 s; mu = 0.6", block,
            SinePulse(**pulse), None, paper_event_times=(0.1135, 0.541),
            paper_displacement=-0.1332),
    )
