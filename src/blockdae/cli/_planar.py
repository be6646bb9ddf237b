"""``blockdae run`` on two or three components: a :class:`~blockdae.PlanarBlock` under
``--y``/``--z`` files or a table of time [s], a_x, a_y[, a_z]."""

import json
import time

from ._common import UsageError, checked, describe_gravity, describe_record, read_options, reader_warnings, save_figure
from ..core import simulate
from ..units import length_units
from ..excitation import BaseMotion, Record, read_motion, record_name
from ..motions import baseline_corrected
from ..planar import PlanarBlock

#: the backend of a planar run unless --backend names one: IDA follows turning slides
PLANAR_BACKEND = "ida"


def read_motion_argument(args):
    """The base motion of ``run``'s files: ``args.record`` (x, or a table of 2-3
    components) with ``--y``, ``--z``, resampled to ``--resample`` [s] if given, each
    component corrected as ``--baseline`` says; errors name the file (and line)."""
    paths = {"record": args.record, "--y": args.y, "--z": args.z}
    for flag, path in paths.items():
        if path is not None and not path.is_file():
            raise UsageError(f"{path}: no such file" if flag == "record" else f"argument {flag}: {path}: no such file")
    try:
        with reader_warnings(args):
            motion = read_motion(args.record, args.y, args.z, resample_dt=args.resample, **read_options(args))
        if args.baseline == "none":
            return motion
        return BaseMotion(*(None if c is None else baseline_corrected(c, args.baseline) for c in motion.components))
    except (ValueError, OSError) as err:
        message, named = str(err), [(path, axis) for path, axis in zip(paths.values(), "xyz") if path]
        if any(str(path) in message for path, _ in named):  # a reader's error names its file (and line)
            raise UsageError(message) from None
        raise UsageError(", ".join(f"{path} ({axis})" for path, axis in named) + f": {message}") from None


def is_planar(motion) -> bool:
    """Whether ``motion`` has a second horizontal or a vertical component."""
    return motion.y is not None or motion.z is not None


def x_record(motion, path):
    """The x component of a one-component motion as :func:`read_record` names it (:func:`record_name`)."""
    x = motion.x
    return Record(x.acceleration_samples, x.dt, record_name(path), x.start_time, units="m/s2", check_peak=False)


def planar_block(args):
    """The PlanarBlock of ``run``'s arguments; --bias is b_x, --bias-y b_y."""
    if args.direction != "both":
        raise UsageError(f"argument --direction: {args.direction!r} applies to one component only; "
                         "a block on a plane slides in any direction")
    try:
        return PlanarBlock(mu=args.mu, mu_kinetic=args.mu_kinetic, bias=(args.bias, args.bias_y), g=args.g)
    except ValueError as err:
        message = str(err)
        flags = {"mu_kinetic": "--mu-kinetic", "mu": "--mu", "bias": "--bias/--bias-y", "g": "--g"}
        flag = next((flag for field, flag in flags.items() if message.startswith(field)), None)
        raise UsageError(f"argument {flag}: {message}" if flag else message) from None


def run_planar(args, motion, print_events):
    """Slide a PlanarBlock under ``motion``; print (u_x, u_y)(t_end) [m], max |u| [m] and the events
    (lengths in g s² where --g is 1, a dimensionless set-up)."""
    block = planar_block(args)
    backend = args.backend or PLANAR_BACKEND
    start = time.perf_counter()
    solution = checked(lambda: simulate(block, motion, t_end=args.t_end, backend=backend), f"{args.record}")
    wall = time.perf_counter() - start
    if args.plot is not None:
        from .._plot import plot

        save_figure(plot(solution, title=f"{args.record.name}: mu = {args.mu}"), args.plot)
    u_x, u_y = solution.displacement
    length = length_units(block.g)[0]
    if args.json:
        print(json.dumps(_json(motion, block, solution, wall), indent=2))
        return 0
    if args.quiet:
        print(f"({u_x:+.6f}, {u_y:+.6f}) {length}")
        return 0
    for axis, component in zip("xyz", motion.components):
        if component is not None:
            print(f"record {axis}: {describe_record(component, block.g)}")
    print(f"block on a plane: mu = {block.mu:g}, f = {block.friction_kinetic:g}, bias (b_x, b_y) = "
          f"({block.bias[0]:g}, {block.bias[1]:g}) [-], {describe_gravity(block.g)}; backend {solution.backend}")
    print(f"final time t_end = {solution.t_end:.4f} s"
          + (" (block at rest after the record)" if args.t_end is None else ""))
    print(f"permanent displacement (u_x, u_y)(t_end) = ({u_x:+.6f}, {u_y:+.6f}) {length}")
    print(f"max |u| = {solution.max_abs_displacement:.6f} {length}")
    print(f"events: {len(solution.events)} (direction: of the relative velocity just before the event, "
          "blank where the block was at rest; slide: of the slide it starts or ends; degrees from +x)")
    print_events(solution, args.events)
    print(f"time: {wall:.3f} s (wall clock)")
    if args.plot is not None:
        print(f"figure: {args.plot}")
    return 0


def _json(motion, block, solution, wall):
    components = {axis: None if c is None else {"record": c.name, "n_samples": int(c.acceleration_samples.size),
                                                "dt_s": c.dt, "peak_acceleration_m_s2": c.peak_acceleration}
                  for axis, c in zip("xyz", motion.components)}
    return {
        "components": components, "mu": block.mu, "mu_kinetic": block.friction_kinetic,
        "bias": list(block.bias), "g_m_s2": block.g, "backend": solution.backend,
        "displacement_m": solution.displacement.tolist(), "max_abs_displacement_m": solution.max_abs_displacement,
        "t_end_s": solution.t_end, "wall_time_s": wall,
        "events": [{"t_s": e.t, "from": e.mode_before.name, "to": e.mode_after.name, "u_x_m": e.u_x, "u_y_m": e.u_y,
                    "direction_deg": e.direction, "slide_deg": slide}
                   for e, slide in zip(solution.events, solution.slide_directions())],
    }
