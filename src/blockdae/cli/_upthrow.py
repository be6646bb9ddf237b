"""``blockdae upthrow``: a compact mass on a spring support under a vertical record
(Newmark 1969), the paper's estimates (eqs. 5, 8, 12, 13) beside the exact flights."""

import json
import math
import pathlib
import sys
import time

from ._common import (checked, clean, describe_record, number, positive, read, record_arguments,
                      record_fields, save_figure)
from ..core import simulate
from ..units import STANDARD_GRAVITY
from ..upthrow import SpringSupportedMass, upthrow_estimate
from ..excitation import pga_factor, unit_factor

#: the backends that run a SpringSupportedMass
BACKENDS = ("exact", "cvode", "ida", "jax")
_FLIGHTS_SHOWN = 5  # flights printed at each end of a long list by default


def add_upthrow_parser(subparsers):
    """The ``upthrow`` subcommand on an argparse ``subparsers`` object."""
    p = subparsers.add_parser("upthrow", help="a mass on a spring support under vertical ground motion (Newmark 1969): "
                                              "the paper's estimates and the exact flights")
    p.add_argument("record", type=pathlib.Path,
                   help="vertical ground acceleration, upward positive (CSV t,a / one column / .AT2)")
    p.add_argument("--frequency", type=positive("--frequency"), required=True,
                   help="natural frequency f of the mass on its support [Hz]")
    p.add_argument("--damping", type=number("--damping", lambda x: 0 <= x < 1, "in [0, 1)"), default=0.0,
                   help="damping ratio zeta of the support [-] (default 0)")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--pga", type=positive("--pga"), default=None, metavar="PGA_G",
                      help="scale the record so that its peak |a| is PGA_G [g] (above 2 g, likely m/s², "
                           "refused unless --accept-peak)")
    size.add_argument("--scale-to", type=positive("--scale-to"), default=None, metavar="PGA_G",
                      help="deprecated: the old name of --pga")
    size.add_argument("--scale", type=number("--scale", lambda x: math.isfinite(x) and x != 0,
                                             "a finite nonzero number"), default=None, metavar="K",
                      help="factor on the record [-] (negative: upside down)")
    p.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                   help="gravitational acceleration [m/s²], also the unit 'g' (default 9.80665)")
    p.add_argument("--t-end", type=positive("--t-end"), default=None,
                   help="final time [s] (default: the record's duration)")
    p.add_argument("--backend", choices=BACKENDS, default="exact", help="solver backend (default exact)")
    record_arguments(p, horizontal=False)
    p.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG", help="save a figure (bd.plot)")
    p.add_argument("--json", action="store_true", help="print the results as JSON (SI units)")
    p.add_argument("--flights", choices=("summary", "all", "none"), default="summary",
                   help=f"flights to print: the first and last {_FLIGHTS_SHOWN} (default), all or none")
    p.add_argument("--quiet", action="store_true", help="print only the number of flights and the largest height")
    p.set_defaults(command=run_upthrow)
    return p


def run_upthrow(args) -> int:
    """Fly the mass that ``args`` describe; print the estimates and the flights; the exit status."""
    if args.units is not None:
        checked(lambda: unit_factor(args.units), "--units")
    record, factor = _scaled(read(args.record, args), args)
    block = SpringSupportedMass(args.frequency, args.damping, args.g)  # the argument types checked them
    t_end = record.duration if args.t_end is None else args.t_end
    start = time.perf_counter()
    solution = checked(lambda: simulate(block, record, t_end=t_end, backend=args.backend), str(args.record))
    wall = time.perf_counter() - start
    estimate = upthrow_estimate(block, record, t_end=t_end)
    if args.plot is not None:
        from .._plot import plot

        title = f"{record.name}: f = {block.frequency:g} Hz, zeta = {block.damping:g}"
        save_figure(plot(solution, title=title), args.plot)
    if args.json:
        print(json.dumps(_json(record, factor, block, solution, estimate, wall), indent=2))
        return 0
    flights = solution.flights
    if args.quiet:
        print(_summary(flights))
        return 0
    print(f"record: {describe_record(record)}; vertical, upward positive")
    if factor != 1.0:
        print(f"scaled by {factor:.6g} [-] to a peak of {record.peak_acceleration / block.g:.6g} g")
    print(f"mass on a spring support: f = {block.frequency:g} Hz, zeta = {block.damping:g}, g = {block.g:g} m/s²; "
          f"backend {solution.backend}; t_end = {solution.t_end:.4f} s")
    print(f"static deflection u0 = g / omega² = {block.static_deflection * 1e3:.6f} mm")
    _print_estimate(estimate)
    _print_flights(flights, solution.t_end, args.flights)
    print(f"time: {wall:.3f} s (wall clock of the simulation, including compilation on a first call)")
    if args.plot is not None:
        print(f"figure: {args.plot}")
    return 0


