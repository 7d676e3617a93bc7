"""A pool worker killed mid-job leaves no semaphore to the resource tracker.

Libraries make multiprocessing locks with the default context inside a worker: numcodecs'
Blosc mutex (a sweep or atlas store written there), Numba's threading-layer RLock.  Workers used
to run with the "spawn" default, whose locks are named and registered with the parent's resource
tracker; a worker killed mid-job (Cancel, a superseded job, a session closed, shutdown) never
unregistered them, and the server's log ended with "resource_tracker: There appear to be 1
leaked semaphore objects to clean up at shutdown".
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from fpucore.parallel import Executor

ROOT = Path(__file__).resolve().parents[2]

KILLED_MID_JOB = """
import time
from fpucore.parallel import Executor

def hold_a_lock(progress=None):
    import multiprocessing as mp
    lock = mp.Lock()  # as numcodecs' Blosc mutex or Numba's lock, with the default context
    progress(0.5)
    time.sleep(60)
    return lock

if __name__ == "__main__":
    ex = Executor(backend="process", workers=1)
    job = ex.submit(hold_a_lock)
    t_end = time.monotonic() + 120
    while job.progress is None and time.monotonic() < t_end:
        time.sleep(0.05)
    assert job.progress is not None, "the job never started"
    job.cancel()  # its worker is killed while the lock exists
    ex.shutdown()
    print("leaving", flush=True)
"""


def lock_name():
    import multiprocessing as mp

    return mp.Lock()._semlock.name  # None: anonymous (unlinked at creation, nothing to track)


def blosc_lock_name():
    """The name of the mutex numcodecs' Blosc makes on its first encode, in this process."""
    import gc
    import multiprocessing.synchronize as sync

    import numcodecs

    numcodecs.Blosc().encode(np.arange(1000.0))
    names = [o._semlock.name for o in gc.get_objects() if isinstance(o, sync.SemLock)]
    return names


def test_locks_made_in_a_worker_are_anonymous():
    with Executor(backend="process", workers=1) as ex:
        assert ex.submit(lock_name).result(timeout=180) is None
        pytest.importorskip("numcodecs")
        names = ex.submit(blosc_lock_name).result(timeout=180)
    assert names and all(n is None for n in names), names


def test_a_worker_killed_holding_a_lock_leaves_nothing_to_the_resource_tracker(tmp_path):
    script = tmp_path / "killed_mid_job.py"
    script.write_text(KILLED_MID_JOB)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, timeout=240, env=env
    )
    assert out.returncode == 0 and "leaving" in out.stdout, out.stderr
    assert "leaked" not in out.stderr and "Traceback" not in out.stderr, out.stderr
