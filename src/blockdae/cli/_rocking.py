"""``blockdae rocking``: a free-standing block under one horizontal record: whether it
rests, slides, rocks, slide-rocks, flies or overturns (the complete block, by default), or
Housner's (1963) block whose pivot never slips; its events, its rest and its energy balance."""

import json
import math
import pathlib
import time
import warnings

from ._common import (UsageError, checked, clean, describe_record, number, positive, read, record_arguments,
                      record_fields, save_figure)
from ..core import simulate
from ..excitation import pga_factor, unit_factor
from ..rocking import FreeStandingBlock, PainleveWarning
from ..units import STANDARD_GRAVITY

#: the backends that run a RockingBlock ("compiled": one that rocks; "exact": the linearised one)
BACKENDS = ("cvode", "ida", "jax", "compiled", "exact")
#: the backends that run the complete block (FreeStandingBlock)
COMPLETE_BACKENDS = ("compiled", "cvode", "ida", "jax")
#: the complete block's kinds of event (:class:`~blockdae.rocking.FreeEvent`), in the report's order
EVENT_KINDS = ("release", "uplift", "slide", "slip", "lift", "stick", "reverse", "apex", "return", "beyond_alpha",
               "land", "chatter", "impact", "zeno", "rest", "overturn")


def add_rocking_parser(subparsers):
    """The ``rocking`` subcommand on an argparse ``subparsers`` object."""
    p = subparsers.add_parser("rocking", help="a free-standing block under a horizontal record: rest, slide, rock, "
                                              "slide-rock, flight with impacts, or overturn")
    p.add_argument("record", type=pathlib.Path, help="horizontal base acceleration (CSV t,a / one column / .AT2)")
    p.add_argument("--b", type=positive("--b"), required=True, help="half-width b of the block [m]")
    p.add_argument("--h", type=positive("--h"), required=True, help="half-height h of the block [m]")
    p.add_argument("--mu", type=number("--mu", lambda x: math.isfinite(x) and x >= 0, "a finite number >= 0"),
                   required=True, help="(static) friction coefficient at the base [-] (below b/h the block slides; "
                                       "linearised: below alpha)")
    p.add_argument("--mu-kinetic", type=number("--mu-kinetic", lambda x: math.isfinite(x) and x >= 0,
                                               "a finite number >= 0"), default=None,
                   help="kinetic friction coefficient [-], at most --mu (complete block; default --mu)")
    p.add_argument("--contact", choices=("complete", "housner"), default=None,
                   help="complete: the block's corners may slip and lift, impacts are plastic with friction (backends "
                        "compiled, cvode, ida, jax); housner: its pivot never slips or lifts, Housner's restitution "
                        "(also exact). Default: complete, unless --linearised, --restitution, --strict or --backend "
                        "exact asks for housner")
    p.add_argument("--restitution", type=number("--restitution", lambda x: 0 <= x <= 1, "in [0, 1]"), default=None,
                   help="ratio of angular velocities through an impact [-] (housner; default Housner's 1 - 1.5 "
                        "sin² alpha)")
    p.add_argument("--linearised", action="store_true",
                   help="the linearised block (housner; slender, small rotations)")
    p.add_argument("--pga", type=positive("--pga"), default=None, metavar="PGA_G",
                   help="scale the record so that its peak |a| is PGA_G [g]")
    p.add_argument("--g", type=positive("--g"), default=STANDARD_GRAVITY,
                   help="gravitational acceleration [m/s²], also the unit 'g' (default 9.80665)")
    p.add_argument("--t-end", type=positive("--t-end"), default=None,
                   help="final time [s] (default: until the block rests or overturns after the record)")
    p.add_argument("--backend", choices=BACKENDS, default=None,
                   help="solver backend (default: compiled for the complete block; for Housner's block that rocks: "
                        "exact with --linearised, else compiled; cvode for one that slides)")
    p.add_argument("--strict", action="store_true",
                   help="housner: stop with an error where the contact force leaves its limits (N <= 0 or |F| > mu "
                        "N) rather than list them")
    record_arguments(p)
    p.add_argument("--plot", type=pathlib.Path, default=None, metavar="PNG", help="save a figure (bd.plot)")
    p.add_argument("--json", action="store_true", help="print the results as JSON (SI units)")
    p.set_defaults(command=run_rocking)
    return p


