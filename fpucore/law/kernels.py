"""Numba kernels of the force laws: f, f′, f″ for a law handle ``(law_id, params)``.

Every jitted integrator (period map, Floquet tangent flow, chain steppers) evaluates the law
through these three functions, so adding a law means one branch here and a Python object in
this subpackage; nothing downstream changes.

Laws: ``LAW_CUBIC`` (p = [a, b], eq. cubic) and the polynomials f = Σ_{k≥1} c_k w^k with
p[k−1] = c_k, one compiled kernel for every polynomial: ``LAW_POLY3`` … ``LAW_POLY8`` for degrees
3–8 (unrolled Horner, selected by the law id alone so the branch is as cheap as the cubic's; the
same operations in the same order as the loop, so bit-identical to it) and ``LAW_POLY`` for any
degree (Horner loop over p, used beyond degree 8; 1.5–1.9× the cubic in-jit —
benchmarks/README.md).  ``LAW_PWL``: continuous piecewise-linear laws (:mod:`.piecewise`).

``LAW_CHEB``: any smooth law (:class:`~fpucore.law.SmoothLaw`), one compiled kernel for all:
p holds a piecewise Chebyshev representation of f, f′, f″ on [lo, hi] (layout in
:mod:`.chebyshev`); NaN outside [lo, hi] (a state that left the represented interval is never
extrapolated; the routes report it).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

LAW_CUBIC = 0
LAW_POLY = 1  # any degree (loop)
LAW_CHEB = 2  # any smooth law: piecewise Chebyshev data (fpucore/law/chebyshev.py)
LAW_POLY3, LAW_POLY4, LAW_POLY5, LAW_POLY6, LAW_POLY7, LAW_POLY8 = 3, 4, 5, 6, 7, 8  # id = degree
POLY_IDS = (LAW_POLY, LAW_POLY3, LAW_POLY4, LAW_POLY5, LAW_POLY6, LAW_POLY7, LAW_POLY8)
LAW_PWL = 20  # continuous piecewise-linear: p = [m, b_1..b_m, s_0..s_m, f(b_1)..f(b_m)]


@njit(cache=True, nogil=True)
def _pwl_piece(p: np.ndarray, w: float) -> int:
    """Piece j of w for a PL law (number of breakpoints <= w; a breakpoint goes right)."""
    m = int(p[0])
    j = 0
    while j < m and w >= p[1 + j]:
        j += 1
    return j


_CHEB_HEADER = 8  # [lo, hi, npan, ncoef, npan/(hi - lo), 0, 0, 0]


@njit(cache=True, nogil=True, inline="always")
def _cheb(p: np.ndarray, which: int, w: float) -> float:
    """Clenshaw on the panel of w of block ``which`` (0: f, 1: f′, 2: f″); NaN outside."""
    x = (w - p[0]) * p[4]
    npan = int(p[2])
    if not (x >= 0.0 and x <= npan):
        return math.nan
    k = int(x)
    if k >= npan:
        k = npan - 1
    t = 2.0 * (x - k) - 1.0
    m = int(p[3])
    base = _CHEB_HEADER + (which * npan + k) * m
    b1 = 0.0
    b2 = 0.0
    t2 = 2.0 * t
    for j in range(m - 1, 0, -1):
        b0 = p[base + j] + t2 * b1 - b2
        b2 = b1
        b1 = b0
    return p[base] + t * b1 - b2


@njit(cache=True, nogil=True)
def force(law_id: int, p: np.ndarray, w: float) -> float:
    """f(w) for the law (law_id, p).  Cubic: p = [a, b], f = a w³ + b w² + w."""
    if law_id == LAW_CUBIC:
        return ((p[0] * w + p[1]) * w + 1.0) * w
    if law_id == LAW_POLY3:  # Horner on p[k−1] = c_k, then the factor w (f(0) = 0)
        return ((p[2] * w + p[1]) * w + p[0]) * w
    if law_id == LAW_POLY4:
        return (((p[3] * w + p[2]) * w + p[1]) * w + p[0]) * w
    if law_id == LAW_POLY5:
        return ((((p[4] * w + p[3]) * w + p[2]) * w + p[1]) * w + p[0]) * w
    if law_id == LAW_POLY6:
        return (((((p[5] * w + p[4]) * w + p[3]) * w + p[2]) * w + p[1]) * w + p[0]) * w
    if law_id == LAW_POLY7:
        return (
            (((((p[6] * w + p[5]) * w + p[4]) * w + p[3]) * w + p[2]) * w + p[1]) * w + p[0]
        ) * w
    if law_id == LAW_POLY8:
        return (
            ((((((p[7] * w + p[6]) * w + p[5]) * w + p[4]) * w + p[3]) * w + p[2]) * w + p[1]) * w
            + p[0]
        ) * w
    if law_id == LAW_POLY:
        acc = 0.0
        for k in range(p.shape[0] - 1, -1, -1):
            acc = acc * w + p[k]
        return acc * w
    if law_id == LAW_PWL:  # f(b_k) + s_j (w - b_k), anchored at the piece's left breakpoint
        m = int(p[0])
        j = _pwl_piece(p, w)
        k = j - 1 if j > 0 else 0
        return p[2 + 2 * m + k] + p[1 + m + j] * (w - p[1 + k])
    if law_id == LAW_CHEB:
        return _cheb(p, 0, w)
    return math.nan


@njit(cache=True, nogil=True)
def dforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f′(w)."""
    if law_id == LAW_CUBIC:
        return (3.0 * p[0] * w + 2.0 * p[1]) * w + 1.0
    if law_id == LAW_POLY3:  # f′ = Σ k c_k w^(k−1)
        return (3.0 * p[2] * w + 2.0 * p[1]) * w + p[0]
    if law_id == LAW_POLY4:
        return ((4.0 * p[3] * w + 3.0 * p[2]) * w + 2.0 * p[1]) * w + p[0]
    if law_id == LAW_POLY5:
        return (((5.0 * p[4] * w + 4.0 * p[3]) * w + 3.0 * p[2]) * w + 2.0 * p[1]) * w + p[0]
    if law_id == LAW_POLY6:
        return (
            ((((6.0 * p[5]) * w + 5.0 * p[4]) * w + 4.0 * p[3]) * w + 3.0 * p[2]) * w + 2.0 * p[1]
        ) * w + p[0]
    if law_id == LAW_POLY7:
        return (
            (((((7.0 * p[6]) * w + 6.0 * p[5]) * w + 5.0 * p[4]) * w + 4.0 * p[3]) * w + 3.0 * p[2])
            * w
            + 2.0 * p[1]
        ) * w + p[0]
    if law_id == LAW_POLY8:
        return (
            (
                (
                    ((((8.0 * p[7]) * w + 7.0 * p[6]) * w + 6.0 * p[5]) * w + 5.0 * p[4]) * w
                    + 4.0 * p[3]
                )
                * w
                + 3.0 * p[2]
            )
            * w
            + 2.0 * p[1]
        ) * w + p[0]
    if law_id == LAW_POLY:
        acc = 0.0
        for k in range(p.shape[0] - 1, -1, -1):
            acc = acc * w + (k + 1) * p[k]
        return acc
    if law_id == LAW_PWL:  # the slope of w's piece (on a breakpoint: the right one)
        return p[1 + int(p[0]) + _pwl_piece(p, w)]
    if law_id == LAW_CHEB:
        return _cheb(p, 1, w)
    return math.nan


