"""Sweeps of the Floquet spectrum along wave families (paper Figs. floquet_SK, floquet_cubicSW).

For each velocity V of a list the discrete wave is solved (``solve_superkink`` /
``solve_solitary``, continued from the previous converged wave when the solver accepts an
initial guess), its spectrum computed with :func:`fpucore.floquet.spectrum`, and one row kept:
V, max |μ|, max |μ| away from the trivial cluster, the error bar, the verdict.  Running the same
sweep at several N measures the N-dependence of the spurious oscillatory instabilities.

Cache.  Every row is stored as one JSON file in ``$FPU_CACHE_DIR/floquet`` (default
``./.fpu_cache/floquet``), named by the SHA-256 of its exact key (kind, law parameters, branch,
w₊, V, N, m, tol, cache version; floats by ``repr``, so equal keys mean bit-equal parameters).  The
key is stored inside the file and compared on load: a row is never returned for other parameters.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from fpucore.errors import ParameterError, require_finite, require_int
from fpucore.floquet.monodromy import MAX_N
from fpucore.floquet.multipliers import spectrum
from fpucore.law import require_law
from fpucore.wave import solve_solitary, solve_superkink
from fpucore.wave.continuation import family_interval, qc_shift_predictor
from fpucore.wave.setup import solitary_spec, superkink_spec

CACHE_VERSION = 1
SWEEP_MAX_V = 10_000  # velocities per sweep
_ROW_KEYS = (
    "V", "max_modulus", "max_modulus_away_from_1", "error", "symmetry_error", "integrator_error",
    "n_unstable", "n_trivial", "trivial_split", "verdict", "wave_converged", "wave_residual",
    "converged", "elapsed_s", "message",
)  # fmt: skip


def cache_dir() -> Path:
    """$FPU_CACHE_DIR/floquet, or ./.fpu_cache/floquet."""
    root = os.environ.get("FPU_CACHE_DIR") or os.path.join(os.getcwd(), ".fpu_cache")
    return Path(root) / "floquet"


def cache_key(law, kind: str, V: float, N: int, w_plus, branch: str, m, tol: float) -> dict:
    return {
        "version": CACHE_VERSION,
        "kind": kind,
        "law_id": int(law.law_id),
        "params": [repr(float(x)) for x in law.params],
        "branch": branch if kind == "superkink" else None,
        "w_plus": None if w_plus is None else repr(float(w_plus)),
        "V": repr(float(V)),
        "N": int(N),
        "m": None if m is None else int(m),
        "tol": repr(float(tol)),
    }


def key_path(key: dict) -> Path:
    h = hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:32]
    return cache_dir() / f"{h}.json"


def cache_load(key: dict) -> dict | None:
    """The cached row for exactly this key, or None (missing, unreadable or a different key)."""
    p = key_path(key)
    try:
        data = json.loads(p.read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("key") != key:
        return None
    row = data.get("row")
    return row if isinstance(row, dict) else None


def cache_store(key: dict, row: dict) -> None:
    """Write atomically (temp file + rename); a failing cache never fails the sweep."""
    p = key_path(key)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        tmp = p.with_suffix(f".tmp{os.getpid()}")
        tmp.write_text(json.dumps({"key": key, "row": _plain(row)}))
        os.replace(tmp, p)
    except OSError:
        pass


def _plain(x):
    if isinstance(x, dict):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple, np.ndarray)):
        return [_plain(v) for v in x]
    if isinstance(x, (np.bool_, bool)):
        return bool(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        x = float(x)
        return x if math.isfinite(x) else None
    return x


@dataclass(frozen=True)
class SweepResult:
    """max |μ| along a family.  Arrays (n,) in the order of V; error is each row's error bar
    (:attr:`fpucore.floquet.FloquetResult.error`); NaN where the wave did not converge."""

    kind: str
    N: int
    w_plus: float | None
    V: np.ndarray
    max_modulus: np.ndarray
    max_modulus_away_from_1: np.ndarray
    error: np.ndarray
    n_unstable: np.ndarray
    converged: np.ndarray
    cached: np.ndarray
    rows: list = field(default_factory=list)
    elapsed_s: float = 0.0
    message: str = ""

    def as_dict(self) -> dict:
        return {"kind": self.kind, "N": self.N, "w_plus": self.w_plus, "rows": self.rows,
                "elapsed_s": self.elapsed_s, "message": self.message}  # fmt: skip

    def to_csv(self, path_or_file) -> None:
        cols = ["N", *_ROW_KEYS, "cached"]
        lines = [",".join(cols)]
        for row, c in zip(self.rows, self.cached, strict=True):
            vals = [self.N, *(row.get(k) for k in _ROW_KEYS), bool(c)]
            lines.append(",".join(_csv(v) for v in vals))
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


def text_progress(stream=None) -> Callable:
    """A progress callback drawing ``[#####.....] i/n V=… max|mu|-1=…`` on stderr."""
    stream = stream or sys.stderr

    def cb(i: int, n: int, V: float, row: dict | None) -> None:
        done = int(30 * i / max(n, 1))
        ex = "" if row is None else f" max|mu|-1={row['max_modulus_away_from_1'] - 1:.2e}"
        if row is not None and not math.isfinite(row["max_modulus_away_from_1"]):
            ex = " (wave not converged)"
        stream.write(f"\r[{'#' * done}{'.' * (30 - done)}] {i}/{n} V={V:.6g}{ex}   ")
        if i == n:
            stream.write("\n")
        stream.flush()

    return cb


def _spec(kind, law, V, w_plus, branch):
    if kind == "superkink":
        return superkink_spec(law, V, branch)
    return solitary_spec(law, w_plus, V)


def _solve(kind, law, V, w_plus, N, branch, tol, prev):
    """Solve the wave at V; continue from prev = (wave, spec) with the QC-shift predictor of
    :mod:`fpucore.wave.continuation` when prev lies on the same branch, else from the QC guess."""

    def solve(pred):
        if kind == "superkink":
            return solve_superkink(law, V, branch, N, tol, predictor=pred)
        return solve_solitary(law, w_plus, V, N, tol, predictor=pred)

    sp = _spec(kind, law, V, w_plus, branch)
    r = None
    if prev is not None:
        r_prev, sp_prev = prev
        if family_interval(law, sp_prev) == family_interval(law, sp):
            x_prev = np.empty(2 * r_prev.N)
            x_prev[0::2], x_prev[1::2] = r_prev.w, r_prev.wdot
            r = solve(qc_shift_predictor(law, sp, x_prev, r_prev.N, sp_prev))
    if r is None or not r.converged:
        r = solve(None)
    return r, sp


def check_sweep_args(law, kind, V_values, w_plus, N, branch, m, tol, time_budget_s):
    """Validate a sweep's arguments before anything is computed (issue 14: tol=0, N=10**6 and
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
    tol = require_finite("tol", tol)
    if not 1e-15 <= tol <= 1e-3:
        raise ParameterError("tol", tol, "[1e-15, 1e-3]", "wave residual tolerance")
    time_budget_s = require_finite("time_budget_s", time_budget_s)
    if time_budget_s <= 0:
        raise ParameterError("time_budget_s", time_budget_s, "> 0 seconds")
    return w_plus, Vs, N, m, tol, time_budget_s


def sweep(
    law,
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
) -> SweepResult:
    """max |μ| against V along a family of discrete waves (Figs. floquet_SK, floquet_cubicSW).

    kind : "superkink" (w_plus unused) or "solitary" (w_plus required).  V_values : velocities,
    swept in the given order (continuation follows it).  N : even chain size.  progress : callback
    ``progress(i, n, V, row)`` (True: a text bar on stderr).  Rows whose wave does not converge are
    kept with NaN moduli and the solver's message.  time_budget_s : the sweep stops (remaining
    rows NaN, message says so) once exceeded.
    """
    t0 = time.perf_counter()
    w_plus, Vs, N, m, tol, time_budget_s = check_sweep_args(
        law, kind, V_values, w_plus, N, branch, m, tol, time_budget_s
    )
    for v in Vs:  # every velocity must lie on the family before anything is computed
        _spec(kind, law, float(v), w_plus, branch)
    if progress is True:
        progress = text_progress()
    rows, cached = [], []
    prev = None
    msg = ""
    n = Vs.size
    for i, V in enumerate(Vs):
        if time.perf_counter() - t0 > time_budget_s:
            msg = f"time budget {time_budget_s:g} s exhausted after {i} of {n} velocities"
            rows += [_nan_row(v, msg) for v in Vs[i:]]
            cached += [False] * (n - i)
            break
        key = cache_key(law, kind, V, N, w_plus, branch, m, tol)
        row = cache_load(key) if use_cache else None
        if row is not None:
            cached.append(True)
            prev = None  # continuation restarts from the solver's own guess after a cache hit
        else:
            cached.append(False)
            row, prev = _one_row(kind, law, V, w_plus, N, branch, m, tol, prev)
            if use_cache and row["wave_converged"]:
                cache_store(key, row)
        rows.append(row)
        if progress:
            progress(i + 1, n, float(V), row)
    arr = lambda k: np.array([np.nan if r[k] is None else r[k] for r in rows], float)  # noqa: E731
    return SweepResult(
        kind=kind,
        N=int(N),
        w_plus=w_plus,
        V=Vs,
        max_modulus=arr("max_modulus"),
        max_modulus_away_from_1=arr("max_modulus_away_from_1"),
        error=arr("error"),
        n_unstable=np.array([r["n_unstable"] or 0 for r in rows], int),
        converged=np.array([bool(r["converged"]) for r in rows]),
        cached=np.array(cached, bool),
        rows=rows,
        elapsed_s=time.perf_counter() - t0,
        message=msg or f"{n} velocities, {int(np.sum(cached))} from cache",
    )


def _nan_row(V: float, message: str) -> dict:
    row = {k: None for k in _ROW_KEYS}
    row.update(V=float(V), n_unstable=0, n_trivial=0, verdict="not computed",
               wave_converged=False, converged=False, elapsed_s=0.0, message=message)  # fmt: skip
    return row


def _one_row(kind, law, V, w_plus, N, branch, m, tol, prev):
    t0 = time.perf_counter()
    try:
        r, sp = _solve(kind, law, float(V), w_plus, N, branch, tol, prev)
    except ParameterError as exc:
        return _nan_row(V, str(exc)), None
    if not getattr(r, "converged", True):
        row = _nan_row(V, f"wave not converged: {getattr(r, 'message', '')}")
        row["wave_residual"] = float(getattr(r, "residual", math.nan))
        return row, None
    fr = spectrum(r, m=m)
    row = {
        "V": float(V),
        "max_modulus": fr.max_modulus,
        "max_modulus_away_from_1": fr.max_modulus_away_from_1,
        "error": fr.error,
        "symmetry_error": fr.symmetry_error,
        "integrator_error": fr.integrator_error,
        "n_unstable": fr.n_unstable,
        "n_trivial": fr.n_trivial,
        "trivial_split": fr.trivial_split,
        "verdict": fr.verdict,
        "wave_converged": True,
        "wave_residual": float(getattr(r, "residual", math.nan)),
        "converged": fr.converged,
        "elapsed_s": time.perf_counter() - t0,
        "message": fr.message,
    }
    return _plain(row), (r, sp)
