"""The loop run by each process-pool worker (in the child process).

Protocol on the worker's duplex pipe.  Parent → worker:
``(job_id, fn, args, kwargs, wants_progress)``, or ``None`` to exit.  Worker → parent:
``("progress", job_id, frac)`` (at most every ``PROGRESS_INTERVAL_S``, except a step of at least
``PROGRESS_STEP`` and the final 1.0, which are sent at once) and
``("done", job_id, ok, value_or_exception)``.
"""

from __future__ import annotations

import multiprocessing as mp
import pickle
import signal
import time
import traceback

from fpucore.parallel.jobs import RemoteError
from fpucore.parallel.threads import apply_thread_policy

PROGRESS_INTERVAL_S = 0.1
#: the default start method inside a worker (see worker_main): its locks are anonymous
WORKER_START_METHOD = "fork" if "fork" in mp.get_all_start_methods() else "spawn"
#: a step this large is news (a job's next stage): sent at once, not left to the throttle — a
#: long uninterrupted call after it (a LAPACK eigenvalue solve) would otherwise hide it
PROGRESS_STEP = 0.05


def portable_exception(exc: BaseException) -> BaseException:
    """``exc`` with the worker's traceback as a note if it survives pickling, else a
    RemoteError carrying its class name, message and traceback."""
    tb = "".join(traceback.format_exception(exc))
    try:
        exc.add_note("worker traceback:\n" + tb)
        pickle.loads(pickle.dumps(exc))
        return exc
    except Exception:
        return RemoteError(f"{type(exc).__name__}: {exc}\nworker traceback:\n{tb}")


def progress_sender(conn, job_id: int):
    """A ``progress(frac)`` callable sending throttled progress messages to the parent."""
    last = [0.0, 0.0]  # time and value of the last message sent

    def progress(frac: float) -> None:
        now = time.monotonic()
        frac = float(frac)
        step = abs(frac - last[1]) >= PROGRESS_STEP
        if frac >= 1.0 or step or now - last[0] >= PROGRESS_INTERVAL_S:
            last[0], last[1] = now, frac
            conn.send(("progress", job_id, frac))

    return progress


def worker_main(conn, n_threads: int = 1) -> None:
    """Serve jobs from ``conn`` until ``None`` arrives or the pipe closes.  Ctrl-C is the
    parent's business (it cancels or shuts down): a worker ignores SIGINT, so an interrupted
    sweep never records a point as failed with KeyboardInterrupt."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # Locks made with the default context in a worker must be anonymous semaphores.  The worker
    # inherits "forkserver" (or "spawn"), whose locks are named and registered with the resource
    # tracker; a worker killed mid-job (Cancel, a superseded job, shutdown) never unregisters
    # them, and the tracker prints "There appear to be N leaked semaphore objects" when the
    # parent exits.  Such locks come from libraries: Numba's threading-layer RLock, numcodecs'
    # Blosc mutex (an atlas or sweep store written here).  A "fork" lock is unlinked at once
    # (nothing to leak); a worker never starts processes of its own with the default context
    # (fpucore's pools name theirs), so "fork" is never used to start anything here.
    mp.set_start_method(WORKER_START_METHOD, force=True)
    apply_thread_policy(n_threads)
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError, KeyboardInterrupt):
            return
        if msg is None:
            return
        job_id, fn, args, kwargs, wants_progress = msg
        if wants_progress:
            kwargs = {**kwargs, "progress": progress_sender(conn, job_id)}
        try:
            out = ("done", job_id, True, fn(*args, **kwargs))
        except BaseException as exc:  # noqa: BLE001  (everything goes back to the caller)
            out = ("done", job_id, False, portable_exception(exc))
        try:
            conn.send(out)
        except Exception as exc:  # an unpicklable return value
            conn.send(("done", job_id, False, portable_exception(exc)))
