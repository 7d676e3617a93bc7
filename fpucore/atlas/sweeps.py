"""Sweeps of the Floquet spectrum along wave families (paper Figs. floquet_SK, floquet_cubicSW).

A sweep is a one-row atlas (:func:`fpucore.atlas.run` with ``floquet=True``), so it lives in the
atlas stage: every velocity is one task (``CHUNK`` = 1) on a worker of the execution layer
(:mod:`fpucore.parallel`; all cores, one BLAS thread each): its wave solved from the QC guess
and its spectrum computed.  A sweep that starts its own pool computes in the calling process
too (``caller_runs``: K cores = the caller and K - 1 workers, so only K - 1 processes pay the
worker start-up and none is oversubscribed).
Each spectrum takes the structured route by default (``method``, as every entry point:
:data:`fpucore.floquet.DEFAULT_METHOD`; the quarter-size reversible one for the paper's families,
max|μ| and classification equal to dense within the error bar).
One task per velocity keeps the workers balanced (spectra near the sonic end cost more: their
finite-size test runs); continuation along V measured no gain (benchmarks/README.md, atlas part C).
One row per V is kept: V and the point's atlas record, under the atlas's names
(:data:`fpucore.atlas.point.FIELDS`: the spectrum's error bar is ``max_modulus_error``, the wave's
``converged`` and ``energy``, ``energy_error`` beside the spectrum's ``floquet_converged``,
``verdict``, ``classification``, …; solitary families: the energy criterion,
:func:`fpucore.floquet.criterion_from_samples`, reads them).  The JSON of ``fpu floquet sweep``
and its CSV columns are these rows.  Running the same
sweep at several N measures the N-dependence of the spurious oscillatory instabilities.

Cache.  With ``use_cache`` the sweep is an atlas store in ``$FPU_CACHE_DIR/floquet`` (default
``./.fpu_cache/floquet``) named by the SHA-256 of its key: the inputs (kind, law parameters,
branch, w₊, the velocities, N, m, tol, chunk; floats by ``repr``, so equal keys mean bit-equal
inputs) **and the code** — the hash of fpucore's source and its version (a
modified copy of the code must not serve the old rows).  Running the same sweep again resumes
that store: nothing is recomputed; an interrupted sweep keeps its finished chunks.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from tqdm import tqdm

from fpucore.atlas.point import FIELDS, empty_record
from fpucore.atlas.run import run as run_atlas
from fpucore.atlas.store import fpucore_version
from fpucore.budget import require_time_budget
from fpucore.errors import ParameterError, require_finite, require_int, require_tol
from fpucore.floquet.monodromy import MAX_N
from fpucore.floquet.multipliers import DEFAULT_METHOD, METHODS
from fpucore.jit_cache import source_hash
from fpucore.law import require_law
from fpucore.parallel import Executor
from fpucore.parallel.threads import on_budget
from fpucore.result import Result, jsonable, status_of
from fpucore.wave.setup import spec_of

if TYPE_CHECKING:
    from typing import IO

    from fpucore.law.base import HardeningSofteningLaw

SWEEP_MAX_V = 10_000  # velocities per sweep
CHUNK = 1  # velocities per task (fixed: results must not depend on the number of workers)
COLUMNS = ("V", *FIELDS)  # a sweep row: the velocity and its atlas record (fpucore.atlas.point)


def cache_dir() -> Path:
    """$FPU_CACHE_DIR/floquet, or ./.fpu_cache/floquet."""
    root = os.environ.get("FPU_CACHE_DIR") or os.path.join(os.getcwd(), ".fpu_cache")
    return Path(root) / "floquet"


def cache_key(
    law,
    kind: str,
    V_values,
    N: int,
    w_plus,
    branch: str,
    m,
    tol: float,
    method: str = DEFAULT_METHOD,
) -> dict:
    """The inputs and the code that determine a sweep's rows (see module doc)."""
    return {
        "method": method,
        "kind": kind,
        "law_id": int(law.law_id),
        "params": [repr(float(x)) for x in law.params],
        "branch": branch if kind == "superkink" else None,
        "w_plus": None if w_plus is None else repr(float(w_plus)),
        "V": [repr(float(v)) for v in V_values],
        "N": int(N),
        "m": None if m is None else int(m),
        "tol": repr(float(tol)),
        "chunk": CHUNK,
        "fpucore_source": source_hash(),
        "fpucore_version": fpucore_version(),
    }


