"""Every available backend on identical cases, against the exact backend.

Cases: the seed-000 examples and pySLAMMER's 18 sample records, one-way and two-way,
with kinetic below static friction and with a bias R/Q. Per backend and case: wall
time of the first call (compilation included) and warm, and the differences of the
displacement and event times from the exact backend. Backends not registered yet are
named and skipped.

    python benchmarks/backends.py [--quick] [--backends exact cvode ...] [--cache-dir DIR]
"""

import argparse
import sys

import numpy as np

import blockdae as bd
from _common import G, enable_compilation_cache, print_table, sample_records, timed

#: backends the project plans; those not in ``bd.backends.available()`` are reported missing
PLANNED = ("exact", "cvode", "ida", "jax")


def cases(quick=False):
    """(label, block, motion, t_end [s] or None) for every comparison."""
    examples = bd.sliding.seed_examples()
    if quick:
        examples = [e for e in examples if e.name in ("Example 1", "Example 5")]
    out = [(e.name, e.block, e.motion, e.t_end) for e in examples]
    for record in sample_records(quick):
        mu = 0.5 * record.peak_acceleration / G
        variants = {"one-way": bd.SlidingBlock(mu, direction="negative", g=G),
                    "two-way": bd.SlidingBlock(mu, g=G),
                    "f<mu": bd.SlidingBlock(mu, mu_kinetic=0.75 * mu, g=G),
                    "bias": bd.SlidingBlock(mu, bias=0.25 * mu, g=G)}
        if quick:
            variants = {k: variants[k] for k in ("one-way", "bias")}
        out += [(f"{record.name} {label}", block, record, None) for label, block in variants.items()]
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="2 seed examples, 1 record (smoke run)")
    parser.add_argument("--backends", nargs="+", default=None, help="names (default: all available)")
    parser.add_argument("--repeat", type=int, default=3, help="warm repetitions (median) per timing")
    parser.add_argument("--cache-dir", default=None, help="JAX persistent compilation cache folder")
    args = parser.parse_args(argv)
    enable_compilation_cache(args.cache_dir)
    available = bd.backends.available(bd.SlidingBlock(0.2))
    names = tuple(args.backends or available)
    missing = [n for n in (*names, *PLANNED) if n not in available]
    if missing:
        print(f"note: backend(s) {', '.join(sorted(set(missing)))} not available in this build "
              f"(available: {', '.join(available)}); skipped")
    names = tuple(n for n in names if n in available)
    repeat = 1 if args.quick else args.repeat
    all_cases = cases(args.quick)
    reference = _compare_backend("exact", all_cases, None, repeat)
    for name in names:
        if name != "exact":
            _compare_backend(name, all_cases, reference, repeat)
    _crosscheck(names, all_cases)
    return 0


def _compare_backend(name, all_cases, reference, repeat):
    """Print one backend's table; returns its solutions by case label.

    ``reference``: the exact backend's solutions, or None for the exact backend itself.
    The first call of a case compiles only where its kernel shape is new to this process.
    """
    against = "the reference" if reference is None else "differences from 'exact'"
    print(f"\nbackend {name!r} (warm: median of {repeat}; {against})")
    rows, du, dt, solutions = [], [], [], {}
    for label, block, motion, t_end in all_cases:
        try:
            solution, first, warm = timed(lambda: bd.simulate(block, motion, t_end, backend=name), repeat)
        except Exception as err:  # a backend under construction: report, go on
            rows.append((label, "failed", "-", "-", "-", f"{type(err).__name__}: {str(err)[:40]}"))
            continue
        solutions[label] = solution
        timing = (label, str(len(solution.events)), f"{first:.3f}", f"{1e3 * warm:.2f}")
        if reference is None:
            rows.append(timing + (f"{solution.displacement:+.6f}", "-"))
            continue
        ref = reference.get(label)
        if ref is None:
            rows.append(timing + ("no reference", "-"))
            continue
        du.append(abs(solution.displacement - ref.displacement))
        rows.append(timing + (f"{du[-1]:.2e}", _event_difference(solution, ref, dt)))
    last = "u [m]" if reference is None else "|du| [m]"
    print_table(["case", "events", "first call [s]", "warm [ms]", last, "max |dt_event| [s]"], rows)
    if du:
        worst_t = f"{max(dt):.2e} s" if dt else "n/a"
        print(f"largest |du| = {max(du):.2e} m, largest event-time difference = {worst_t}")
    return solutions


def _event_difference(solution, ref, collected):
    if len(solution.events) != len(ref.events):
        return f"{len(solution.events)} vs {len(ref.events)} events"
    if not solution.events:
        return "0"
    worst = float(np.max(np.abs(solution.t_events - ref.t_events)))
    collected.append(worst)
    return f"{worst:.2e}"


def _crosscheck(names, all_cases):
    """The project's own cross-check table, where ``bd.crosscheck`` exists."""
    if not hasattr(bd, "crosscheck"):
        print("\nnote: bd.crosscheck is not in this build; the tables above compare the backends directly")
        return
    for label, block, motion, t_end in all_cases:
        print(f"\ncrosscheck: {label}")
        runs = [n for n in names if bd.backends.make_backend(n).runs(block)]  # "compiled": planar blocks only
        print(bd.crosscheck(block, motion, t_end=t_end, backends=runs))


if __name__ == "__main__":
    sys.exit(main())