@njit(cache=True, nogil=True)
def ddforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f″(w)."""
    if law_id == LAW_CUBIC:
        return 6.0 * p[0] * w + 2.0 * p[1]
    if law_id == LAW_POLY3:  # f″ = Σ k (k−1) c_k w^(k−2)
        return 6.0 * p[2] * w + 2.0 * p[1]
    if law_id == LAW_POLY4:
        return (12.0 * p[3] * w + 6.0 * p[2]) * w + 2.0 * p[1]
    if law_id == LAW_POLY5:
        return ((20.0 * p[4] * w + 12.0 * p[3]) * w + 6.0 * p[2]) * w + 2.0 * p[1]
    if law_id == LAW_POLY6:
        return (
            (((30.0 * p[5]) * w + 20.0 * p[4]) * w + 12.0 * p[3]) * w + 6.0 * p[2]
        ) * w + 2.0 * p[1]
    if law_id == LAW_POLY7:
        return (
            ((((42.0 * p[6]) * w + 30.0 * p[5]) * w + 20.0 * p[4]) * w + 12.0 * p[3]) * w
            + 6.0 * p[2]
        ) * w + 2.0 * p[1]
    if law_id == LAW_POLY8:
        return (
            (
                ((((56.0 * p[7]) * w + 42.0 * p[6]) * w + 30.0 * p[5]) * w + 20.0 * p[4]) * w
                + 12.0 * p[3]
            )
            * w
            + 6.0 * p[2]
        ) * w + 2.0 * p[1]
    if law_id == LAW_POLY:
        acc = 0.0
        for k in range(p.shape[0] - 1, 0, -1):
            acc = acc * w + (k + 1) * k * p[k]
        return acc
    if law_id == LAW_PWL:  # zero between breakpoints (the Dirac masses are located, not sampled)
        return 0.0
    if law_id == LAW_CHEB:
        return _cheb(p, 2, w)
    return math.nan


@njit(cache=True, nogil=True)
def forces_into(law_id: int, p: np.ndarray, w: np.ndarray, out: np.ndarray) -> None:
    """out[k] = f(w[k]) for k < len(w).  The paper's cubic gets a loop of its own, its law id a
    constant: with the id tested inside the loop (``force`` per site, one branch per law) the
    loop over the chain did not vectorise, and the simulation's right-hand side cost ~2x the CPU
    (L = 3600 Riemann run: 1.34 s -> 0.70 s).  Other laws keep the per-site dispatch."""
    if law_id == LAW_CUBIC:
        for k in range(w.shape[0]):
            out[k] = force(LAW_CUBIC, p, w[k])
    else:
        for k in range(w.shape[0]):
            out[k] = force(law_id, p, w[k])