def cache_path(key: dict) -> Path:
    h = hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:32]
    return cache_dir() / f"sweep-{h}.zarr"


@dataclass(frozen=True)
class SweepResult(Result):
    """max |μ| along a family: a one-row atlas, its records named as the atlas's
    (:data:`fpucore.atlas.point.FIELDS`).

    rows : one dict per V, in the order of V — ``V`` and the point's atlas record (``status``,
    ``message``, the wave's ``converged``, ``residual``, ``energy``, ``energy_error``, …, the
    spectrum's ``max_modulus``, ``max_modulus_error`` (its error bar,
    :attr:`fpucore.floquet.FloquetResult.error`), ``floquet_converged``, ``verdict``,
    ``classification``, ``headline``, …; ``status`` "" for a velocity never computed).
    V, max_modulus, max_modulus_away_from_1, max_modulus_error, energy, energy_error : (n,)
    arrays of those columns, NaN where nothing was computed; n_unstable : (n,) int (0 there);
    floquet_converged : (n,) bool, the spectrum converged; cached : (n,) bool, the row was read
    from the cache store (computed by an earlier run); classification : (n,) "stable" |
    "finite_size" | "unstable" | "undetermined" ("" where not computed).  method : the spectra's
    eigenvalue route ("structured" | "dense").
    converged : every velocity has a converged spectrum; stopped : the time budget ended the
    sweep (rows left not computed)."""

    kind: str
    N: int
    w_plus: float | None
    method: str
    V: np.ndarray
    max_modulus: np.ndarray
    max_modulus_away_from_1: np.ndarray
    max_modulus_error: np.ndarray
    n_unstable: np.ndarray
    floquet_converged: np.ndarray
    cached: np.ndarray
    energy: np.ndarray
    energy_error: np.ndarray
    classification: tuple
    rows: list
    converged: bool
    stopped: bool
    message: str
    elapsed_s: float

    ERROR_FIELDS: ClassVar = ("max_modulus_error",)

    @property
    def status(self) -> str:
        return status_of(self.converged, self.stopped)

    def to_csv(self, path_or_file: str | os.PathLike | IO[str]) -> None:
        """One line per row: the columns :data:`COLUMNS` (the atlas's names) and ``cached``."""
        cols = [*COLUMNS, "cached"]
        lines = [",".join(cols)]
        for row, c in zip(self.rows, self.cached, strict=True):
            lines.append(",".join(_csv(v) for v in [*(row[k] for k in COLUMNS), bool(c)]))
        text = "\n".join(lines) + "\n"
        if hasattr(path_or_file, "write"):
            path_or_file.write(text)
        else:
            Path(path_or_file).write_text(text)


def _csv(v) -> str:
    if v is None:
        return ""
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ""
    s = str(v)
    return '"' + s.replace('"', "'") + '"' if ("," in s or '"' in s) else s


def tqdm_progress(n: int, desc: str = "floquet sweep") -> Callable:
    """A ``progress(i, n, V, row)`` callback drawing a tqdm bar on stderr."""
    bar = tqdm(total=n, desc=desc, unit="V", dynamic_ncols=True)

    def cb(i: int, n: int, V: float, row: dict | None) -> None:
        bar.update(i - bar.n)
        ex = row.get("max_modulus_away_from_1") if row else None
        bar.set_postfix_str(f"V={V:.6g}" + ("" if ex is None else f" max|mu|-1={ex - 1:.2e}"))

    cb.close = bar.close  # type: ignore[attr-defined]
    return cb


