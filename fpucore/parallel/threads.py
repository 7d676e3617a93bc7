"""The thread budget of fpucore — the one place where BLAS, OpenMP and Numba threads are set.

Why.  One Floquet spectrum at N = 500 is a LAPACK ``dgeev`` of a ~1000 × 1000 matrix; two of them
at once with OpenBLAS's default (one thread per core each) took 5.4 s instead of 0.7 s on the
2-core machine (issue 17): threads of two processes fighting for the same cores.  So threads are
never left at a library's default, and parallelism across jobs comes from *processes*.

The policy
----------
* A process that runs **one heavy job at a time** (the ``fpu`` CLI computing one wave or one
  spectrum) may use every core for it: ``apply_thread_policy(None)`` → BLAS/OpenMP/Numba threads =
  ``os.cpu_count()``.
* A process that runs **one of several concurrent jobs** — every worker of
  :class:`fpucore.parallel.Executor` (process pool or Dask worker), the atlas's workers, the CLI
  while it drives a sweep, the dashboard server (several sessions compute at once) — uses
  **one thread**: ``apply_thread_policy(1)``.  K jobs then run on K cores without
  oversubscription, and the throughput scales with the number of processes.  A caller that
  computes jobs of its own pool (``Executor(caller_runs=True)``: ``fpu floquet sweep``) is one
  of them while it runs a job: :func:`thread_policy` gives it one thread for that job only.
* Limits are set with threadpoolctl on every BLAS (OpenBLAS/MKL, numpy's and scipy's own copies:
  both are imported here first so that both are loaded when the limit is applied) and OpenMP
  library in the process, and with ``numba.set_num_threads`` for Numba's parallel kernels
  (``wave.period_map``).  ``numba.set_num_threads`` is *per calling thread*: a server thread that
  computes calls ``apply_thread_policy`` itself (it is cheap: ~0.1 ms after the first call).
* Numba's threading layer is chosen deliberately: ``"omp"`` (GNU OpenMP), set by
  :func:`configure_threading_layer` when fpucore is imported.  It is thread-safe (the server calls
  parallel kernels from several threads; ``"workqueue"`` aborts on concurrent use) and TBB is not
  installed.  GNU OpenMP does not survive ``fork()`` ("fork() called from a process already using
  GNU OpenMP" and a pool that never returns, issue 14 item 5), so **no fpucore process pool ever
  forks the process that ran a kernel**: the Executor starts its workers with the ``forkserver``
  method (a clean server process, started by exec, that imported fpucore but never ran a
  kernel, forks the workers), and Dask's nannies use ``spawn``.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

import numba
import numpy  # noqa: F401  (numpy's OpenBLAS is loaded before the limit is applied)
import scipy.linalg  # noqa: F401  (load scipy's own OpenBLAS so the limit reaches it)
from threadpoolctl import threadpool_info, threadpool_limits

from fpucore.errors import require_int

THREADING_LAYER = "omp"
MAX_THREADS = 4096  # per process: far above any machine's cores
_limiter = None  # the active threadpoolctl limiter (kept alive: the limit holds while it lives)


def configure_threading_layer(layer: str = THREADING_LAYER) -> str:
    """Select Numba's threading layer (before the first parallel kernel runs; later calls can
    no longer change the layer already launched and return the one in use)."""
    try:
        return numba.threading_layer()  # raises ValueError until a parallel kernel has run
    except ValueError:
        numba.config.THREADING_LAYER = layer
        return layer


def cores() -> int:
    """Cores this process may use (its CPU affinity, else os.cpu_count())."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def thread_count(n_threads: int | None) -> int:
    """The thread count of a policy: :func:`cores` for None, else an integer >= 1 (ParameterError
    for 'x', 2.5, True ...: ``int('x')`` used to escape as a ValueError)."""
    if n_threads is None:
        return cores()
    return require_int("n_threads", n_threads, 1, MAX_THREADS)


def apply_thread_policy(n_threads: int | None = 1) -> dict:
    """Limit BLAS, OpenMP and Numba threads of this process (Numba: of the calling thread).

    n_threads : 1 for a process running one of several concurrent jobs (the default: workers,
    server); None for a process running a single heavy job (all :func:`cores`).
    Returns {"threads": n, "blas": [...], "openmp": [...], "numba": n, "layer": ...}: the
    libraries found and the limits now in force.
    """
    global _limiter
    n = thread_count(n_threads)
    # Numba first: it launches its layer (loading libgomp), which threadpoolctl then limits too
    numba.set_num_threads(min(n, numba.config.NUMBA_NUM_THREADS))
    if _limiter is not None:
        _limiter.restore_original_limits()
    _limiter = threadpool_limits(limits=n)
    info = threadpool_info()
    return {
        "threads": n,
        "blas": [(d["internal_api"], d["num_threads"]) for d in info if d["user_api"] == "blas"],
        "openmp": [(d["prefix"], d["num_threads"]) for d in info if d["user_api"] == "openmp"],
        "numba": numba.get_num_threads(),
        "layer": numba.config.THREADING_LAYER,
        "pid": os.getpid(),
    }


@contextmanager
def thread_policy(n_threads: int | None = 1) -> Iterator[None]:
    """``apply_thread_policy(n_threads)`` for the block only, then the limits in force before it.

    For a process that computes a pool's jobs itself between other work (``Executor(...,
    caller_runs=True)``): while it runs a job it is one of several concurrent jobs, so it runs
    one thread like a worker; afterwards it is back to its own budget (the ``fpu`` CLI: all
    cores).  Costs ~1.5 ms (threadpoolctl scans the loaded libraries)."""
    n = thread_count(n_threads)
    old = numba.get_num_threads()
    numba.set_num_threads(min(n, numba.config.NUMBA_NUM_THREADS))
    try:
        with threadpool_limits(limits=n):
            yield
    finally:
        numba.set_num_threads(old)
