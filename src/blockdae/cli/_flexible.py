"""``blockdae flexible``: the flexible sliding-mass analyses (decoupled or coupled,
linear-elastic or equivalent-linear, both polarities) of one record, exact in time."""

import json

import pathlib

from ._common import (UsageError, checked, describe_record, in_units_out, ky_table, ky_table_row, number, positive,
                      read, reader_warnings, record_arguments, record_fields, save_figure, units_out_argument)
from ..core import simulate
from ..units import STANDARD_GRAVITY
from ..flexible_mass import (INTEGRATIONS, METHODS, POLARITIES, FlexibleSlidingMass, ShearColumn, flexible,
                             prechecked_column, with_zero_sample)

def _columns(unit):
    """(field, heading, format) of the printed table, displacements in ``unit`` (--units-out)."""
    return (("ky_g", "ky [g]", "{:.4g}"), (f"normal_{unit}", f"normal [{unit}]", "{:.6g}"),
            (f"inverse_{unit}", f"inverse [{unit}]", "{:.6g}"), ("kmax_g", "kmax [g]", "{:.5f}"),
            ("kmax_sup_g", "kmax sup [g]", "{:.5f}"), ("vs_final_m_s", "vs final [m/s]", "{:.2f}"),
            ("damping_final", "damping final", "{:.4f}"), ("episodes_normal", "episodes n", "{}"),
            ("episodes_inverse", "episodes i", "{}"))


def add_flexible_parser(subparsers):
    """The ``flexible`` subcommand on an argparse ``subparsers`` object."""
    p = subparsers.add_parser("flexible", help="flexible sliding mass (Bray & Rathje decoupled, Rathje & Bray "
                                               "coupled): downslope displacement, exact in time")
    p.add_argument("record", type=pathlib.Path, help="ground acceleration along the slope (CSV t,a / one column / "
                                                     ".AT2)")
    ky = p.add_mutually_exclusive_group(required=True)
    ky.add_argument("--ky", type=number("--ky", lambda x: x >= 0, "a yield acceleration >= 0 [g]"), nargs="+",
                    help="yield acceleration(s) [g]; 0.05 g is 0.49 m/s²: a ky typed in m/s² is read 9.8 "
                         "times too large and gives millimetres")
    ky.add_argument("--ky-table", type=ky_table_row, nargs="+", metavar="D_M:KY_G",
                    help="ky [g] against the sliding displacement D [m] as rows D:ky, D increasing (linear "
                         "between rows, constant beyond: bd.KyTable)")
    p.add_argument("--height", type=positive("--height"), required=True, help="height H of the sliding mass [m]")
    p.add_argument("--vs", type=positive("--vs"), required=True, help="its shear-wave velocity [m/s]")
    p.add_argument("--vr", type=positive("--vr"), default=None, help="shear-wave velocity below the slip surface "
                                                                      "[m/s] (default: --vs)")
    p.add_argument("--damping", type=number("--damping", lambda x: -1 < x < 1, "in (-1, 1)"), default=0.05,
                   help="the soil's damping ratio [-]; impedance damping from vr/vs is added (default 0.05)")
    p.add_argument("--method", choices=METHODS, default="coupled", help="slip equations (default coupled)")
    p.add_argument("--reference-strain", type=positive("--reference-strain"), default=None, metavar="FRACTION",
                   help="run the equivalent-linear iteration with this reference strain (a fraction, e.g. 0.0005)")
    p.add_argument("--pga", type=positive("--pga"), default=None, metavar="PGA_G",
                   help="scale the record so that its peak |a| is PGA_G [g] (above 2 g, likely m/s², refused unless "
                        "--accept-peak; its exact peak; with --integration "
                        "slammer its peak rounded to 0.001 g, as SLAMMER scales)")
    p.add_argument("--integration", choices=tuple(INTEGRATIONS), default="exact",
                   help="exact (continuous time, events located; default) or slammer (SLAMMER 1.1's fixed-step "
                        "scheme, to reproduce its results)")
    p.add_argument("--polarity", choices=POLARITIES, default="both", help="record as given, inverted, or both")
    p.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                   help="gravitational acceleration [m/s²], also the unit 'g' (default 9.80665)")
    p.add_argument("--t-end", type=positive("--t-end"), default=None,
                   help="end on the record's axis [s] (default: its last sample)")
    record_arguments(p)
    p.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG",
                   help="save the figure of the first ky, normal polarity (bd.plot; the exact solution)")
    units_out_argument(p)
    p.add_argument("--json", action="store_true", help="print the rows as JSON (SI units, displacements in "
                                                       "--units-out)")
    p.set_defaults(command=run_flexible)
    return p