def _row(V: float, N: int, rec: dict) -> dict:
    """The sweep row of one atlas record (a record of a point never computed gets the sweep's
    N, the chain size it was asked for)."""
    row = {"V": float(V), **{k: jsonable(rec[k]) for k in FIELDS}}
    if row["N"] < 0:
        row["N"] = int(N)
    return row


def check_sweep_args(
    law, kind, V_values, w_plus, N, branch, m, tol, time_budget_s, method=DEFAULT_METHOD
):
    """Validate a sweep's arguments before anything is computed (tol=0, N=10**6 and
    time_budget_s=-1 used to return NaN rows).  Returns (w_plus, Vs, N, m, tol, time_budget_s)."""
    require_law(law)
    if not isinstance(kind, str) or kind not in ("superkink", "solitary"):
        raise ParameterError("kind", kind, "'superkink' | 'solitary'")
    if kind == "solitary":
        if w_plus is None:
            raise ParameterError("w_plus", w_plus, "a strain", "required for solitary waves")
        w_plus = require_finite("w_plus", w_plus)
    else:
        w_plus = None
    if not isinstance(branch, str) or branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' | 'upper'")
    if isinstance(V_values, (str, bytes)):
        raise ParameterError("V_values", V_values, "a non-empty list of velocities V > 0")
    items = list(V_values) if isinstance(V_values, (list, tuple, np.ndarray)) else [V_values]
    Vs = np.array([require_finite("V", v) for v in items], dtype=float)
    if Vs.size == 0 or Vs.size > SWEEP_MAX_V or np.any(Vs <= 0):
        raise ParameterError(
            "V_values", list(Vs)[:5], f"a list of 1 to {SWEEP_MAX_V} velocities V > 0"
        )
    N = require_int("N", N, 8, MAX_N)
    if N % 2:
        raise ParameterError("N", N, f"an even integer in [8, {MAX_N}]")
    if m is not None:
        m = require_int("m", m, 2, 20000)
    tol = require_tol(tol)
    if not isinstance(method, str) or method not in METHODS:
        raise ParameterError("method", method, " | ".join(repr(x) for x in METHODS))
    time_budget_s = require_time_budget(time_budget_s, none_ok=False)
    return w_plus, Vs, N, m, tol, time_budget_s


