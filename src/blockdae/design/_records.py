"""The record set of a design study: names, records and each one's target PGA."""

import math

from ..excitation import BaseMotion, Record


def record_set(records, pga, model=None):
    """[(name, record, target PGA [g] or None)] of ``records`` (a Record, a sequence or a
    dict name -> Record; BaseMotions of Records too where ``model`` takes them: its
    ``MOTIONS``) and ``pga`` (None: as given; a number: every record; a dict name ->
    number: each record its own; a BaseMotion only as given)."""
    kinds = getattr(model, "MOTIONS", (Record,))
    if isinstance(records, (Record, BaseMotion)):
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
        if not isinstance(record, kinds):
            raise ValueError(f"record {name!r} must be a {' or a '.join(k.__name__ for k in kinds)}, got "
                             f"{type(record).__name__}")
        if isinstance(record, BaseMotion) and not all(isinstance(c, (Record, type(None))) for c in record.components):
            raise ValueError(f"record {name!r}: a BaseMotion of Records (its components {record.components!r})")
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
        if target is not None and isinstance(record, BaseMotion):
            raise ValueError(f"pga={target!r} for record {name!r}: a target PGA scales a record of one component; "
                             "give a BaseMotion at its own amplitude (pga=None)")
    return [(n, r, None if t is None else float(t)) for n, r, t in zip(names, values, targets)]
