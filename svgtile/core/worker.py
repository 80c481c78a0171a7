"""Handing work to an executor's worker that may have died (``svgtile score``'s second process).

Standard library only: :mod:`svgtile.cli.score` imports it before anything heavy, and the
texture reader (:mod:`svgtile.svg.uselines`) and the figures (:mod:`svgtile.metrics.scoring`)
hand their parts over through it.  A worker killed (out of memory, a signal) breaks its pool:
the pool then refuses new work and fails the futures it held, and the caller computes the part
itself — the same figures, a little later.
"""

from __future__ import annotations

from concurrent.futures import BrokenExecutor, Executor, Future


def worker_submit(pool: Executor | None, fn, *args) -> Future | None:
    """``pool.submit(fn, *args)``, or None if there is no pool or its worker has died (killed, out
    of memory, before this task: a broken pool refuses new work); the caller then computes it
    itself, as for :func:`worker_result`."""
    try:
        return pool.submit(fn, *args) if pool is not None else None
    except BrokenExecutor:
        return None


def worker_result(future: Future | None):
    """What ``future`` computed, or None if there is none or its worker died (killed, out of
    memory): the caller then computes it itself, the same a little later."""
    try:
        return future.result() if future is not None else None
    except BrokenExecutor:
        return None
