"""The bordered Newton system of the flat-top route (:mod:`fpucore.wave.plateau`'s module doc):
one side of V_SK as a family in s = ln|V − V_SK|, the exact V column, the bordered (2N+1)
system solved by block elimination with the banded LU of the ordinary Jacobian (one step of
iterative refinement), damped Newton at fixed plateau mass M, and the tangent dx/dM, ds/dM
along the family."""

from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import replace as _replace
from typing import TYPE_CHECKING

import numpy as np
from scipy.linalg import lapack

from fpucore import qc
from fpucore.budget import work_clock
from fpucore.wave.system import WaveSystem

if TYPE_CHECKING:
    from fpucore.law import HardeningSofteningLaw

DS_NEWTON = 1.0  # largest change of s per Newton step (V(s) is exponential)


@dataclass(frozen=True)
class PlateauFamily:
    """V-dependent pieces of one side of V_SK: boundary strain w_B(V), its derivative, systems."""

    law: HardeningSofteningLaw
    w_plus: float
    v_sk: float
    sgn: float  # +1 above V_SK (tensile, w_B = w_S(V)), −1 below (compressive, w_B = w₊)
    N: int
    m: int
    K: int

    def ok(self, V: float) -> bool:
        return math.isfinite(V) and self.sgn * (V - self.v_sk) > 0.0

    def w_B(self, V: float) -> float:
        return qc.w_S(self.law, self.w_plus, V) if self.sgn > 0 else self.w_plus

    def dw_B(self, V: float) -> float:
        if self.sgn < 0:
            return 0.0
        ws = self.w_B(V)
        return 2.0 * V * (ws - self.w_plus) / (float(self.law.df(ws)) - V * V)

    def system(self, V: float) -> WaveSystem:
        wb = self.w_B(V)
        return WaveSystem(self.law, V, self.N, wb, wb, "wd", 0.0, self.m, self.K)

    def s(self, V: float) -> float:
        return math.log(abs(V - self.v_sk))

    def V(self, s: float) -> float:
        return self.v_sk + self.sgn * math.exp(s)


def _rhs_T(S: WaveSystem, r) -> np.ndarray:
    """∂F/∂T at fixed x: the chain's right-hand side (ẇ(T), ẅ(T)) in the rows of the shifted map."""
    f = S.law.f
    g = np.concatenate([[f(S.w_left)], f(r.w), [f(S.w_right)]])
    wdd = g[2:] - 2.0 * g[1:-1] + g[:-2]
    N = S.N
    col = np.zeros(2 * N)
    col[S.row_w[: N - 1]] = r.wd[1:]
    col[S.row_wd] = wdd[1:]
    col[S.row_pin] = wdd[S.i_pin]
    return col


def _v_column(fam: PlateauFamily, S: WaveSystem, x: np.ndarray, r) -> np.ndarray:
    """dF/dV at fixed x (see module doc): −T² ∂F/∂T + dw_B/dV · ∂F/∂w_B."""
    col = -(S.T**2) * _rhs_T(S, r)
    dwb = fam.dw_B(S.V)
    if dwb != 0.0:
        h = 1e-6 * max(1.0, abs(S.w_left))
        Fp, _ = _replace(S, w_left=S.w_left + h, w_right=S.w_right + h).residual(x)
        Fm, _ = _replace(S, w_left=S.w_left - h, w_right=S.w_right - h).residual(x)
        col += dwb * (Fp - Fm) / (2.0 * h)
    return col


def band_matvec(ab: np.ndarray, kl: int, ku: int, v: np.ndarray) -> np.ndarray:
    """J v for J in LAPACK dgbtrf band storage (ab[kl + ku + i − j, j] = J[i, j])."""
    n = v.size
    out = np.zeros(n)
    for q in range(kl, 2 * kl + ku + 1):
        off = q - kl - ku  # i − j
        j0, j1 = max(0, -off), min(n, n - off)
        if j1 > j0:
            out[j0 + off : j1 + off] += ab[q, j0:j1] * v[j0:j1]
    return out


