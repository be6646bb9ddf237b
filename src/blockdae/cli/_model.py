"""``blockdae run --model package.module:Class --param name=value ... RECORD``: any model of
the contract (a user's own, or a built-in one) on any record and backend, with the table
and JSON of the built-in commands."""

import importlib
import importlib.util
import json
import pathlib
import time

from ._common import (UsageError, checked, clean, describe_record, print_run_end, record_fields, save_figure,
                      write_csv)
from ._planar import read_motion_argument, x_record
from ..core import AbstractHybridModel, simulate, state_columns


def parameter(text):
    """``name=value`` of --param: (name, a float, or the text where it is no number)."""
    name, sep, value = text.partition("=")
    if not sep or not name.isidentifier():
        raise ValueError(f"{text!r} must be name=value (e.g. mu=0.06)")
    try:
        return name, float(value)
    except ValueError:
        return name, value


def load_model(spec, parameters):
    """The model ``module:Class`` (a module importable by name, or a path to a .py file)
    built from ``parameters`` (name -> value); UsageError naming --model or --param."""
    where, sep, name = spec.rpartition(":")
    if not sep or not where or not name.isidentifier():
        raise UsageError(f"argument --model: {spec!r} must be package.module:Class (or path/to/file.py:Class)")
    try:
        if where.endswith(".py"):
            path = pathlib.Path(where)
            if not path.is_file():
                raise UsageError(f"argument --model: {path}: no such file")
            module_spec = importlib.util.spec_from_file_location(path.stem, path)
            module = importlib.util.module_from_spec(module_spec)
            module_spec.loader.exec_module(module)
        else:
            module = importlib.import_module(where)
    except ImportError as err:
        raise UsageError(f"argument --model: cannot import {where!r}: {err}") from None
    cls = getattr(module, name, None)
    if not (isinstance(cls, type) and issubclass(cls, AbstractHybridModel)):
        raise UsageError(f"argument --model: {where} has no model class {name!r} (a subclass of "
                         "blockdae.AbstractHybridModel)")
    try:
        return cls(**parameters)
    except (TypeError, ValueError) as err:
        raise UsageError(f"argument --param: {name}({', '.join(f'{k}={v!r}' for k, v in parameters.items())}): "
                         f"{err}") from None


def run_model(args, print_events):
    """The ``run`` command with --model: the model under the record (its x component)."""
    parameters = dict(args.param or ())
    model = load_model(args.model, parameters)
    motion = read_motion_argument(args)
    record = x_record(motion, args.record) if len(model.component_names) == 1 else motion
    start = time.perf_counter()
    solution = checked(lambda: simulate(model, record, t_end=args.t_end, backend=args.backend), f"{args.record}")
    wall = time.perf_counter() - start
    if args.plot is not None:
        from .._plot import plot

        save_figure(plot(solution, title=f"{getattr(record, 'name', args.record)}: {args.model}"), args.plot)
    if args.history is not None:
        history = solution.history()
        write_csv(args.history, history.to_dict(orient="records"), list(history.columns))
    if args.json:
        print(json.dumps(_json(args, record, model, parameters, solution, wall), indent=2, default=float))
        return 0
    if args.quiet:
        print(_displacement_text(solution, model.displacement_unit))
        return 0
    print(f"record: {describe_record(record) if hasattr(record, 'dt') else args.record}")
    print(f"model: {args.model} ({_describe(model, parameters)}); backend {solution.backend}")
    print(f"final time t_end = {solution.t_end:.4f} s" + (" (at rest after the record)" if args.t_end is None else ""))
    print(f"displacement at t_end = {_displacement_text(solution, model.displacement_unit)}")
    print(f"max |displacement| = {solution.max_abs_displacement:.6f} {model.displacement_unit}")
    print_run_end(solution, args, wall, print_events)
    return 0


def _units(model):
    """name -> unit of the model's parameters, where it declares them (``parameter_units``)."""
    try:
        return model.parameter_units()
    except (AttributeError, NotImplementedError):
        return {}


def _describe(model, parameters):
    units = _units(model)
    return ", ".join(f"{k} = {v:g}{f' {units[k]}' if units.get(k, '-') != '-' else ''}" if isinstance(v, float)
                     else f"{k} = {v}" for k, v in parameters.items()) or "its defaults"


def _displacement_text(solution, unit):
    """The displacement at t_end in ``unit`` (the model's ``displacement_unit``)."""
    u = solution.displacement
    return f"{u:+.6f} {unit}" if isinstance(u, float) else "(" + ", ".join(f"{x:+.6f}" for x in u) + f") {unit}"


def _json(args, record, model, parameters, solution, wall):
    fields = record_fields(record) if hasattr(record, "dt") else {"record": str(args.record)}
    names = state_columns(model)
    u = solution.displacement
    return {
        **fields, "model": args.model, "parameters": parameters, "parameter_units": _units(model),
        "backend": solution.backend, "u_end_m": u if isinstance(u, float) else [float(x) for x in u],
        "max_abs_displacement_m": solution.max_abs_displacement, "t_end_s": clean(solution.t_end),
        "wall_time_s": wall,
        "events": [{"t_s": e.t, "from": e.mode_before.name, "to": e.mode_after.name,
                    **dict(zip(names, map(float, getattr(e, "state", ()))))} for e in solution.events],
    }
