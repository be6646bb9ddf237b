"""Run one case on several backends and compare them with the exact one."""

import dataclasses
import time

import numpy as np

from ._sensitivities import derivative_unit, finite_differences, sensitivities
from ._simulate import simulate
from ._registry import AbstractBackend, backend_name, make_backend
from .contract import AbstractHybridModel, DifferentiableModel
from ._repr import compact_repr

#: the backends a cross-check runs by default, those that run the block, in this order
DEFAULT_BACKENDS = ("exact", "cvode", "ida", "jax")

#: a row agrees while max |dt| <= TIME_BAR * rtol * max(1 s, t_end) and rel |du| <=
#: DISPLACEMENT_BAR * rtol [-]. Measured worst over seed examples 1-6, two sine pulses,
#: the spring-supported mass, Northridge PAC-175, Kobe TAK-090 and the README's planar
#: wave, cvode/ida/jax at rtol 1e-12, 1e-10, 1e-7, 1e-4 and 1e-3: 9.95 rtol s (IDA,
#: spring-supported mass, rtol 1e-12) and 1.7e3 rtol (IDA, seed example 1, rtol 1e-12:
#: u_end is 3 % of max |u|, so its relative difference is large). Each bar is about ten
#: times that, so no sample case disagrees; the tests' 1e-9 s and 1e-7 at rtol 1e-10 are tighter.
TIME_BAR = 100
DISPLACEMENT_BAR = 1e4
#: the rtol [-] of a backend without one ("exact", "exact-jax": exact to rounding)
ROUNDING = float(np.finfo(float).eps)


@dataclasses.dataclass(frozen=True)
class CrossCheck:
    """Per-backend results of one case; ``rows`` is a list of dicts with keys

    backend, displacement [m] (a float, or the model's displacement vector, e.g.
    (u_x, u_y) for a PlanarBlock), n_events, t_events [s] (array), max_dt [s] (largest
    event-time difference against the reference, inf if the event lists differ in
    length or modes), rel_du [-] (|u - u_ref| / |u_ref| (Euclidean norms), or the
    absolute difference [m] when u_ref = 0), first [s] (wall time of the first call, which includes JIT
    compilation when this process has not compiled that shape yet) and warm [s] (of a
    second, identical call); with ``wrt``, also sensitivities (name -> d u / d p, see
    :func:`blockdae.sensitivities`: differentiated kernels for "exact" and "jax", finite
    differences for the others, one-sided at a bound such as mu_kinetic = mu) and
    rel_dsens [-] (largest relative difference of those against the reference's).

    Each row also has rtol [-] (the looser of its backend's and the reference's relative
    tolerance, :data:`ROUNDING` for an exact backend) and agrees (bool): the same events
    and modes as the reference, max_dt <= :data:`TIME_BAR` * rtol * ``span`` and rel_du
    <= :data:`DISPLACEMENT_BAR` * rtol (see :func:`agrees`); the reference row always
    agrees. The derivatives are not judged (finite differences carry their own step
    error), nor is ``atol``: a loose atol that governs the error shows as a disagreement.
    ``span`` [s] is max(1 s, t_end of the reference).
    """

    def __repr__(self):
        return compact_repr(self)

    rows: list
    reference: str
    wrt: tuple = ()
    span: float = 1.0
    block: object = dataclasses.field(default=None, repr=False)

    @property
    def agrees(self) -> bool:
        """Whether every row agrees with the reference within its bar."""
        return not self.disagreements

    @property
    def disagreements(self) -> list:
        """The rows that disagree with the reference beyond their bar."""
        return [row for row in self.rows if not row["agrees"]]

    def row(self, backend) -> dict:
        """The row of ``backend``: its label (a name as given) or the backend object given."""
        label = _label(backend)
        for row in self.rows:
            if row["backend"] == label:
                return row
        raise KeyError(f"backend {label!r} is not in this cross-check")

    def __str__(self):
        width = max(16, max(len(_values(r["displacement"])) for r in self.rows))
        d_width = max([17] + [len(_values(r["sensitivities"][n])) for r in self.rows for n in self.wrt])
        derivative_heads = "".join(f" {f'du/d{name} [{derivative_unit(self.block, name)}]':>{d_width}}"
                                   for name in self.wrt)
        name_width = max(8, max(len(r["backend"]) for r in self.rows))
        head = (f"{'backend':<{name_width}} {'u_end [m]':>{width}} {'events':>6} {'max |dt| [s]':>13} "
                f"{'rel |du| [-]':>13} {'first [s]':>9} {'warm [s]':>9}" + derivative_heads
                + (f" {'rel |dS| [-]':>13}" if self.wrt else "") + f" {'rtol [-]':>8} {'verdict':>9}")
        lines = [head, "-" * len(head)]
        for r in self.rows:
            derivatives = "".join(f" {_values(r['sensitivities'][name], '.10g'):>{d_width}}" for name in self.wrt)
            lines.append(f"{r['backend']:<{name_width}} {_values(r['displacement']):>{width}} {r['n_events']:>6d} "
                         f"{r['max_dt']:>13.2e} {r['rel_du']:>13.2e} {r['first']:>9.3f} {r['warm']:>9.3f}"
                         + derivatives
                         + (f" {r['rel_dsens']:>13.2e}" if self.wrt else "")
                         + f" {r['rtol']:>8.1e} {'ok' if r['agrees'] else 'DISAGREES':>9}")
        return "\n".join(lines) + "\n" + self._footer()

    def _footer(self):
        return (f"(differences against {self.reference!r}; a row DISAGREES where its events or modes differ,\n"
                f" max |dt| [s] > {TIME_BAR:g} rtol × {self.span:.3g} s or rel |du| [-] > {DISPLACEMENT_BAR:g} rtol)")


