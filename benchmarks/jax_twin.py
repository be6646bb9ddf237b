"""JAX twin vs exact backend on pySLAMMER's 18 sample records: agreement and speed.

Run: ``python benchmarks/jax_twin.py`` (needs the test extra, pyslammer). For each
record and two blocks (f = mu two-way; f < mu with a bias) it prints the relative
difference in u(t_end), the largest difference in event times [s], the wall time of
one run after compilation [s], and the largest relative difference between the two
backends' sensitivities d u / d (mu, mu_kinetic, bias, A). The bars, a decade above the
worst measured (1.2e-14 relative in u, 3.6e-15 s; docs/verification.md): the script exits
with 1 where one is not met.
"""

import sys

import numpy as np

import blockdae as bd
from _common import sample_records, timed

BAR_DU, BAR_DT = 1.2e-13, 3.6e-14  # relative [-], event times [s]


def main():
    print(f"{'record':<32} {'n':>6} {'block':<16} {'u [m]':>10} {'rel du':>8} {'max dt_ev [s]':>13} "
          f"{'exact [s]':>9} {'jax [s]':>8} {'rel dsens':>9}")
    worst = {"du": 0.0, "dt": 0.0, "sens": 0.0}
    for record in sample_records():
        A = record.peak_acceleration / bd.STANDARD_GRAVITY
        for label, block in [("f=mu", bd.SlidingBlock(0.3 * A)),
                             ("f<mu, bias", bd.SlidingBlock(0.5 * A, 0.35 * A, bias=0.1 * A))]:
            exact, _, t_exact = timed(lambda: bd.simulate(block, record), 1)
            twin, _, t_twin = timed(lambda: bd.simulate(block, record, backend="jax"), 1)
            du = abs(twin.displacement / exact.displacement - 1)
            same = len(exact.events) == len(twin.events)
            dt = np.max(np.abs(exact.t_events - twin.t_events), initial=0.0) if same else np.inf
            s_exact = bd.sensitivities(block, record)
            s_twin = bd.sensitivities(block, record, backend="jax")
            ds = max(abs(s_twin[k] / s_exact[k] - 1) for k in s_exact if s_exact[k] != 0)
            worst = {"du": max(worst["du"], du), "dt": max(worst["dt"], dt), "sens": max(worst["sens"], ds)}
            print(f"{record.name[:32]:<32} {record.acceleration_samples.size:>6} {label:<16} "
                  f"{exact.displacement:>10.5f} {du:>8.1e} {dt:>13.1e} {t_exact:>9.3f} {t_twin:>8.3f} {ds:>9.1e}",
                  flush=True)
    print(f"worst: rel du = {worst['du']:.1e}, event times {worst['dt']:.1e} s, "
          f"rel sensitivities {worst['sens']:.1e}")
    met = worst["du"] <= BAR_DU and worst["dt"] <= BAR_DT
    print(f"bars: rel du <= {BAR_DU:g}, event times <= {BAR_DT:g} s: {'met' if met else 'NOT met'}")
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
