"""One execution layer for every heavy job of fpucore and the explorer: :class:`Executor`.

Backends: ``"process"`` (default; a local pool of ``workers`` processes, default all cores —
:mod:`fpucore.parallel.pool`), ``"dask"`` (a ``dask.distributed`` scheduler at ``address``, or
a LocalCluster of ``workers`` processes when ``address`` is None —
:mod:`fpucore.parallel.dask_backend`) and ``"inline"`` (the calling thread, at submit time; for
tests and debugging).  Every worker runs one BLAS/OpenMP/Numba thread
(:mod:`fpucore.parallel.threads`).

``fn`` must be a picklable module-level function; if it has a ``progress`` parameter the layer
passes a callable ``progress(frac)`` whose values appear as ``Job.progress`` in the caller.

``caller_runs=True`` (process backend): the calling process computes too.  ``workers`` then
counts it: the pool has ``workers - 1`` processes (at least 1), started in the background and
each given its next job ahead (``lookahead``, see :mod:`fpucore.parallel.pool`), and
while the caller waits for a result (:meth:`Executor.map`, :meth:`Executor.next_done`) it takes
jobs no worker has taken yet (:meth:`ProcessPool.steal`) and runs them itself, one at a time, with
the workers' thread policy (1 thread, :func:`fpucore.parallel.threads.thread_policy`).  For a
sweep that starts its own pool on K cores: K processes compute (no oversubscription), only K - 1
pay the worker start-up, and the first result does not wait for it.  A job run by the caller
yields its exception like a worker's (without the worker-traceback note); it cannot be stopped
while it runs (its cancel only drops its result), so a loop over results notices a cancel, a
time budget or its own exit between two of the caller's jobs.  Not for a server (its process
must stay free): the dashboard uses a long-lived pool without it.
"""

from __future__ import annotations

import queue
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from fpucore.errors import ParameterError, import_extra
from fpucore.parallel.jobs import Cancelled, Job, accepts_progress
from fpucore.parallel.pool import ProcessPool
from fpucore.parallel.threads import cores, thread_policy

BACKENDS = ("process", "dask", "inline")


class InlineBackend:
    """Runs each job at submit, in the calling thread (progress and exceptions as the others)."""

    n_workers = 1

    def submit(self, fn, args: tuple, kwargs: dict, index: int = 0) -> Job:
        job = Job(index)
        job.state = "running"
        if accepts_progress(fn):
            kwargs = {**kwargs, "progress": job.set_progress}
        try:
            job.set_result(fn(*args, **kwargs))
        except Exception as exc:  # noqa: BLE001  (handed to the caller by result())
            job.set_exception(exc)
        return job

    def shutdown(self) -> None:
        pass


def make_dask_backend(address: str | None, workers: int):
    # distributed is imported only here: its ~1 s import stays out of every `import fpucore`
    import_extra("distributed", "atlas", "the Dask backend")
    from fpucore.parallel.dask_backend import DaskBackend

    return DaskBackend(address, workers)


