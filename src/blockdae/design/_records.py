"""The record set of a design study: names, records and each one's target PGA."""

import math

from ..excitation import Record


def record_set(records, pga):
    """[(name, record, target PGA [g] or None)] of ``records`` (a Record, a sequence or a
    dict name -> Record) and ``pga`` (None: as given; a number: every record; a dict
    name -> number: each record its own)."""
    if isinstance(records, Record):
        records = [records]
    if isinstance(records, dict):
        names, values = list(records), list(records.values())
    else:
        values = list(records)
        names = [getattr(r, "name", None) or f"motion {i}" for i, r in enumerate(values)]
    if not values:
        raise ValueError("records holds no record: give a Record, or a sequence or dict of them")
    if len(set(names)) != len(names):
        raise ValueError(f"the records' names must differ (give a dict name -> Record), got {names}")
    for name, record in zip(names, values):
        if not isinstance(record, Record):
            raise ValueError(f"record {name!r} must be a Record, got {type(record).__name__}")
    if isinstance(pga, dict):
        unknown = set(pga) - set(names)
        missing = [n for n in names if n not in pga]
        if unknown or missing:
            raise ValueError(f"pga must give a target PGA [g] for each record: missing {missing}, unknown "
                             f"{sorted(unknown)}")
        targets = [pga[n] for n in names]
    else:
        targets = [pga] * len(names)
    for name, target in zip(names, targets):
        if target is not None and not (isinstance(target, (int, float)) and not isinstance(target, bool)
                                       and math.isfinite(target) and target > 0):
            raise ValueError(f"pga={target!r} for record {name!r} must be a target PGA > 0 [g] (or None)")
    return [(n, r, None if t is None else float(t)) for n, r, t in zip(names, values, targets)]