def run_rocking(args) -> int:
    """Run the block that ``args`` describe; print what it did; the exit status."""
    contact = contact_model(args)
    if args.units is not None:
        checked(lambda: unit_factor(args.units), "--units")
    record = read(args.record, args)
    factor = 1.0
    if args.pga is not None:
        factor = checked(lambda: pga_factor(record.peak_acceleration, args.pga, args.g, name="--pga",
                                            check_peak=not args.accept_peak), str(args.record))
        record = record.scaled(factor)
    housner = dict(restitution=args.restitution, linearised=args.linearised, strict=args.strict) \
        if contact == "housner" else {}
    with warnings.catch_warnings(record=True) as caught:  # printed with the block
        warnings.simplefilter("always", PainleveWarning)
        block = checked(lambda: FreeStandingBlock(b=args.b, h=args.h, mu=args.mu, mu_kinetic=args.mu_kinetic,
                                                  g=args.g, contact=contact, **housner), "")
    exact = contact == "housner" and block.linearised and not block.slides  # the closed form
    backend = args.backend or ("exact" if exact else block.default_backend)
    start = time.perf_counter()
    solution = checked(lambda: simulate(block, record, t_end=args.t_end, backend=backend), str(args.record))
    wall = time.perf_counter() - start
    fields, lines = REPORTS[contact]
    if args.plot is not None:
        from .._plot import plot

        kinetic = f", mu_k = {block.friction_kinetic:g}" if contact == "complete" else ""
        save_figure(plot(solution, title=f"{record.name}: b = {block.b:g} m, h = {block.h:g} m, mu = {block.mu:g}"
                                         f"{kinetic}"), args.plot)
    if args.json:
        print(json.dumps({**record_fields(record), "scale": factor, "contact": contact, "b_m": block.b,
                          "h_m": block.h, "mu": block.mu, "alpha_rad": block.alpha, "p_rad_s": block.frequency,
                          "backend": solution.backend, "t_end_s": clean(solution.t_end),
                          "max_theta_over_alpha": solution.max_theta_over_alpha, "overturned": solution.overturned,
                          "overturn_time_s": _finite_or_none(solution.overturn_time),
                          "rest_time_s": _finite_or_none(solution.rest_time), **fields(block, solution),
                          "wall_time_s": wall}, indent=2))
        return 0
    print(f"record: {describe_record(record)}")
    if factor != 1.0:
        print(f"scaled by {factor:.6g} [-] to a peak of {record.peak_acceleration / block.g:.6g} g")
    for warning in caught:
        print(f"warning: {warning.message}")
    print("\n".join(lines(block, solution)))
    print(f"time: {wall:.3f} s (wall clock of the simulation, including compilation on a first call)")
    if args.plot is not None:
        print(f"figure: {args.plot}")
    return 0


def _finite_or_none(x):
    return x if math.isfinite(x) else None


def _housner_fields(block, solution) -> dict:
    """Housner's block in the JSON: its restitution, regime, impacts and contact limits."""
    return {"restitution": block.r, "linearised": block.linearised, "regime": "slide" if block.slides else "rock",
            "displacement": solution.displacement, "time_beyond_alpha_s": _finite_or_none(solution.time_beyond_alpha),
            "impacts": [{"t_s": e.t, "theta_rate_before_rad_s": e.rate, "theta_rate_after_rad_s": e.rate_after}
                        for e in solution.impacts],
            "contact_limits": [{"t_s": c.t, "kind": c.kind, "theta_rad": c.theta, "theta_rate_rad_s": c.theta_rate,
                                "F_m_s2": c.force, "N_m_s2": c.normal} for c in solution.contact_events]}


