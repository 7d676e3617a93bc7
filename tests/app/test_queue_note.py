"""A job that waits for a free worker says so before it starts: ``run_job`` tells its caller how
many earlier jobs it waits behind, and the scene shows it in its progress line."""

from __future__ import annotations

import os
import threading
import time

import pytest

pytest.importorskip("panel")

from app import compute  # noqa: E402
from app.explorer import Explorer  # noqa: E402


def test_a_job_behind_a_busy_pool_hears_how_many_jobs_are_ahead_then_that_it_started():
    workers = compute.workers.executor().workers
    tag = time.time()
    blockers = [
        threading.Thread(
            target=compute.workers.run_job, args=(("sleep", tag, k), time.sleep, (3.0,))
        )
        for k in range(workers)
    ]
    for t in blockers:
        t.start()
    deadline = time.monotonic() + 30
    while compute.workers.jobs_in_flight() < workers and time.monotonic() < deadline:
        time.sleep(0.01)
    seen: list[int] = []
    pid = compute.workers.run_job(("pid", tag), os.getpid, (), queued=seen.append).value
    for t in blockers:
        t.join()
    assert pid != os.getpid()
    assert seen[0] == workers, seen  # every worker busy with an earlier job: said at once
    assert seen[-1] == 0 and seen == sorted(seen, reverse=True), seen


def test_a_job_with_a_free_worker_reports_no_queue():
    seen: list[int] = []
    compute.workers.run_job(("pid", time.time()), os.getpid, (), queued=seen.append)
    assert seen == [0]  # no earlier job: nothing to wait for, said once


def test_the_scene_shows_the_queue_before_the_job_starts_and_clears_it():
    sc = Explorer().scene("simulation")
    hooks = sc.job_hooks("simulation")
    assert hooks["queued"] == sc.note_queue and hooks["stop"] == sc.superseded
    sc.note_queue(2)
    assert sc.progress_text.object == (
        "waiting for a free worker: 2 jobs ahead (other runs on this server)"
    )
    sc.note_queue(1)
    assert "1 job ahead" in sc.progress_text.object
    sc.note_queue(0)
    assert "waiting" not in sc.progress_text.object
