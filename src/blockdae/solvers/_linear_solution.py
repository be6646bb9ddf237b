"""The compiled linear engine (:mod:`._linear`) behind the exact backend: a model's
solution from its knot log, with dense output in closed form, and final numbers over
many excitations, parameter sets and scales."""

import numpy as np

from ..core import SolverError, notice_numba
from . import _linear

#: knot-log rows per piece of a(t) at the start (one per piece, one per event, grown
#: if a run needs more)
_ROWS_PER_PIECE = 2


def linear_pieces(excitation, t_end):
    """The pieces of ``excitation`` up to ``t_end`` [s] as the engine's arrays, or None
    where a piece is a sine (the Python closed-form path takes those)."""
    pieces = excitation.pieces(t_end)
    if pieces.has_sine:
        return None
    return pieces, tuple(np.ascontiguousarray(x, dtype=float) for x in (pieces.t0, pieces.h, pieces.p0, pieces.p1))


def solve_linear_compiled(model, pieces, arrays, name):
    """``model`` (its ``linear_modes()``) over the linear ``pieces`` (``arrays`` from
    :func:`linear_pieces`): the model's solution, events located to adjacent floats."""
    run, _ = _linear.kernels()
    notice_numba("the linear engine", 5, run)
    tables = model.linear_modes()
    capacity = _ROWS_PER_PIECE * len(pieces.t0) + 8
    while True:
        log = np.empty((capacity, 6))
        outcome, n_rows = run(*arrays, 1.0, *tables.arrays(), tables.initial_mode, log)
        if outcome[7] != _linear.LOG_FULL:
            break
        capacity *= 4
    log = log[:n_rows]
    _check(outcome, model)
    t, u, u_rate, mode, before, is_event = log.T
    mode, before = mode.astype(int), before.astype(int)
    events = tuple(model.event(float(t[i]), model.modes(before[i]), model.modes(mode[i]), log[i, 1:3])
                   for i in np.flatnonzero(is_event))
    dense = LinearDense(pieces, tables, t, u, u_rate, mode)
    stats = {"max_events_at_one_instant": int(outcome[8]), "n_events": len(events), "n_knots": len(t)}
    return model.solution(t=t, y=np.column_stack([u, u_rate]), mode=mode, events=events, backend=name,
                          dense=dense, stats=stats)


def _check(outcome, model, where=""):
    """Raise as the Python path does: chatter, or a root search that did not settle."""
    status = int(outcome[7])
    if status == _linear.CHATTER:
        raise RuntimeError(f"more than {_linear.MAX_EVENTS_AT_ONE_INSTANT} events at t = {outcome[5]:.12g} s or "
                           f"later within {_linear.EVENT_RESOLUTION:g} s{where}: chatter of the "
                           f"{type(model).__name__}")
    if status == _linear.UNSETTLED:
        raise SolverError(f"a guard's root search did not settle in {_linear.MAX_INTERVALS} intervals{where} "
                          f"(a degenerate touch of zero); use backend 'cvode' or 'ida'")


class LinearDense:
    """The state between knots in closed form: from each knot (a piece start or an event)
    the mode's solution under the piece's a(t); ``__call__(t)`` -> (u [m], u' [m/s])."""

    def __init__(self, pieces, tables, t, u, u_rate, mode):
        self.pieces, self.tables = pieces, tables
        self.t, self.u, self.u_rate, self.mode = t, u, u_rate, mode

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        i = np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, len(self.t) - 1)
        knot = self.t[i]
        j = np.clip(np.searchsorted(self.pieces.t0, knot, side="right") - 1, 0, len(self.pieces.t0) - 1)
        p1 = self.pieces.p1[j]
        p0 = self.pieces.p0[j] + p1 * (knot - self.pieces.t0[j])
        mode = self.mode[i]
        k, c, b = self.tables.stiffness[mode], self.tables.damping[mode], self.tables.offset[mode]
        return _closed_form(k, c, b, p0, p1, self.u[i], self.u_rate[i], t - knot)


