"""Units of work (map units, tiles) run by Dask, their results handed over as they finish.

Three places to run, by ``--scheduler``:

* ``local`` (the default) — Dask's local scheduler on this machine (:mod:`dask.local`): its
  multiprocessing scheduler with ``workers`` processes, or its synchronous one, in this process,
  for one worker;
* ``processes`` — a :class:`distributed.LocalCluster` of ``workers`` single-threaded worker
  processes, started for the run and stopped after it: a cluster's code path on one machine;
* an address (``tcp://host:8786``) — the Dask cluster whose scheduler listens there
  (:class:`distributed.Client`); its workers must see the exemplar files at the same paths.

A unit never raises: :func:`guarded` turns a failure into a one-line message, so one unit's
failure is reported on its own and the others are kept; a worker that dies (killed, out of
memory) fails only the units it held.  Results reach ``on_done`` in completion order, in the
calling process, and are dropped by the scheduler once handed over: nothing holds all of them.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import logging
import multiprocessing
import os
import signal
import sys
import uuid
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from svgtile.errors import ParameterError, SvgtileError

#: The scheduler names; anything else is a cluster address.
SCHEDULERS = ("local", "processes")

#: ``on_done(index, value, error)``: ``value`` None and ``error`` a one-line message on failure.
Done = Callable[[int, Any, "str | None"], None]


@dataclass(frozen=True)
class Unit:
    """One unit of work: ``fn(*args)``, named ``name`` in messages and on the Dask dashboard."""

    name: str
    fn: Callable[..., Any]
    args: tuple = ()


def guarded(fn: Callable[..., Any], *args: Any) -> tuple[Any, str | None]:
    """``(fn(*args), None)``, or ``(None, message)``: a unit's failure as one line, never raised."""
    try:
        return fn(*args), None
    except SvgtileError as exc:
        return None, " ".join(str(exc).split())
    except MemoryError:
        return None, "out of memory"
    except Exception as exc:  # a bug in one unit must not lose the others
        return None, f"internal error: {type(exc).__name__}: {' '.join(str(exc).split())}"


def check_scheduler(scheduler: str) -> str:
    """``scheduler`` if it is a scheduler name or looks like an address; a clear error otherwise."""
    if scheduler in SCHEDULERS or "://" in scheduler or ":" in scheduler:
        return scheduler
    raise ParameterError(f"--scheduler must be local, processes or a Dask scheduler address such as "
                         f"tcp://host:8786, not {scheduler!r}")  # fmt: skip


def run(units: Sequence[Unit], on_done: Done, *, scheduler: str = "local", workers: int = 1,
        progress: bool = False) -> None:  # fmt: skip
    """Run every unit; ``on_done`` gets each result as it finishes (any order).

    Parameters
    ----------
    units : the work
    on_done : called in this process as ``on_done(index, value, error)``, once per unit
    scheduler : ``local``, ``processes`` or a cluster address (see the module docstring)
    workers : worker processes for ``local`` and ``processes`` (an address's cluster has its own)
    progress : show Dask's progress bar (on a terminal)
    """
    check_scheduler(scheduler)
    if not units:
        return
    if scheduler == "local":
        _run_local(units, on_done, workers, progress)
    else:
        _run_distributed(units, on_done, scheduler, workers, progress)


class _Handover(dict):
    """The local scheduler's store of results (the ``cache`` of :func:`dask.local.get_async`):
    a unit's result goes to ``on_done`` the moment the scheduler stores it, and only a
    placeholder is kept (no unit depends on another, so nothing reads it back)."""

    def __init__(self, index: dict[str, int], on_done: Done) -> None:
        super().__init__()
        self.index, self.on_done, self.handed = index, on_done, set()
        self.failure: BaseException | None = None  # raised by on_done itself (the writer's)

    def __setitem__(self, key, value) -> None:
        n = self.index.get(key)
        if n is not None and n not in self.handed:
            self.handed.add(n)
            try:
                self.on_done(n, *value)
            except BaseException as exc:
                self.failure = exc
                raise
            value = None
        super().__setitem__(key, value)


