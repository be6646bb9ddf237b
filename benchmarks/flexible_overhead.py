"""One warm ``bd.flexible`` coupled call on Northridge PAC-175 (1,000 samples; H = 10 m,
vs = vr = 300 m/s, damping 0.05, ky = 0.1 g, normal polarity) beside pySLAMMER's
``Coupled`` on the same record, and what the call is made of: the compiled engine alone
(its arrays prepared once), the planning of the analyses and the rest (Python). Times are
CPU seconds of this process (``time.process_time``), the least of several bursts, so that
a machine shared with other work still gives the quiet figure; NUMBA_NUM_THREADS=1.

    NUMBA_NUM_THREADS=1 python benchmarks/flexible_overhead.py [--quick]
"""

import argparse
import time

import numpy as np
import pyslammer

import blockdae as bd
from blockdae.flexible_mass import _analysis, _fused
from _common import G, print_table, sample_records, verdict

BARS = {"coupled speed-up, one warm call [x]": (300.0, True)}


def _cpu(action, calls, bursts):
    """The least CPU time of one call [s] over ``bursts`` bursts of ``calls`` calls."""
    action()
    best = []
    for _ in range(bursts):
        start = time.process_time()
        for _ in range(calls):
            action()
        best.append((time.process_time() - start) / calls)
    return min(best)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="a smoke run: few calls, no measurement")
    args = parser.parse_args(argv)
    calls, bursts, peer_calls = (20, 2, 1) if args.quick else (500, 7, 3)
    record = next(r for r in sample_records() if r.name == "Northridge_1994_PAC-175")  # [m/s²]
    motion = pyslammer.GroundMotion(record.acceleration_samples / G, record.dt, record.name)
    ours = lambda: bd.flexible(record, ky=0.1, height=10.0, vs=300.0, method="coupled", polarity="normal")
    peer = lambda: pyslammer.Coupled(0.1, motion, 10.0, 300.0, 300.0, 0.05).max_sliding_disp
    plan = lambda: _analysis.plan(record, 0.1, 10.0, 300.0, None, 0.05, "coupled", False, None, None, "normal",
                                  "exact", G, None)
    analysis = plan()[0]
    arrays = _analysis._engine_input(analysis.record, analysis.t_end)
    (omega, xi, kyg, coupled), _ = _analysis._final_columns([analysis], [arrays], [0])[0]
    tasks = np.array([(0, omega, xi, kyg, coupled, True, False, False, True)], dtype=float)
    out, offsets, serial = np.empty((1, 3, _fused.WIDTH)), _analysis._offsets(len(arrays[0])), _fused.kernels()[1]
    seconds = {"pySLAMMER Coupled": _cpu(peer, peer_calls, bursts), "bd.flexible, whole call": _cpu(ours, calls, bursts),
               "compiled engine alone": _cpu(lambda: serial(*arrays, offsets, tasks, out), calls, bursts),
               "planning (checks, models)": _cpu(plan, calls, bursts)}
    whole = seconds["bd.flexible, whole call"]
    rows = [(name, f"{s * 1e6:.1f}") for name, s in seconds.items()]
    rows.append(("the rest (rows, result; Python)",
                 f"{(whole - seconds['compiled engine alone'] - seconds['planning (checks, models)']) * 1e6:.1f}"))
    print(f"{record.name}: {record.acceleration_samples.size} samples, coupled, ky = 0.1 g\n")
    print_table(("part", "CPU time [us]"), rows)
    speedup = seconds["pySLAMMER Coupled"] / whole
    print(f"\ncoupled speed-up, one warm call: {speedup:.0f}x")
    bound, at_least = BARS["coupled speed-up, one warm call [x]"]
    ok = speedup >= bound if at_least else speedup <= bound
    print(f"bar coupled speed-up >= {bound:g}x: {verdict(ok, args.quick)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