class Executor:
    """``Executor(backend="process", workers=None, address=None, caller_runs=False)``.

    workers : processes (None: all cores of this machine; for "dask" with an address: the
    cluster's own workers are used and this is ignored).  address : "tcp://host:port" of a Dask
    scheduler (backend "dask" only).  caller_runs : the calling process computes jobs too and
    counts as one of ``workers`` (process backend; see the module doc).  Use as a context
    manager or call :meth:`shutdown`.
    """

    def __init__(
        self,
        backend: str = "process",
        workers: int | None = None,
        address: str | None = None,
        caller_runs: bool = False,
    ):
        if backend not in BACKENDS:
            raise ParameterError("backend", backend, " | ".join(BACKENDS))
        if workers is not None and not (isinstance(workers, int) and 1 <= workers <= 4096):
            raise ParameterError("workers", workers, "an integer in [1, 4096] or None (all cores)")
        if address is not None and backend != "dask":
            raise ParameterError(
                "address", address, "None", "a scheduler address needs backend='dask'"
            )
        if address is not None and not (isinstance(address, str) and "://" in address):
            raise ParameterError("address", address, "a scheduler address 'tcp://host:port'")
        if not isinstance(caller_runs, bool) or (caller_runs and backend == "dask"):
            raise ParameterError(
                "caller_runs", caller_runs, "True | False (True: not with backend='dask')"
            )
        self.backend = backend
        self.caller_runs = caller_runs and backend == "process"
        n = cores() if workers is None else workers
        if self.caller_runs:  # this process is one of the n; its workers start in the background
            self._impl: Any = ProcessPool(max(1, n - 1), background_start=True, lookahead=True)
        elif backend == "process":
            self._impl = ProcessPool(n)
        elif backend == "dask":
            self._impl = make_dask_backend(address, n)
        else:
            self._impl = InlineBackend()
        self._count = 0

    @property
    def workers(self) -> int:
        """Number of processes computing jobs (Dask: the workers the scheduler knows now; with
        caller_runs: the pool's processes and this one)."""
        return self._impl.n_workers + (1 if self.caller_runs else 0)

    @property
    def impl(self) -> Any:
        """The backend object (ProcessPool, DaskBackend or InlineBackend)."""
        return self._impl

    def submit(self, fn: Callable, *args: Any, **kwargs: Any) -> Job:
        """Run ``fn(*args, **kwargs)`` on a worker; returns its :class:`Job` at once."""
        self._count += 1
        return self._impl.submit(fn, args, kwargs, self._count - 1)

    def run_pending(self) -> Job | None:
        """caller_runs: run one job that no worker has taken yet here, in the calling thread,
        with the workers' thread policy; returns that job (finished: value or exception), or
        None if none was waiting (or caller_runs is off).  Ctrl-C (KeyboardInterrupt) during
        the job cancels it and propagates."""
        if not self.caller_runs:
            return None
        taken = self._impl.steal()
        if taken is None:
            return None
        job, fn, args, kwargs, wants_progress = taken
        if wants_progress:
            kwargs = {**kwargs, "progress": job.set_progress}
        try:
            with thread_policy(self._impl.n_threads):
                value = fn(*args, **kwargs)
        except Exception as exc:  # noqa: BLE001  (handed to the caller like a worker's)
            job.set_exception(exc)
        except BaseException:
            job.set_exception(Cancelled(f"job {job.index} interrupted in the calling process"))
            raise
        else:
            job.set_result(value)
        return job

    def next_done(self, finished: queue.Queue, timeout: float | None = None) -> Job:
        """The next job from ``finished`` (a queue the jobs' done callbacks put into).  With
        caller_runs, if none has finished yet this process first runs one waiting job itself
        (:meth:`run_pending`), which then is (or a worker's job that finished meanwhile is) the
        one returned.  Raises ``queue.Empty`` if nothing finished within ``timeout`` s."""
        if self.caller_runs and finished.empty():
            self.run_pending()
        return finished.get(timeout=timeout)

    def map(
        self, fn: Callable, items: Iterable, progress: Callable[[int, int], Any] | None = None
    ) -> Iterator[tuple[int, Any]]:
        """Yield ``(index, value_or_exception)`` for ``fn(item)`` in order of completion; a
        failing item yields its exception and the others go on.  ``progress(done, total)`` is
        called after each completion.  Leaving the loop early cancels the jobs not yet done.
        With caller_runs this process computes items too while it waits (:meth:`next_done`)."""
        done_q: queue.Queue = queue.Queue()
        jobs = []
        for i, item in enumerate(items):
            job = self._impl.submit(fn, (item,), {}, i)
            job.add_done_callback(done_q.put)
            jobs.append(job)
        total = len(jobs)
        try:
            for k in range(total):
                job = self.next_done(done_q)
                exc = job.exception()
                if progress is not None:
                    progress(k + 1, total)
                yield job.index, (exc if exc is not None else job.result())
        finally:
            for job in jobs:
                job.cancel()

    def shutdown(self) -> None:
        """Cancel what is queued or running and release the workers."""
        self._impl.shutdown()

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *exc) -> None:
        self.shutdown()
