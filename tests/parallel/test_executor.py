"""The execution layer (fpucore.parallel): a pool after a wave solve in the parent (the fork /
GNU OpenMP deadlock), cancel, exceptions, dead workers, Dask = pool = inline.

Every wait has a timeout, so a regression fails instead of hanging.  Reference values are the
same computation done in this process (bit-equal: same code, same inputs, one thread).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numba
import probes
import pytest

from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.parallel import Cancelled, Executor, WorkerDied, apply_thread_policy
from fpucore.wave import solve_superkink

T = 180  # s: generous (a cold Numba cache compiles in the workers), never reached when healthy


@pytest.fixture(scope="module")
def pool():
    ex = Executor("process", workers=2)
    yield ex
    ex.shutdown()


def wait_running(job, timeout=T):
    t0 = time.monotonic()
    while job.state != "running":
        assert time.monotonic() - t0 < timeout, "job never started"
        time.sleep(0.01)


def test_pool_after_a_wave_solve_in_the_parent():
    r = solve_superkink(CubicLaw(-1.0, 10.0), 5.2, N=64)  # starts Numba's OpenMP threads here
    assert r.converged and numba.threading_layer() == "omp"
    ex = Executor("process", workers=2)
    try:
        jobs = [ex.submit(probes.superkink, V, 64) for V in (5.2, 5.3, 5.2)]
        out = [j.result(timeout=T) for j in jobs]
    finally:
        ex.shutdown()
    assert all(o["converged"] and o["layer"] == "omp" for o in out)
    assert out[0]["w_max"] == out[2]["w_max"] == float(r.w.max())
    assert {o["pid"] for o in out} != {os.getpid()}


def test_workers_run_one_thread(pool):
    b = [pool.submit(probes.thread_budget).result(timeout=T) for _ in range(4)]
    assert all(x["numba"] == 1 for x in b)
    assert all(n == 1 for x in b for _, n in x["pools"])


def test_thread_policy_in_this_process():
    info = apply_thread_policy(1)
    assert info["numba"] == 1 and all(n == 1 for _, n in info["blas"])
    info = apply_thread_policy(None)
    assert info["threads"] >= 1 and all(n == info["threads"] for _, n in info["blas"])
    apply_thread_policy(1)


def test_values_and_progress(pool):
    assert pool.submit(probes.square, 3.0).result(timeout=T) == 9.0
    job = pool.submit(probes.sleep, 1.0)
    seen = []
    while not job.done():
        if job.progress is not None:
            seen.append(job.progress)
        time.sleep(0.01)
    assert job.result() >= 1.0 and job.progress == 1.0
    assert seen and 0.0 <= min(seen) < 1.0


def test_parameter_error_keeps_class_and_message(pool):
    with pytest.raises(ParameterError) as e:
        pool.submit(probes.refuse, 7.5).result(timeout=T)
    assert e.value.name == "x" and e.value.value == 7.5 and e.value.valid == "(0, 1)"
    assert str(e.value).startswith("x=7.5 is out of range: valid (0, 1)")


def test_cancel_a_running_job_is_prompt_and_the_pool_goes_on(pool):
    job = pool.submit(probes.spin, 600.0)
    wait_running(job)
    old = job.worker
    t0 = time.monotonic()
    assert job.cancel()
    with pytest.raises(Cancelled):
        job.result(timeout=5)
    assert time.monotonic() - t0 < 5
    assert pool.submit(probes.square, 4.0).result(timeout=T) == 16.0
    deadline = time.monotonic() + 30
    while old in pool.impl.pids():
        assert time.monotonic() < deadline, "the cancelled job's worker was not replaced"
        time.sleep(0.05)
    assert len(pool.impl.pids()) == 2


def test_cancel_a_queued_job():
    ex = Executor("process", workers=1)
    try:
        first = ex.submit(probes.sleep, 0.5)
        queued = ex.submit(probes.square, 2.0)
        assert queued.cancel()
        assert first.result(timeout=T) >= 0.5
        with pytest.raises(Cancelled):
            queued.result(timeout=1)
        assert ex.impl.replaced == 0  # nothing was running it: no worker terminated
    finally:
        ex.shutdown()


def test_a_killed_worker_is_that_jobs_failure(pool):
    with pytest.raises(WorkerDied, match="SIGKILL"):
        pool.submit(probes.die, signal.SIGKILL).result(timeout=T)
    job = pool.submit(probes.spin, 600.0)  # killed from outside, as an OOM killer would
    wait_running(job)
    os.kill(job.worker, signal.SIGKILL)
    with pytest.raises(WorkerDied):
        job.result(timeout=T)
    assert pool.submit(probes.square, 5.0).result(timeout=T) == 25.0


def test_map_unordered_with_a_failing_item(pool):
    calls = []
    out = dict(pool.map(probes.square, [1.0, "x", 3.0], progress=lambda d, n: calls.append(d)))
    assert out[0] == 1.0 and out[2] == 9.0 and isinstance(out[1], TypeError)
    assert calls == [1, 2, 3]


def test_bad_arguments_are_refused():
    with pytest.raises(ParameterError, match="backend"):
        Executor("threads")
    with pytest.raises(ParameterError, match="workers"):
        Executor("process", workers=0)
    with pytest.raises(ParameterError, match="address"):
        Executor("process", address="tcp://localhost:1")


def test_dask_local_cluster_equals_pool_and_inline(pool):
    Vs = [5.0, 5.2, 5.5]
    inline = Executor("inline")
    ref = {i: v["w_max"] for i, v in inline.map(probes.superkink, Vs)}
    loc = {i: v["w_max"] for i, v in pool.map(probes.superkink, Vs)}
    ex = Executor("dask", workers=2)
    try:
        got = {i: v["w_max"] for i, v in ex.map(probes.superkink, Vs)}
        with pytest.raises(ParameterError) as e:
            ex.submit(probes.refuse, 2.0).result(timeout=T)
        assert e.value.name == "x"
        job = ex.submit(probes.sleep, 1.0)
        assert job.result(timeout=T) >= 1.0 and job.progress == 1.0
        assert all(x["numba"] == 1 for x in [ex.submit(probes.thread_budget).result(timeout=T)])
        job = ex.submit(probes.spin, 600.0)  # cancel while running: its worker is restarted
        wait_running(job)
        job.cancel()
        with pytest.raises(Cancelled):
            job.result(timeout=5)
        deadline = time.monotonic() + 120
        while any(ex.impl.client.processing().values()) or ex.workers < 2:
            assert time.monotonic() < deadline, "the spinning task was not stopped"
            time.sleep(0.2)
        assert ex.submit(probes.square, 6.0).result(timeout=T) == 36.0
    finally:
        ex.shutdown()
    assert got == loc == ref


EXIT_SCRIPT = """
from fpucore.parallel import Executor
from probes import sleep

if __name__ == "__main__":
    ex = Executor(backend="process", workers=2)
    assert ex.submit(sleep, 0.01).result(60) >= 0.01
    for job in [ex.submit(sleep, 30.0) for _ in range(2)]:
        job.cancel()  # the pool replaces both workers while the script exits
    print("leaving")
"""


def test_exit_right_after_cancelling_is_quiet(tmp_path):
    """A script that cancels running jobs and exits with its pool still open: no traceback
    (the pool is shut down at exit, and a shutdown that meets a worker replacement does not
    wait on the stopped worker's closed pipe — it did in ~1 run in 5), and no wait for the
    cancelled 30 s jobs."""
    script = tmp_path / "exit_after_cancel.py"
    script.write_text(EXIT_SCRIPT)
    root = Path(__file__).resolve().parents[2]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(root), str(root / "tests" / "support")]))
    for _ in range(8):
        out = subprocess.run(
            [sys.executable, str(script)], capture_output=True, text=True, timeout=25, env=env
        )
        assert out.returncode == 0 and "leaving" in out.stdout, out.stderr
        assert "Traceback" not in out.stderr and "Exception in" not in out.stderr, out.stderr
