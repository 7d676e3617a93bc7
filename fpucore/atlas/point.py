"""One chunk of the atlas, computed on a worker: the waves along a run of V (continuation from
the converged neighbour, in grid order) and, on request, their Floquet spectra.

A worker gets one :class:`ChunkTask` (the run's settings, its :class:`FloquetOptions`, the row
and the velocities) and returns one record per point.  A record's keys are :data:`FIELDS`, read
from the results' ``as_dict()`` (the result protocol, :mod:`fpucore.result`) as :data:`COLUMNS`
says — the names of the CLI's JSON fields (``fpu wave … --json`` for the wave, ``fpu floquet …
--json`` for the spectrum, where the spectrum's ``error`` is stored as ``max_modulus_error``,
its ``integrator_error`` as ``floquet_integrator_error``, its ``converged`` as
``floquet_converged``, the wave having fields of those names).  ``status``:

* ``"ok"``            — wave converged (and its spectrum, with ``floquet``);
* ``"not_converged"`` — the solver finished without meeting its check (``message`` says why);
* ``"no_wave"``       — (w₊, V) outside the existence region: the ParameterError's text;
* ``"failed"``        — the solver refused the settings (e.g. N too small for the wave's width:
  its ParameterError), an exception while computing (its class and message), or the worker died.

Continuation never makes a point depend on worker timing: a chunk is solved start to end in a
fixed order, its first point from the QC guess; a continued solve that does not converge is
redone from the QC guess.  So two runs of the same grid give bit-identical points, whatever the
backend, the number of workers or the order in which chunks finish.
"""

from __future__ import annotations

import math
import time
import traceback
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, NamedTuple

from fpucore.errors import ParameterError
from fpucore.floquet.finite_size import SENTENCE_CHARS
from fpucore.floquet.multipliers import DEFAULT_METHOD, FloquetResult, spectrum
from fpucore.wave import solve_solitary, solve_superkink
from fpucore.wave.continuation import solve_from_neighbour
from fpucore.wave.driver import WaveResult
from fpucore.wave.setup import spec_of

if TYPE_CHECKING:
    from collections.abc import Callable

    from fpucore.atlas.grid import Grid
    from fpucore.law.base import HardeningSofteningLaw
    from fpucore.wave.setup import Spec


@dataclass(frozen=True)
class FloquetOptions:
    """What each point's spectrum is asked for (:func:`fpucore.floquet.spectrum`).

    enabled : compute the spectrum of every converged wave.  finite_size : with the spectrum's
    finite-size test (its classification).  method : the eigenvalue route, "structured" |
    "dense".  m : RK steps per period of the tangent integration (None: automatic)."""

    enabled: bool = False
    finite_size: bool = True
    method: str = DEFAULT_METHOD
    m: int | None = None

    def spectrum(self, r: WaveResult) -> FloquetResult:
        """The spectrum of the wave ``r`` with these options."""
        return spectrum(r, m=self.m, finite_size=self.finite_size, method=self.method)


@dataclass(frozen=True)
class ChunkTask:
    """One chunk of an atlas, as a worker computes it: the points ``V`` along one row, and where
    their records go in the grid (``row_index``, ``start``: the column of ``V[0]``).  The same
    record, without row and V, describes every chunk of a run (:meth:`at` places it).

    law : the force law.  kind : "solitary" | "superkink".  row : w₊ (solitary) or the branch
    (superkink).  V : velocities, in grid order.  N : chain size (None: automatic per point).
    tol : Newton tolerance.  floquet : the spectra's options.  continuation : each point from
    its converged neighbour (else from the QC guess)."""

    law: HardeningSofteningLaw
    kind: str
    N: int | None
    tol: float
    floquet: FloquetOptions = FloquetOptions()
    continuation: bool = True
    row: Any = None
    V: tuple[float, ...] = ()
    row_index: int = 0
    start: int = 0

    @property
    def stop(self) -> int:
        """The grid column after the chunk's last point."""
        return self.start + len(self.V)

    def at(self, grid: Grid, i: int, j0: int, j1: int) -> ChunkTask:
        """This task for the chunk of row ``i``, columns ``j0:j1`` of ``grid``."""
        return replace(
            self,
            row=grid.rows[i],
            V=tuple(float(v) for v in grid.V[j0:j1]),
            row_index=int(i),
            start=int(j0),
        )


