"""Upthrow (seed 004): every backend that runs a SpringSupportedMass against the exact one.

Cases: a 10 Hz, 5 % mass under three cycles of a 0.5 g, 0.13 s sine; an undamped 5 Hz mass
under a constant y'' = -0.55 g for 3.5 s (17 equal bounces); the 18 pySLAMMER sample
records as vertical motion scaled to a peak of 0.6 g, 5 and 10 Hz, 5 %, the first 15 s,
where the linear response exceeds g (A > 1; 22 cases, 19 of which fly). Per backend and case, at rtol 1e-10: the largest event-time
difference from exact [s] (inf where the event lists differ), the largest difference of the
liftoff/landing speeds relative to the largest of them [-], and the wall time of a warm run
[s] (median of --repeat; "jax" compiles on its first call, which is not counted). Each
backend's worst case is printed against its bars (``BARS``): the solvers' bar of 1e-9 s and
1e-7 for CVODE; for IDA a decade above its worst, the undamped bouncing (3.6e-8 s and
2.5e-7: its BDF steps are dissipative, and undamped bouncing never forgets an energy error;
on the records 2.2e-9 s and 9.1e-8; docs/verification.md); for JAX a decade above its
measured 2.1e-13 s and 3.6e-12. The script exits with 1 where a bar is not met.

    python benchmarks/upthrow.py [--quick] [--repeat N]
"""

import argparse

import numpy as np

import blockdae as bd
from _common import G, print_table, sample_records, timed, verdict

BACKENDS = ("cvode", "ida", "jax")
RTOL = 1e-10
#: backend -> (bar on event times [s], on the liftoff and landing speeds, relative [-])
BARS = {"cvode": (1e-9, 1e-7), "ida": (3.6e-7, 2.5e-6), "jax": (2.1e-12, 3.6e-11)}
RECORD_PEAK, RECORD_WINDOW = 0.6 * G, 15.0  # [m/s²], [s]
QUICK_RECORDS, QUICK_WINDOW = ("Kobe_1995_TAK-090",), 8.0  # [s]


def cases(quick=False):
    """(label, mass, motion, t_end [s]) of every comparison."""
    train = bd.Harmonic(0.5 * G, 0.13, cycles=3)
    out = [("sine train, 10 Hz 5 %", bd.SpringSupportedMass(10.0, 0.05), train, train.duration),
           ("y'' = -0.55 g, 5 Hz 0 %", bd.SpringSupportedMass(5.0), bd.Record(np.full(8, -0.55 * G), dt=0.5), 3.5)]
    for record in sample_records():
        if quick and record.name not in QUICK_RECORDS:
            continue
        motion = record.scaled(RECORD_PEAK / record.peak_acceleration)
        t_end = min(record.duration, QUICK_WINDOW if quick else RECORD_WINDOW)
        for frequency in (5.0,) if quick else (5.0, 10.0):
            mass = bd.SpringSupportedMass(frequency, 0.05)
            if bd.upthrow.upthrow_estimate(mass, motion, t_end=t_end).lifts_off:
                out.append((f"{record.name}, {frequency:g} Hz 5 %", mass, motion, t_end))
    return out


def differences(solution, exact):
    """(largest event-time difference [s], largest liftoff/landing speed difference relative
    to the largest such speed [-]); (inf, inf) if the event lists differ."""
    if [e.kind for e in solution.events] != [e.kind for e in exact.events]:
        return np.inf, np.inf
    dt = float(np.max(np.abs(solution.t_events - exact.t_events), initial=0.0))
    pairs = np.array([(e.u_rate, r.u_rate) for e, r in zip(solution.events, exact.events)
                      if r.kind in ("liftoff", "landing")]).reshape(-1, 2)
    scale = np.max(np.abs(pairs[:, 1]), initial=0.0)
    speed = float(np.max(np.abs(pairs[:, 0] - pairs[:, 1]), initial=0.0) / scale) if scale > 0 else 0.0
    return dt, speed


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help=f"the two synthetic cases and the first {QUICK_WINDOW:g} s of "
                             f"{', '.join(QUICK_RECORDS)} at 5 Hz (smoke run)")
    parser.add_argument("--repeat", type=int, default=1, help="warm repetitions (median) per timing")
    args = parser.parse_args(argv)
    bd.simulate(bd.SpringSupportedMass(10.0), bd.Harmonic(0.5 * G, 0.13, cycles=1), t_end=0.13, backend="jax")
    rows, found = [], {name: [] for name in BACKENDS}  # backend -> [(dt, speed, label)]
    for label, mass, motion, t_end in cases(args.quick):
        exact, _, exact_time = timed(lambda: bd.simulate(mass, motion, t_end=t_end), args.repeat)
        row = [label, str(len(exact.events)), f"{exact_time:.3f}"]
        for name in BACKENDS:
            solution, _, wall = timed(lambda: bd.simulate(mass, motion, t_end=t_end, backend=name, rtol=RTOL),
                                      args.repeat)
            dt, speed = differences(solution, exact)
            row += [f"{dt:.1e}", f"{speed:.1e}", f"{wall:.3f}"]
            found[name].append((dt, speed, label))
        rows.append(tuple(row))
    headers = ["case", "events", "exact [s]"]
    for name in BACKENDS:
        headers += [f"{name} max|dt| [s]", f"{name} speeds [-]", f"{name} [s]"]
    print(f"rtol {RTOL:g}; differences against the exact backend; warm wall times\n")
    print_table(headers, rows)
    print()
    failed = 0
    for name, results in found.items():
        dt, _, label = max(results)
        speed = max(r[1] for r in results)
        bar_dt, bar_speed = BARS[name]
        over = [r[2] for r in results if r[0] > bar_dt or r[1] > bar_speed]
        failed += bool(over)
        print(f"{name}: worst event time {dt:.1e} s ({label}), worst speed {speed:.1e}; bar {bar_dt:g} s and "
              f"{bar_speed:g}: " + verdict(not over, args.quick, f"NOT met in {len(over)} of {len(results)} cases"))
    return 1 if failed and not args.quick else 0


if __name__ == "__main__":
    raise SystemExit(main())