def _closed_form(k, c, b, p0, p1, u, v, tau):
    """(u, u') at ``tau`` [s] of u'' + c u' + k u = b - (p0 + p1 tau) from (u, v), elementwise
    (the engine's ``_solve`` for arrays)."""
    oscillator = k > 0
    k_safe = np.where(oscillator, k, 1.0)
    sigma = 0.5 * c
    w = np.sqrt(np.where(oscillator, k_safe - sigma**2, 1.0))
    a1 = -p1 / k_safe
    a0 = (b - p0 - c * a1) / k_safe
    C = u - a0
    D = (v - a1 + sigma * C) / w
    decay = np.exp(-sigma * tau)
    cos, sin = np.cos(w * tau), np.sin(w * tau)
    u_osc = a0 + a1 * tau + decay * (C * cos + D * sin)
    v_osc = a1 + decay * ((-sigma * C + w * D) * cos + (-sigma * D - w * C) * sin)
    q2, q3 = 0.5 * (b - p0), -p1 / 6.0
    u_free = u + v * tau + q2 * tau**2 + q3 * tau**3
    v_free = v + 2 * q2 * tau + 3 * q3 * tau**2
    return np.where(oscillator, u_osc, u_free), np.where(oscillator, v_osc, v_free)


def solve_linear_final(models, excitations, t_end, scale=(1.0,)):
    """Final numbers (``_linear.OUTCOME_FIELDS``) of every excitation under every model
    (a sequence of models with ``linear_modes()`` of one shape) at every factor of
    ``scale`` [-] on a(t), in one compiled call parallel over cores.

    Returns:
        (len(excitations), len(models) * len(scale), len(OUTCOME_FIELDS)); model j at
        factor s in column j * len(scale) + s.
    """
    inputs = []
    for excitation in excitations:
        found = linear_pieces(excitation, t_end)
        if found is None:
            raise ValueError("the compiled linear engine takes records (linear pieces); "
                             f"{type(excitation).__name__} has sine pieces")
        inputs.append(found[1])
    offsets = np.concatenate([[0], np.cumsum([len(x[0]) for x in inputs])]).astype(np.int64)
    columns = [np.concatenate([x[i] for x in inputs]) for i in range(4)]
    tables = [m.linear_modes() for m in models]
    stacked = tuple(np.stack([getattr(tb, f) for tb in tables])
                    for f in ("stiffness", "damping", "offset", "guards", "next_mode", "resets"))
    stacked += (np.array([tb.initial_mode for tb in tables], dtype=np.int64),)
    _, run_batch = _linear.kernels()
    notice_numba("the linear engine", 5, run_batch)
    out = run_batch(*columns, offsets, np.asarray(scale, dtype=float).ravel(), stacked)
    for e, j in zip(*np.nonzero(out[:, :, 7] != _linear.FINISHED)):
        _check(out[e, j], models[j // len(scale)], f" (excitation {e}, column {j})")
    return out


def simulate_linear_final(models, motions, t_end, scale=(1.0,)):
    """Final numbers of every model under every motion at every factor on a(t), in one
    compiled call parallel over cores (models whose ``engines`` name the "linear" engine,
    e.g. :class:`~blockdae.SpringSupportedMass` over a grid of frequencies and damping).

    Args:
        models: a sequence of models of one kind (each with ``linear_modes()``).
        motions: records (linear pieces), or a dict name -> record.
        t_end: final time [s] of every run.
        scale: factors [-] on a(t).

    Returns:
        A pandas DataFrame, one row per motion × model × scale: motion, model (index into
        ``models``), scale [-], u_m and u_rate_m_s at t_end [m, m/s], mode (the model's
        mode name at t_end), n_events, max_u_at_events_m (largest u at an event [m]: for a
        spring-supported mass the highest top), t_first_event_s [s] and
        u_rate_first_event_m_s [m/s] (nan without events).
    """
    import pandas as pd

    models = list(models)
    if not models or any(getattr(m, "engines", {}).get("exact") != "linear" for m in models):
        raise ValueError("models must be a non-empty sequence of models on the linear engine "
                         "(engines['exact'] == 'linear', e.g. SpringSupportedMass)")
    names = list(motions) if isinstance(motions, dict) else [getattr(m, "name", "") or f"motion {i}"
                                                             for i, m in enumerate(motions)]
    records = list(motions.values()) if isinstance(motions, dict) else list(motions)
    scale = np.asarray(scale, dtype=float).ravel()
    out = solve_linear_final(models, records, float(t_end), scale)
    rows = out.reshape(-1, out.shape[-1])
    table = pd.DataFrame({
        "motion": np.repeat(names, len(models) * len(scale)),
        "model": np.tile(np.repeat(np.arange(len(models)), len(scale)), len(records)),
        "scale": np.tile(scale, len(records) * len(models)),
        "u_m": rows[:, 0], "u_rate_m_s": rows[:, 1],
        "mode": [models[0].modes(int(m)).name for m in rows[:, 2]],
        "n_events": rows[:, 3].astype(int), "max_u_at_events_m": rows[:, 4],
        "t_first_event_s": rows[:, 5], "u_rate_first_event_m_s": rows[:, 6]})
    return table
