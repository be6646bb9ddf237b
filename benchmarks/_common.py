"""Helpers shared by the benchmark scripts: records, timing, tables."""

import argparse
import importlib.resources
import pathlib
import statistics
import time

import numpy as np

import blockdae as bd

#: what a --quick run says where a full run judges a bar: too few cases, too short to judge
SMOKE_RUN = "smoke run, not a measurement"


def verdict(ok: bool, quick: bool, failed: str = "NOT met") -> str:
    """"met" or ``failed`` for a bar in a full run; in a --quick run :data:`SMOKE_RUN`,
    since its few short cases measure nothing a bar is about."""
    if quick:
        return SMOKE_RUN
    return "met" if ok else failed


#: pySLAMMER's gravity, also the value of the unit "g" in its sample records [m/s²]
G = 9.80665


def sample_records(quick=False) -> list[bd.Record]:
    """pySLAMMER's 18 sample records [m/s²]; with ``quick`` only the two shortest."""
    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    paths = sorted(p for p in folder.iterdir() if p.name.endswith(".csv"))
    records = [bd.read_record(p, units="g", g=G) for p in paths]
    if quick:
        records = sorted(records, key=lambda r: r.acceleration_samples.size)[:2]
    return records


def sample_record_arguments(description, argv=None):
    """The arguments of a benchmark over :func:`sample_records`: --quick (the two shortest
    records) and --repeat (warm repetitions per timing, their median)."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--quick", action="store_true", help="the two shortest records (smoke run)")
    parser.add_argument("--repeat", type=int, default=3, help="warm repetitions (median) per timing")
    return parser.parse_args(argv)


def timed(action, repeat):
    """(result, seconds of the first call, median seconds of ``repeat`` further calls)."""
    start = time.perf_counter()
    result = action()
    first = time.perf_counter() - start
    warm = []
    for _ in range(repeat):
        start = time.perf_counter()
        action()
        warm.append(time.perf_counter() - start)
    return result, first, statistics.median(warm) if warm else first


def paired(ours, peer, rounds):
    """A speed-up measured alike on both sides, in interleaved rounds so that both share
    the machine's load: after one warm-up call of each (imports, compilation, caches),
    each round times one call of ``ours`` and one of ``peer``, in alternating order.
    Returns (ours' result, peer's result, ours' median [s], peer's median [s], the median
    over rounds of peer / ours [-]): the same number of calls and the same statistic on
    both sides."""
    result, peer_result = ours(), peer()
    mine, theirs = [], []
    for index in range(rounds):
        for action, times in ((ours, mine), (peer, theirs))[:: 1 if index % 2 == 0 else -1]:
            start = time.perf_counter()
            action()
            times.append(time.perf_counter() - start)
    ratios = [p / o for o, p in zip(mine, theirs)]
    return result, peer_result, statistics.median(mine), statistics.median(theirs), statistics.median(ratios)


def print_table(headers, rows):
    """Print ``rows`` (tuples of str) under ``headers`` (strings with their units)."""
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(headers)]
    print("  ".join(h.rjust(w) for h, w in zip(headers, widths)))
    for row in rows:
        print("  ".join(c.rjust(w) for c, w in zip(row, widths)))


def enable_compilation_cache(folder):
    """Use JAX's persistent compilation cache in ``folder`` (this script's process)."""
    if folder:
        import jax

        pathlib.Path(folder).mkdir(parents=True, exist_ok=True)
        jax.config.update("jax_compilation_cache_dir", str(folder))


def synthetic_record(n_samples, dt=0.01, peak=0.5 * G, seed=0) -> bd.Record:
    """Band-limited noise under a smooth envelope, peak ``peak`` [m/s²], ``n_samples`` long."""
    rng = np.random.default_rng(seed)
    kernel = np.hanning(15)
    noise = np.convolve(rng.standard_normal(n_samples + kernel.size), kernel, mode="same")[:n_samples]
    envelope = np.sin(np.pi * np.arange(n_samples) / (n_samples - 1)) ** 0.5
    a = noise * envelope
    return bd.Record(a * peak / np.max(np.abs(a)), dt, f"synthetic-{n_samples}")
