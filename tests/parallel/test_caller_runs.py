"""``Executor(caller_runs=True)``: the calling process computes the jobs no worker has taken yet
(a sweep on K cores = the caller and K - 1 workers).

References: the same items run inline in this process (values, bit-equal), the pids the items
report (who ran them), and this process's thread budget before the map.  Every wait has a
timeout or a bounded item, so a regression fails instead of hanging.
"""

from __future__ import annotations

import functools
import os
import queue
import signal
import time

import numba
import numpy as np
import probes
import pytest
from threadpoolctl import threadpool_info

from fpucore import atlas
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.parallel import (
    Cancelled,
    Executor,
    WorkerDied,
    apply_thread_policy,
    cores,
)

T = 180  # s: generous (a cold Numba cache compiles in the workers), never reached when healthy


@pytest.fixture
def ex():
    e = Executor("process", workers=2, caller_runs=True)
    yield e
    e.shutdown()


def worker_up(e: Executor) -> int:
    """Wait until the (background-started) worker has run a job; its pid.  A plain submit is
    never run by the caller (it only computes while it waits in map / next_done)."""
    return e.submit(probes.where, 0).result(timeout=T)[1]


def test_counts_the_caller_and_starts_one_worker_fewer(ex):
    assert ex.workers == 2 and ex.impl.n_workers == 1
    assert worker_up(ex) != os.getpid()
    assert len(ex.impl.pids()) == 1


def test_values_equal_inline_every_index_once_progress_to_total(ex):
    items = [0.5 * k - 3.0 for k in range(15)]
    ref = dict(Executor("inline").map(probes.square, items))
    calls = []
    got = list(ex.map(probes.square, items, progress=lambda d, n: calls.append((d, n))))
    assert sorted(i for i, _ in got) == list(range(len(items)))  # every index exactly once
    assert dict(got) == ref
    assert calls == [(k, len(items)) for k in range(1, len(items) + 1)]


def test_the_caller_runs_items_with_one_thread_and_gets_its_budget_back(ex):
    apply_thread_policy(None)  # this process's own budget: all cores
    try:
        before = numba.get_num_threads(), [d["num_threads"] for d in threadpool_info()]
        out = dict(ex.map(probes.where, range(6)))
        mine = [o for o in out.values() if o[1] == os.getpid()]
        assert mine, "the calling process ran no item"
        assert all(o[2] == 1 and set(o[3]) == {1} for o in out.values())  # caller and worker
        after = numba.get_num_threads(), [d["num_threads"] for d in threadpool_info()]
        assert after == before and before[0] == min(cores(), numba.config.NUMBA_NUM_THREADS)
    finally:
        apply_thread_policy(1)


def test_an_exception_is_yielded_from_the_caller_and_from_a_worker(ex):
    worker = worker_up(ex)
    out = dict(ex.map(probes.fail_where, [0.3] * 6))
    assert len(out) == 6 and all(isinstance(e, ValueError) for e in out.values())
    where = {e.args[0] for e in out.values()}
    assert where == {os.getpid(), worker}  # both raised, both were yielded, the map went on
    assert ex.submit(probes.square, 3.0).result(timeout=T) == 9.0


def test_a_parameter_error_run_by_the_caller_keeps_its_fields(ex):
    out = dict(ex.map(probes.refuse, [7.5]))
    assert isinstance(out[0], ParameterError) and out[0].name == "x" and out[0].value == 7.5


def test_leaving_the_loop_cancels_the_rest_and_leaves_no_live_worker():
    e = Executor("process", workers=2, caller_runs=True)
    try:
        worker = worker_up(e)
        fn = functools.partial(probes.sleep_in_workers, seconds=60.0)
        t0 = time.monotonic()
        for _, pid in e.map(fn, [os.getpid()] * 8):
            assert pid == os.getpid()  # the worker is asleep on its item: the caller's is first
            time.sleep(0.5)  # the idle worker surely took an item meanwhile
            break
        assert time.monotonic() - t0 < 20
        deadline = time.monotonic() + 30
        while e.impl.replaced < 1 or worker in e.impl.pids():
            assert time.monotonic() < deadline, "the worker on a cancelled item was not stopped"
            time.sleep(0.05)
        assert e.impl.steal() is None  # nothing of the map left to run
        pids = e.impl.pids()
    finally:
        e.shutdown()
    for pid in [worker, *pids]:
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)


