"""Running an atlas: chunks submitted through the execution layer, records gathered into a
table (and the Zarr store), resumable.

    res = atlas.run(law, "solitary", rows="0.2:6.5:40", V=40, N=500, floquet=True,
                    out="atlas.zarr", backend="process", workers=None, resume=False)
    res.dataset        # xarray.Dataset (w_plus, V): every field of point.FIELDS, plus done

Everything is checked first; then one :class:`~fpucore.atlas.point.ChunkTask` (the settings and
the Floquet options, :class:`~fpucore.atlas.point.FloquetOptions`) is placed on each chunk not
done and computed through :func:`fpucore.atlas.execute.execute`.  Chunks that were stored before
(``resume=True``) are loaded, not recomputed.  A chunk whose worker died is retried once in the
same run; if it dies again its points are recorded as ``failed`` with the reason but not marked
done, so a later ``--resume`` retries them.  Ctrl-C (KeyboardInterrupt) cancels the running
chunks, releases the store and re-raises: every chunk written so far is kept.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from fpucore.atlas.estimate import measure, require_within
from fpucore.atlas.execute import Hooks, Pool, Table, execute
from fpucore.atlas.grid import Grid, make_grid
from fpucore.atlas.plan import plan
from fpucore.atlas.point import ChunkTask, FloquetOptions
from fpucore.atlas.store import (
    StoreLock,
    Writer,
    check_out,
    create,
    identity_attrs,
    open_existing,
    read_done,
    xarray_module,
    zarr_module,
)
from fpucore.budget import require_time_budget
from fpucore.errors import ParameterError, require_tol
from fpucore.floquet.monodromy import MAX_N
from fpucore.floquet.multipliers import DEFAULT_METHOD, METHODS
from fpucore.law import HardeningSofteningLaw

if TYPE_CHECKING:
    import os
    from collections.abc import Sequence

    import xarray as xr
from fpucore.parallel import BACKENDS, Executor
from fpucore.parallel.scheduler import check_scheduler, parse_scheduler_address
from fpucore.result import Result, status_of

MAX_STEPS = 20_000  # RK steps per period: floquet.spectrum's range of m

STATUS_COUNTS = ("ok", "not_converged", "no_wave", "failed")


@dataclass(frozen=True)
class AtlasResult(Result):
    """Summary of an atlas run.  dataset : the full table (xarray, dims (row_dim, V)).
    n_* : points by status over the whole grid (``n_pending``: not computed, e.g. budget hit);
    n_computed / n_loaded : points computed in this run / read back from the store.
    max_residual, max_modulus_error : the largest wave residual and Floquet error bar over
    the ``ok`` points (NaN if none).  points_per_s : n_computed / elapsed_s.  notes : what the
    run decided before it started (workers capped, ...).  memory_estimate_bytes : the memory
    estimate checked against the budget (:mod:`fpucore.atlas.plan`)."""

    kind: str
    shape: tuple
    path: str | None
    dataset: xr.Dataset
    n_points: int
    n_ok: int
    n_not_converged: int
    n_no_wave: int
    n_failed: int
    n_pending: int
    n_computed: int
    n_loaded: int
    max_residual: float
    max_modulus_error: float
    backend: str
    workers: int
    points_per_s: float
    converged: bool
    stopped: bool
    message: str
    elapsed_s: float
    notes: tuple = ()
    memory_estimate_bytes: float = math.nan

    ERROR_FIELDS: ClassVar = ("max_residual", "max_modulus_error")
    EXCLUDE: ClassVar = ("dataset",)

    @property
    def status(self) -> str:
        return status_of(self.converged, self.stopped)


def check_args(N, tol, time_budget_s, m=None, **flags) -> None:
    """Every scalar option of :func:`run`, refused up front (the grid, the law and the store are
    checked by their own modules).  flags : name → value of the options that must be bools."""
    if N is not None and not (isinstance(N, (int, np.integer)) and 8 <= N <= MAX_N and N % 2 == 0):
        raise ParameterError("N", N, f"an even integer in [8, {MAX_N}] or None (automatic)")
    require_tol(tol)
    require_time_budget(time_budget_s)
    if m is not None and not (
        isinstance(m, (int, np.integer)) and not isinstance(m, bool) and 2 <= m <= MAX_STEPS
    ):
        raise ParameterError(
            "m",
            m,
            f"an integer in [2, {MAX_STEPS}] or None (automatic)",
            "RK steps per period of the Floquet integration",
        )
    for name, value in flags.items():
        if not isinstance(value, (bool, np.bool_)):
            raise ParameterError(name, value, "True | False")


def run(
    law: HardeningSofteningLaw,
    kind: str,
    rows: Any = None,
    V: str | Sequence[float] | np.ndarray | int = "40",
    N: int | None = None,
    tol: float = 1e-12,
    floquet: bool = False,
    finite_size: bool = True,
    floquet_method: str = DEFAULT_METHOD,
    m: int | None = None,
    chunk: int | None = None,
    continuation: bool = True,
    out: str | os.PathLike | None = None,
    resume: bool = False,
    executor: Executor | None = None,
    backend: str = "process",
    workers: int | None = None,
    address: str | None = None,
    progress: Callable[[int, int, int], None] | None = None,
    on_points: Callable[[list[tuple[int, int, dict]]], None] | None = None,
    time_budget_s: float | None = None,
    caller_runs: bool = False,
    force_workers: bool = False,
    memory_budget: str | float | None = None,
    note: Callable[[str], None] | None = None,
    estimate: bool = False,
) -> AtlasResult:
    """Compute (or resume) an atlas over the grid (rows × V) — see :mod:`fpucore.atlas`.

    law : a force law (CubicLaw or any HardeningSofteningLaw).  kind : "solitary" (rows = w₊
    values) | "superkink" (rows = branches).
    V : ``"LO:HI:K"``, a list, or a count K spanning the existence intervals.  N : chain size
    (None: automatic per point).  floquet : also compute spectra; finite_size : with the
    spectrum's finite-size test (spectra at 0.4N, 0.6N), which gives the classification;
    floquet_method : the spectrum's eigenvalue route, "structured" (the default of every entry
    point, :data:`fpucore.floquet.DEFAULT_METHOD`) | "dense" (the reference;
    :func:`fpucore.floquet.spectrum`).
    chunk : points per chunk.
    out : Zarr store path (None: in memory only).  resume : continue an existing store.
    executor : an Executor to use (else one is made from backend / workers / address and shut
    down at the end).  progress(done, total, failed) after each chunk; on_points([(i, j,
    record), ...]) with the records of each chunk.  time_budget_s : stop submitting and cancel
    what runs once exceeded (points left pending, status "stopped").  caller_runs : when the
    run starts its own process pool, this process computes chunks too and the pool has one
    process fewer (``Executor(caller_runs=True)``; sweeps use it); the time budget is then
    checked between two of its chunks.
    workers : processes of a local pool or LocalCluster (None: min(cores, chunks)); a larger
    count is capped at that (with a note) unless force_workers, and refused above 4 x cores
    (:mod:`fpucore.atlas.plan`).  address : a Dask scheduler "tcp://HOST:PORT" (backend "dask"),
    checked with a bounded connect and handshake before the store is created
    (:func:`fpucore.parallel.scheduler.check_scheduler`).  memory_budget : the memory the
    table and the workers may take (default ``FPU_MEMORY_BUDGET`` or 25 % of RAM), estimated
    before anything starts.  note(text) : each decision of the plan (e.g. workers capped),
    before the run starts; also in ``AtlasResult.notes``.  estimate : time two points here first
    and note the estimated wall time; a ``time_budget_s`` below it is refused then
    (:mod:`fpucore.atlas.estimate`; the ``fpu atlas`` command does this).

    Everything is checked before the store is created or anything computed: a refused run
    leaves no store behind, so its corrected retry is not refused as "the store exists".
    """
    t0 = time.perf_counter()
    if not isinstance(law, HardeningSofteningLaw):
        raise ParameterError("law", law, "a force law (CubicLaw, PolynomialLaw, ...)")
    check_args(
        N,
        tol,
        time_budget_s,
        m,
        floquet=floquet,
        finite_size=finite_size,
        continuation=continuation,
        resume=resume,
        caller_runs=caller_runs,
    )
    if floquet_method not in METHODS:
        raise ParameterError("floquet_method", floquet_method, " | ".join(map(repr, METHODS)))
    if backend not in BACKENDS:
        raise ParameterError("backend", backend, " | ".join(BACKENDS))
    if address is not None:
        if backend != "dask":
            raise ParameterError("backend", backend, "'dask' with a scheduler address")
        parse_scheduler_address(address, "address")  # no traffic yet: the form first
    grid = make_grid(law, kind, rows, V, chunk)
    if executor is not None:  # its workers run already: only the table is a new request
        p = plan(grid, "external", executor.workers, None, True, N, floquet, memory_budget)
    else:
        p = plan(grid, backend, workers, address, force_workers, N, floquet, memory_budget)
    # the one task every chunk is computed from (its row and V set per chunk)
    task = ChunkTask(
        law,
        grid.kind,
        N=None if N is None else int(N),
        tol=float(tol),
        floquet=FloquetOptions(
            bool(floquet), bool(finite_size), floquet_method, None if m is None else int(m)
        ),
        continuation=bool(continuation),
    )
    attrs = identity_attrs(grid, task)
    path = None
    if out is not None:
        path = check_out(out)
        if path.exists() and not resume:
            raise ParameterError(
                "out", str(out), "a new path, or resume=True (--resume)", "the store exists"
            )
    notes = list(p.notes)
    if address is not None:  # last check before the store: a bounded connect and handshake
        ident = check_scheduler(address, name="address")
        notes.append(f"Dask scheduler {address}: {ident.get('n_workers')} workers")
    for text in notes:
        if note is not None:
            note(text)
    if out is not None:  # a store needs the atlas extra: refused before any point is timed
        xarray_module()
        zarr_module()
    if estimate:  # measured before the store exists: a refused run leaves nothing behind
        est = measure(grid, _stored_done(path, grid, attrs, resume), task, p.workers or 1)
        notes.append(est.line())
        if note is not None:
            note(est.line())
        require_within(est, time_budget_s)
    table = Table(grid, attrs)
    lock = writer = None
    if path is not None:
        lock = StoreLock(path)
    try:
        n_loaded = 0
        if path is not None:
            if path.exists():
                n_loaded = table.load(open_existing(path, grid, attrs))
            else:
                create(path, table.ds, grid.chunk)
            writer = Writer(path)
        pool = Pool(backend, p.workers, workers is None, address, caller_runs)
        res = execute(
            task, grid, table, writer, executor, pool, Hooks(progress, on_points, time_budget_s, t0)
        )
        if writer is not None:
            writer.touch()
    finally:
        if lock is not None:
            lock.release()
    c = table.cols
    ok = c["status"] == "ok"
    n_pending = int(np.sum(c["done"] == 0))
    elapsed = time.perf_counter() - t0
    counts = {s: table.count(s) for s in STATUS_COUNTS}
    maxf = lambda a: float(np.nanmax(a[ok])) if ok.any() and np.isfinite(a[ok]).any() else math.nan  # noqa: E731
    summary = ", ".join(f"{v} {k}" for k, v in counts.items() if v) or "nothing"
    return AtlasResult(
        kind=grid.kind,
        shape=grid.shape,
        path=None if path is None else str(path),
        dataset=table.ds,
        n_points=grid.size,
        n_ok=counts["ok"],
        n_not_converged=counts["not_converged"],
        n_no_wave=counts["no_wave"],
        n_failed=counts["failed"],
        n_pending=n_pending,
        n_computed=res.n_computed,
        n_loaded=n_loaded,
        max_residual=maxf(c["residual"]),
        max_modulus_error=maxf(c["max_modulus_error"]),
        backend=res.backend,
        workers=res.workers,
        points_per_s=res.n_computed / elapsed if elapsed > 0 else math.nan,
        converged=n_pending == 0 and counts["failed"] == 0,
        stopped=res.stopped,
        message=res.message or f"{grid.size} points: {summary} ({n_loaded} from the store)",
        elapsed_s=elapsed,
        notes=tuple(notes),
        memory_estimate_bytes=p.memory_bytes,
    )


def _stored_done(path, grid: Grid, attrs: dict, resume: bool) -> np.ndarray:
    """The points a resumed store holds already (none for a new store); a damaged or different
    store is refused here, with its reason, before anything is timed."""
    if path is None or not resume or not path.exists():
        return np.zeros(grid.shape, bool)
    open_existing(path, grid, attrs)
    return read_done(path, grid)
