"""The thread budget of fpucore — the one place where BLAS, OpenMP and Numba threads are set.

Why.  One Floquet spectrum at N = 500 is a LAPACK ``dgeev`` of a ~1000 × 1000 matrix; two of them
at once with OpenBLAS's default (one thread per core each) took 5.4 s instead of 0.7 s on the
2-core machine: threads of two processes fighting for the same cores.  So threads are
never left at a library's default, and parallelism across jobs comes from *processes*.

The policy
----------
* **fpucore's own calls run on a thread budget, in every process** — a script, a notebook, the
  ``fpu`` CLI as well as the workers.  Every public entry point that does heavy work
  (``floquet.spectrum``, ``wave.solve_*``, ``simulate.*`` ...) runs under :func:`budgeted`: for
  the call only, BLAS/OpenMP (threadpoolctl) and Numba (``set_num_threads``, calling thread) are
  limited to :func:`thread_budget` threads, then restored — the caller's own numpy keeps its
  settings.  The budget is **one thread** unless the user says otherwise: measured on the 2-core
  machine, ``floquet.spectrum`` of the superkink V = 5.2, N = 500 took 0.55 s with one thread and
  2.5 s with OpenBLAS's default two on an idle-looking machine (load 2), 20 s under load 5–9:
  ``dgeev`` gains little from a second thread and loses everything when a core is
  busy.  Override: the environment variable ``FPU_THREADS`` (a positive integer, or ``all`` for
  :func:`cores`), or ``apply_thread_policy(n)`` in a script (the process's budget from then on).
* A process that runs **one of several concurrent jobs** — every worker of
  :class:`fpucore.parallel.Executor` (process pool or Dask worker), the atlas's workers, the CLI
  while it drives a sweep, the dashboard server (several sessions compute at once) — uses
  **one thread** whatever ``FPU_THREADS`` says: ``apply_thread_policy(1)``.  K jobs then run on
  K cores without oversubscription, and the throughput scales with the number of processes.  A
  caller that computes jobs of its own pool (``Executor(caller_runs=True)``: ``fpu floquet
  sweep``) is one of them while it runs a job: :func:`thread_policy` gives it one thread for that
  job only.
* Limits are set with threadpoolctl on every BLAS (OpenBLAS/MKL, numpy's and scipy's own copies:
  both are imported here first so that both are loaded when the limit is applied) and OpenMP
  library in the process, and with ``numba.set_num_threads`` for Numba's parallel kernels
  (``wave.period_map``).  ``numba.set_num_threads`` is *per calling thread*: a server thread that
  computes calls ``apply_thread_policy`` itself (it is cheap: ~0.1 ms after the first call).
* Numba's threading layer is chosen deliberately: ``"omp"`` (GNU OpenMP), set by
  :func:`configure_threading_layer` when fpucore is imported.  It is thread-safe (the server calls
  parallel kernels from several threads; ``"workqueue"`` aborts on concurrent use) and TBB is not
  installed.  GNU OpenMP does not survive ``fork()`` ("fork() called from a process already using
  GNU OpenMP" and a pool that never returns), so **no fpucore process pool ever
  forks the process that ran a kernel**: the Executor starts its workers with the ``forkserver``
  method (a clean server process, started by exec, that imported fpucore but never ran a
  kernel, forks the workers), and Dask's nannies use ``spawn``.
"""

from __future__ import annotations

import functools
import os
import threading
from collections.abc import Iterator
from contextlib import contextmanager

import numba
import numpy  # noqa: F401  (numpy's OpenBLAS is loaded before the limit is applied)
import scipy.linalg  # noqa: F401  (load scipy's own OpenBLAS so the limit reaches it)
from threadpoolctl import ThreadpoolController, threadpool_info, threadpool_limits

from fpucore.errors import ParameterError, require_int

THREADING_LAYER = "omp"  # the layer fpucore/__init__ also puts in the environment
ENV_VAR = "FPU_THREADS"  # the user's override of the budget (a positive integer or "all")
MAX_THREADS = 4096  # per process: far above any machine's cores
_limiter = None  # the active threadpoolctl limiter (kept alive: the limit holds while it lives)
_process_budget: int | None = None  # set by apply_thread_policy / thread_policy
_in_force: int | None = None  # the BLAS/OpenMP limit this module last applied process-wide
_controller: ThreadpoolController | None = None  # libraries scanned once (a scan costs ~1.5 ms)
_scope_lock = threading.Lock()
_scope_depth = 0  # calls inside budgeted() in this process (all threads): the limit is shared
_scope_limiter = None


def configure_threading_layer(layer: str = THREADING_LAYER) -> str:
    """Select Numba's threading layer (before the first parallel kernel runs; later calls can
    no longer change the layer already launched and return the one in use)."""
    try:
        return numba.threading_layer()  # raises ValueError until a parallel kernel has run
    except ValueError:
        numba.config.THREADING_LAYER = layer  # type: ignore[attr-defined]
        return layer