def test_ctrl_c_in_an_item_run_by_the_caller_propagates_and_cancels_the_rest():
    e = Executor("process", workers=2, caller_runs=True)
    try:
        worker_up(e)
        t0 = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            for _ in e.map(probes.interrupt_in, [os.getpid()] * 6):
                pass
        assert time.monotonic() - t0 < 20  # the workers' 60 s items were cancelled, not awaited
        # a worker still asleep on an item (not cancelled) would keep this job waiting 60 s
        assert e.submit(probes.square, 2.0).result(timeout=20) == 4.0
    finally:
        e.shutdown()


def test_next_done_times_out_when_nothing_is_waiting(ex):
    with pytest.raises(queue.Empty):
        ex.next_done(queue.Queue(), timeout=0.05)


def test_bad_caller_runs_is_refused():
    with pytest.raises(ParameterError, match="caller_runs"):
        Executor("dask", caller_runs=True)
    with pytest.raises(ParameterError, match="caller_runs"):
        Executor("process", caller_runs=1)


def test_sweep_on_its_own_execution_equals_inline():
    """atlas.sweep without an executor (the caller and a worker compute) gives bit-equal rows
    to the same sweep run inline in this process."""
    law, V = CubicLaw(-1.0, 10.0), [5.0, 5.2, 5.4, 5.6]
    own = atlas.sweep(law, "superkink", V, N=64, use_cache=False, workers=2)
    ref = atlas.sweep(law, "superkink", V, N=64, use_cache=False, executor=Executor("inline"))
    assert own.message == ref.message and own.converged
    np.testing.assert_array_equal(own.max_modulus, ref.max_modulus)
    np.testing.assert_array_equal(own.max_modulus_error, ref.max_modulus_error)


# -- lookahead: a caller_runs pool sends a busy worker its next job ahead ----------------------
def test_a_cancelled_job_waiting_in_a_busy_workers_pipe():
    """A runs on the worker, B waits in its pipe (C, the last one queued, stays in the queue):
    cancelling B leaves A's value, B raises Cancelled, C still runs, and the worker that
    started B is replaced."""
    e = Executor("process", workers=2, caller_runs=True)
    try:
        worker = worker_up(e)
        a = e.submit(probes.sleep, 1.5)
        b = e.submit(probes.square, 2.0)
        c = e.submit(probes.square, 3.0)
        wait_state(a, "running")
        time.sleep(0.3)  # the manager sends B ahead at once
        assert b.cancel()
        assert a.result(timeout=T) >= 1.5
        with pytest.raises(Cancelled):
            b.result(timeout=1)
        assert c.result(timeout=T) == 9.0
        deadline = time.monotonic() + 30
        while e.impl.replaced < 1 or worker in e.impl.pids():
            assert time.monotonic() < deadline, "the worker that started B was not replaced"
            time.sleep(0.05)
        assert e.submit(probes.square, 4.0).result(timeout=T) == 16.0
    finally:
        e.shutdown()


def test_a_job_waiting_in_a_killed_workers_pipe_runs_elsewhere():
    e = Executor("process", workers=2, caller_runs=True)
    try:
        worker_up(e)
        a = e.submit(probes.spin, 600.0)
        wait_state(a, "running")
        b, c = e.submit(probes.square, 5.0), e.submit(probes.square, 6.0)
        time.sleep(0.3)
        os.kill(a.worker, signal.SIGKILL)  # as an OOM killer would
        with pytest.raises(WorkerDied):
            a.result(timeout=T)
        assert b.result(timeout=T) == 25.0 and c.result(timeout=T) == 36.0  # B never started
    finally:
        e.shutdown()


def wait_state(job, state: str, timeout: float = T) -> None:
    t0 = time.monotonic()
    while job.state != state:
        assert time.monotonic() - t0 < timeout, f"job never {state}"
        time.sleep(0.01)