class _Bordered:
    """[J c; r d] with r = (1 on w-entries, 0 on ẇ), solved by block elimination with the banded
    LU of J plus one step of iterative refinement (J is nearly singular: σ_min ∝ δ)."""

    def __init__(self, ab, kl, ku, c, d):
        self.ab, self.kl, self.ku, self.c, self.d = ab, kl, ku, c, d
        self.lu, self.piv, self.info = lapack.dgbtrf(ab, kl, ku)
        self.y = self._J(c) if self.info == 0 else None

    def _J(self, b, trans=0):
        x, _ = lapack.dgbtrs(self.lu, self.kl, self.ku, b.reshape(-1, 1), self.piv, trans=trans)
        return x[:, 0]

    def _once(self, f, g):
        z = self._J(f)
        den = self.d - self.y[0::2].sum()
        t = (g - z[0::2].sum()) / den if den != 0.0 else math.nan
        return z - t * self.y, t

    def solve(self, f: np.ndarray, g: float):
        u, t = self._once(f, g)
        rf = f - band_matvec(self.ab, self.kl, self.ku, u) - self.c * t
        rg = g - u[0::2].sum() - self.d * t
        du, dt = self._once(rf, rg)
        return u + du, t + dt


@dataclass(frozen=True)
class BorderedOutcome:
    x: np.ndarray
    s: float  # ln|V − V_SK|
    converged: bool
    residual: float
    iterations: int
    message: str


def _state(fam: PlateauFamily, x, s, M):
    V = fam.V(s)
    S = fam.system(V)
    F, _ = S.residual_from(x, S.integrate(x))
    G = float(x[0::2].sum() - fam.N * fam.w_B(V) - M)
    return F, G, max(float(np.max(np.abs(F))), abs(G) / fam.N)


def _linearize(fam: PlateauFamily, x, s):
    """Bordered Jacobian in the unknowns (x, s), s = ln|V − V_SK| (dV/ds = V − V_SK): V(s) is
    exponential like the plateau physics, so Newton's s-update stays on the right side of V_SK."""
    V = fam.V(s)
    S = fam.system(V)
    ab, kl, ku, _, F, _ = S.jacobian_banded(x)
    dVds = V - fam.v_sk
    c = _v_column(fam, S, x, S.integrate(x)) * dVds
    return _Bordered(ab, kl, ku, c, -fam.N * fam.dw_B(V) * dVds), F


def bordered_newton(
    fam: PlateauFamily, x0, s0, M, tol, max_iter=20, deadline=math.inf
) -> BorderedOutcome:
    """Damped Newton for (F, G) = 0 in (x, s) at plateau mass M; residual max(|F|∞, |G|/N).
    Iterates on towards the round-off floor (goal tol/100) and reports converged if the residual
    ended ≤ tol: the secant on s needs states as exact as double precision allows."""
    x, s = np.array(x0, dtype=float), float(s0)
    F, G, res = _state(fam, x, s, M)
    it, msg = 0, "converged"
    while res > 1e-2 * tol:
        if it >= max_iter or work_clock() > deadline or not math.isfinite(res):
            msg = f"bordered Newton: residual {res:.3g} after {it} iterations"
            break
        it += 1
        B, F = _linearize(fam, x, s)
        if B.info != 0:
            msg = "bordered Newton: singular LU"
            break
        dx, ds = B.solve(-F, -G)
        if not (np.all(np.isfinite(dx)) and math.isfinite(ds)):
            msg = "bordered Newton: non-finite step"
            break
        lam = min(1.0, DS_NEWTON / abs(ds)) if ds else 1.0  # trust region on s = ln δ
        while lam >= 1.0 / 64:
            xt, st = x + lam * dx, s + lam * ds
            Ft, Gt, rt = _state(fam, xt, st, M)
            if math.isfinite(rt) and rt < (1.0 - 0.1 * lam) * res:
                break
            lam *= 0.5
        else:
            msg = f"bordered Newton stalled at {res:.3g}"
            break
        x, s, F, G, res = xt, st, Ft, Gt, rt
    ok = res <= tol
    return BorderedOutcome(x, s, ok, res, it, "converged" if ok else msg)


def mass_tangent(fam: PlateauFamily, x, s):
    """(dx/dM, ds/dM) along the family: the bordered system with right-hand side (0, 1)."""
    B, _ = _linearize(fam, x, s)
    if B.info != 0:
        return None
    return B.solve(np.zeros(x.size), 1.0)
