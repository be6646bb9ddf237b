"""``blockdae spectrum`` and ``blockdae two-point``: command functions for the CLI.

``blockdae.cli`` adds them with ``add_spectrum_parser(sub)`` and
``add_two_point_parser(sub)``; each sets ``command`` to a function of the parsed args
returning the exit status (errors: :class:`UsageError`, one ``blockdae: error: ...``
line and status 2).
"""

import json
import pathlib

import numpy as np

from ._common import UsageError, checked, number, positive, read, record_arguments, save_figure, write_csv
from ..units import STANDARD_GRAVITY
from ..excitation import pga_factor

SEED_LAGS = np.geomspace(0.05, 3.0, 20)  # Christian 1973: 20 lags from 0.05 to 3 s
DEFAULT_PERIODS = np.geomspace(0.01, 10.0, 100)


def _common(parser, baseline):
    parser.add_argument("record", type=pathlib.Path, help="accelerogram (CSV t,a / one column / .AT2)")
    record_arguments(parser, baseline)
    parser.add_argument("--g", type=positive("--g"),
                        default=STANDARD_GRAVITY, help="the unit 'g' [m/s²] (default 9.80665)")
    parser.add_argument("--pga", type=positive("--pga"),
                        default=None, help="scale the record to this PGA [g] (Christian 1973: 0.1)")
    parser.add_argument("--csv", type=pathlib.Path, default=None, help="write the table as CSV")
    parser.add_argument("--json", action="store_true", help="print the results as JSON")
    parser.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG", help="save a figure")


def add_spectrum_parser(subparsers):
    """The ``spectrum`` subcommand: exact response spectra of one record."""
    p = subparsers.add_parser("spectrum", help="exact response spectra of a record (Sd, Sv, Sa, PSa, ...)")
    _common(p, baseline="none")
    p.add_argument("--periods", nargs="+", default=None,
                   type=positive("--periods"),
                   help="oscillator periods [s] (default 100 log-spaced from 0.01 to 10 s)")
    p.add_argument("--damping", nargs="+", default=[0.05],
                   type=number("--damping", lambda x: np.isfinite(x) and 0 <= x < 1, "in [0, 1)"),
                   help="fractions of critical damping [-] (default 0.05)")
    p.add_argument("--t-end", type=positive("--t-end"),
                   default=None, help="end of the window [s] (default the record's duration)")
    p.set_defaults(command=run_spectrum)
    return p


def add_two_point_parser(subparsers):
    """The ``two-point`` subcommand: relative motion of two surface points (Christian 1973)."""
    p = subparsers.add_parser("two-point", help="largest relative displacement of two points τ = b/c apart "
                                                "(Christian 1973)")
    _common(p, baseline="polynomial")
    p.add_argument("--lags", nargs="+", default=None,
                   type=number("--lags", lambda x: np.isfinite(x) and x >= 0, "a number >= 0"),
                   help="lags τ = b/c [s] (default the paper's 20 lags, 0.05 to 3 s)")
    p.add_argument("--damping", type=number("--damping", lambda x: np.isfinite(x) and 0 <= x < 1, "in [0, 1)"),
                   default=0.05, help="damping of the 2 Sd(2τ) estimate [-] (default 0.05)")
    p.set_defaults(command=run_two_point)
    return p


def _record(args):
    rec = read(args.record, args)  # baseline corrected as --baseline says
    if args.pga is not None:
        rec = rec.scaled(checked(lambda: pga_factor(rec.peak_acceleration, args.pga, args.g, name="--pga",
                                                    check_peak=not args.accept_peak), str(args.record)))
    return rec


