"""``blockdae fragility`` and ``blockdae hazard``: Newmark analyses of records × target PGAs ×
ky, a displacement fragility P(D > d | PGA) fitted per ky (D the larger polarity's), and with
a site's PGA hazard curve the annual rate λ(D > d)."""

import argparse
import pathlib
import time
import warnings

import numpy as np

from ..units import STANDARD_GRAVITY
from ..excitation import UnitsWarning
from ..hazard import HazardCurve, displacement_hazard, fit_fragility, plot_displacement_hazard, plot_fragility
from ..sliding import newmark
from ._common import (UsageError, checked, files_or_set, folder_files, positive, read, record_arguments,
                      recursive_argument, save_figure, set_argument, write_csv)

#: how --curve is read: a table of levels and annual rates, OpenQuake's hazard-curve CSV, USGS's JSON
CURVE_FORMATS = ("table", "openquake", "usgs")


def add_hazard_parsers(sub):
    """The ``fragility`` and ``hazard`` subcommands."""
    fragility = sub.add_parser("fragility", help="P(D > d | PGA) of a rigid slope fitted to records x PGA x ky")
    _common_arguments(fragility)
    fragility.add_argument("--at", type=positive("--at"), nargs="+", default=None, metavar="PGA_G",
                           help="PGAs [g] to tabulate P(D > d | PGA) at (default: 6 across the --pga grid)")
    fragility.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG",
                           help="save the fragility curves of the first ky, one panel per d")
    fragility.set_defaults(command=_fragility)

    hazard = sub.add_parser("hazard", help="annual rate of D > d of a rigid slope: a fragility fitted to records "
                                           "x PGA x ky, over a site's PGA hazard curve")
    _common_arguments(hazard)
    hazard.add_argument("--curve", type=pathlib.Path, required=True, metavar="FILE",
                        help="the site's PGA hazard curve: PGA [g] and annual rate of exceedance [1/yr]")
    hazard.add_argument("--curve-format", choices=CURVE_FORMATS, default="table",
                        help="table (CSV of two columns, default), openquake (hazard_curve CSV) or usgs (JSON)")
    hazard.add_argument("--site", type=int, default=None, help="openquake: the site's row (default: the only one)")
    hazard.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG",
                        help="save λ(D > d) against d, one curve per ky")
    hazard.set_defaults(command=_hazard)


def _common_arguments(p):
    p.add_argument("records", type=pathlib.Path, nargs="*", metavar="RECORD",
                   help="accelerogram files or folders of them (at least 10 records); or --set NAME")
    p.add_argument("--ky", type=positive("--ky"), nargs="+", required=True, help="yield acceleration(s) [g]")
    p.add_argument("--pga", type=_grid, required=True, metavar="START:STOP:N",
                   help="target PGAs [g] each record is scaled to: N values spaced evenly in log from START to "
                        "STOP (e.g. 0.05:1.2:40), or a list 0.1,0.2,0.4")
    p.add_argument("--d", type=positive("--d"), nargs="+", default=[0.05, 0.15, 0.30], metavar="D_M",
                   help="displacements d [m] (default 0.05 0.15 0.30)")
    p.add_argument("--d0", type=positive("--d0"), default=0.01, metavar="D_M",
                   help="negligible displacement [m]: the fit's threshold (default 0.01, as Bray & Travasarou 2007)")
    p.add_argument("--boot", type=int, default=200, metavar="N",
                   help="bootstrap refits over records drawn with replacement, for the 90 %% bands (default 200)")
    p.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                   help="the unit 'g' [m/s²] of the files and the PGAs (default 9.80665)")
    record_arguments(p)
    recursive_argument(p)
    set_argument(p)
    p.add_argument("--csv", type=pathlib.Path, default=None, metavar="PATH", help="write the table as CSV")


def _grid(text):
    """"START:STOP:N" (N values evenly spaced in log, ends included) or "a,b,c"; each > 0 [g]."""
    try:
        if ":" in text:
            start, stop, n = text.split(":")
            values = np.geomspace(float(start), float(stop), int(n))
        else:
            values = np.array([float(x) for x in text.split(",")])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected START:STOP:N or a list a,b,c of PGAs [g], got {text!r}") from None
    if values.size == 0 or not np.all(np.isfinite(values) & (values > 0)):
        raise argparse.ArgumentTypeError(f"PGAs must be positive [g], got {text!r}")
    return values


def _fits(args):
    """{ky [g]: Fragility} of the command's records x --pga x --ky; prints what ran."""
    record_set = files_or_set(args, args.records)
    paths = [] if record_set is not None else \
        [p for arg in args.records for p in (folder_files(arg, args) if arg.is_dir() else [arg])]
    records = record_set if record_set is not None else [read(path, args) for path in paths]
    start = time.perf_counter()
    with warnings.catch_warnings():  # a PGA grid reaches below ky on purpose: D = 0 there is data
        warnings.simplefilter("ignore", UnitsWarning)
        sweep = checked(lambda: newmark(records, ky=np.asarray(args.ky), g=args.g, pga=args.pga,
                                        check_peak=not args.accept_peak), "")
    wall = time.perf_counter() - start
    n_records, n_pga, n_ky = sweep.shape
    print(f"{n_records} records x {n_pga} PGAs x {n_ky} ky, both polarities: {2 * n_records * n_pga * n_ky} Newmark "
          f"analyses in {wall:.1f} s; D is the larger polarity's")
    table = sweep.to_dataframe()
    return {ky: checked(lambda ky=ky: fit_fragility(table[table.ky_g == ky], im="pga_g", displacement="max_m",
                                                    d0_m=args.d0, n_boot=args.boot), f"ky = {ky:g} g")
            for ky in sweep.ky}


