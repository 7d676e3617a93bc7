"""Explicit Runge–Kutta Butcher tableaux, held as data.

``DOP853``: the 12-stage, 8th-order Dormand–Prince method (Hairer, Nørsett & Wanner, *Solving ODEs
I*, 2nd ed., §II.10; the coefficients are those of Hairer's DOP853 code as shipped in
``scipy.integrate._ivp.dop853_coefficients``, BSD-licensed, copied here so the kernels see plain
arrays).  Only the 12 stages of the 8th-order solution are kept; the embedded error weights and the
dense-output stages are not needed because :mod:`fpucore.period_map` estimates its error by step
doubling.

``RK4``: the classical 4-stage, 4th-order method, used as a low-order reference in the measured
order-of-convergence tests.

Every tableau satisfies ΣB = 1 and Σ_j A_ij = C_i (tested in tests/test_period_map.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate._ivp import dop853_coefficients as _dop

from .errors import ParameterError


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

    @property
    def stages(self) -> int:
        return int(self.B.size)


def _frozen(x: np.ndarray) -> np.ndarray:
    x = np.ascontiguousarray(x, dtype=np.float64).copy()
    x.setflags(write=False)
    return x


_S = _dop.N_STAGES  # 12
DOP853 = Tableau("dop853", _frozen(_dop.A[:_S, :_S]), _frozen(_dop.B[:_S]), _frozen(_dop.C[:_S]), 8)

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
