"""What an atlas will cost, measured before it starts: one or two of its own points are solved
in this process and timed, and the wall time of the points still to do is extrapolated over the
workers.  A run whose estimate exceeds its time budget is refused with the estimate, before the
store is created (``fpu atlas … --time-budget S``).

The probe points are solved cold (no continuation from a neighbour) and the second one is the
one timed (the first may load compiled kernels): a point inside a chunk, continued from its
neighbour, costs less, so the estimate errs long (and the points' costs vary over the grid:
an estimate, not a bound).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from fpucore.atlas.grid import Grid
from fpucore.atlas.point import ChunkTask, solve_chunk
from fpucore.errors import ParameterError

PROBE_POINTS = 2


@dataclass(frozen=True)
class Estimate:
    """n_points : the grid; n_todo : points not in the store yet; workers : processes computing;
    per_point_s : the measured cost of one point (s); seconds : n_todo × per_point_s / workers;
    probe_s : the time the measurement itself took."""

    n_points: int
    n_todo: int
    workers: int
    per_point_s: float
    seconds: float
    probe_s: float

    def line(self) -> str:
        todo = "" if self.n_todo == self.n_points else f", {self.n_todo} to do"
        return (
            f"{self.n_points} points{todo}; estimate {self.per_point_s:.3g} s per point "
            f"(timed on {PROBE_POINTS} cold points) x {self.n_todo} / {self.workers} worker"
            f"{'s' if self.workers != 1 else ''} = about {duration(self.seconds)}"
        )


def duration(s: float) -> str:
    """Seconds as a short human duration: 42 s, 3.5 min, 2.9 h, 4.1 days."""
    if s < 90:
        return f"{s:.0f} s"
    if s < 5400:
        return f"{s / 60:.1f} min"
    if s < 172800:
        return f"{s / 3600:.1f} h"
    return f"{s / 86400:.1f} days"


def measure(grid: Grid, done: np.ndarray, task: ChunkTask, workers: int) -> Estimate:
    """Time :data:`PROBE_POINTS` points of the first row with points to do (``task``: the run's
    chunk task, placed on each probe point) and extrapolate to the points not ``done`` (bool,
    ``grid.shape``) over ``workers`` processes."""
    t0 = time.perf_counter()
    n_todo = int(grid.size - done.sum())
    rows = [i for i in range(grid.shape[0]) if not done[i].all()]
    per_point = 0.0
    if rows:
        i = rows[0]
        js = np.flatnonzero(~done[i])[:PROBE_POINTS]
        for j in js:  # one by one: the last one timed is warm (kernels loaded)
            t = time.perf_counter()
            solve_chunk(replace(task.at(grid, i, j, j + 1), continuation=False))
            per_point = time.perf_counter() - t
    w = max(1, int(workers))
    return Estimate(
        grid.size, n_todo, w, per_point, n_todo * per_point / w, time.perf_counter() - t0
    )


def require_within(est: Estimate, time_budget_s: float | None) -> None:
    """Refuse a run whose estimate exceeds the time budget, saying the estimate and the ways
    out (a larger budget, a smaller grid, or a run in parts: every chunk is saved)."""
    if time_budget_s is None or est.seconds <= time_budget_s:
        return
    raise ParameterError(
        "time_budget_s",
        float(time_budget_s),
        f">= the estimated {est.seconds:.3g} s ({duration(est.seconds)})",
        f"{est.line()}; raise --time-budget, use a coarser grid or fewer points, or run without "
        "a budget and stop with Ctrl-C: every finished chunk is saved and --resume goes on",
    )
