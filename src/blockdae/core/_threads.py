"""Batches of compiled runs shared among threads: the engines' kernels release the GIL, so
one process runs parts of a batch on every core without numba's parallel loops (which
compile the engine a second time and spin while waiting for a busy core)."""

import concurrent.futures
import functools

import numba
import numpy as np


def run_items(run, items: np.ndarray, work: float, threshold: float, parts_per_thread: int = 1) -> None:
    """``run(part)`` over the batch's ``items`` (int64, in the order the engine prefers):
    all at once on the calling thread where ``work`` (the engine's measure of the batch's
    cost) is below ``threshold``, else in strided parts on the shared pool of numba's
    number of threads, ``parts_per_thread`` parts each (strided, so that each part gets
    cheap and costly items alike; more parts balance items of uneven cost, each part is
    one more call of ``run``). ``run`` writes its items' results itself (into disjoint
    parts of one output array)."""
    threads = min(numba.get_num_threads(), len(items)) if work >= threshold else 1
    if threads <= 1:
        run(items)
        return
    n_parts = threads * parts_per_thread
    parts = [part for part in (items[k::n_parts].copy() for k in range(n_parts)) if part.size]
    # the calling thread takes parts too: waking a worker costs tens of microseconds
    others = [_pool(threads - 1).submit(run, part) for part in parts[parts_per_thread:]]
    for part in parts[:parts_per_thread]:
        run(part)
    for done in others:
        done.result()


@functools.cache
def _pool(workers: int) -> concurrent.futures.ThreadPoolExecutor:
    """The process's pool of ``workers`` threads beside the calling one, started on first use."""
    return concurrent.futures.ThreadPoolExecutor(workers, thread_name_prefix="blockdae-engine")
