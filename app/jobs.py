"""Worker processes for the dashboard's heavy computations.

A stand-in with the interface of the project's execution layer (``fpucore.parallel``:
``Executor(backend="process", workers=None)``, ``submit`` → :class:`Job` with ``result``,
``done``, ``cancel``, ``progress``; ``map``; ``shutdown``), so switching to it is one import in
``app/compute.py``.  Until that layer lands on main this module provides it:

* ``workers`` persistent processes started with the *spawn* method (no fork of a threaded
  server), one BLAS/OpenMP thread each (the machine's cores are the pool);
* a job runs in an idle worker; ``Job.cancel()`` drops a queued job or **kills** the worker that
  runs it (and starts a fresh one), so a superseded Floquet spectrum stops at once;
* if ``fn`` accepts a ``progress`` keyword it gets a callback ``progress(x)`` with x in [0, 1]
  (or ``progress(i, n, ...)``), forwarded to ``Job.progress`` (at most every 0.1 s).

Exceptions raised by ``fn`` reach ``Job.result()``; ``ParameterError`` keeps its fields.
"""

from __future__ import annotations

import inspect
import itertools
import multiprocessing as mp
import os
import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import CancelledError
from typing import Any

from fpucore.errors import ParameterError

__all__ = ["Executor", "Job", "CancelledError"]

#: thread limits for numerical libraries inside a worker (set before numpy is imported there)
THREAD_ENV = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS")


class Job:
    """A submitted call: ``result(timeout)``, ``done()``, ``cancel()``, ``progress``."""

    def __init__(self, executor: Executor, jid: int, fn: Callable, args: tuple, kwargs: dict):
        self.id = jid
        self.fn, self.args, self.kwargs = fn, args, kwargs
        self.progress: float | None = None
        self.submitted = time.perf_counter()
        self.finished: float | None = None
        self._executor = executor
        self._event = threading.Event()
        self._value: Any = None
        self._exc: BaseException | None = None

    def done(self) -> bool:
        return self._event.is_set()

    def result(self, timeout: float | None = None) -> Any:
        """The return value of ``fn`` (re-raises its exception; TimeoutError if not done)."""
        if not self._event.wait(timeout):
            raise TimeoutError(f"job {self.id} still running")
        if self._exc is not None:
            raise self._exc
        return self._value

    def cancel(self) -> bool:
        """Drop the job if queued, kill its worker if running; False if it already finished."""
        return self._executor.cancel_job(self)

    def finish(self, value: Any = None, exc: BaseException | None = None) -> None:
        if self._event.is_set():
            return
        self._value, self._exc = value, exc
        self.finished = time.perf_counter()
        self._event.set()


class _Worker:
    """One spawned process and the thread that reads its messages."""

    def __init__(self, executor: Executor):
        ctx = mp.get_context("spawn")
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=worker_main, args=(child,), daemon=True)
        self.proc.start()
        child.close()
        self.job: Job | None = None
        self.executor = executor
        self.reader = threading.Thread(target=self._read, name="fpu-worker-reader", daemon=True)
        self.reader.start()

    def _read(self) -> None:
        while True:
            try:
                msg = self.conn.recv()
            except (EOFError, OSError):
                self.executor.worker_died(self)
                return
            self.executor.message(self, msg)

    def run(self, job: Job) -> None:
        self.job = job
        self.conn.send(("run", job.id, job.fn, job.args, job.kwargs))

    def kill(self) -> None:
        try:
            self.proc.kill()
        except (OSError, AttributeError):
            pass
        try:
            self.conn.close()
        except OSError:
            pass