class Column(NamedTuple):
    """One field of a point's record (one variable of the store): its dtype, the fill of a point
    not computed, and where its value comes from — ``source`` "point" (the chunk's own: status,
    message, total time), "wave" (:class:`~fpucore.wave.driver.WaveResult`) or "floquet"
    (:class:`~fpucore.floquet.FloquetResult`), under the key ``key`` of that result's
    ``as_dict()`` (the result protocol; "a.b" reads the nested record ``a``)."""

    dtype: str
    fill: object
    source: str
    key: str


def _wave(dtype: str, fill: object, key: str) -> Column:
    return Column(dtype, fill, "wave", key)


def _floquet(dtype: str, fill: object, key: str) -> Column:
    return Column(dtype, fill, "floquet", key)


NAN = math.nan
# record name → Column: the one list of a record's fields, in store order
COLUMNS: dict[str, Column] = {
    "status": Column("<U16", "", "point", "status"),
    "message": Column("<U512", "", "point", "message"),
    "kind": _wave("<U16", "", "kind"),
    "converged": _wave("bool", False, "converged"),
    "amplitude": _wave("f8", NAN, "amplitude"),
    "energy": _wave("f8", NAN, "energy"),
    "residual": _wave("f8", NAN, "residual"),
    "dropped_residual": _wave("f8", NAN, "dropped_residual"),
    "tail_error": _wave("f8", NAN, "tail_error"),
    "integrator_error": _wave("f8", NAN, "integrator_error"),
    "qc_max_deviation": _wave("f8", NAN, "qc_max_deviation"),
    "profile_error": _wave("f8", NAN, "profile_error"),
    "amplitude_error": _wave("f8", NAN, "amplitude_error"),
    "energy_error": _wave("f8", NAN, "energy_error"),
    "N": _wave("i8", -1, "N"),
    "iterations": _wave("i8", -1, "iterations"),
    "wave_elapsed_s": _wave("f8", NAN, "elapsed_s"),
    "max_modulus": _floquet("f8", NAN, "max_modulus"),
    "max_modulus_away_from_1": _floquet("f8", NAN, "max_modulus_away_from_1"),
    "max_modulus_error": _floquet("f8", NAN, "error"),
    "symmetry_error": _floquet("f8", NAN, "symmetry_error"),
    "floquet_integrator_error": _floquet("f8", NAN, "integrator_error"),
    "n_unstable": _floquet("i8", -1, "n_unstable"),
    "n_trivial": _floquet("i8", -1, "n_trivial"),
    "trivial_split": _floquet("f8", NAN, "trivial_split"),
    # the decision's sentence (fpucore.floquet.finite_size.Decision: at most SENTENCE_CHARS)
    "verdict": _floquet(f"<U{SENTENCE_CHARS}", "", "verdict"),
    "classification": _floquet("<U32", "", "classification"),
    "headline": _floquet("<U64", "", "decision.headline"),
    "floquet_converged": _floquet("bool", False, "converged"),
    "floquet_elapsed_s": _floquet("f8", NAN, "elapsed_s"),
    "elapsed_s": Column("f8", NAN, "point", "elapsed_s"),
}
# name → (numpy dtype, fill value of a point not computed): the store's schema
FIELDS: dict[str, tuple[str, object]] = {k: (c.dtype, c.fill) for k, c in COLUMNS.items()}
MESSAGE_CHARS = 512


def empty_record(status: str = "", message: str = "") -> dict[str, Any]:
    """The record of a point with nothing computed (every field its fill), with ``status`` and
    ``message`` (cut to :data:`MESSAGE_CHARS`)."""
    rec = {k: fill for k, (_, fill) in FIELDS.items()}
    rec["status"], rec["message"] = status, message[:MESSAGE_CHARS]
    return rec