def cores() -> int:
    """Cores this process may use (its CPU affinity, else os.cpu_count())."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def thread_count(n_threads: int | None) -> int:
    """The thread count of a policy: :func:`cores` for None, else an integer >= 1 (ParameterError
    for 'x', 2.5, True ..., never a bare ValueError from ``int('x')``)."""
    if n_threads is None:
        return cores()
    return require_int("n_threads", n_threads, 1, MAX_THREADS)


def default_threads() -> int:
    """The budget the user asked for: ``FPU_THREADS`` (a positive integer, or ``all`` for every
    core), else 1.  A malformed value is refused with a ParameterError naming the variable."""
    raw = os.environ.get(ENV_VAR, "").strip()
    if not raw:
        return 1
    if raw.lower() == "all":
        return cores()
    try:
        n = int(raw)
    except ValueError:
        n = 0
    if not 1 <= n <= MAX_THREADS:
        raise ParameterError(
            ENV_VAR, raw, f"an integer in [1, {MAX_THREADS}] or 'all'", "environment variable"
        )
    return n


def thread_budget() -> int:
    """Threads fpucore's own calls use in this process now: the budget set by
    :func:`apply_thread_policy` / :func:`thread_policy`, else :func:`default_threads`."""
    return default_threads() if _process_budget is None else _process_budget


def _numba_threads(n: int) -> int:
    return min(n, numba.config.NUMBA_NUM_THREADS)  # type: ignore[attr-defined]


def apply_thread_policy(n_threads: int | None = 1) -> dict:
    """Set this process's thread budget and apply it at once to BLAS, OpenMP and Numba (Numba: of
    the calling thread); fpucore's calls keep to it from then on.

    n_threads : 1 for a process running one of several concurrent jobs (the default: workers,
    server); None for all :func:`cores`; any other count (a script's choice).
    Returns {"threads": n, "blas": [...], "openmp": [...], "numba": n, "layer": ...}: the
    libraries found and the limits now in force.
    """
    global _limiter, _process_budget, _in_force
    n = thread_count(n_threads)
    # Numba first: it launches its layer (loading libgomp), which threadpoolctl then limits too
    numba.set_num_threads(_numba_threads(n))
    if _limiter is not None:
        _limiter.restore_original_limits()
    _limiter = threadpool_limits(limits=n)
    _process_budget = _in_force = n
    info = threadpool_info()
    return {
        "threads": n,
        "blas": [(d["internal_api"], d["num_threads"]) for d in info if d["user_api"] == "blas"],
        "openmp": [(d["prefix"], d["num_threads"]) for d in info if d["user_api"] == "openmp"],
        "numba": numba.get_num_threads(),
        "layer": numba.config.THREADING_LAYER,  # type: ignore[attr-defined]
        "pid": os.getpid(),
    }


@contextmanager
def thread_policy(n_threads: int | None = 1) -> Iterator[None]:
    """``apply_thread_policy(n_threads)`` for the block only, then the limits in force before it.

    For a process that computes a pool's jobs itself between other work (``Executor(...,
    caller_runs=True)``): while it runs a job it is one of several concurrent jobs, so it runs
    one thread like a worker; afterwards it is back to its own budget.  Costs ~1.5 ms
    (threadpoolctl scans the loaded libraries)."""
    global _process_budget, _in_force
    n = thread_count(n_threads)
    old = numba.get_num_threads()
    saved = _process_budget, _in_force
    numba.set_num_threads(_numba_threads(n))
    try:
        with threadpool_limits(limits=n):
            _process_budget = _in_force = n
            yield
    finally:
        _process_budget, _in_force = saved
        numba.set_num_threads(old)


@contextmanager
def budgeted() -> Iterator[int]:
    """Run the block (one of fpucore's own calls) on :func:`thread_budget` threads; yields it.

    Free when the process's policy is already in force (workers, server, CLI: nothing to do but
    compare two integers); otherwise (a script, a notebook) the BLAS/OpenMP limit is set for the
    outermost call in progress in the process (the limit is process-wide: concurrent calls from
    several threads share it, the last one out restores the caller's settings) and Numba's count
    of the calling thread for this call."""
    global _controller, _scope_depth, _scope_limiter
    n = thread_budget()
    old = numba.get_num_threads()
    if old != _numba_threads(n):
        numba.set_num_threads(_numba_threads(n))
    scoped = _in_force != n
    if scoped:
        with _scope_lock:
            if _scope_depth == 0:
                if _controller is None:
                    _controller = ThreadpoolController()
                _scope_limiter = _controller.limit(limits=n)
            _scope_depth += 1
    try:
        yield n
    finally:
        if scoped:
            with _scope_lock:
                _scope_depth -= 1
                if _scope_depth == 0:
                    _scope_limiter.restore_original_limits()  # type: ignore[union-attr]
                    _scope_limiter = None
        if old != numba.get_num_threads():
            numba.set_num_threads(old)


def on_budget(fn):
    """Decorator: ``fn`` (a public entry point of fpucore) runs under :func:`budgeted`."""

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with budgeted():
            return fn(*args, **kwargs)

    return wrapper
