"""CVODE over pySLAMMER's 18 sample records at rtol 1e-10, against the exact backend.

Two-way sliding with f < mu and a bias (mu 0.15, f 0.12, R/Q 0.03), until rest.
Prints per record: events, u(t_end) [m], relative |du| and max |dt| [s] against the
exact backend, CVODE wall time [s] of a warm call; then the total wall time and the worst
differences. The bars, a decade above the worst measured (docs/verification.md): CVODE
rel |du| <= 1e-8 and |dt| <= 4.8e-11 s (measured 9.3e-10, 5.1e-12 s), IDA 2.1e-7 and
7.5e-10 s (measured 2.1e-8, 7.5e-11 s); the script exits with 1 where one is not met.
Needs the test extra (pyslammer) for the records.

    python benchmarks/cvode_records.py [backend]      # backend: cvode (default) or ida
"""

import sys

import blockdae as bd
from _common import sample_records

BLOCK = bd.SlidingBlock(mu=0.15, mu_kinetic=0.12, bias=0.03)
RTOL = 1e-10
#: backend -> (bar on the worst relative |du| [-], on the worst |dt| [s])
BARS = {"cvode": (1e-8, 4.8e-11), "ida": (2.1e-7, 7.5e-10)}


def main(backend="cvode"):
    records = sample_records()
    print(f"{backend} vs exact, rtol = {RTOL:g}, mu = {BLOCK.mu}, f = {BLOCK.friction_kinetic}, "
          f"R/Q = {BLOCK.bias}, until rest")
    head = (f"{'record':<34} {'samples':>7} {'events':>6} {'u_end [m]':>12} {'rel |du| [-]':>12} "
            f"{'max |dt| [s]':>12} {'warm [s]':>8}")
    print(head)
    print("-" * len(head))
    total, worst_dt, worst_du = 0.0, 0.0, 0.0
    for record in records:
        table = bd.crosscheck(BLOCK, record, backends=("exact", backend), rtol=RTOL)
        row = table.row(backend)
        total += row["warm"]
        worst_dt, worst_du = max(worst_dt, row["max_dt"]), max(worst_du, row["rel_du"])
        print(f"{record.name:<34} {record.acceleration_samples.size:>7d} {row['n_events']:>6d} "
              f"{row['displacement']:>12.6f} {row['rel_du']:>12.2e} {row['max_dt']:>12.2e} {row['warm']:>8.3f}")
    print("-" * len(head))
    print(f"{backend} total wall time: {total:.2f} s over {len(records)} records "
          f"(worst max |dt| {worst_dt:.2e} s, worst rel |du| {worst_du:.2e})")
    bar_du, bar_dt = BARS[backend]
    met = worst_du <= bar_du and worst_dt <= bar_dt
    print(f"bars: rel |du| <= {bar_du:g}, max |dt| <= {bar_dt:g} s: {'met' if met else 'NOT met'}")
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
