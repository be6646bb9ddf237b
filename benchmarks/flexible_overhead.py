"""One warm ``bd.flexible`` coupled call on Northridge PAC-175 (1,000 samples at dt =
0.02 s; H = 10 m, vs = vr = 300 m/s, damping 0.05, ky = 0.1 g, normal polarity) beside
pySLAMMER's ``Coupled`` on the same record, and what the call is made of: the compiled
engine alone (its arrays prepared once), the planning of the analyses and the rest
(Python).

The speed-up is measured alike on both sides, in interleaved rounds so that both share
the machine's load: both warmed first, each round times a burst of our calls (about a
few milliseconds, as long as a pySLAMMER call, so that the clock's own cost does not count) and one pySLAMMER call, in
alternating order, in CPU time of this process (``time.process_time``) and in wall time;
the speed-up is the median over rounds of pySLAMMER's time over ours per call, the bar's
figure. The parts, and pySLAMMER's call, are also timed as the least CPU time of several
bursts (the quiet figure on a shared machine; their ratio printed beside).
NUMBA_NUM_THREADS=1 (one core, as pySLAMMER).

    NUMBA_NUM_THREADS=1 python benchmarks/flexible_overhead.py [--quick]
"""

import argparse
import statistics
import time

import numpy as np
import pyslammer

import blockdae as bd
from blockdae.flexible_mass import _analysis, _fused
from _common import G, print_table, sample_records, verdict

BARS = {"coupled speed-up, one warm call, CPU time [x]": (300.0, True)}


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


def _burst(action, calls):
    """(CPU, wall) seconds of one call of ``action``, over a burst of ``calls`` calls."""
    cpu, wall = time.process_time(), time.perf_counter()
    for _ in range(calls):
        action()
    return (time.process_time() - cpu) / calls, (time.perf_counter() - wall) / calls


def paired_bursts(ours, peer, rounds, calls):
    """Medians over ``rounds`` interleaved rounds (alternating order; both warmed first)
    of ours' and peer's (CPU, wall) seconds per call and of the per-round ratios peer /
    ours: ((ours CPU, ours wall), (peer CPU, peer wall), (ratio CPU, ratio wall))."""
    ours(), peer()
    mine, theirs = [], []
    for index in range(rounds):
        pair = ((ours, calls, mine), (peer, 1, theirs))
        for action, count, times in pair[:: 1 if index % 2 == 0 else -1]:
            times.append(_burst(action, count))
    medians = lambda pairs: tuple(statistics.median(p[k] for p in pairs) for k in range(2))
    ratios = [(p[0] / o[0], p[1] / o[1]) for o, p in zip(mine, theirs)]
    return medians(mine), medians(theirs), medians(ratios)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="a smoke run: few calls, no measurement")
    args = parser.parse_args(argv)
    calls, bursts, rounds, burst_calls, peer_calls = (20, 2, 2, 5, 1) if args.quick else (500, 7, 41, 200, 3)
    record = next(r for r in sample_records() if r.name == "Northridge_1994_PAC-175")  # [m/s²]
    motion = pyslammer.GroundMotion(record.acceleration_samples / G, record.dt, record.name)
    ours = lambda: bd.flexible(record, ky=0.1, height=10.0, vs=300.0, method="coupled", polarity="normal")
    peer = lambda: pyslammer.Coupled(0.1, motion, 10.0, 300.0, 300.0, 0.05).max_sliding_disp
    plan = lambda: _analysis.plan(record, 0.1, 10.0, 300.0, None, 0.05, "coupled", False, None, None, "normal",
                                  "exact", G, None)
    arrays, offsets, tasks, _, _, _, _ = _analysis._prepared(plan())
    out, serial = np.empty((1, 3, _fused.WIDTH)), _fused.kernels()[1]
    (our_cpu, our_wall), (peer_cpu, peer_wall), (speedup, speedup_wall) = paired_bursts(ours, peer, rounds,
                                                                                        burst_calls)
    seconds = {"pySLAMMER Coupled": _cpu(peer, peer_calls, bursts),
               "bd.flexible, whole call": _cpu(ours, calls, bursts),
               "compiled engine alone": _cpu(lambda: serial(*arrays, offsets, tasks, out), calls, bursts),
               "planning (checks, models)": _cpu(plan, calls, bursts)}
    print(f"{record.name}: {record.acceleration_samples.size} samples, coupled, ky = 0.1 g, one polarity\n")
    print(f"{rounds} interleaved rounds (a burst of {burst_calls} of our calls, one pySLAMMER call), medians:")
    print_table(("", "CPU time [us]", "wall time [us]"),
                [("pySLAMMER Coupled", f"{peer_cpu * 1e6:.1f}", f"{peer_wall * 1e6:.1f}"),
                 ("bd.flexible", f"{our_cpu * 1e6:.2f}", f"{our_wall * 1e6:.2f}"),
                 ("speed-up [x]", f"{speedup:.0f}", f"{speedup_wall:.0f}")])
    whole = seconds["bd.flexible, whole call"]
    rows = [(name, f"{s * 1e6:.2f}") for name, s in seconds.items()]
    rows.append(("the rest (rows, checks, result; Python)",
                 f"{(whole - seconds['compiled engine alone'] - seconds['planning (checks, models)']) * 1e6:.2f}"))
    print(f"\nthe call's parts, the least CPU time of {bursts} bursts of {calls} calls ({peer_calls} of pySLAMMER's):")
    print_table(("what", "CPU time [us]"), rows)
    quiet = seconds["pySLAMMER Coupled"] / whole
    print(f"\ncoupled speed-up, one warm call: {speedup:.0f}x in CPU time ({speedup_wall:.0f}x in wall time); "
          f"least times: {quiet:.0f}x")
    bound, at_least = BARS["coupled speed-up, one warm call, CPU time [x]"]
    ok = speedup >= bound if at_least else speedup <= bound
    print(f"bar coupled speed-up (CPU time) >= {bound:g}x: {verdict(ok, args.quick)}")
    return 0 if ok or args.quick else 1


if __name__ == "__main__":
    raise SystemExit(main())
