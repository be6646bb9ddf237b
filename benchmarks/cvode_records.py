"""CVODE over pySLAMMER's 18 sample records at rtol 1e-10, against the exact backend.

Two-way sliding with f < mu and a bias (mu 0.15, f 0.12, R/Q 0.03), until rest.
Prints per record: events, u(t_end) [m], relative |du| and max |dt| [s] against the
exact backend, CVODE wall time [s] of a warm call; then the total CVODE wall time (bar: <= 10 s).
Needs the test extra (pyslammer) for the records.

    python benchmarks/cvode_records.py [backend]      # backend: cvode (default) or ida
"""

import sys

import blockdae as bd
from _common import sample_records

BLOCK = bd.SlidingBlock(mu=0.15, mu_kinetic=0.12, bias=0.03)
RTOL = 1e-10


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


if __name__ == "__main__":
    main(*sys.argv[1:])
