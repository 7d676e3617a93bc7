"""Embedded Runge–Kutta pairs with error estimators, held as data (for adaptive steppers).

``DOP853E``: Dormand–Prince 8(5,3) — the 12 stages of :data:`fpucore.tableaux.rk.DOP853` plus
Hairer's two embedded error-weight vectors E5, E3 (13 entries: the 13th multiplies the FSAL stage
f(t+h, y₁)).  The error norm is Hairer's combination ‖e5‖² / √(‖e5‖² + 0.01 ‖e3‖²) (Hairer,
Nørsett & Wanner, *Solving ODEs I*, §II.10; the same as scipy's DOP853).  Coefficients as data in
:mod:`.dop853_data` (with their source).

``DOPRI5``: Dormand–Prince 5(4) (the method of Matlab's ode45 used in the paper), 6 stages + FSAL;
E is b − b̂ (7 entries), E3 is zero (single estimator).

The stepper (:mod:`fpucore.simulate.kernels`) fuses the error estimate into one pass over at most
eight stage rows; both pairs qualify (tested)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fpucore.errors import ParameterError
from fpucore.tableaux import dop853_data as _dop
from fpucore.tableaux.rk import DOP853, check_consistency


@dataclass(frozen=True)
class EmbeddedTableau:
    """Explicit RK pair. A (s, s), B (s,), C (s,); E5, E3 (s+1,) error weights including the FSAL
    stage; ``order`` of the propagated solution; ``err_order`` of the error estimator (the step
    controller uses the exponent −1/(err_order+1)); ``dual`` selects Hairer's two-estimator norm."""

    name: str
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    E5: np.ndarray
    E3: np.ndarray
    order: int
    err_order: int
    dual: bool

    def __post_init__(self):
        check_consistency(self.name, self.A, self.B, self.C)
        s = self.B.size
        if self.E5.shape != (s + 1,) or self.E3.shape != (s + 1,):
            raise ValueError(f"pair {self.name}: error weights must have s + 1 = {s + 1} entries")
        if abs(float(self.E5.sum())) > 1e-14:  # b − b̂ of two consistent methods sums to 0
            raise ValueError(f"pair {self.name}: sum(E5) = {self.E5.sum()!r} != 0")

    @property
    def stages(self) -> int:
        return int(self.B.size)


def _ro(x) -> np.ndarray:
    x = np.ascontiguousarray(np.asarray(x, dtype=np.float64)).copy()
    x.setflags(write=False)
    return x


DOP853E = EmbeddedTableau(
    "dop853",
    DOP853.A,
    DOP853.B,
    DOP853.C,
    _ro(_dop.E5),
    _ro(_dop.E3),
    order=8,
    err_order=7,
    dual=True,
)

_A5 = np.zeros((6, 6))
_A5[1, :1] = [1 / 5]
_A5[2, :2] = [3 / 40, 9 / 40]
_A5[3, :3] = [44 / 45, -56 / 15, 32 / 9]
_A5[4, :4] = [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729]
_A5[5, :5] = [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]
_B5 = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
# b − b̂ with b̂ the 4th-order weights (7 stages, the last is the FSAL stage).
_E5 = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])

DOPRI5 = EmbeddedTableau(
    "dopri5",
    _ro(_A5),
    _ro(_B5),
    _ro([0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1]),
    _ro(_E5),
    _ro(np.zeros(7)),
    order=5,
    err_order=4,
    dual=False,
)

EMBEDDED = {t.name: t for t in (DOP853E, DOPRI5)}


def get(name: str) -> EmbeddedTableau:
    """Embedded pair by name (``"dop853"`` or ``"dopri5"``)."""
    try:
        return EMBEDDED[name]
    except KeyError:
        raise ParameterError("method", name, " | ".join(EMBEDDED)) from None
