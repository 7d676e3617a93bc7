"""What an atlas run will take, decided before anything starts: how many worker processes, and
the memory of the table and of the workers against the memory budget (:mod:`fpucore.budget`).

Workers (local backends: the process pool and a Dask LocalCluster).  More processes than cores
only queue for the same cores and each costs a Python + Numba process (~140 MiB, ~1.2 s to
start); more than chunks idle.  So by default ``workers`` is capped at min(cores, chunks) (a
note says so); a request above :data:`OVERSUBSCRIBE_MAX` × cores is refused as a slip; with
``force_workers`` any count up to :data:`MAX_WORKERS` is run (capped only at the chunks), still
within the memory budget.  A Dask scheduler given by address brings its own workers.

Memory.  The parent holds the table (one array per field of :data:`~fpucore.atlas.point.FIELDS`
over the grid: ``POINT_BYTES`` ≈ 2.6 KiB a point, the 512-character message being most of it)
plus, transiently, one field while the store is written or read back; each worker holds one
process (:data:`WORKER_BYTES`) and, with ``floquet``, the spectrum's dense matrices of order 2N
(:data:`SPECTRUM_MATRICES` of them, the automatic N taken at the spectrum's maximum).  Measured
(ru_maxrss, one point, dense route): 248 MiB at N = 200, 411 MiB at N = 1200, against the model's
278 and 524 MiB.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fpucore.atlas.grid import Grid
from fpucore.atlas.point import FIELDS
from fpucore.budget import fmt_bytes, require_memory
from fpucore.errors import ParameterError
from fpucore.floquet.monodromy import MAX_N
from fpucore.parallel import cores

MAX_WORKERS = 4096  # the execution layer's own ceiling (fpucore.parallel.Executor)
OVERSUBSCRIBE_MAX = 4  # x cores: a larger request is refused unless forced
# bytes of one point in the table: every field plus the done flag
POINT_BYTES = sum(np.dtype(dt).itemsize for dt, _ in FIELDS.values()) + 1
# the parent's growth over its table (ru_maxrss): 1.11 creating a 120 x 1000 store, 1.21 after
# resuming it (one block of one field read back at a time); with a margin.  Held to the
# measured peak by tests/atlas/test_refusals.py (549 MiB against an estimate of 631 MiB)
PARENT_FACTOR = 1.25
PARENT_BASE = 256 * 2**20  # bytes: Python, NumPy, Numba, xarray, zarr (185 MiB) + a read block
WORKER_BYTES = 260 * 2**20  # bytes: a worker's peak solving waves (measured 140-250 MiB)
SPECTRUM_MATRICES = 6  # dense (2N)² float64 matrices alive at once in a spectrum (~3.5 seen)


@dataclass(frozen=True)
class Plan:
    """workers : processes to start (None: the backend decides, e.g. a scheduler's cluster);
    notes : what was decided and why (shown by the CLI before the run); memory_bytes : the
    estimate checked against the budget; table_bytes : its part in this process (the rest:
    the workers); memory_detail : what it is made of."""

    workers: int | None
    notes: tuple[str, ...]
    memory_bytes: float
    table_bytes: float
    memory_detail: str


def plan_workers(backend: str, workers, n_chunks: int, address, force: bool):
    """(processes to start or None, notes) — see the module doc."""
    if workers is not None and not (
        isinstance(workers, (int, np.integer)) and not isinstance(workers, bool) and workers >= 1
    ):
        raise ParameterError("workers", workers, "an integer >= 1 or None (all cores)")
    if not isinstance(force, bool):
        raise ParameterError("force_workers", force, "True | False")
    if backend == "external":  # an Executor the caller made: its processes exist already
        return workers, ()
    if backend == "inline":
        note = (
            ()
            if workers in (None, 1)
            else (f"workers={workers} ignored: the inline backend computes in this process",)
        )
        return 1, note
    if address is not None:
        note = (
            ()
            if workers is None
            else (f"workers={workers} ignored: the scheduler's own workers compute",)
        )
        return None, note
    n_cores = cores()
    if workers is None:
        return min(n_cores, n_chunks), ()
    workers = int(workers)
    if workers > MAX_WORKERS:
        raise ParameterError("workers", workers, f"[1, {MAX_WORKERS}]")
    if force:
        n = min(workers, n_chunks)
        return n, () if n == workers else (
            f"workers={workers} capped at {n}: the grid has {n_chunks} chunks",
        )
    if workers > OVERSUBSCRIBE_MAX * n_cores:
        raise ParameterError(
            "workers",
            workers,
            f"[1, {OVERSUBSCRIBE_MAX * n_cores}] ({OVERSUBSCRIBE_MAX} x the "
            f"{n_cores} cores; used: at most {n_cores})",
            "more processes than cores only queue for them; force_workers=True "
            "(--force-workers) runs them anyway",
        )
    n = min(workers, n_cores, n_chunks)
    if n == workers:
        return n, ()
    return n, (
        f"workers={workers} capped at {n} = min(cores {n_cores}, chunks {n_chunks}); "
        "force_workers=True (--force-workers) runs more processes than cores",
    )


def worker_bytes(N: int | None, floquet: bool) -> float:
    """Peak memory of one worker (see the module doc)."""
    if not floquet:
        return float(WORKER_BYTES)
    n = MAX_N if N is None else int(N)
    return WORKER_BYTES + SPECTRUM_MATRICES * 8.0 * (2 * n) ** 2


def plan(
    grid: Grid,
    backend: str,
    workers,
    address,
    force_workers: bool,
    N: int | None,
    floquet: bool,
    memory_budget=None,
) -> Plan:
    """Workers and memory of a run, refused (ParameterError naming ``grid`` or ``workers``, with
    the estimate and the budget) if the memory estimate exceeds the budget.  backend : "process"
    | "dask" | "inline", or "external" for an Executor the caller made (``workers`` = its
    count; its processes run already, so only the table is a new request)."""
    n_chunks = len(grid.chunks())
    n, notes = plan_workers(backend, workers, n_chunks, address, force_workers)
    table = PARENT_BASE + PARENT_FACTOR * POINT_BYTES * grid.size
    per_worker = worker_bytes(N, floquet) if backend not in ("inline", "external") else 0.0
    if backend == "inline" and floquet:  # the spectrum's matrices live in this process
        per_worker = worker_bytes(N, True) - WORKER_BYTES
    pool = (n or 0) * per_worker
    detail = (
        f"table {fmt_bytes(table)} ({grid.size} points x {POINT_BYTES} B x "
        f"{PARENT_FACTOR:g} + {fmt_bytes(PARENT_BASE)}) + {n or 0} workers x "
        f"{fmt_bytes(per_worker)}"
    )
    if pool > table:
        require_memory("workers", table + pool, detail, value=n, budget=memory_budget)
    else:
        require_memory(
            "grid",
            table + pool,
            detail,
            value=f"{grid.shape[0]} x {grid.shape[1]}",
            budget=memory_budget,
        )
    return Plan(n, notes, table + pool, table, detail)
