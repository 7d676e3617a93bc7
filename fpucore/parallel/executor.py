"""One execution layer for every heavy job of fpucore and the explorer: :class:`Executor`.

Backends: ``"process"`` (default; a local pool of ``workers`` processes, default all cores —
:mod:`fpucore.parallel.pool`), ``"dask"`` (a ``dask.distributed`` scheduler at ``address``, or
a LocalCluster of ``workers`` processes when ``address`` is None —
:mod:`fpucore.parallel.dask_backend`) and ``"inline"`` (the calling thread, at submit time; for
tests and debugging).  Every worker runs one BLAS/OpenMP/Numba thread
(:mod:`fpucore.parallel.threads`).

``fn`` must be a picklable module-level function; if it has a ``progress`` parameter the layer
passes a callable ``progress(frac)`` whose values appear as ``Job.progress`` in the caller.
"""

from __future__ import annotations

import queue
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from fpucore.errors import ParameterError
from fpucore.parallel.jobs import Job, accepts_progress
from fpucore.parallel.pool import ProcessPool
from fpucore.parallel.threads import cores

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
    from fpucore.parallel.dask_backend import DaskBackend

    return DaskBackend(address, workers)


class Executor:
    """``Executor(backend="process", workers=None, address=None)``.

    workers : processes (None: all cores of this machine; for "dask" with an address: the
    cluster's own workers are used and this is ignored).  address : "tcp://host:port" of a Dask
    scheduler (backend "dask" only).  Use as a context manager or call :meth:`shutdown`.
    """

    def __init__(self, backend: str = "process", workers: int | None = None,
                 address: str | None = None):  # fmt: skip
        if backend not in BACKENDS:
            raise ParameterError("backend", backend, " | ".join(BACKENDS))
        if workers is not None and not (isinstance(workers, int) and 1 <= workers <= 4096):
            raise ParameterError("workers", workers, "an integer in [1, 4096] or None (all cores)")
        if address is not None and backend != "dask":
            raise ParameterError("address", address, "None", "a scheduler address needs "
                                 "backend='dask'")  # fmt: skip
        if address is not None and not (isinstance(address, str) and "://" in address):
            raise ParameterError("address", address, "a scheduler address 'tcp://host:port'")
        self.backend = backend
        n = cores() if workers is None else workers
        if backend == "process":
            self._impl = ProcessPool(n)
        elif backend == "dask":
            self._impl = make_dask_backend(address, n)
        else:
            self._impl = InlineBackend()
        self._count = 0

    @property
    def workers(self) -> int:
        """Number of worker processes (Dask: the workers the scheduler knows now)."""
        return self._impl.n_workers

    @property
    def impl(self):
        """The backend object (ProcessPool, DaskBackend or InlineBackend)."""
        return self._impl

    def submit(self, fn: Callable, *args, **kwargs) -> Job:
        """Run ``fn(*args, **kwargs)`` on a worker; returns its :class:`Job` at once."""
        self._count += 1
        return self._impl.submit(fn, args, kwargs, self._count - 1)

    def map(
        self, fn: Callable, items: Iterable, progress: Callable[[int, int], Any] | None = None
    ) -> Iterator[tuple[int, Any]]:
        """Yield ``(index, value_or_exception)`` for ``fn(item)`` in order of completion; a
        failing item yields its exception and the others go on.  ``progress(done, total)`` is
        called after each completion.  Leaving the loop early cancels the jobs not yet done."""
        done_q: queue.Queue = queue.Queue()
        jobs = []
        for i, item in enumerate(items):
            job = self._impl.submit(fn, (item,), {}, i)
            job.add_done_callback(done_q.put)
            jobs.append(job)
        total = len(jobs)
        try:
            for k in range(total):
                job = done_q.get()
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