def _run_local(units: Sequence[Unit], on_done: Done, workers: int, progress: bool) -> None:
    import dask

    tag = uuid.uuid4().hex[:8]
    tasks = [dask.delayed(guarded, pure=False)(u.fn, *u.args, dask_key_name=f"{u.name}-{tag}-{n}")
             for n, u in enumerate(units)]  # fmt: skip
    store = _Handover({t.key: n for n, t in enumerate(tasks)}, on_done)
    pool = None
    how: dict[str, object] = {"scheduler": "synchronous"}
    if workers > 1 and len(units) > 1:
        # forked workers start at once (spawned ones import svgtile again, seconds each); our own
        # pool, so that its workers end with this process (_die_with_parent) and on ^C (_stop)
        context = multiprocessing.get_context("fork" if sys.platform == "linux" else None)
        pool = concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=context,
                                                      initializer=_die_with_parent, initargs=(os.getpid(),))  # fmt: skip
        how = {"scheduler": "processes", "pool": pool}
    bar = _local_bar() if progress else None
    stopped = False
    try:
        with bar or contextlib.nullcontext():
            dask.compute(*tasks, cache=store, optimize_graph=False, **how)
    except Exception as exc:  # the pool itself broke (a worker killed): the units not done fail
        if store.failure is not None:  # not the pool: the caller's writer failed
            raise store.failure from None
        for n in range(len(units)):
            if n not in store.handed:
                store.handed.add(n)
                on_done(n, None, f"worker failed: {type(exc).__name__}")
    except BaseException:  # ^C, SIGTERM: stop the workers now rather than let them finish
        if pool is not None:
            _stop(pool)
            stopped = True
        raise
    finally:
        if pool is not None and not stopped:
            # waited for (the workers are idle or gone): a pool left to close itself races the
            # interpreter's exit on Python 3.11 ("Exception ignored … Bad file descriptor")
            pool.shutdown(wait=True, cancel_futures=True)


def _die_with_parent(parent: int) -> None:
    """Worker set-up: end when the parent process ends, even by SIGKILL (Linux's
    ``PR_SET_PDEATHSIG``; elsewhere the pool's own check, when the next task is due, has to do)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:  # the parent died before the request took effect
        os._exit(1)


def _stop(pool: concurrent.futures.ProcessPoolExecutor) -> None:
    """End ``pool``'s workers at once (their units are lost anyway) and release the pool."""
    processes = list((getattr(pool, "_processes", None) or {}).values())  # no public handle
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in processes:
        proc.kill()
    for proc in processes:
        proc.join(5)


def _local_bar():
    from dask.diagnostics import ProgressBar

    return ProgressBar(out=sys.stderr, minimum=1.0)


def _run_distributed(units: Sequence[Unit], on_done: Done, scheduler: str, workers: int, progress: bool) -> None:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise ParameterError(f"--scheduler {scheduler} needs Dask's distributed scheduler: "
                             "pip install 'svgtile[cluster]'") from None  # fmt: skip
    if scheduler == "processes":
        # Dask's own log lines (workers starting, stopping) would break svgtile's one-line output
        cluster = LocalCluster(n_workers=max(1, workers), threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.CRITICAL)  # fmt: skip
        client = Client(cluster)
    else:
        cluster = None
        try:
            client = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise ParameterError(f"--scheduler: cannot reach a Dask scheduler at {scheduler} "
                                 f"({' '.join(str(exc).split()) or type(exc).__name__})") from None  # fmt: skip
    try:
        consume(client, units, on_done, progress=progress, as_completed=as_completed)
    finally:
        quiet = logging.getLogger("distributed")
        level = quiet.level
        quiet.setLevel(logging.CRITICAL)
        try:
            client.close()
            if cluster is not None:
                cluster.close()
        finally:
            quiet.setLevel(level)


def consume(client, units: Sequence[Unit], on_done: Done, *, progress: bool = False, as_completed=None,
            order: Callable[[list], list] | None = None) -> None:  # fmt: skip
    """Submit ``units`` to a :class:`distributed.Client` and hand results over as they finish.

    ``order`` (for tests) may reorder the futures before they are consumed, standing for any
    completion order.
    """
    if as_completed is None:
        from distributed import as_completed
    tag = uuid.uuid4().hex[:8]
    futures = [client.submit(guarded, u.fn, *u.args, key=f"{u.name}-{tag}-{n}", pure=False)
               for n, u in enumerate(units)]  # fmt: skip
    index = {f.key: n for n, f in enumerate(futures)}
    if progress:
        _cluster_bar(client, futures)
    stream = order(list(futures)) if order is not None else as_completed(futures)
    del futures  # each result is released once handed over
    for future in stream:
        n = index[future.key]
        try:
            value, error = future.result()
        except Exception as exc:  # the worker died, or the cluster lost the unit
            value, error = None, f"worker failed: {type(exc).__name__}"
        future.release()
        on_done(n, value, error)


def _cluster_bar(client, futures) -> None:
    """distributed's text progress bar, in a thread of its own (it blocks while it draws); it
    draws on standard output, so only when that is a terminal."""
    import threading

    if not sys.stdout.isatty():
        return

    from distributed.diagnostics.progressbar import TextProgressBar

    keys = [f.key for f in futures]
    threading.Thread(target=TextProgressBar, args=(keys,), kwargs={"scheduler": client.scheduler.address},
                     daemon=True).start()  # fmt: skip
