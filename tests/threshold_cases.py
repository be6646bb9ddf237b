"""Cases built to sit on thresholds (issue 28), shared by the adversarial cross-checks.

Each case is a block, an excitation and an end time where the demand touches or
barely crosses a threshold: mu g = A exactly and A one to a few ulps either side, bias
on both sides, f = mu, touches at the start and the end of a record, at a sample and
between samples (the peak of a sine piece), harmonic and pulse excitations. The exact
backend's answer is the reference for the 1-D block (its onsets are decided in
closed form on monotone pieces); the planar backends are checked against each other
and, under x-only motion, against the exact 1-D block.
"""

import dataclasses

import numpy as np

import blockdae as bd

G = 9.81  # mu g and A are not exact in binary: rounding must still agree
MU = 0.5


def ulps(x, k):
    """``x`` moved by ``k`` ulps (k < 0: down)."""
    for _ in range(abs(k)):
        x = np.nextafter(x, np.inf if k > 0 else -np.inf)
    return float(x)


@dataclasses.dataclass(frozen=True)
class Case:
    name: str
    block: object
    motion: object
    t_end: float
    fast: bool = False  # in the CI subset

    def __str__(self):
        return self.name


def _harmonics():
    limit = MU * G
    for k in (0, 1, -1, 4, -4):
        yield Case(f"harmonic A=mu g{k:+d}ulp", bd.SlidingBlock(mu=MU, g=G), bd.Harmonic(ulps(limit, k), 1.0), 3.0,
                   fast=k in (0, 1))
    for direction in ("negative", "positive"):
        yield Case(f"harmonic A=mu g one-way {direction}", bd.SlidingBlock(mu=MU, g=G, direction=direction),
                   bd.Harmonic(limit, 1.0), 3.0)
    for bias in (0.1, -0.1):  # a touch on one side, a real slide on the other
        yield Case(f"harmonic touch one side bias={bias:+}", bd.SlidingBlock(mu=MU - abs(bias), bias=bias, g=G),
                   bd.Harmonic(limit, 1.0), 3.0, fast=bias > 0)
    yield Case("harmonic f=mu A=mu g+1ulp", bd.SlidingBlock(mu=MU, mu_kinetic=MU, g=G),
               bd.Harmonic(ulps(limit, 1), 1.0), 3.0)
    yield Case("harmonic f=mu above", bd.SlidingBlock(mu=MU, mu_kinetic=MU, g=G), bd.Harmonic(1.3 * limit, 1.0), 3.0,
               fast=True)
    yield Case("harmonic period 0.3 s A=mu g", bd.SlidingBlock(mu=MU, g=G), bd.Harmonic(limit, 0.3), 2.0)


def _pulses():
    limit = MU * G
    for cls in (bd.RectangularPulse, bd.TriangularPulse, bd.SinePulse):
        for k in (0, 1):
            yield Case(f"{cls.__name__} A=mu g{k:+d}ulp", bd.SlidingBlock(mu=MU, g=G), cls(ulps(limit, k), 0.5), 1.5,
                       fast=cls is bd.SinePulse and k == 0)


def _records():
    limit, dt = MU * G, 0.01
    samples = {  # a(t) samples [m/s²]
        "touch at a sample": [0.0, 0.5 * limit, limit, 0.5 * limit, 0.0, -1.2 * limit, 0.0],
        "touch at the start, falling": [limit, 0.5 * limit, 0.0, -1.2 * limit, 0.0],
        "at the threshold at the start, rising": [limit, 1.5 * limit, 0.0, 0.0],
        "touch at the end": [0.0, 0.5 * limit, -1.2 * limit, 0.0, limit],
        "flat top at the threshold": [0.0, limit, limit, limit, 0.0, -limit, -limit, 0.0],
        "one ulp over at a sample": [0.0, ulps(limit, 1), 0.0, -ulps(limit, 1), 0.0],
    }
    for name, a in samples.items():
        yield Case(f"record {name}", bd.SlidingBlock(mu=MU, g=G), bd.Record(a, dt, units="m/s2"), (len(a) - 1) * dt,
                   fast=name.startswith(("touch at a sample", "touch at the start")))
    yield Case("record touch with bias", bd.SlidingBlock(mu=0.4, bias=0.1, g=G),
               bd.Record([0.0, limit, 0.0, -limit, 0.0], dt, units="m/s2"), 0.04)


def sliding_cases():
    """The 1-D block's threshold cases."""
    return [*_harmonics(), *_pulses(), *_records()]


def planar_cases():
    """The planar block's threshold cases: (case, x-only twin for the exact 1-D block or None)."""
    limit = MU * G
    block = bd.PlanarBlock(mu=MU, g=G)
    x = bd.Harmonic(limit, 1.0)
    yield Case("planar x-only A=mu g", block, x, 3.0, fast=True), bd.SlidingBlock(mu=MU, g=G)
    yield Case("planar x-only A=mu g+1ulp", block, bd.Harmonic(ulps(limit, 1), 1.0), 3.0), bd.SlidingBlock(mu=MU, g=G)
    # the vertical brings n = g + a_z to exactly 0 at its troughs: a touch, no flight
    vertical = bd.Harmonic(-G, 1.0)
    yield Case("planar n touches 0", block, bd.BaseMotion(bd.Harmonic(0.0, 1.0), z=vertical), 2.0, fast=True), None
    yield Case("planar n touches 0 under x", block, bd.BaseMotion(bd.Harmonic(0.2 * G, 0.7), z=vertical), 2.0), None
