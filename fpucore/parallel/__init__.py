"""Execution layer: every heavy job of fpucore, the CLI and the explorer runs through it.

threads (the thread budget: 1 BLAS/OpenMP/Numba thread per worker, Numba's "omp" layer, never
fork after a kernel)  →  jobs (Job, Cancelled, WorkerDied)  →  worker (the child's loop)
→  pool (local processes, forkserver) | dask_backend (dask.distributed)  →  executor (Executor)

    ex = Executor(backend="process", workers=None, address=None)   # or "dask", "inline"
    job = ex.submit(fn, *args, **kwargs); job.result(); job.cancel(); job.progress
    for index, value_or_exc in ex.map(fn, items, progress=cb): ...
"""

from fpucore.parallel.executor import BACKENDS, Executor
from fpucore.parallel.jobs import Cancelled, Job, RemoteError, WorkerDied
from fpucore.parallel.threads import apply_thread_policy, configure_threading_layer, cores

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
]
