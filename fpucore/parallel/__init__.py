"""Execution layer: every heavy job of fpucore, the CLI and the explorer runs through it.

threads (the thread budget: 1 BLAS/OpenMP/Numba thread per worker, Numba's "omp" layer, never
fork after a kernel)  →  jobs (Job, Cancelled, WorkerDied)  →  worker (the child's loop)
→  pool (local processes, forkserver) | dask_backend (dask.distributed)  →  executor
(Executor).  In use::

    ex = Executor(backend="process", workers=None, address=None)   # or "dask", "inline"
    job = ex.submit(fn, *args, **kwargs); job.result(); job.cancel(); job.progress
    for index, value_or_exc in ex.map(fn, items, progress=cb): ...

Who computes.  A pool's workers, K on K cores, one thread each — and, with
``Executor(..., caller_runs=True)``, the calling process as one of the K: it starts K - 1
workers in the background and, while it waits for results (``map``, ``next_done``), takes jobs
no worker has taken yet and runs them itself under the same thread policy (``thread_policy(1)``
for the job only).  Sweeps that start their own pool (``atlas.sweep``, ``fpu floquet sweep``)
use it: the caller computes at once instead of idling through the pool's start, and one process
fewer pays the worker start-up (forkserver import + loading Numba's cache, ~1.2 s).  A server
never does: the dashboard's process only serves, its long-lived pool computes.
"""

from fpucore.parallel.executor import BACKENDS, Executor
from fpucore.parallel.jobs import Cancelled, Job, RemoteError, WorkerDied
from fpucore.parallel.threads import (
    apply_thread_policy,
    configure_threading_layer,
    cores,
    thread_policy,
)

__all__ = [
    "BACKENDS",
    "Executor",
    "Job",
    "Cancelled",
    "RemoteError",
    "WorkerDied",
    "apply_thread_policy",
    "configure_threading_layer",
    "cores",
    "thread_policy",
]
