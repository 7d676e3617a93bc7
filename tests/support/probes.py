"""Test support for tests/parallel (not part of fpucore): small jobs that check a backend
(picklable, module-level): echo, sleep, fail, die, report the thread budget, solve a wave.

Imported as ``probes``: pytest puts tests/support on ``sys.path`` (pyproject's ``pythonpath``),
and the pool's and Dask's worker processes inherit the parent's ``sys.path``, so they unpickle
these jobs by that name."""

from __future__ import annotations

import os
import signal
import time

import numba
import numpy as np
from threadpoolctl import threadpool_info

from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.wave import solve_superkink


def square(x: float) -> float:
    return x * x


def sleep(seconds: float, progress=None) -> float:
    """Sleep in 20 ms slices reporting progress; returns the seconds slept."""
    t0 = time.monotonic()
    while (t := time.monotonic() - t0) < seconds:
        if progress is not None:
            progress(t / seconds)
        time.sleep(0.02)
    return time.monotonic() - t0


def spin(seconds: float) -> int:
    """Busy loop (no sleep: a job that never yields), returns the iterations."""
    t0, n = time.monotonic(), 0
    while time.monotonic() - t0 < seconds:
        n += 1
    return n


def refuse(x: float) -> None:
    """Raise ParameterError naming x (to check that the class and message cross processes)."""
    raise ParameterError("x", x, "(0, 1)", "probe")


def die(code: int = 9) -> None:
    """Kill the worker process itself with signal ``code``."""
    os.kill(os.getpid(), code if code else signal.SIGKILL)


def thread_budget() -> dict:
    """pid, Numba threads and every BLAS/OpenMP library's thread count in this process."""

    return {
        "pid": os.getpid(),
        "numba": numba.get_num_threads(),
        "pools": [(d["user_api"], d["num_threads"]) for d in threadpool_info()],
    }


def where(x):
    """``(x, pid, Numba threads, [threads of each BLAS/OpenMP library])`` of the process that ran
    it (which process computed an item, under which thread budget)."""
    return x, os.getpid(), numba.get_num_threads(), [d["num_threads"] for d in threadpool_info()]


def fail_where(seconds: float) -> None:
    """Sleep ``seconds``, then raise ValueError(pid): which process ran a failing item."""
    time.sleep(seconds)
    raise ValueError(os.getpid())


def sleep_in_workers(caller_pid: int, seconds: float = 30.0) -> int:
    """Return the pid at once in the process ``caller_pid``, sleep ``seconds`` first anywhere
    else (a pool worker is busy while the caller's items are done: early exit, cancel)."""
    if os.getpid() != caller_pid:
        time.sleep(seconds)
    return os.getpid()


def interrupt_in(caller_pid: int) -> int:
    """Raise KeyboardInterrupt in the process ``caller_pid`` (Ctrl-C while the caller computes),
    sleep 60 s anywhere else; returns the pid."""
    if os.getpid() == caller_pid:
        raise KeyboardInterrupt
    time.sleep(60.0)
    return os.getpid()


def superkink(V: float, N: int = 64) -> dict:
    """A discrete superkink solved in this process (runs Numba's parallel period map):
    residual, amplitude-like summary and the threading layer used."""
    r = solve_superkink(CubicLaw(-1.0, 10.0), V, N=N)
    return {
        "converged": bool(r.converged),
        "residual": float(r.residual),
        "w_max": float(np.max(r.w)),
        "layer": numba.threading_layer(),
        "pid": os.getpid(),
    }
