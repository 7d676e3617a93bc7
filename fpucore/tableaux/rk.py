"""Explicit Runge–Kutta Butcher tableaux, held as data.

``DOP853``: the 12-stage, 8th-order Dormand–Prince method (Hairer, Nørsett & Wanner, *Solving ODEs
I*, 2nd ed., §II.10; coefficients as data in :mod:`.dop853_data`, with their source).  Only the 12
stages of the 8th-order solution are kept; the embedded error weights and the dense-output stages
are not needed because :mod:`fpucore.wave.period_map` estimates its error by step doubling.

``RK4``: the classical 4-stage, 4th-order method, used as a low-order reference in the measured
order-of-convergence tests.

Every tableau is validated when it is built (:func:`check_consistency`: ΣB = 1, Σ_j A_ij = C_i,
A strictly lower triangular), so a mistyped coefficient fails at import.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fpucore.errors import ParameterError
from fpucore.tableaux import dop853_data as _dop


@dataclass(frozen=True)
class Tableau:
    """Butcher tableau of an explicit RK method.

    name : identifier; A : (s, s) strictly lower triangular; B : (s,) weights; C : (s,) nodes;
    order : classical order of the method.
    """

    name: str
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    order: int

    def __post_init__(self):
        check_consistency(self.name, self.A, self.B, self.C)

    @property
    def stages(self) -> int:
        return int(self.B.size)


def check_consistency(
    name: str, A: np.ndarray, B: np.ndarray, C: np.ndarray, tol: float = 1e-15
) -> None:
    """Raise ValueError unless ΣB = 1, Σ_j A_ij = C_i and A is strictly lower triangular (explicit).

    These are the order-1 conditions and the row-sum simplifying assumption that every explicit
    RK method used here satisfies; a failure means a mistyped coefficient."""
    s = B.size
    if A.shape != (s, s) or C.shape != (s,):
        raise ValueError(f"tableau {name}: shapes A {A.shape}, B {B.shape}, C {C.shape} disagree")
    if np.any(np.triu(A) != 0):
        raise ValueError(f"tableau {name}: A is not strictly lower triangular")
    if abs(float(B.sum()) - 1.0) > tol * s:
        raise ValueError(f"tableau {name}: sum(B) = {B.sum()!r} != 1")
    dev = float(np.max(np.abs(A.sum(axis=1) - C)))
    if dev > 4 * tol * s:
        raise ValueError(f"tableau {name}: rows of A miss C by {dev:.2e}")


def _lower(rows: list[list[float]]) -> np.ndarray:
    s = len(rows)
    a = np.zeros((s, s))
    for i, r in enumerate(rows):
        a[i, : len(r)] = r
    return a


def _frozen(x: np.ndarray) -> np.ndarray:
    x = np.ascontiguousarray(x, dtype=np.float64).copy()
    x.setflags(write=False)
    return x


DOP853 = Tableau(
    "dop853", _frozen(_lower(_dop.A)), _frozen(np.array(_dop.B)), _frozen(np.array(_dop.C)), 8
)

RK4 = Tableau(
    "rk4",
    _frozen(np.array([[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 1.0, 0]], float)),
    _frozen(np.array([1 / 6, 1 / 3, 1 / 3, 1 / 6])),
    _frozen(np.array([0.0, 0.5, 0.5, 1.0])),
    4,
)

TABLEAUX = {t.name: t for t in (DOP853, RK4)}


def get(name: str) -> Tableau:
    """Tableau by name (``"dop853"`` or ``"rk4"``)."""
    try:
        return TABLEAUX[name]
    except KeyError:
        raise ParameterError("tableau", name, " | ".join(TABLEAUX)) from None
