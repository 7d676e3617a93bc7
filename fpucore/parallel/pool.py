"""The local process pool: one pipe per worker, one manager thread, workers replaceable.

Why not ``concurrent.futures.ProcessPoolExecutor``: a killed worker breaks the whole pool there
(BrokenProcessPool) and a running job cannot be stopped.  Here each worker is a
``multiprocessing`` process with its own duplex pipe; the manager thread waits on every pipe, every
process sentinel and a wake-up pipe at once (``multiprocessing.connection.wait``), hands queued
jobs to idle workers, forwards progress, and when a worker dies or its job is cancelled it
terminates / reaps that process, fails or cancels only that job, and starts a replacement.

A caller that computes too (``Executor(..., caller_runs=True)``) takes jobs not yet handed to a
worker with :meth:`ProcessPool.steal` (atomic with the manager's dispatch: every job runs once),
and such a pool starts its workers in the manager thread (``background_start``), so that the
caller computes while the forkserver imports fpucore (~0.7 s) instead of waiting for it.  Its
workers also get their next job ahead (``lookahead``: one more job waits in a busy worker's pipe):
the caller holds the GIL through a LAPACK call (scipy's ``geev`` does not release it), so this
manager thread could not hand a worker its next job until the caller's call returned — measured
0.2 s of idle worker per job at 0.5 s jobs.

Start method: ``forkserver`` with fpucore preloaded (see :mod:`fpucore.parallel.threads`: the
process that forks workers has never run an OpenMP kernel), ``spawn`` where forkserver is missing.
"""

from __future__ import annotations

import atexit
import itertools
import multiprocessing as mp
import os
import signal
import threading
import weakref
from collections import deque
from multiprocessing.connection import wait

from fpucore.parallel.jobs import Cancelled, Job, WorkerDied, accepts_progress
from fpucore.parallel.worker import worker_main

START_METHOD = "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"
PRELOAD = ["fpucore"]
TERMINATE_GRACE_S = 2.0


def context(method: str = START_METHOD):
    """The multiprocessing context of the pool (never ``fork``: see module docstring)."""
    if method == "fork":
        raise ValueError("fork is unsafe after an OpenMP kernel has run (GNU OpenMP deadlocks)")
    ctx = mp.get_context(method)
    if method == "forkserver":
        ctx.set_forkserver_preload(PRELOAD)
    return ctx


class _Worker:
    def __init__(self, ctx, n_threads: int):
        self.conn, child = ctx.Pipe(duplex=True)
        self.process = ctx.Process(target=worker_main, args=(child, n_threads), daemon=True)
        self.process.start()
        child.close()
        self.job: Job | None = None
        self.job_id: int | None = None
        self.next: tuple | None = None  # lookahead: (job_id, job, payload) waiting in its pipe
        self.drop_next = False  # the job waiting in its pipe was cancelled: stop it when it starts
        self.doomed = False  # it has started that cancelled job: to be replaced

    def stop(self, grace_s: float = TERMINATE_GRACE_S) -> None:
        p = self.process
        if p.is_alive():
            p.terminate()
            p.join(grace_s)
            if p.is_alive():
                p.kill()
        p.join(grace_s)
        self.conn.close()


def describe_exit(exitcode: int | None) -> str:
    if exitcode is None:
        return "no exit code"
    if exitcode < 0:
        try:
            return f"killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            return f"killed by signal {-exitcode}"
    return f"exit code {exitcode}"


def shutdown_at_exit(ref: weakref.ref) -> None:
    """Interpreter exit with a pool still open: stop its manager thread and workers before the
    modules are torn down (the daemon thread, still replacing a cancelled job's worker, printed
    a traceback)."""
    pool = ref()
    if pool is not None:
        pool.shutdown()