def _fragility(args) -> int:
    fits = _fits(args)
    at = np.asarray(args.at) if args.at is not None else \
        np.geomspace(args.pga[0], args.pga[-1], 6) if args.pga.size > 1 else args.pga
    rows = []
    for ky, fit in fits.items():
        print(f"\nky = {ky:g} g: P(D > d | PGA), maximum likelihood over {fit.n_records} records "
              f"(d0 = {fit.d0_m:g} m; median D above d0 = exp({fit.c0:.3f} + {fit.c1:.3f} ln PGA) m, "
              f"sigma ln D = {fit.sigma:.3f}); 90 % bootstrap band in brackets")
        print(f"{'PGA [g]':>8}" + "".join(f"{f'P(D > {d:g} m)':>24}" for d in args.d))
        for pga in at:
            cells = []
            for d in args.d:
                p = float(fit.exceedance(d, pga))
                low, high = (float(x) for x in fit.band(d, pga)) if fit.boot.size else (np.nan, np.nan)
                cells.append(f"{p:.3f} [{low:.3f}, {high:.3f}]")
                rows.append({"ky_g": ky, "pga_g": pga, "d_m": d, "p_exceedance": p, "p_band_low": low,
                             "p_band_high": high})
            print(f"{pga:8.4f}" + "".join(f"{cell:>24}" for cell in cells))
    if args.csv is not None:
        write_csv(args.csv, rows)
        print(f"results: {args.csv}")
    if args.plot is not None:
        _plot_fragility(args, fits)
        print(f"figure: {args.plot}")
    return 0


def _plot_fragility(args, fits):
    import matplotlib.pyplot as plt

    ky, fit = next(iter(fits.items()))
    figure, axes = plt.subplots(1, len(args.d), figsize=(4.2 * len(args.d), 3.8), squeeze=False)
    pga = np.geomspace(args.pga[0], args.pga[-1], 200) if args.pga.size > 1 else args.pga
    for ax, d in zip(axes[0], args.d):
        plot_fragility(fit, d, pga, ax=ax)
        ax.set(xscale="log", xlabel="Peak ground acceleration [g]", ylabel=f"P(D > {d:g} m | PGA)",
               title=f"ky = {ky:g} g, d = {d:g} m")
    figure.tight_layout()
    save_figure(figure, args.plot)


def _hazard(args) -> int:
    curve = _curve(args)
    fits = _fits(args)
    d = np.asarray(args.d, dtype=float)
    print(f"\nhazard curve: {args.curve} ({curve.im.size} levels, PGA {curve.im[0]:g} to {curve.im[-1]:g} g)")
    print(f"{'ky [g]':>8} {'d [m]':>8} {'rate of D > d [1/yr]':>22} {'return period [yr]':>20}")
    rows, rates = [], {}
    for ky, fit in fits.items():
        rates[ky] = np.atleast_1d(displacement_hazard(curve, fit, d))
        for d_m, rate in zip(d, rates[ky]):
            period = 1.0 / rate if rate > 0 else np.inf
            print(f"{ky:8.4f} {d_m:8.4f} {rate:22.4e} {period:20.4g}")
            rows.append({"ky_g": ky, "d_m": d_m, "rate_per_yr": rate, "return_period_yr": period})
    if args.csv is not None:
        write_csv(args.csv, rows)
        print(f"results: {args.csv}")
    if args.plot is not None:
        import matplotlib.pyplot as plt

        figure, ax = plt.subplots(figsize=(6, 4))
        grid = np.geomspace(d.min(), d.max(), 60) if d.size > 1 else d
        plot_displacement_hazard(grid, {f"ky = {ky:g} g": displacement_hazard(curve, fit, grid)
                                        for ky, fit in fits.items()}, ax=ax)
        figure.tight_layout()
        save_figure(figure, args.plot)
        print(f"figure: {args.plot}")
    return 0


def _curve(args):
    """The --curve file as a HazardCurve of PGA [g]."""
    if not args.curve.is_file():
        raise UsageError(f"--curve {args.curve}: no such file")
    if args.curve_format == "openquake":
        return checked(lambda: HazardCurve.from_openquake_csv(args.curve, site=args.site, imt="PGA"), "--curve")
    if args.curve_format == "usgs":
        return checked(lambda: HazardCurve.from_usgs_json(args.curve, imt="PGA"), "--curve")
    return checked(lambda: HazardCurve.read_csv(args.curve), "--curve")
