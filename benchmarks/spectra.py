"""Exact response spectra against eqsig and pyrotd on pySLAMMER's 18 sample records.

200 periods from 0.01 to 10 s, 5 % damping, PSa = ω² Sd. blockdae's spectra are exact for
the piecewise-linear records (maxima located between samples); the table gives each
library's relative difference from them by period band, and the speed ratios: every
library imported before any timing and warmed by one call, then each timed alike (the
median of --repeat calls over all the records). The bar: at least 10 times eqsig at its
accurate setting (dt/4); the script exits with 1 where it is not met.

  * eqsig (sample grid): ``eqsig.sdof.pseudo_response_spectra`` at the record's dt
    (Nigam-Jennings at the samples; Sa := PGA below 6 dt);
  * eqsig (dt/4): ``AccSignal.gen_response_spectrum``, which interpolates to dt/4 first;
  * pyrotd: ``calc_spec_accels`` (frequency domain, single process).

    python benchmarks/spectra.py [--quick] [--threads N]
"""

import argparse
import sys

import eqsig
import eqsig.sdof
import numpy as np
import pyrotd

import blockdae as bd
from _common import print_table, sample_records, timed, verdict

BAR_SPEEDUP = 10.0  # vs eqsig at its accurate setting (dt/4), single thread [-]
BANDS = ((0.01, 0.1), (0.1, 1.0), (1.0, 10.0))


def _eqsig_grid(records, periods):
    return np.array([eqsig.sdof.pseudo_response_spectra(r.acceleration_samples, r.dt, periods, 0.05)[2]
                     for r in records])


def _eqsig_interp(records, periods):
    out = []
    for r in records:
        sig = eqsig.AccSignal(r.acceleration_samples, r.dt)
        sig.gen_response_spectrum(response_times=periods, xi=0.05)
        out.append(sig.s_a)
    return np.array(out)


def _pyrotd(records, periods):
    pyrotd.processes = 1
    return np.array([pyrotd.calc_spec_accels(r.dt, r.acceleration_samples, 1 / periods, 0.05).spec_accel
                     for r in records])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="2 short records, 40 periods (smoke run)")
    parser.add_argument("--threads", type=int, default=1, help="numba threads for blockdae (default 1)")
    parser.add_argument("--repeat", type=int, default=3, help="warm repeats for blockdae")
    args = parser.parse_args(argv)
    import numba

    numba.set_num_threads(min(args.threads, numba.config.NUMBA_NUM_THREADS))
    records = sample_records(quick=args.quick)
    periods = np.geomspace(0.01, 10.0, 40 if args.quick else 200)
    n_samples = sum(r.acceleration_samples.size for r in records)
    print(f"{len(records)} records ({n_samples} samples), {periods.size} periods "
          f"{periods[0]:g}-{periods[-1]:g} s, 5 % damping, blockdae on {numba.get_num_threads()} thread(s)\n")

    exact, first, _ = timed(lambda: bd.motions.response_spectrum(records, periods, 0.05).psa, 0)
    # every library imported above and warmed on one call before its timing; then each timed
    # alike: --repeat warm calls over all the records, their median
    libraries = {f"blockdae (exact, {numba.get_num_threads()} thr.)":
                 lambda: bd.motions.response_spectrum(records, periods, 0.05).psa,
                 "eqsig (sample grid)": lambda: _eqsig_grid(records, periods),
                 "eqsig (dt/4)": lambda: _eqsig_interp(records, periods),
                 "pyrotd": lambda: _pyrotd(records, periods)}
    results = {}
    for label, action in libraries.items():
        values, _, seconds = timed(action, args.repeat)
        results[label] = (values, seconds)
    warm = next(iter(results.values()))[1]
    rows = []
    for label, (values, seconds) in results.items():
        rel = np.abs(values / exact - 1)
        cells = []
        for lo, hi in BANDS:
            band = rel[:, (periods >= lo) & (periods < hi if hi < 10 else periods <= hi)]
            cells.append(f"{np.median(band):.1e} / {band.max():.1e}")
        rows.append((label, *cells, f"{seconds:.3f}", f"{seconds / warm:.1f}"))
    print_table(["PSa vs exact: median / max |rel. diff|", *(f"T {lo:g}-{hi:g} s" for lo, hi in BANDS),
                 "time [s]", "time / blockdae"], rows)
    print(f"\n(every time the median of {args.repeat} warm calls over all the records, each library imported and "
          f"called once before; blockdae's first call in this process (numba's cache or compiling) {first:.2f} s; "
          f"{warm / (n_samples * periods.size) * 1e9:.1f} ns per sample and period)")
    speedup = results["eqsig (dt/4)"][1] / warm
    print(f"speed-up over eqsig (dt/4): {speedup:.1f}x (bar {BAR_SPEEDUP:g}x): "
          f"{verdict(speedup >= BAR_SPEEDUP, args.quick)}; over eqsig (sample grid): "
          f"{results['eqsig (sample grid)'][1] / warm:.1f}x; over pyrotd: {results['pyrotd'][1] / warm:.1f}x "
          f"(blockdae on {numba.get_num_threads()} thread(s), the others single-threaded)")
    return 1 if speedup < BAR_SPEEDUP and not args.quick else 0


if __name__ == "__main__":
    sys.exit(main())