class Executor:
    """A pool of spawned worker processes (``backend="process"``; the only backend here)."""

    def __init__(self, backend: str = "process", workers: int | None = None):
        if backend != "process":
            raise ParameterError("backend", backend, "'process'")
        self.n_workers = max(1, int(workers or os.cpu_count() or 1))
        self._lock = threading.Lock()
        self._queue: deque[Job] = deque()
        self._workers: list[_Worker] = []
        self._ids = itertools.count(1)
        self._closed = False

    # ---------------------------------------------------------------- public API
    def submit(self, fn: Callable, *args, **kwargs) -> Job:
        """Run ``fn(*args, **kwargs)`` in a worker (fn must be picklable: module level)."""
        with self._lock:
            if self._closed:
                raise RuntimeError("executor is shut down")
            job = Job(self, next(self._ids), fn, args, kwargs)
            self._queue.append(job)
        self._dispatch()
        return job

    def map(
        self, fn: Callable, items: Iterable, progress: Callable | None = None
    ) -> Iterator[tuple[int, Any]]:
        """Yield (index, value or exception) as the calls finish; progress(done, total)."""
        jobs = [self.submit(fn, item) for item in items]
        left = dict(enumerate(jobs))
        n = len(jobs)
        while left:
            for i, job in list(left.items()):
                if job.done():
                    del left[i]
                    try:
                        yield i, job.result()
                    except Exception as exc:  # noqa: BLE001 - handed to the caller
                        yield i, exc
                    if progress is not None:
                        progress(n - len(left), n)
            time.sleep(0.02)

    def cancel_job(self, job: Job) -> bool:
        with self._lock:
            if job.done():
                return False
            if job in self._queue:
                self._queue.remove(job)
                victim = None
            else:
                victim = next((w for w in self._workers if w.job is job), None)
                if victim is not None:
                    self._workers.remove(victim)
        if victim is not None:
            victim.job = None
            victim.kill()
        job.finish(exc=CancelledError(f"job {job.id} cancelled"))
        self._dispatch()
        return True

    def shutdown(self) -> None:
        with self._lock:
            self._closed = True
            workers, self._workers = self._workers, []
            queued, self._queue = list(self._queue), deque()
        for job in queued:
            job.finish(exc=CancelledError("executor shut down"))
        for w in workers:
            if w.job is not None:
                w.job.finish(exc=CancelledError("executor shut down"))
            w.kill()

    def busy(self) -> int:
        """Jobs running or queued."""
        with self._lock:
            return len(self._queue) + sum(w.job is not None for w in self._workers)

    # ---------------------------------------------------------------- worker bookkeeping
    def _dispatch(self) -> None:
        with self._lock:
            while self._queue and not self._closed:
                idle = next((w for w in self._workers if w.job is None), None)
                if idle is None and len(self._workers) < self.n_workers:
                    idle = _Worker(self)
                    self._workers.append(idle)
                if idle is None:
                    return
                job = self._queue.popleft()
                try:
                    idle.run(job)
                except (OSError, ValueError) as exc:  # a dead pipe: retire the worker
                    self._workers.remove(idle)
                    idle.kill()
                    job.finish(exc=RuntimeError(f"worker unavailable: {exc}"))

    def message(self, worker: _Worker, msg: tuple) -> None:
        kind, jid = msg[0], msg[1]
        job = worker.job
        if job is None or job.id != jid:
            return
        if kind == "progress":
            job.progress = float(msg[2])
            return
        ok, payload = msg[2], msg[3]
        with self._lock:
            worker.job = None
        if ok:
            job.finish(value=payload)
        else:
            job.finish(exc=rebuild_exception(payload))
        self._dispatch()

    def worker_died(self, worker: _Worker) -> None:
        with self._lock:
            if worker in self._workers:
                self._workers.remove(worker)
            job, worker.job = worker.job, None
        if job is not None:
            code = worker.proc.exitcode
            job.finish(exc=RuntimeError(f"the worker process ended (exit code {code})"))
        self._dispatch()


# -------------------------------------------------------------------- inside a worker
def exception_payload(exc: BaseException) -> tuple:
    """A picklable description of an exception (ParameterError keeps its fields)."""
    if isinstance(exc, ParameterError):
        return ("ParameterError", exc.name, exc.value, exc.valid, exc.reason)
    return ("other", type(exc).__name__, str(exc))


def rebuild_exception(payload: tuple) -> BaseException:
    if payload[0] == "ParameterError":
        return ParameterError(*payload[1:])
    return RuntimeError(f"{payload[1]}: {payload[2]}")


def worker_main(conn) -> None:
    """Loop of a worker process: run jobs, send progress and results, exit when the pipe
    closes (the server went away)."""
    for name in THREAD_ENV:
        os.environ[name] = "1"
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError):
            return
        _, jid, fn, args, kwargs = msg
        last = [0.0]

        def progress(*p, _jid=jid, last=last):
            if not p:
                return
            x = float(p[0]) / float(p[1]) if len(p) >= 2 and float(p[1]) else float(p[0])
            now = time.monotonic()
            if now - last[0] >= 0.1:
                last[0] = now
                conn.send(("progress", _jid, min(max(x, 0.0), 1.0)))

        try:
            if "progress" in inspect.signature(fn).parameters:
                kwargs = dict(kwargs, progress=progress)
            out = ("done", jid, True, fn(*args, **kwargs))
        except Exception as exc:  # noqa: BLE001 - sent to the server as the job's outcome
            out = ("done", jid, False, exception_payload(exc))
        try:
            conn.send(out)
        except (EOFError, OSError):
            return
        except Exception as exc:  # noqa: BLE001 - e.g. an unpicklable result
            conn.send(("done", jid, False, ("other", type(exc).__name__, str(exc))))