def _scaled(record, args):
    """The record scaled as --pga (or its deprecated name --scale-to) or --scale say, and the factor [-]."""
    if args.scale is not None:
        return record.scaled(args.scale), args.scale
    if args.scale_to is not None:
        print("blockdae: warning: --scale-to is deprecated; use --pga (the same target peak [g])", file=sys.stderr)
    flag, pga = ("--scale-to", args.scale_to) if args.scale_to is not None else ("--pga", args.pga)
    if pga is None:
        return record, 1.0
    factor = checked(lambda: pga_factor(record.peak_acceleration, pga, args.g, name=flag,
                                        check_peak=not args.accept_peak), str(args.record))
    return record.scaled(factor), factor


def _print_estimate(estimate):
    print(f"Newmark 1969 estimate from the linear response: A = {estimate.response_acceleration:.6f} g")
    if not estimate.lifts_off:
        print("  A <= 1 g: no liftoff predicted")
        return
    print(f"  eq. 12 liftoff velocity u'0 = {estimate.liftoff_velocity:.6f} m/s")
    print(f"  eq. 13 height z = {estimate.height * 1e3:.6f} mm")
    print(f"  eq. 8 time to the top Delta t = {estimate.time_to_top:.6f} s "
          f"(flight about 2 Delta t = {estimate.flight_duration:.6f} s)")


def _print_flights(flights, t_end, which):
    if not flights:
        print(f"exact flights: none (no liftoff until t_end = {t_end:.4f} s)")
        return
    print(f"exact flights: {len(flights)} (velocities u' relative to the ground; height: largest u - u0, "
          "above the unloaded support)")
    if which == "none":
        return
    numbered = list(enumerate(flights, 1))
    shown = numbered if which == "all" or len(flights) <= 2 * _FLIGHTS_SHOWN \
        else numbered[:_FLIGHTS_SHOWN] + [None] + numbered[-_FLIGHTS_SHOWN:]
    print(f"{'#':>4}  {'liftoff [s]':>12}  {'liftoff velocity [m/s]':>22}  {'largest height [mm]':>19}  "
          f"{'landing [s]':>12}  {'impact velocity [m/s]':>21}")
    for row in shown:
        if row is None:
            print(f"{'...':>4}  ({len(flights) - 2 * _FLIGHTS_SHOWN} more flights; --flights all prints them)")
            continue
        k, f = row
        height = f"{f.height * 1e3:+19.6f}" if math.isfinite(f.height) else f"{'(rising)':>19}"
        landing = (f"{f.landing:12.6f}  {f.impact_velocity:+21.6f}" if math.isfinite(f.landing)
                   else f"{'(in flight)':>12}  {'-':>21}")
        print(f"{k:4d}  {f.liftoff:12.6f}  {f.liftoff_velocity:+22.6f}  {height}  {landing}")


def _summary(flights):
    if not flights:
        return "no liftoff"
    heights = [f.height for f in flights if math.isfinite(f.height)]
    largest = f"{max(heights) * 1e3:+.6f} mm" if heights else "not reached (rising at t_end)"
    return f"{len(flights)} flights, largest height {largest}"


def _finite_or_none(x):
    """``x`` for JSON: None where it is nan (not landed) or -inf (no top yet)."""
    return x if math.isfinite(x) else None


def _json(record, factor, block, solution, estimate, wall):
    return {
        **record_fields(record), "scale": factor, "peak_acceleration_g": record.peak_acceleration / block.g,
        "frequency_hz": block.frequency, "damping": block.damping, "g_m_s2": block.g,
        "backend": solution.backend, "t_end_s": clean(solution.t_end),
        "static_deflection_m": block.static_deflection,
        "estimate": {"response_acceleration_g": estimate.response_acceleration,
                     "liftoff_velocity_m_s": estimate.liftoff_velocity, "height_m": estimate.height,
                     "time_to_top_s": estimate.time_to_top, "flight_duration_s": estimate.flight_duration},
        "flights": [{"liftoff_s": f.liftoff, "liftoff_velocity_m_s": f.liftoff_velocity,
                     "height_m": _finite_or_none(f.height), "landing_s": _finite_or_none(f.landing),
                     "impact_velocity_m_s": _finite_or_none(f.impact_velocity)} for f in solution.flights],
        "wall_time_s": wall,
    }
