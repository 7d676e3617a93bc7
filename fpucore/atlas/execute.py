"""Computing an atlas's chunks: each chunk's :class:`~fpucore.atlas.point.ChunkTask` submitted
through the execution layer (:mod:`fpucore.parallel`), its records gathered into the
:class:`Table` (and the Zarr store) as it finishes.

A chunk whose worker died is retried once in the same run; if it dies again its points are
recorded as ``failed`` with the reason but not marked done, so a later resume retries them.  A
time budget stops the submitting and cancels what runs (points left pending).  Ctrl-C cancels the
running chunks and re-raises: every chunk gathered so far is kept.
"""

from __future__ import annotations

import queue
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from fpucore.atlas.grid import Grid
from fpucore.atlas.point import FIELDS, ChunkTask, empty_record, failure_text, solve_chunk
from fpucore.atlas.store import load_records, skeleton
from fpucore.parallel import Cancelled, Executor, WorkerDied

if TYPE_CHECKING:
    from fpucore.atlas.store import Writer

Record = dict[str, Any]


class Table:
    """The grid's records as one numpy array per field (what the store holds)."""

    def __init__(self, grid: Grid, attrs: dict):
        self.ds = skeleton(grid, attrs)
        self.cols = {k: self.ds[k].values for k in [*FIELDS, "done"]}
        self.grid = grid

    def put(self, i: int, j0: int, records: list[Record], final: bool) -> None:
        for j, rec in enumerate(records, start=j0):
            for k in FIELDS:
                self.cols[k][i, j] = rec[k]
            self.cols["done"][i, j] = 1 if final else 0

    def load(self, group) -> int:
        """The stored records of the done points (damaged chunks left to recompute, see
        :func:`fpucore.atlas.store.load_records`); returns how many were loaded."""
        done = load_records(group, self.grid, self.cols)
        self.cols["done"][done] = 1
        return int(done.sum())

    def count(self, status: str) -> int:
        return int(np.sum(self.cols["status"] == status))


@dataclass(frozen=True)
class Pool:
    """The executor a run starts when it was given none.  backend : "process" | "inline" |
    "dask"; workers : the plan's count (None: the backend's); automatic : that count was chosen
    by the plan (``workers=None``), not asked for; address : a Dask scheduler or None;
    caller_runs : this process computes chunks too (process backend)."""

    backend: str
    workers: int | None
    automatic: bool
    address: str | None
    caller_runs: bool

    def start(self, n_chunks: int) -> Executor:
        """An executor for ``n_chunks`` chunks (one chunk, automatic: inline, no pool to start)."""
        backend = self.backend
        if backend == "process" and n_chunks == 1 and self.automatic:
            backend = "inline"
        n = None if self.workers is None else min(self.workers, n_chunks)
        return Executor(
            backend,
            workers=n,
            address=self.address,
            caller_runs=self.caller_runs and backend == "process",
        )


@dataclass(frozen=True)
class Hooks:
    """What the caller hears and the budget: progress(done, total, failed) after each chunk;
    on_points([(i, j, record), ...]) with each chunk's records; time_budget_s (s, None: none)
    counted from t0 (``time.perf_counter()`` at the run's start)."""

    progress: Callable[[int, int, int], None] | None
    on_points: Callable[[list[tuple[int, int, Record]]], None] | None
    time_budget_s: float | None
    t0: float


@dataclass(frozen=True)
class Outcome:
    """What the chunks' execution did: points computed, the backend and workers it ran on,
    whether the time budget stopped it and why."""

    n_computed: int
    backend: str
    workers: int
    stopped: bool
    message: str


def execute(
    task: ChunkTask,
    grid: Grid,
    table: Table,
    writer: Writer | None,
    executor: Executor | None,
    pool: Pool,
    hooks: Hooks,
) -> Outcome:
    """Submit the chunks of ``grid`` not done in ``table`` (each ``task.at(...)``), gather and
    store them.  executor : the caller's (kept running), else one started from ``pool`` (and
    shut down at the end)."""
    done = table.cols["done"] == 1
    todo = [task.at(grid, i, j0, j1) for i, j0, j1 in grid.chunks() if not done[i, j0:j1].all()]
    own = executor is None and bool(todo)
    if own:
        executor = pool.start(len(todo))
    total, failed = grid.size, int(np.sum(table.cols["status"] == "failed"))
    n_done = int(done.sum())
    if hooks.progress is not None:
        hooks.progress(n_done, total, failed)
    if executor is None:  # nothing to do, and no executor was given
        return Outcome(0, "none", 0, False, "")
    ex: Executor = executor
    finished: queue.Queue = queue.Queue()
    jobs: dict[Any, ChunkTask] = {}
    retried: set[tuple[int, int]] = set()  # (row_index, start) of chunks resubmitted

    def submit(t: ChunkTask) -> None:
        job = ex.submit(solve_chunk, t)
        jobs[job] = t
        job.add_done_callback(finished.put)

    n_computed, stopped, msg = 0, False, ""
    n_workers = ex.workers
    waiting = deque(todo)  # chunks not submitted yet

    def gather(job) -> None:
        """One finished chunk: stored and reported, or retried once if its worker died."""
        nonlocal n_computed, n_done, failed
        t = jobs.pop(job)
        i, j0, j1 = t.row_index, t.start, t.stop
        exc = job.exception()
        if isinstance(exc, Cancelled):
            return
        final = True
        if exc is None:
            records = job.result()
        elif isinstance(exc, WorkerDied) and (i, j0) not in retried:
            retried.add((i, j0))
            submit(t)
            return
        else:  # the chunk as a whole failed (worker died twice, unpicklable, ...)
            final = not isinstance(exc, WorkerDied)  # a dead worker is retried on resume
            records = [empty_record("failed", failure_text(exc)) for _ in range(j1 - j0)]
        table.put(i, j0, records, final)
        if writer is not None:
            writer.write(i, j0, j1, records, final)
        n_computed += j1 - j0
        n_done += j1 - j0
        failed += sum(r["status"] == "failed" for r in records)
        if hooks.on_points is not None:
            hooks.on_points([(i, j, r) for j, r in enumerate(records, start=j0)])
        if hooks.progress is not None:
            hooks.progress(n_done, total, failed)

    budget = hooks.time_budget_s
    try:
        while waiting or jobs:
            if budget is not None and time.perf_counter() - hooks.t0 > budget:
                stopped = True
                msg = (
                    f"time budget {budget:g} s exhausted: "
                    f"{len(waiting) + len(jobs)} chunks not done"
                )
                break
            if waiting:
                submit(waiting.popleft())
                # an inline executor has run the chunk already: gather it now, so progress,
                # on_points and the time budget follow each chunk rather than the whole grid
                while not finished.empty():
                    gather(finished.get_nowait())
                continue
            try:
                job = ex.next_done(finished, timeout=0.2)  # caller_runs: computes here
            except queue.Empty:
                continue
            gather(job)
    finally:
        for job in list(jobs):
            job.cancel()
        if own:
            ex.shutdown()
    return Outcome(n_computed, ex.backend, n_workers, stopped, msg)
