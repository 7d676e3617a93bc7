"""Numba kernels of the force laws: f, f′, f″ for a law handle ``(law_id, params)``.

Every jitted integrator (period map, Floquet tangent flow, chain steppers) evaluates the law
through these three functions, so adding a law means one branch here and a Python object in
this subpackage; nothing downstream changes.

Laws: ``LAW_CUBIC`` (p = [a, b], eq. cubic) and ``LAW_POLY`` (p[k−1] = c_k, f = Σ_{k≥1} c_k w^k,
any degree, one compiled kernel for every polynomial).  Polynomials of degree ≤ 5 take an
unrolled Horner fast path (a branch on the length of p, predictable inside a loop): the generic
loop over p costs 1.8–2.3× the cubic in-jit, the unrolled forms ≤ 1.3× (benchmarks/README.md).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

LAW_CUBIC = 0
LAW_POLY = 1


@njit(cache=True, nogil=True)
def force(law_id: int, p: np.ndarray, w: float) -> float:
    """f(w) for the law (law_id, p).  Cubic: p = [a, b], f = a w³ + b w² + w."""
    if law_id == LAW_CUBIC:
        return ((p[0] * w + p[1]) * w + 1.0) * w
    if law_id == LAW_POLY:  # Horner on p[k−1] = c_k, then the factor w (f(0) = 0)
        n = p.shape[0]
        if n == 3:
            return ((p[2] * w + p[1]) * w + p[0]) * w
        if n == 4:
            return (((p[3] * w + p[2]) * w + p[1]) * w + p[0]) * w
        if n == 2:
            return (p[1] * w + p[0]) * w
        if n == 5:
            return ((((p[4] * w + p[3]) * w + p[2]) * w + p[1]) * w + p[0]) * w
        acc = 0.0
        for k in range(n - 1, -1, -1):
            acc = acc * w + p[k]
        return acc * w
    return math.nan


@njit(cache=True, nogil=True)
def dforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f′(w)."""
    if law_id == LAW_CUBIC:
        return (3.0 * p[0] * w + 2.0 * p[1]) * w + 1.0
    if law_id == LAW_POLY:  # f′ = Σ k c_k w^(k−1)
        n = p.shape[0]
        if n == 3:
            return (3.0 * p[2] * w + 2.0 * p[1]) * w + p[0]
        if n == 4:
            return ((4.0 * p[3] * w + 3.0 * p[2]) * w + 2.0 * p[1]) * w + p[0]
        if n == 2:
            return 2.0 * p[1] * w + p[0]
        if n == 5:
            return (((5.0 * p[4] * w + 4.0 * p[3]) * w + 3.0 * p[2]) * w + 2.0 * p[1]) * w + p[0]
        acc = 0.0
        for k in range(n - 1, -1, -1):
            acc = acc * w + (k + 1) * p[k]
        return acc
    return math.nan


@njit(cache=True, nogil=True)
def ddforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f″(w)."""
    if law_id == LAW_CUBIC:
        return 6.0 * p[0] * w + 2.0 * p[1]
    if law_id == LAW_POLY:  # f″ = Σ k (k−1) c_k w^(k−2)
        n = p.shape[0]
        if n == 3:
            return 6.0 * p[2] * w + 2.0 * p[1]
        if n == 4:
            return (12.0 * p[3] * w + 6.0 * p[2]) * w + 2.0 * p[1]
        if n == 2:
            return 2.0 * p[1]
        if n == 5:
            return ((20.0 * p[4] * w + 12.0 * p[3]) * w + 6.0 * p[2]) * w + 2.0 * p[1]
        acc = 0.0
        for k in range(n - 1, 0, -1):
            acc = acc * w + (k + 1) * k * p[k]
        return acc
    return math.nan
