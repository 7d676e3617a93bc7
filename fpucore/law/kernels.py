"""Numba kernels of the force laws: f, f′, f″ for a law handle ``(law_id, params)``.

Every jitted integrator (period map, Floquet tangent flow, chain steppers) evaluates the law
through these three functions, so adding a law means one branch here and a Python object in
this subpackage; nothing downstream changes.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

LAW_CUBIC = 0


@njit(cache=True, nogil=True)
def force(law_id: int, p: np.ndarray, w: float) -> float:
    """f(w) for the law (law_id, p).  Cubic: p = [a, b], f = a w³ + b w² + w."""
    if law_id == LAW_CUBIC:
        return ((p[0] * w + p[1]) * w + 1.0) * w
    return math.nan


@njit(cache=True, nogil=True)
def dforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f′(w)."""
    if law_id == LAW_CUBIC:
        return (3.0 * p[0] * w + 2.0 * p[1]) * w + 1.0
    return math.nan


@njit(cache=True, nogil=True)
def ddforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f″(w)."""
    if law_id == LAW_CUBIC:
        return 6.0 * p[0] * w + 2.0 * p[1]
    return math.nan