def _lookup(d: dict[str, Any], key: str) -> Any:
    for part in key.split("."):
        d = d[part]
    return d


def _fill_from(rec: dict[str, Any], source: str, d: dict[str, Any]) -> None:
    """The record's fields of ``source`` from that result's ``as_dict()``."""
    for name, col in COLUMNS.items():
        if col.source == source:
            rec[name] = _lookup(d, col.key)


def failure_text(exc: BaseException) -> str:
    """``Class: message`` of an exception plus where it was raised (last frame)."""
    where = traceback.extract_tb(exc.__traceback__)[-1:] if exc.__traceback__ else []
    at = f" (at {where[0].filename.rsplit('/', 1)[-1]}:{where[0].lineno})" if where else ""
    return f"{type(exc).__name__}: {exc}{at}"


def wave_record(r: WaveResult) -> dict[str, Any]:
    """The record of a solved wave (its status and message; no spectrum yet)."""
    rec = empty_record(r.status, r.message)
    _fill_from(rec, "wave", r.as_dict(profile=False))
    rec["elapsed_s"] = r.elapsed_s
    return rec


def add_floquet(rec: dict[str, Any], fr: FloquetResult) -> None:
    """Add the spectrum ``fr`` of the record's wave; a spectrum that did not converge makes the
    point ``not_converged`` with the spectrum's message."""
    _fill_from(rec, "floquet", fr.as_dict(arrays=False))
    rec["elapsed_s"] = rec["wave_elapsed_s"] + fr.elapsed_s
    if not fr.converged:
        rec["status"], rec["message"] = "not_converged", f"spectrum: {fr.message}"[:MESSAGE_CHARS]


def solve_point(
    sp: Spec, N: int | None, tol: float, prev: tuple[WaveResult, Spec] | None
) -> WaveResult:
    """The wave ``sp`` describes — from prev = (wave, spec) by the QC-shift predictor when both
    lie on the same velocity interval, else (or if that fails) from the QC guess
    (:func:`fpucore.wave.continuation.solve_from_neighbour`)."""

    def solve(pred):
        if sp.kind == "superkink":
            return solve_superkink(sp.law, sp.V, sp.branch, N, tol, predictor=pred)
        return solve_solitary(sp.law, sp.w_plus, sp.V, N, tol, predictor=pred)

    return solve_from_neighbour(sp, prev, solve)


def solve_chunk(
    task: ChunkTask, progress: Callable[[float], None] | None = None
) -> list[dict[str, Any]]:
    """The records of the points ``task.V`` along the row ``task.row``, in order (keys
    :data:`FIELDS`).  ``progress(frac)`` after each point."""
    out: list[dict[str, Any]] = []
    prev = None
    Vs = task.V
    for k, V in enumerate(Vs):
        t0 = time.perf_counter()
        try:
            sp = spec_of(task.law, task.kind, task.row, float(V))
        except ParameterError as exc:  # outside the existence region
            out.append(empty_record("no_wave", str(exc)) | {"elapsed_s": time.perf_counter() - t0})
            prev = None
            if progress is not None:
                progress((k + 1) / len(Vs))
            continue
        try:
            r = solve_point(sp, task.N, task.tol, prev)
            rec = wave_record(r)
            prev = (r, sp) if (r.converged and task.continuation) else None
            if r.converged and task.floquet.enabled:
                add_floquet(rec, task.floquet.spectrum(r))
        except ParameterError as exc:  # the wave exists, the settings do not suit it (N, ...)
            rec, prev = empty_record("failed", str(exc)), None
        except Exception as exc:  # noqa: BLE001  (recorded with its reason; the sweep goes on)
            rec, prev = empty_record("failed", failure_text(exc)), None
        if not math.isfinite(rec["elapsed_s"]):
            rec["elapsed_s"] = time.perf_counter() - t0
        out.append(rec)
        if progress is not None:
            progress((k + 1) / len(Vs))
    return out