def _housner_lines(block, solution) -> list:
    """Housner's block in the text: the block, the backend, what it did, where its contact
    force left its limits."""
    lines = [f"block (Housner's contact): b = {block.b:g} m, h = {block.h:g} m, alpha = {block.alpha:.6f} rad, "
             f"p = {block.frequency:.6f} rad/s, r = {block.r:.6f}, mu = {block.mu:g} "
             f"({'slides' if block.slides else 'rocks'}: mu {'<' if block.slides else '>='} "
             f"{'alpha' if block.linearised else 'b/h'} = {block.rocking_threshold:.6g})"
             f"{'; linearised' if block.linearised else ''}",
             f"backend {solution.backend}; t_end = {solution.t_end:.4f} s"]
    if block.slides:
        return lines + [f"slides: u(t_end) = {solution.displacement:+.6f} m, {len(solution.events)} events"]
    lines.append(f"max |theta| / alpha = {solution.max_theta_over_alpha:.6f} [-]; impacts located: "
                 f"{len(solution.impacts)}")
    if solution.overturned:
        lines.append(f"overturned at t = {solution.overturn_time:.6f} s (|theta| passed alpha at "
                     f"t = {solution.time_beyond_alpha:.6f} s)")
    elif math.isfinite(solution.rest_time):
        lines.append(f"at rest from t = {solution.rest_time:.6f} s (the last tail of impacts summed: "
                     f"{solution.zeno_tail:.3e} s)")
    if solution.contact_events:
        lines.append(f"contact limits: {len(solution.contact_events)} (Housner's pivot holds through them; the "
                     "complete block would slip or lift there: --contact complete)")
        lines += [f"  {limit}" for limit in solution.contact_events]
    return lines


def _complete_fields(block, solution) -> dict:
    """The complete block in the JSON: its kinetic friction, slip, events and energy balance."""
    return {"mu_kinetic": block.friction_kinetic, "final_slip_m": solution.final_slip,
            "event_counts": {kind: len(solution.events_of(kind)) for kind in EVENT_KINDS},
            "events": [{"t_s": e.t, "kind": e.kind, "mode_before": str(e.mode_before),
                        "mode_after": str(e.mode_after), "theta_rad": e.state[2],
                        "theta_rate_before_rad_s": e.state[5], "theta_rate_after_rad_s": e.state_after[5]}
                       for e in solution.events],
            "energy_residual_J_kg": solution.energy_residual, "energy_scale_J_kg": solution.energy_scale}


def _complete_lines(block, solution) -> list:
    """The complete block in the text: the block, the backend, its events, its slip and its
    energy balance."""
    counts = {kind: len(solution.events_of(kind)) for kind in EVENT_KINDS}
    lines = [f"block (complete contact): b = {block.b:g} m, h = {block.h:g} m, b/h = {block.slenderness_ratio:.6g}, "
             f"alpha = {block.alpha:.6f} rad, p = {block.frequency:.6f} rad/s, mu = {block.mu:g}, "
             f"mu_k = {block.friction_kinetic:g} [-]",
             f"backend {solution.backend}; t_end = {solution.t_end:.4f} s",
             "events: " + (", ".join(f"{kind} {n}" for kind, n in counts.items() if n) or "none")]
    lines += [f"  t = {event.t:.6f} s  {event.kind:<12} {str(event.mode_before):<18} -> {event.mode_after}"
              for event in solution.events]
    lines.append(f"max |theta| / alpha = {solution.max_theta_over_alpha:.6f} [-]; slip at t_end = "
                 f"{solution.final_slip:+.6f} m; impacts: {len(solution.impacts)}")
    if solution.overturned:
        lines.append(f"overturned at t = {solution.overturn_time:.6f} s")
    elif math.isfinite(solution.rest_time):
        lines.append(f"at rest from t = {solution.rest_time:.6f} s")
    return lines + [f"energy balance: residual {solution.energy_residual:.3e} J/kg of a scale "
                    f"{solution.energy_scale:.3e} J/kg"]


#: each contact's JSON fields and text lines
REPORTS = {"complete": (_complete_fields, _complete_lines), "housner": (_housner_fields, _housner_lines)}


def contact_model(args) -> str:
    """"complete" or "housner": --contact, or by default the complete block unless an option
    only Housner's block has asks for it (a UsageError where --contact complete meets one)."""
    options = (("--linearised", args.linearised), ("--restitution", args.restitution is not None),
               ("--strict", args.strict), (f"--backend {args.backend}", args.backend not in (None, *COMPLETE_BACKENDS)))
    housner_only = [flag for flag, given in options if given]
    if args.contact == "complete" and housner_only:
        raise UsageError(f"--contact complete: {', '.join(housner_only)} applies to Housner's block only "
                         "(--contact housner)")
    return args.contact or ("housner" if housner_only else "complete")