@on_budget
def sweep(
    law: HardeningSofteningLaw,
    kind: str,
    V_values: Sequence[float],
    w_plus: float | None = None,
    N: int = 500,
    progress: Callable | bool | None = None,
    branch: str = "lower",
    m: int | None = None,
    tol: float = 1e-12,
    use_cache: bool = True,
    time_budget_s: float = 3600.0,
    executor: Executor | None = None,
    workers: int | None = None,
    method: str = DEFAULT_METHOD,
) -> SweepResult:
    """max |μ| against V along a family of discrete waves (Figs. floquet_SK, floquet_cubicSW).

    kind : "superkink" (w_plus unused) or "solitary" (w_plus required).  V_values : velocities
    (one task each).  N : even chain size.
    progress : callback ``progress(i, n, V, row)`` (True: a tqdm bar on stderr).  Rows whose
    wave does not converge are kept with NaN moduli and the solver's message.  time_budget_s :
    the sweep stops (remaining rows NaN, message says so) once exceeded (checked between
    velocities).  executor : an :class:`fpucore.parallel.Executor` to run on (default: one
    started for this sweep with ``workers`` computing processes, all cores: this process and a
    pool of ``workers - 1``, ``caller_runs=True``).  method : each spectrum's eigenvalue route
    (:func:`fpucore.floquet.spectrum`): "structured" (the default of every entry point,
    :data:`fpucore.floquet.DEFAULT_METHOD`: the quarter-size reversible
    route for the paper's families, ~0.2× the dense call at N = 500, max|μ| and classification
    equal within the error bar, tests/floquet/test_sweep_method.py) or "dense" (the reference).
    """
    w_plus, Vs, N, m, tol, time_budget_s = check_sweep_args(
        law, kind, V_values, w_plus, N, branch, m, tol, time_budget_s, method
    )
    row = w_plus if kind == "solitary" else branch
    for v in Vs:  # every velocity must lie on the family before anything is computed
        spec_of(law, kind, row, float(v))
    n = Vs.size
    bar = progress = tqdm_progress(n) if progress is True else progress
    rows: list = [None] * n
    computed = np.zeros(n, bool)
    count = [0]

    def on_points(points) -> None:
        for _, j, rec in points:
            rows[j] = _row(Vs[j], N, rec)
            computed[j] = True
            count[0] += 1
            if progress:
                progress(count[0], n, float(Vs[j]), rows[j])

    def first(done: int, total: int, failed: int) -> None:
        if count[0] == 0:
            count[0] = done  # rows already in the cache store

    kw = dict(
        rows=[row],
        V=Vs,
        N=int(N),
        tol=tol,
        floquet=True,
        floquet_method=method,
        m=m,
        chunk=CHUNK,
        executor=executor,
        workers=workers,
        progress=first,
        on_points=on_points,
        time_budget_s=time_budget_s,
        caller_runs=True,
    )
    res = None
    if use_cache:
        path = cache_path(cache_key(law, kind, Vs, N, w_plus, branch, m, tol, method))
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            res = run_atlas(law, kind, out=path, resume=True, **kw)
        except ParameterError as exc:
            if exc.name != "out":
                raise
            if "locked" not in str(exc):  # an unreadable or foreign store under our key
                shutil.rmtree(path, ignore_errors=True)
                res = run_atlas(law, kind, out=path, resume=True, **kw)
        except OSError:
            res = None
    if res is None:  # no cache, or another sweep is writing this one right now
        res = run_atlas(law, kind, **kw)
    ds = res.dataset
    recs = {k: ds[k].values[0] for k in ds.data_vars}
    for j in range(n):
        if rows[j] is None:
            done = recs["done"][j]
            rec = (
                {k: v[j] for k, v in recs.items()}
                if done
                else empty_record("", res.message or "not computed")
            )
            rows[j] = _row(Vs[j], N, rec)
    if bar is not None and hasattr(bar, "close"):
        bar.close()  # type: ignore[union-attr]

    def arr(k: str, where=None) -> np.ndarray:  # a column, NaN where not computed (or not where)
        x = np.array([np.nan if r[k] is None else r[k] for r in rows], float)
        return x if where is None else np.where(where, x, np.nan)

    cached = ~computed & (recs["done"] == 1)
    fl_ok = np.array([bool(r["floquet_converged"]) for r in rows])
    wave_ok = np.array([bool(r["converged"]) for r in rows])
    message = res.message if res.stopped else f"{n} velocities, {int(cached.sum())} from cache"
    if not res.stopped and not fl_ok.all():
        message += f"; {int((~fl_ok).sum())} without a converged spectrum"
    return SweepResult(
        kind=kind,
        N=int(N),
        w_plus=w_plus,
        method=method,
        V=Vs,
        max_modulus=arr("max_modulus"),
        max_modulus_away_from_1=arr("max_modulus_away_from_1"),
        max_modulus_error=arr("max_modulus_error"),
        n_unstable=np.array([max(int(r["n_unstable"]), 0) for r in rows], int),
        floquet_converged=fl_ok,
        cached=cached,
        energy=arr("energy", wave_ok),
        energy_error=arr("energy_error", wave_ok),
        classification=tuple(r["classification"] for r in rows),
        rows=rows,
        converged=bool(fl_ok.all()) and not res.stopped,
        stopped=bool(res.stopped),
        message=message,
        elapsed_s=res.elapsed_s,
    )
