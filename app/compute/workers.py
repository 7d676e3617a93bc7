"""The worker processes of the heavy computations and :func:`run_job`, the one way into them.

The pool is the project's execution layer (:mod:`fpucore.parallel`), started on first use and
shared by all sessions.  :func:`run_job` runs a job through the cache
(:mod:`app.compute.cache`): progress is forwarded, a caller that no longer wants the result (a
newer slider value, the Cancel button) leaves with :class:`Superseded`, and the job is killed
once nobody waits for it; two sessions asking for the same key share one job.  The server's
warm-up (app/warm.py) warms every worker's JIT through :func:`warm_workers`.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Hashable

from fpucore.parallel import Executor
from fpucore.warm import warm_all

from .cache import CACHE, Computed

__all__ = [
    "Superseded",
    "CANCELLED",
    "executor",
    "shutdown_executor",
    "jobs_in_flight",
    "run_job",
    "warm_job",
    "warm_workers",
]


class Superseded(Exception):
    """The caller stopped waiting (a newer request, or Cancel): nothing to show."""


_EXECUTOR: Executor | None = None
_EXECUTOR_LOCK = threading.Lock()
_INFLIGHT: dict[Hashable, list] = {}  # key -> [job, number of waiters, submit time]
_INFLIGHT_LOCK = threading.Lock()
#: jobs cancelled because nobody waited for them any more (for tests and the benchmark)
CANCELLED = [0]


def executor() -> Executor:
    """The process-wide pool of worker processes (started on first use)."""
    global _EXECUTOR
    with _EXECUTOR_LOCK:
        if _EXECUTOR is None:
            _EXECUTOR = Executor(backend="process", workers=None)
        return _EXECUTOR


def shutdown_executor() -> None:
    """Stop the worker pool (server shutdown); a later job starts a new one."""
    global _EXECUTOR
    with _EXECUTOR_LOCK:
        ex, _EXECUTOR = _EXECUTOR, None
    if ex is not None:
        ex.shutdown()


def jobs_in_flight() -> int:
    """Heavy jobs running or queued (for tests and the benchmark)."""
    with _INFLIGHT_LOCK:
        return len(_INFLIGHT)


def run_job(
    key: Hashable,
    fn: Callable,
    args: tuple,
    stop: Callable[[], bool] | None = None,
    progress: Callable[[float], None] | None = None,
    poll_s: float = 0.05,
    queued: Callable[[int], None] | None = None,
) -> Computed:
    """``fn(*args)`` in a worker process, through the cache.

    Waits polling ``stop()`` every ``poll_s``: when it returns True the caller leaves
    (:class:`Superseded`) and, if no other caller waits for the same key, the job is
    cancelled (its worker killed).  ``progress(x)`` gets the job's progress in [0, 1].
    Exceptions of ``fn`` (ParameterError ...) are re-raised here.  ``queued(n)`` hears, while
    the job waits for a free worker, the number n of earlier jobs still running or waiting
    (any session's, this one's included), and ``queued(0)`` once a worker has taken it.
    """
    hit = CACHE.lookup(key)
    if hit is not None:
        return hit
    if stop is not None and stop():  # not wanted any more: submit nothing (no worker killed)
        raise Superseded()
    with _INFLIGHT_LOCK:
        entry = _INFLIGHT.get(key)
        if entry is None or (entry[0].done() and entry[1] == 0):
            entry = _INFLIGHT[key] = [executor().submit(fn, *args), 0, time.perf_counter()]
        entry[1] += 1
    job = entry[0]
    ahead = -1
    try:
        while True:
            if queued is not None and ahead != 0:
                n = _jobs_ahead(entry)
                if n != ahead:
                    ahead = n
                    queued(n)
            try:
                value = job.result(timeout=poll_s)
                if queued is not None and ahead > 0:
                    queued(0)  # taken and finished between two polls
                break
            except TimeoutError:
                if stop is not None and stop():
                    raise Superseded() from None
                if progress is not None and job.progress is not None:
                    progress(job.progress)
    finally:
        with _INFLIGHT_LOCK:
            entry[1] -= 1
            orphan = entry[1] <= 0 and not job.done()
            if (entry[1] <= 0 or job.done()) and _INFLIGHT.get(key) is entry:
                del _INFLIGHT[key]
        if orphan and job.cancel():
            CANCELLED[0] += 1
    elapsed = time.perf_counter() - entry[2]
    CACHE.put(key, value, elapsed)
    return Computed(value, elapsed, False)


def _jobs_ahead(entry: list) -> int:
    """Jobs submitted before ``entry``'s that are not done, if its job has no worker yet."""
    if entry[0].state != "pending":
        return 0
    with _INFLIGHT_LOCK:
        return sum(
            1 for e in _INFLIGHT.values() if e is not entry and not e[0].done() and e[2] <= entry[2]
        )


def warm_job() -> float:
    """Load (or compile) every Numba kernel in a worker process; seconds spent."""
    t0 = time.perf_counter()
    # a worker warms itself (no processes of its own), the essential routes only: the lazy ones
    # are compiled by the server's background `fpu warm` and loaded from the cache when used
    warm_all(parallel=False, lazy=False)
    return time.perf_counter() - t0


def warm_workers() -> None:
    """Start every worker process and warm its JIT (one warm_job per worker, concurrently)."""
    ex = executor()
    for job in [ex.submit(warm_job) for _ in range(ex.workers)]:
        try:
            job.result(timeout=600)
        except Exception:  # noqa: BLE001 - warm-up must never keep the server from starting
            pass