class ProcessPool:
    """``workers`` processes with ``n_threads`` BLAS/Numba threads each (the policy: 1).
    background_start : start the workers in the manager thread (the constructor returns at
    once; jobs wait in the queue until a worker is up, or are stolen by the caller).
    lookahead : send a busy worker its next job ahead (not the last one queued), so it never
    waits for this process (a cancelled job waiting there has its worker replaced when it starts
    it)."""

    def __init__(
        self,
        workers: int,
        n_threads: int = 1,
        start_method: str = START_METHOD,
        background_start: bool = False,
        lookahead: bool = False,
    ):
        self.n_workers, self.n_threads = int(workers), int(n_threads)
        self.start_method, self.lookahead = start_method, bool(lookahead)
        self._ctx = context(start_method)
        self._lock = threading.Lock()
        self._queue: deque[tuple[int, Job, tuple]] = deque()
        self._kill: deque[Job] = deque()  # running jobs whose worker must be terminated
        self._ids = itertools.count()
        self._closed = False
        self._wake_r, self._wake_w = self._ctx.Pipe(duplex=False)
        self._workers: list[_Worker] = []
        self._to_start = self.n_workers if background_start else 0
        if not background_start:
            self._workers = [_Worker(self._ctx, self.n_threads) for _ in range(self.n_workers)]
        self.replaced = 0  # workers started to replace a dead or cancelled one
        self.start_error: Exception | None = None  # background_start: a worker failed to start
        self._thread = threading.Thread(target=self._loop, name="fpucore-pool", daemon=True)
        self._thread.start()
        atexit.register(shutdown_at_exit, weakref.ref(self))

    # -- caller's side --------------------------------------------------------------------------
    def submit(self, fn, args: tuple, kwargs: dict, index: int = 0) -> Job:
        job = Job(index)
        if self._closed:
            job.set_exception(Cancelled("the executor is shut down"))
            return job
        if self.start_error is not None and not self._workers:
            job.set_exception(WorkerDied(f"no worker process could start: {self.start_error!r}"))
            return job
        job.cancel_hook = self._on_cancel
        with self._lock:
            self._queue.append((next(self._ids), job, (fn, args, kwargs, accepts_progress(fn))))
        self._wake()
        return job

    def steal(self) -> tuple | None:
        """Take the oldest job not yet handed to a worker, for the caller to run itself:
        ``(job, fn, args, kwargs, wants_progress)`` with the job marked running in this process,
        or None if none is waiting.  Atomic with the manager's dispatch (the same lock), so a job
        runs exactly once; a cancelled job still in the queue is skipped."""
        with self._lock:
            while self._queue:
                _, job, (fn, args, kwargs, wants_progress) = self._queue.popleft()
                if not job.done():
                    job.state, job.worker = "running", os.getpid()
                    return job, fn, args, kwargs, wants_progress
        return None

    def _on_cancel(self, job: Job) -> None:
        with self._lock:
            queued = [item for item in self._queue if item[1] is job]
            for item in queued:
                self._queue.remove(item)
            if not queued:
                self._kill.append(job)
        self._wake()

    def _wake(self) -> None:
        try:
            self._wake_w.send_bytes(b"x")
        except OSError:
            pass

    def pids(self) -> list[int]:
        """Process ids of the current workers."""
        return [w.process.pid for w in self._workers]

    def shutdown(self) -> None:
        """Cancel queued and running jobs, stop the workers and the manager thread."""
        if self._closed:
            return
        self._closed = True
        with self._lock:
            pending = [job for _, job, _ in self._queue]
            self._queue.clear()
        for job in pending:
            job.set_exception(Cancelled("the executor was shut down"))
        self._wake()
        self._thread.join(30)
        for w in self._workers:
            for job in (w.job, w.next[1] if w.next is not None else None):  # type: ignore[assignment]
                if job is not None:
                    job.set_exception(Cancelled("the executor was shut down"))
            try:
                w.conn.send(None)
            except OSError:
                pass
        for w in self._workers:
            if w.next is None and not (w.drop_next or w.doomed):  # else it would start a job
                w.process.join(TERMINATE_GRACE_S)
            w.stop()
        self._wake_r.close()
        self._wake_w.close()

    # -- manager thread -------------------------------------------------------------------------
    def _start_workers(self) -> None:
        """background_start: start the workers one by one (the first start also starts the
        forkserver); each takes a job as soon as it is up."""
        while self._to_start and not self._closed:
            try:
                self._workers.append(_Worker(self._ctx, self.n_threads))
            except Exception as exc:  # noqa: BLE001  (no worker: jobs must fail, not wait forever)
                self.start_error, self._to_start = exc, 0
                if not self._workers:
                    with self._lock:
                        pending = [job for _, job, _ in self._queue]
                        self._queue.clear()
                    for job in pending:
                        job.set_exception(WorkerDied(f"no worker process could start: {exc!r}"))
                return
            self._to_start -= 1
            self._dispatch()

    def _loop(self) -> None:
        self._start_workers()
        while True:
            if self._closed:
                return
            self._reap_cancelled()
            self._dispatch()
            if self._closed:
                # shutdown() began while a cancelled job's worker was stopped: that worker was
                # not replaced and its pipe is closed (waiting on it raised "handle is closed")
                return
            watch = [self._wake_r]
            for w in self._workers:
                watch += [w.conn, w.process.sentinel]
            for obj in wait(watch, timeout=1.0):
                if obj is self._wake_r:
                    while self._wake_r.poll():  # type: ignore[union-attr]
                        self._wake_r.recv_bytes()  # type: ignore[union-attr]
                    continue
                for w in list(self._workers):
                    if obj is w.conn:
                        self._drain(w)
                    elif obj == w.process.sentinel:
                        self._on_death(w)
            for w in list(self._workers):
                if w.doomed:  # it started a cancelled job that waited in its pipe
                    self._replace(w)

    def _takes_job(self, w: _Worker) -> bool:
        """w is idle, or (lookahead) busy with nothing waiting in its pipe."""
        if w.doomed:
            return False
        return w.job is None or (self.lookahead and w.next is None and not w.drop_next)

    def _dispatch(self) -> None:
        for w in self._workers:
            while self._takes_job(w):
                with self._lock:
                    if not self._queue:
                        return
                    if w.job is not None and len(self._queue) < 2:
                        break  # the last job waits for whoever is free first (the caller too)
                    item = self._queue.popleft()
                job_id, job, (fn, args, kwargs, wants_progress) = item
                if job.done():
                    continue
                try:
                    w.conn.send((job_id, fn, args, kwargs, wants_progress))
                except Exception as exc:  # unpicklable arguments: that job fails, the worker stays
                    job.set_exception(exc)
                    continue
                if w.job is None:
                    w.job, w.job_id = job, job_id
                    job.state, job.worker = "running", w.process.pid
                else:  # lookahead: the worker starts it as soon as its current job is done
                    w.next = item

    def _drain(self, w: _Worker) -> bool:
        """Read every message waiting on w's pipe; False if the pipe is broken."""
        try:
            while w.conn.poll():
                msg = w.conn.recv()
                if msg[1] != w.job_id or w.job is None:
                    continue  # a message of a job already cancelled
                if msg[0] == "progress":
                    w.job.set_progress(msg[2])
                else:
                    _, _, ok, payload = msg
                    job, w.job, w.job_id = w.job, None, None
                    self._promote(w)
                    job.set_result(payload) if ok else job.set_exception(payload)
        except (EOFError, OSError):
            return False
        except Exception as exc:  # a value the parent cannot unpickle
            if w.job is not None:
                job, w.job, w.job_id = w.job, None, None
                self._promote(w)
                job.set_exception(exc)
        return True

    def _promote(self, w: _Worker) -> None:
        """w finished its job and has started the one waiting in its pipe (lookahead)."""
        if w.drop_next:  # that one was cancelled: the loop stops and replaces w
            w.drop_next, w.doomed = False, True
            return
        if w.next is not None:
            job_id, job, _ = w.next
            w.next = None
            w.job, w.job_id = job, job_id
            job.state, job.worker = "running", w.process.pid

    def _on_death(self, w: _Worker) -> None:
        self._drain(w)  # its last message may have arrived just before it exited
        if w.process.is_alive():
            return
        if w.job is not None:
            why = describe_exit(w.process.exitcode)
            w.job.set_exception(
                WorkerDied(
                    f"worker process {w.process.pid} died ({why}) while running job {w.job.index}"
                )
            )
        self._replace(w)

    def _reap_cancelled(self) -> None:
        with self._lock:
            kill, self._kill = list(self._kill), deque()
        for job in kill:
            for w in list(self._workers):
                if w.job is job:
                    self._replace(w)
                elif w.next is not None and w.next[1] is job:  # not started: stop it when it is
                    w.next, w.drop_next = None, True

    def _replace(self, w: _Worker) -> None:
        if w.next is not None and not w.next[1].done():  # never started: back to the queue head
            with self._lock:
                requeued = not self._closed
                if requeued:
                    self._queue.appendleft(w.next)
            if not requeued:
                w.next[1].set_exception(Cancelled("the executor was shut down"))
        w.job = w.job_id = w.next = None
        w.stop()
        i = self._workers.index(w)
        if not self._closed:
            self._workers[i] = _Worker(self._ctx, self.n_threads)
            self.replaced += 1
