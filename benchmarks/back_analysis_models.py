"""What a back-analysis costs per design model (design.back_analysis with method="laplace"):
the rigid block (ky), the block on a plane (mu, bias_x -0.05 held), the flexible mass
decoupled (ky) and coupled (vs), H 10 m, vs 250 m/s, vr 800 m/s held, one displacement
seen at PGA 0.3 g with sigma_ln 0.05, on a decaying 1 Hz sine of --seconds (default 3 s,
the tests' record). Per model: a warm forward run of one parameter set [s], one dD/dp (the
first call, JAX compiling, and the median of --repeat warm ones) [s], the whole Laplace
back-analysis [s] and how many gradient calls it made.

    python benchmarks/back_analysis_models.py [--seconds S] [--repeat N] [--quick]

--quick (a smoke run, not a measurement): the rigid block and the plane on 1.5 s, no warm repeats.
"""

import argparse
import time
import warnings

import numpy as np

import blockdae as bd
from blockdae import design
from _common import G, SMOKE_RUN, print_table, timed

PGA = 0.3  # [g]
CASES = (("rigid, ky", design.Rigid(), {"ky": design.LogNormal(0.1, 0.3)}, "ky", 0.1),
         ("plane, mu", design.Planar(), {"mu": design.Truncated(design.LogNormal(0.2, 0.3), low=0.06),
                                         "bias_x": -0.05}, "mu", 0.2),
         ("flexible decoupled, ky", design.Flexible(method="decoupled"),
          {"ky": design.LogNormal(0.1, 0.3), "height": 10.0, "vs": 250.0, "vr": 800.0}, "ky", 0.1),
         ("flexible coupled, vs", design.Flexible(method="coupled"),
          {"ky": 0.1, "height": 10.0, "vs": design.LogNormal(250.0, 0.3), "vr": 800.0}, "vs", 250.0))


def counting(model):
    """``model``'s gradient wrapped to count its calls: (calls list, restore function)."""
    cls = type(model)
    calls, own, inherited = [], cls.gradient, "gradient" not in vars(cls)

    def gradient(self, *args, **kwargs):
        calls.append(1)
        return own(self, *args, **kwargs)

    cls.gradient = gradient
    return calls, lambda: delattr(cls, "gradient") if inherited else setattr(cls, "gradient", own)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=3.0, help="the record's duration [s]")
    parser.add_argument("--repeat", type=int, default=3, help="warm gradient calls timed per model")
    parser.add_argument("--quick", action="store_true", help="a smoke run: the rigid block and the plane, 1.5 s")
    args = parser.parse_args(argv)
    if args.quick:
        args.seconds, args.repeat = 1.5, 0
    warnings.simplefilter("ignore", bd.CompileNotice)
    t = np.arange(0, args.seconds, 0.01)
    record = bd.Record(0.3 * G * np.sin(2 * np.pi * t) * np.exp(-0.3 * t), 0.01, "decaying sine")
    print(f"record {record.name!r}: {record.duration:.2f} s, scaled to PGA {PGA} g")
    rows = []
    for label, model, priors, name, truth in CASES[:2] if args.quick else CASES:
        values = {k: v for k, v in priors.items() if k != name} | {name: np.array([truth])}
        d, _, forward = timed(lambda: model.displacements(record, PGA, values), args.repeat)
        _, first, warm = timed(lambda: model.gradient(record, PGA, values, (name,)), args.repeat)
        seen = design.Observation(record, sigma_ln=0.05, displacement_m=float(d[0]), pga_g=PGA)
        calls, restore = counting(model)
        start = time.perf_counter()
        result = design.back_analysis(seen, model, priors, method="laplace", draws=500)
        laplace = time.perf_counter() - start
        restore()
        rows.append([label, f"{float(d[0]):.4f}", f"{forward:.4f}", f"{first:.2f}", f"{warm:.2f}", f"{laplace:.1f}",
                     str(len(calls)), f"{result.map_value:.4g} {result.unit}"])
    print_table(["model, parameter", "D [m]", "forward [s]", "dD/dp first [s]", "dD/dp warm [s]", "Laplace [s]",
                 "gradient calls", "MAP"], rows)
    if args.quick:
        print(SMOKE_RUN)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