def run_flexible(args) -> int:
    """Run the analyses that ``args`` describe; print one row per ky; the exit status."""
    record = read(args.record, args)
    table = ky_table(args)
    ky = args.ky if table is None else table
    with reader_warnings(args):  # the plausibility rules' warnings (ky, H, vs, damping) as lines
        result = checked(lambda: flexible(record, ky, args.height, args.vs, args.vr, args.damping, args.method,
                                          args.reference_strain is not None, args.reference_strain, args.pga,
                                          args.polarity, args.integration, args.g, args.t_end,
                                          check_peak=not args.accept_peak), str(args.record))
    rows = result.rows
    if args.plot is not None:
        from .._plot import plot

        motion = record if args.pga is None else record.scaled(args.pga * args.g / record.peak_acceleration)
        column = prechecked_column(args.height, rows[0]["vs_final_m_s"], args.vr or args.vs,
                                   args.damping if args.reference_strain is None else rows[0]["damping_final"],
                                   impedance=args.reference_strain is None)
        model = FlexibleSlidingMass(column, ky if args.ky is None else ky[0], args.method, args.g)
        end = (record.duration if args.t_end is None else args.t_end) + record.dt
        solution = checked(lambda: simulate(model, with_zero_sample(motion), t_end=end), str(args.record))
        save_figure(plot(solution, title=f"{record.name}: t from the virtual zero sample at -dt"), args.plot)
    rows = [in_units_out(row, args.units_out) for row in rows]
    if args.json:
        print(json.dumps({**record_fields(record), "method": args.method, "rows": rows}, indent=2, default=float))
        return 0
    print(f"record: {describe_record(record)}")
    print(f"{args.method} flexible sliding mass: H = {args.height:g} m, vs = {args.vs:g} m/s, "
          f"vr = {args.vr or args.vs:g} m/s, damping {args.damping:g} (+ impedance), "
          f"{'equivalent-linear' if args.reference_strain else 'linear-elastic'}")
    if args.ky_table is not None:
        print(f"ky against the sliding displacement: {ky} (the column ky [g]: at D = 0)")

    columns = _columns(args.units_out)
    table = [[fmt.format(row[key]) if row[key] is not None and row[key] == row[key] else "-"  # None, nan: "-"
              for key, _, fmt in columns] for row in rows]
    widths = [max(len(head), *(len(line[i]) for line in table)) for i, (_, head, _) in enumerate(columns)]
    print("  ".join(head.rjust(w) for (_, head, _), w in zip(columns, widths)))
    for line in table:
        print("  ".join(cell.rjust(w) for cell, w in zip(line, widths)))
    if args.plot is not None:
        print(f"figure: {args.plot}")
    return 0


def add_flexible_study_arguments(parser):
    """``blockdae study``'s options of the flexible sliding mass (with ``--ky`` or
    ``--ky-table`` in place of ``--mu``)."""
    group = parser.add_argument_group("the flexible sliding mass (with --ky or --ky-table)")
    group.add_argument("--height", type=positive("--height"), default=None, help="height H of the sliding mass [m]")
    group.add_argument("--vs", type=positive("--vs"), default=None, help="its shear-wave velocity [m/s]")
    group.add_argument("--vr", type=positive("--vr"), default=None,
                       help="shear-wave velocity below the slip surface [m/s] (default: --vs)")
    group.add_argument("--soil-damping", type=number("--soil-damping", lambda x: -1 < x < 1, "in (-1, 1)"),
                       default=None, help="the soil's damping ratio [-]; impedance damping from vr/vs is added "
                                          "(default 0.05)")
    group.add_argument("--method", choices=METHODS, default=None, help="slip equations (default coupled)")


def flexible_study_block(args):
    """(the flexible sliding mass of ``blockdae study``'s ``args``, the ky to sweep: numbers
    [g] or a :class:`KyTable`); UsageError where --height or --vs is missing."""
    missing = [flag for flag, value in (("--height", args.height), ("--vs", args.vs)) if value is None]
    if missing:
        raise UsageError(f"--ky and --ky-table study the flexible sliding mass: give {' and '.join(missing)}")
    table = ky_table(args)
    ky = args.ky if table is None else table
    damping = 0.05 if args.soil_damping is None else args.soil_damping
    with reader_warnings(args):
        column = checked(lambda: ShearColumn(args.height, args.vs, args.vr, damping), "--soil-damping")
    return FlexibleSlidingMass(column, ky=0.0, method=args.method or "coupled", g=args.g), ky
