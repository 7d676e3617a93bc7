"""The Dask backend: jobs as ``dask.distributed`` futures, on a scheduler given by address or on
a LocalCluster started here (one process per worker, one thread each).

Each task runs through :func:`run_task`, which applies the thread policy once per worker process,
announces its start (so a cancel knows which worker to restart) and forwards ``progress(frac)``
as Dask structured events (``log_event`` / ``subscribe_topic``), throttled to 10 per second.
A worker that dies has its task re-run elsewhere by the scheduler; after
``distributed.scheduler.allowed-failures`` deaths the job fails with Dask's ``KilledWorker``.
Cancel: queued tasks are dropped; a running task's worker is restarted through its nanny
(``Client.restart_workers``), which is Dask's way of stopping a running Python function.
"""

from __future__ import annotations

import logging
import threading
import time
import uuid

import distributed

from fpucore.parallel.jobs import Cancelled, Job, accepts_progress
from fpucore.parallel.threads import apply_thread_policy

_policy = {"applied": False}  # per worker process


def run_task(fn, args: tuple, kwargs: dict, wants_progress: bool, topic: str):
    """Executed on a Dask worker: the policy, a start event, progress events, then ``fn``."""
    if not _policy["applied"]:
        apply_thread_policy(1)
        _policy["applied"] = True
    worker = distributed.get_worker()
    key = str(worker.get_current_task())
    worker.log_event(topic, {"key": key, "start": worker.address})
    if wants_progress:
        last = [0.0]

        def progress(frac: float) -> None:
            now = time.monotonic()
            if frac >= 1.0 or now - last[0] >= 0.1:
                last[0] = now
                worker.log_event(topic, {"key": key, "frac": float(frac)})

        kwargs = {**kwargs, "progress": progress}
    return fn(*args, **kwargs)


class DaskBackend:
    """``address``: "tcp://host:port" of a running scheduler, or None for a LocalCluster with
    ``workers`` processes (default: all cores)."""

    def __init__(self, address: str | None, workers: int):
        self.cluster = None
        if address is None:
            self.cluster = distributed.LocalCluster(
                n_workers=workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
                silence_logs=logging.ERROR,
            )
            self.client = distributed.Client(self.cluster)
        else:
            self.client = distributed.Client(address, timeout=30)
        self.topic = f"fpucore-{uuid.uuid4().hex}"
        self._jobs: dict[str, Job] = {}
        self._futures: dict[Job, distributed.Future] = {}
        self._lock = threading.Lock()
        self._closed_workers: int | None = None
        self.client.subscribe_topic(self.topic, self._on_event)

    @property
    def n_workers(self) -> int:
        """Workers the scheduler knows now (after shutdown: the number at shutdown)."""
        if self._closed_workers is not None:
            return self._closed_workers
        return len(self.client.scheduler_info().get("workers", {}))

    def _on_event(self, event) -> None:
        msg = event[1] if isinstance(event, tuple) else event
        job = self._jobs.get(msg.get("key"))
        if job is None:
            return
        if "start" in msg:
            job.worker, job.state = msg["start"], "running"
        if "frac" in msg:
            job.set_progress(msg["frac"])

    def submit(self, fn, args: tuple, kwargs: dict, index: int = 0) -> Job:
        job = Job(index)
        fut = self.client.submit(
            run_task, fn, args, kwargs, accepts_progress(fn), self.topic, pure=False
        )
        with self._lock:
            self._jobs[fut.key] = job  # type: ignore[index]
            self._futures[job] = fut
        job.cancel_hook = self._on_cancel
        fut.add_done_callback(lambda f: self._finish(job, f))
        return job

    def _finish(self, job: Job, fut) -> None:
        with self._lock:
            self._jobs.pop(fut.key, None)
            self._futures.pop(job, None)
        if fut.status == "finished":
            job.set_result(fut.result())
        elif fut.status == "cancelled":
            job.set_exception(Cancelled(f"job {job.index} cancelled"))
        else:
            job.set_exception(fut.exception())

    def _on_cancel(self, job: Job) -> None:
        with self._lock:
            fut = self._futures.pop(job, None)
        if fut is None:
            return
        running_on = job.worker
        self.client.cancel(fut, force=True)
        if running_on:  # stop the Python function still running there
            threading.Thread(target=self._restart, args=(running_on,), daemon=True).start()

    def _restart(self, address: str) -> None:
        try:
            self.client.restart_workers([address], raise_for_error=False)
        except Exception:  # noqa: BLE001  (a worker without nanny cannot be restarted)
            logging.getLogger(__name__).warning("could not restart Dask worker %s", address)

    def shutdown(self) -> None:
        if self._closed_workers is not None:
            return
        self._closed_workers = self.n_workers
        with self._lock:
            jobs = list(self._futures)
        for job in jobs:
            job.set_exception(Cancelled("the executor was shut down"))
        try:
            self.client.unsubscribe_topic(self.topic)
        except Exception:  # noqa: BLE001
            pass
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()