def crosscheck(block, motion, backends=None, t_end=None, wrt=(), **options) -> CrossCheck | list[CrossCheck]:
    """Solve ``block`` under ``motion`` with each backend (twice: first and warm call)
    and compare with the first backend.

    Args:
        block: the block (a SlidingBlock or another model, e.g. a PlanarBlock); for a
            batch of n parameter sets, each is checked on its own.
        motion: base excitation (for a PlanarBlock also a BaseMotion).
        backends: backend names or backend objects (e.g. ``bd.CVODE(rtol=1e-12)``;
            its row is labelled "cvode(rtol=1e-12)": its name and the settings that
            differ from its defaults); the first is the reference (normally "exact");
            None: those of "exact", "cvode", "ida", "jax" that run the block, in this order.
        t_end: final time [s], or None (until rest after a finite excitation).
        wrt: parameters to differentiate u(t_end) by (see :func:`blockdae.sensitivities`),
            e.g. ("mu", "mu_kinetic", "bias", "A"); none by default (none for a
            SpringSupportedMass, whose derivatives are those of its flights).
        **options: settings passed to every backend given by name that has them (e.g.
            ``rtol``); a backend object runs with its own.

    Returns:
        A :class:`CrossCheck`, or a list of n of them for a batch.
    """
    if not isinstance(block, AbstractHybridModel):
        raise TypeError(f"block must be a model (SlidingBlock, PlanarBlock, SpringSupportedMass), "
                        f"got {type(block).__name__}")
    if backends is None:
        backends = tuple(name for name in DEFAULT_BACKENDS if make_backend(name).runs(block))
    backends = tuple(backends)
    accepted = [set() if isinstance(backend, AbstractBackend) else _fields(make_backend(backend))
                for backend in backends]
    labels = [_label(backend) for backend in backends]
    unknown = set(options) - set().union(*accepted)
    if unknown:
        raise TypeError(f"no backend given by name in {tuple(labels)} takes the option(s) {sorted(unknown)}")
    if wrt and not isinstance(block, DifferentiableModel):
        raise ValueError(f"crosscheck's wrt differentiates u(t_end); a {type(block).__name__} declares no "
                         "derivatives (a bd.core.contract.DifferentiableModel does)")
    if wrt and not block.differentiates_displacement:
        raise ValueError(f"crosscheck's wrt differentiates u(t_end); for a {type(block).__name__} use "
                         "bd.sensitivities(block, motion, t_end, wrt=..., of=...) (the derivatives it has)")
    if block.batch_shape:
        return [crosscheck(block.item(i), motion, backends, t_end, wrt, **options)
                for i in range(block.batch_shape[0])]
    mine = [{key: value for key, value in options.items() if key in fields} for fields in accepted]
    solutions = []
    for backend, settings in zip(backends, mine):
        walls = []
        for _ in range(2):
            start = time.perf_counter()
            solution = simulate(block, motion, t_end=t_end, backend=backend, **settings)
            walls.append(time.perf_counter() - start)
        solutions.append((solution, walls))
    ref = solutions[0][0]
    span = max(1.0, ref.t_end)
    rtols = [_rtol(backend, settings) for backend, settings in zip(backends, mine)]
    rows = [dict(backend=label, displacement=s.displacement, n_events=len(s.events), t_events=s.t_events,
                 max_dt=_max_event_dt(ref, s), rel_du=_relative(s.displacement, ref.displacement),
                 first=first, warm=warm, rtol=max(rtol, rtols[0]))
            for label, (s, (first, warm)), rtol in zip(labels, solutions, rtols)]
    for row in rows:
        row["agrees"] = agrees(row, span)
    if wrt:
        wrt = (wrt,) if isinstance(wrt, str) else tuple(wrt)
        for row, backend, settings in zip(rows, backends, mine):
            differentiated = backend_name(backend) in block.differentiated_backends
            derivative = sensitivities if differentiated else finite_differences
            row["sensitivities"] = derivative(block, motion, t_end=t_end, wrt=wrt, backend=backend, **settings)
        ref_sens = rows[0]["sensitivities"]
        for row in rows:
            row["rel_dsens"] = max(_relative(row["sensitivities"][n], ref_sens[n]) for n in wrt)
    return CrossCheck(rows=rows, reference=labels[0], wrt=tuple(wrt), span=span, block=block)