def run_spectrum(args):
    from ..motions import response_spectrum

    rec = _record(args)
    periods = DEFAULT_PERIODS if args.periods is None else np.array(args.periods)
    try:
        spec = response_spectrum(rec, periods, np.array(args.damping), t_end=args.t_end)
    except ValueError as err:
        raise UsageError(str(err)) from None
    rows = []
    for j, zeta in enumerate(args.damping):
        one = spec if spec.sd.ndim == 1 else _index(spec, j)
        rows += one.table()
    if args.csv:
        write_csv(args.csv, rows)
    if args.json:
        print(json.dumps({"record": rec.name, "dt_s": rec.dt, "pga_m_s2": rec.peak_acceleration,
                          "baseline": args.baseline, "rows": rows}, indent=1))
    else:
        print(f"{rec.name}: {rec.acceleration_samples.size} samples, dt = {rec.dt:g} s, "
              f"PGA {rec.peak_acceleration:.4g} m/s², baseline {args.baseline}")
        print(f"{'T [s]':>9} {'ζ':>5} {'Sd [m]':>11} {'Sv [m/s]':>11} {'Sa [m/s²]':>11} {'PSa [m/s²]':>11} "
              f"{'Sd,abs [m]':>11}")
        for r in rows:
            print(f"{r['period_s']:9.4g} {r['damping']:5.3g} {r['sd_m']:11.5g} {r['sv_m_s']:11.5g} "
                  f"{r['sa_m_s2']:11.5g} {r['psa_m_s2']:11.5g} {r['sd_abs_m']:11.5g}")
    if args.plot:
        from ..motions import plot_spectrum

        save_figure(plot_spectrum(spec, title=f"{rec.name}: PSa"), args.plot)
    return 0


def _index(spec, j):
    import dataclasses

    fields = {f.name: getattr(spec, f.name) for f in dataclasses.fields(spec)}
    for name in ("sd", "sv", "sa", "sd_abs", "t_sd", "t_sv", "t_sa", "t_sd_abs"):
        fields[name] = fields[name][j]
    fields["damping"] = spec.damping[j]
    return type(spec)(**fields)


#: what each column of the two-point table holds (Christian's words), printed under it
TWO_POINT_LEGEND = (
    "τ = b/c: time the wave takes from one point to the other; R: largest |d(t) − d(t − τ)|, computed "
    "directly (at t_R);",
    "v_m τ: first term of Newmark's formula, the bound |R| <= v_m b/c (eq. 2); eq.1 −, eq.1 +: Newmark's "
    "formula v_m τ − a_m τ²/2 and v_m τ + a_m τ²/2 (eq. 1, Table I);",
    "2 Fourier, 2 Sd(2τ): twice the Fourier amplitude of d and twice the spectral displacement at "
    "T = 2τ (method d);",
    "envelope: min(v_m τ, d_m), eqs. 2-3 (|R| <= d_m holds 'for most earthquakes', not always: R may "
    "exceed it).",
)


def _print_two_point_table(rows):
    """The two-point table: every column with its unit, then :data:`TWO_POINT_LEGEND`."""
    estimates = ("velocity_bound_m", "eq1_minus_m", "eq1_plus_m", "fourier_m", "spectral_m", "envelope_m")
    print(f"{'τ [s]':>8} {'R [m]':>10} {'t_R [s]':>8} {'v_m τ [m]':>10} {'eq.1 − [m]':>10} {'eq.1 + [m]':>10} "
          f"{'2 Fourier [m]':>13} {'2 Sd(2τ) [m]':>12} {'envelope [m]':>12}")
    for r in rows:
        cells = [f"{r[key]:{width}.4g}" for key, width in zip(estimates, (10, 10, 10, 13, 12, 12))]
        print(f"{r['lag_s']:8.4g} {r['r_m']:10.4g} {r['t_r_s']:8.3f} " + " ".join(cells))
    print("\n".join(TWO_POINT_LEGEND))


def run_two_point(args):
    from ..motions import relative_motion

    rec = _record(args)
    lags = SEED_LAGS if args.lags is None else np.array(args.lags)
    try:
        rm = relative_motion(rec, lags, damping=args.damping)
    except ValueError as err:
        raise UsageError(str(err)) from None
    rows = rm.table()
    if args.csv:
        write_csv(args.csv, rows)
    if args.json:
        print(json.dumps({"record": rec.name, "baseline": args.baseline, "pga_m_s2": rm.pga, "pgv_m_s": rm.pgv,
                          "pgd_m": rm.pgd, "d_max_m": rm.d_max, "d_min_m": rm.d_min, "rows": rows}, indent=1))
    else:
        print(f"{rec.name}: a_m = {rm.pga:.4g} m/s², v_m = {rm.pgv:.4g} m/s, d_m = {rm.pgd:.4g} m "
              f"(d from {rm.d_min:.4g} to {rm.d_max:.4g} m), baseline {args.baseline}")
        _print_two_point_table(rows)
    if args.plot:
        from ..motions import plot_relative_motion

        save_figure(plot_relative_motion(rm), args.plot)
    return 0
