"""Families of discrete waves over V with continuation (paper §5, Figs. TWcubic,
SWs_cubic_DvsQC, SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC): each wave is predicted from its
converged neighbour by the QC-shift predictor of :mod:`.continuation`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fpucore.errors import ParameterError
from fpucore.result import Result, status_of
from fpucore.wave.continuation import solve_from_neighbour
from fpucore.wave.driver import solve_solitary, solve_superkink
from fpucore.wave.setup import solitary_spec, superkink_spec

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from fpucore.law.base import HardeningSofteningLaw
    from fpucore.wave.driver import WaveResult


@dataclass(frozen=True)
class Family(Result):
    """A family of discrete waves over V.  kind : "superkink" | "solitary".
    results : list of WaveResult (V in the order requested); V, amplitude, energy, residual,
    qc_max_deviation : arrays; wave_converged : bool array (each wave's ``converged``).
    converged : every wave converged; message : how many did not, and the first one's reason."""

    kind: str
    results: list
    V: np.ndarray
    wave_converged: np.ndarray
    amplitude: np.ndarray
    energy: np.ndarray
    residual: np.ndarray
    qc_max_deviation: np.ndarray
    elapsed_s: float

    ERROR_FIELDS: ClassVar = ("residual",)
    DERIVED: ClassVar = ("status", "converged", "message")

    @property
    def converged(self) -> bool:
        return bool(np.all(self.wave_converged))

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        n, bad = len(self.results), [r for r in self.results if not r.converged]
        if not bad:
            return f"{n} waves converged"
        return (
            f"{len(bad)} of {n} waves did not converge (first at V = {bad[0].V:.10g}: "
            f"{bad[0].message})"
        )


def require_V_values(V_values) -> np.ndarray:
    """V_values as a non-empty 1-D array of finite velocities, else ParameterError (the one
    check of a list of velocities: families, the energy criterion)."""
    try:
        V = np.atleast_1d(np.asarray(V_values, dtype=float))
    except (TypeError, ValueError, OverflowError):  # ['a'], [None], ragged, 10**400: numpy's own
        V = None
    if V is None or V.ndim != 1 or V.size == 0 or not np.all(np.isfinite(V)):
        raise ParameterError("V_values", V_values, "a non-empty 1-D array of finite velocities")
    return V


def superkink_family(
    law: HardeningSofteningLaw,
    V_values: Sequence[float] | np.ndarray,
    branch: str = "lower",
    N: int | None = None,
    tol: float = 1e-12,
    progress: Callable[[int, int, WaveResult], None] | None = None,
) -> Family:
    """Discrete superkinks at each V (continuation with the QC-shift predictor).  Sort V_values
    so neighbours are close; each point is solved independently if its predictor fails.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    V_values : array_like, shape (n_V,)
        Wave velocities, sites per unit time, each in the superkink interval.
    branch : {"lower", "upper"}
        Which superkink branch.
    N : int or None
        Number of sites for every wave; None: automatic per wave.
    tol : float
        Relative tolerance of each solve, as in :func:`fpucore.wave.solve_superkink`.
    progress : callable or None
        ``progress(i, n_V, result)`` after each wave (i counts from 1).

    Returns
    -------
    Family
        The n_V results and their arrays of shape (n_V,) (V, converged, amplitude, energy,
        residual, qc_max_deviation) and the run time.

    Raises
    ------
    ParameterError
        When ``V_values`` is not a non-empty 1-D array of finite velocities, or any V or
        ``branch`` is invalid (checked before any solve).
    """

    V = require_V_values(V_values)
    specs = [superkink_spec(law, float(v), branch) for v in V]  # validates every V first

    def solve(sp, pred):
        return solve_superkink(law, sp.V, branch, N, tol, predictor=pred)

    return _family_wrap(specs, solve, "superkink", progress)


def solitary_family(
    law: HardeningSofteningLaw,
    w_plus: float,
    V_values: Sequence[float] | np.ndarray,
    N: int | None = None,
    tol: float = 1e-12,
    progress: Callable[[int, int, WaveResult], None] | None = None,
) -> Family:
    """Discrete solitary waves for state w₊ at each V in (c₊, V_SK) ∪ (V_SK, c₋).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_plus : float
        Strain w₊ ahead of the associated superkink.
    V_values : array_like, shape (n_V,)
        Wave velocities, sites per unit time.
    N : int or None
        Number of sites for every wave; None: automatic per wave.
    tol : float
        Relative tolerance of each solve, as in :func:`fpucore.wave.solve_solitary`.
    progress : callable or None
        ``progress(i, n_V, result)`` after each wave (i counts from 1).

    Returns
    -------
    Family
        The n_V results, their arrays of shape (n_V,) and the run time.

    Raises
    ------
    ParameterError
        When ``V_values`` is not a non-empty 1-D array of finite velocities, or ``w_plus`` or
        any V is invalid (checked before any solve).
    """

    V = require_V_values(V_values)
    specs = [solitary_spec(law, w_plus, float(v)) for v in V]

    def solve(sp, pred):
        return solve_solitary(law, w_plus, sp.V, N, tol, predictor=pred)

    return _family_wrap(specs, solve, "solitary", progress)


def _family_wrap(specs, solve, kind, progress):
    """Solve specs in order (``solve(spec, predictor)``), each from the previous converged wave
    on the same velocity interval (:func:`.continuation.solve_from_neighbour`)."""
    t0 = time.perf_counter()
    results, prev = [], None
    for i, sp in enumerate(specs):
        r = solve_from_neighbour(sp, prev, lambda pred, sp=sp: solve(sp, pred))
        results.append(r)
        prev = (r, sp) if r.converged else None
        if progress is not None:
            progress(i + 1, len(specs), r)
    arr = lambda k: np.array([getattr(r, k) for r in results])  # noqa: E731
    return Family(
        kind,
        results,
        arr("V"),
        arr("converged"),
        arr("amplitude"),
        arr("energy"),
        arr("residual"),
        arr("qc_max_deviation"),
        time.perf_counter() - t0,
    )
