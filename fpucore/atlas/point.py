"""One chunk of the atlas, computed on a worker: the waves along a run of V (continuation from
the converged neighbour, in grid order) and, on request, their Floquet spectra.

Each point becomes a record whose keys are :data:`FIELDS` — the names of the CLI's JSON fields
(``fpu wave … --json`` for the wave, ``fpu floquet … --json`` for the spectrum, where the
spectrum's ``error`` is stored as ``max_modulus_error`` and its ``integrator_error`` as
``floquet_integrator_error``, the wave having fields of those names).  ``status``:

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
from typing import TYPE_CHECKING

from fpucore.errors import ParameterError
from fpucore.floquet.finite_size import SENTENCE_CHARS
from fpucore.floquet.multipliers import spectrum
from fpucore.wave import solve_solitary, solve_superkink
from fpucore.wave.continuation import solve_from_neighbour
from fpucore.wave.setup import spec_of

if TYPE_CHECKING:
    from collections.abc import Callable

# name → (numpy dtype, fill value of a point not computed)
FIELDS: dict[str, tuple[str, object]] = {
    "status": ("<U16", ""),
    "message": ("<U512", ""),
    "kind": ("<U16", ""),
    "converged": ("bool", False),
    "amplitude": ("f8", math.nan),
    "energy": ("f8", math.nan),
    "residual": ("f8", math.nan),
    "dropped_residual": ("f8", math.nan),
    "tail_error": ("f8", math.nan),
    "integrator_error": ("f8", math.nan),
    "qc_max_deviation": ("f8", math.nan),
    "profile_error": ("f8", math.nan),
    "amplitude_error": ("f8", math.nan),
    "energy_error": ("f8", math.nan),
    "N": ("i8", -1),
    "iterations": ("i8", -1),
    "wave_elapsed_s": ("f8", math.nan),
    "max_modulus": ("f8", math.nan),
    "max_modulus_away_from_1": ("f8", math.nan),
    "max_modulus_error": ("f8", math.nan),
    "symmetry_error": ("f8", math.nan),
    "floquet_integrator_error": ("f8", math.nan),
    "n_unstable": ("i8", -1),
    "n_trivial": ("i8", -1),
    "trivial_split": ("f8", math.nan),
    # the decision's sentence (fpucore.floquet.finite_size.Decision: at most SENTENCE_CHARS)
    "verdict": (f"<U{SENTENCE_CHARS}", ""),
    "classification": ("<U32", ""),
    "headline": ("<U64", ""),
    "floquet_converged": ("bool", False),
    "floquet_elapsed_s": ("f8", math.nan),
    "elapsed_s": ("f8", math.nan),
}
MESSAGE_CHARS = 512


def empty_record(status: str = "", message: str = "") -> dict:
    rec = {k: fill for k, (_, fill) in FIELDS.items()}
    rec["status"], rec["message"] = status, message[:MESSAGE_CHARS]
    return rec


def failure_text(exc: BaseException) -> str:
    """``Class: message`` of an exception plus where it was raised (last frame)."""
    where = traceback.extract_tb(exc.__traceback__)[-1:] if exc.__traceback__ else []
    at = f" (at {where[0].filename.rsplit('/', 1)[-1]}:{where[0].lineno})" if where else ""
    return f"{type(exc).__name__}: {exc}{at}"


def wave_record(r) -> dict:
    rec = empty_record(r.status, r.message)
    rec.update(
        kind=r.kind, converged=bool(r.converged), amplitude=r.amplitude, energy=r.energy,
        residual=r.residual, dropped_residual=r.dropped_residual, tail_error=r.tail_error,
        integrator_error=r.integrator_error, qc_max_deviation=r.qc_max_deviation,
        # error bounds added to WaveResult by the "error bars that bound the truth" work
        profile_error=getattr(r, "profile_error", math.nan),
        amplitude_error=getattr(r, "amplitude_error", math.nan),
        energy_error=getattr(r, "energy_error", math.nan),
        N=r.N, iterations=r.iterations, wave_elapsed_s=r.elapsed_s, elapsed_s=r.elapsed_s,
    )  # fmt: skip
    return rec


def add_floquet(rec: dict, fr) -> None:
    rec.update(
        max_modulus=fr.max_modulus, max_modulus_away_from_1=fr.max_modulus_away_from_1,
        max_modulus_error=fr.error, symmetry_error=fr.symmetry_error,
        floquet_integrator_error=fr.integrator_error, n_unstable=fr.n_unstable,
        n_trivial=fr.n_trivial, trivial_split=fr.trivial_split, verdict=fr.verdict,
        classification=str(getattr(fr, "classification", "")),
        headline=fr.decision.headline if fr.decision is not None else "",
        floquet_converged=bool(fr.converged), floquet_elapsed_s=fr.elapsed_s,
        elapsed_s=rec["wave_elapsed_s"] + fr.elapsed_s,
    )  # fmt: skip
    if not fr.converged:
        rec["status"], rec["message"] = "not_converged", f"spectrum: {fr.message}"[:MESSAGE_CHARS]


def solve_point(sp, N: int, tol: float, prev):
    """The wave ``sp`` (a :class:`fpucore.wave.Spec`) describes — from prev = (wave, spec) by the
    QC-shift predictor when both lie on the same velocity interval, else (or if that fails) from
    the QC guess (:func:`fpucore.wave.continuation.solve_from_neighbour`)."""

    def solve(pred):
        if sp.kind == "superkink":
            return solve_superkink(sp.law, sp.V, sp.branch, N, tol, predictor=pred)
        return solve_solitary(sp.law, sp.w_plus, sp.V, N, tol, predictor=pred)

    return solve_from_neighbour(sp, prev, solve)


def solve_chunk(task: dict, progress: Callable[[float], None] | None = None) -> list[dict]:
    """Records of the points ``task["V"]`` along one row, in order.  task: law (a force-law
    object), kind, row, V (list), N (int or None: automatic), tol, floquet (bool), m (RK steps or
    None), finite_size (bool: the spectrum's finite-size test, which gives the classification),
    floquet_method ("structured" | "dense"), continuation (bool).
    ``progress(frac)`` after each point."""
    law = task["law"]
    kind, row, N, tol = task["kind"], task["row"], task["N"], task["tol"]
    out, prev = [], None
    Vs = list(task["V"])
    for k, V in enumerate(Vs):
        t0 = time.perf_counter()
        try:
            sp = spec_of(law, kind, row, float(V))
        except ParameterError as exc:  # outside the existence region
            out.append(empty_record("no_wave", str(exc)) | {"elapsed_s": time.perf_counter() - t0})
            prev = None
            if progress is not None:
                progress((k + 1) / len(Vs))
            continue
        try:
            r = solve_point(sp, N, tol, prev)
            rec = wave_record(r)
            prev = (r, sp) if (r.converged and task.get("continuation", True)) else None
            if r.converged and task["floquet"]:
                fs = task.get("finite_size", True)
                method = task["floquet_method"]
                add_floquet(rec, spectrum(r, m=task.get("m"), finite_size=fs, method=method))
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
