"""The complete free-standing block's derivatives on the JAX twin against finite differences.

b = 0.25 m, h = 1.0 m, mu_s = 0.3, mu_k = 0.28 under one-sine pulses: "overturn" (0.5 g,
0.6 s, to 4 s: the pivot slips and sticks, the block strikes, slips again and overturns)
and "rocks" (0.6 g, 0.4 s, to 1.5 s: the pivot slips and sticks, two impacts, the largest
rotation after the first). d(max |theta| / alpha), d(slip at t_end) and d(overturning
time) by b, h, mu, mu_kinetic and A (``bd.sensitivities(..., of=...)``) against central
differences of CVODE runs at rtol 1e-12 extrapolated from the relative steps 1e-4, 2e-4,
4e-4 (Richardson; "estimate": the extrapolation's own error, from the steps twice as
large). tests/test_free_standing_derivatives.py sets its bar at 3e-8 from this table.

    python benchmarks/free_standing_derivatives.py
"""

import time

import numpy as np

import blockdae as bd
from _common import G, print_table
from blockdae.rocking import FreeStandingBlock, pulse

OF = ("max_theta_over_alpha", "slip", "overturn_time")
WRT = ("b", "h", "mu", "mu_kinetic", "A")


def quantities(block, motion, t_end):
    sol = bd.simulate(block, motion, t_end=t_end, backend="cvode", rtol=1e-12, atol=1e-14)
    return np.array([sol.max_theta_over_alpha, sol.final_slip, sol.overturn_time])


def central(block, motion, t_end, name, step):
    if name == "A":
        up, down = (quantities(block, motion.scaled(1 + s * step), t_end) for s in (1, -1))
        return (up - down) / (2 * step * motion.peak_acceleration / G)
    value = block.parameters()[name]
    up, down = (quantities(block.replace(**{name: value * (1 + s * step)}), motion, t_end) for s in (1, -1))
    return (up - down) / (2 * step * value)


def richardson(block, motion, t_end, name, step=1e-4):
    d1, d2, d4 = (central(block, motion, t_end, name, k * step) for k in (1, 2, 4))
    fine, coarse = (4 * d1 - d2) / 3, (4 * d2 - d4) / 3
    return fine, np.abs(fine - coarse)


def main():
    rows, worst = [], 0.0
    block = FreeStandingBlock(b=0.25, h=1.0, mu=0.3, mu_kinetic=0.28)
    for label, motion, t_end, of in [("overturn", pulse("sine", 0.5 * G, 0.6), 4.0, OF[1:]),
                                     ("rocks", pulse("sine", 0.6 * G, 0.4), 1.5, OF[:2])]:
        start = time.perf_counter()
        found = bd.sensitivities(block, motion, t_end=t_end, wrt=WRT, of=of)
        wall = time.perf_counter() - start
        for name in WRT:
            reference, estimate = richardson(block, motion, t_end, name)
            for quantity in of:
                k = OF.index(quantity)
                rel = abs(found.of(quantity)[name] - reference[k]) / abs(reference[k])
                worst = max(worst, rel)
                rows.append((label, quantity, name, f"{found.of(quantity)[name]:+.10e}", f"{reference[k]:+.10e}",
                             f"{rel:.1e}", f"{estimate[k] / abs(reference[k]):.1e}", f"{wall:.1f}"))
    print_table(("run", "quantity", "by", "twin", "differences", "relative difference [-]", "estimate [-]",
                 "twin wall [s]"), rows)
    print(f"largest relative difference: {worst:.1e}")


if __name__ == "__main__":
    main()