def agrees(row: dict, span: float) -> bool:
    """Whether ``row`` agrees with the reference: the same events and modes (max_dt [s]
    finite), max_dt <= TIME_BAR * rtol * ``span`` [s] and rel_du [-] <= DISPLACEMENT_BAR
    * rtol, with the row's rtol [-]; ``span`` [s]: max(1 s, t_end of the reference)."""
    return bool(row["max_dt"] <= TIME_BAR * row["rtol"] * span and row["rel_du"] <= DISPLACEMENT_BAR * row["rtol"])


def _rtol(backend, options):
    """The relative tolerance [-] of ``backend`` (a name or an object) under ``options``;
    ROUNDING for one without."""
    return float(getattr(make_backend(backend, **options), "rtol", ROUNDING))


def _fields(backend) -> set:
    """The settings a backend object takes (its dataclass fields; none for another class)."""
    return {f.name for f in dataclasses.fields(backend)} if dataclasses.is_dataclass(backend) else set()


def _label(backend) -> str:
    """A row's label: a name as given; for a backend object its name and the settings
    that differ from its class's defaults, e.g. "cvode(rtol=1e-12)"."""
    if isinstance(backend, str):
        return backend
    fields = dataclasses.fields(backend) if dataclasses.is_dataclass(backend) else ()
    changed = [f"{f.name}={getattr(backend, f.name)!r}" for f in fields
               if f.default is not dataclasses.MISSING and getattr(backend, f.name) != f.default]
    return backend.name + (f"({', '.join(changed)})" if changed else "")


def _max_event_dt(ref, sol):
    same = len(ref.events) == len(sol.events) and all(
        (a.mode_before, a.mode_after) == (b.mode_before, b.mode_after) for a, b in zip(ref.events, sol.events))
    if not same:
        return np.inf
    return float(np.max(np.abs(ref.t_events - sol.t_events), initial=0.0))


def _relative(u, u_ref):
    """|u - u_ref| / |u_ref| (Euclidean norms), or |u - u_ref| when u_ref = 0."""
    difference, size = float(np.linalg.norm(np.subtract(u, u_ref))), float(np.linalg.norm(u_ref))
    return difference / size if size != 0 else difference


def _values(x, spec=".10f"):
    """A number, or a vector as "(a, b)", formatted with ``spec``."""
    x = np.asarray(x, dtype=float)
    return format(float(x), spec) if x.ndim == 0 else "(" + ", ".join(format(v, spec) for v in x) + ")"
