"""Flat-top solitary waves next to V_SK (paper §4–5, Fig. stabSW): continuation in plateau mass.

Near V_SK a solitary wave is a kink–antikink bundle: a plateau at the superkink's other state
between two fronts.  The plateau length is tied to V only exponentially weakly: with λ the discrete
tail rate at the plateau state (:func:`fpucore.wave.tails.decay_rate`) the fronts interact like
e^{−2λ·(front distance)}, so each front moves by ln(10)/(2λ) sites per decade of δ = |V − V_SK|.
At fixed V the Newton Jacobian of eq. nonlin_system therefore has a near-null vector that is EVEN
in n (the two fronts moving apart), with smallest singular value σ_min ∝ δ: natural continuation
in V stalls and, at δ ≈ 1e-11, the double-precision residual cannot fix the plateau length.

Remedy (this module).  Parametrize by the plateau mass instead of V:

    unknowns (x, V),  equations  F(x, V) = 0  (eq. nonlin_system, pin ẇ_1(T) = 0)
                                 G(x, V) = Σ_n (w_n(0) − w_B(V)) − M = 0.

The V column is exact where it matters: with T = 1/V, ∂Φ_T/∂T at fixed state is the chain's
right-hand side at t = T, (ẇ(T), ẅ(T)), times dT/dV = −T², placed in the rows of the shifted map
like every other entry.  Above V_SK the boundary strains are w_B = w_S(V) (eq. wS), so F and G
also depend on V through w_B: dw_S/dV = 2V(w_S − w₊)/(f′(w_S) − V²) (implicit differentiation of
eq. wS, closed form) times ∂F/∂w_B.  ∂F/∂w_B is exact in the boundary row (w_right − w_{N/2−1})
and in G (−N); the boundary forcing f(w_B) inside the period map enters by a central difference
in w_B (relative error ~1e-9, two period integrations) — a quasi-Newton correction that is tiny
next to the plateau term (dM/dV ≈ 2A/(2λδ) ≫ N |dw_S/dV| for δ ≪ 1e-3), so Newton stays quadratic
to round-off.  The bordered (2N+1) system is solved by block elimination with the banded LU of the
ordinary Jacobian (two banded solves, one step of iterative refinement); band storage is kept.

Continuation.  From a converged wave at δ₀ (where the QC half-plateau is short, γ·x_f ≈ 5.5) the
mass M is stepped with a front-translation predictor (the discrete wave's own motion moves both
fronts by ΔM/(2A) sites); the target is reached by a secant on s = ln δ, which is nearly linear
in M (slope −2λ/(2A)).  The caller then polishes at fixed V with
the ordinary pinning.  :func:`front_uncertainty` converts the round-off floor of the residual
along the near-null direction into an error bar on the front position (sites).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import lapack
from scipy.optimize import brentq

from fpucore.budget import work_clock
from fpucore.wave import period_map as pm
from fpucore.wave import tails as wt
from fpucore.wave.plateau_newton import (
    DS_NEWTON,  # noqa: F401  (re-exported: the route's constants are read from here)
    BorderedOutcome,  # noqa: F401  (re-exported: the outcome of bordered_newton)
    PlateauFamily,
    band_matvec,
    bordered_newton,
    mass_tangent,
)
from fpucore.wave.setup import Spec
from fpucore.wave.system import WaveSystem

FRONT_MAX = 1.0  # sites: a larger round-off error bar on the fronts is reported as failure
GX_DIRECT = 8.5  # QC γ·x_f from which solve_solitary goes straight to this route (δ ≲ 2e-7;
# measured: the ordinary route needs 5–6 s of V-continuation at δ = 1e-7, this one < 1 s)
GX_FALLBACK = 7.0  # … from which it is tried after the ordinary route failed (δ ≲ 3e-6)
GX_START = (5.5, 4.5)  # start waves: short plateau, where the ordinary route converges
DS_MAX = 3.0  # largest step in s = ln δ per continuation step (≈ 0.5 site of front motion)
FRONT_STEP = 0.8  # sites: largest front move per step (translate_fronts moves by < 1 site)
SECANT_AGREE = 0.25  # a secant of ln δ against M over >= SECANT_SPAN must agree with the exact
SECANT_SPAN = 0.1  # tangent within this (measured, w₊ = 1: 2 % down to δ ≈ 2e-13·V_SK, then
# 35 %, then opposite signs: ln δ no longer follows the mass in double precision)


# =============================================================================== QC geometry
def qc_front(sw) -> float:
    """QC front position x_f > 0 (sites): where the profile crosses (w_B + w_M)/2."""
    mid = 0.5 * (sw.w_B + sw.w_M)
    g = lambda xi: (float(sw.profile(xi)) - mid) * (sw.w_M - sw.w_B)  # noqa: E731  > 0 inside
    hi = 1.0
    while g(hi) > 0.0:
        hi *= 2.0
        if hi > 1e6:
            return math.inf
    return brentq(g, 0.0, hi, xtol=1e-12)


def qc_half_plateau(sw) -> float:
    """γ·x_f: the QC half-plateau in units of the front width (≈ ln(1/δ)/2 + const)."""
    return sw.gamma * qc_front(sw)


def half_plateau(w: np.ndarray, w_B: float) -> float:
    """Equivalent half-length of the plateau (sites): Σ_n (w_n − w_B) / (2 (w_0 − w_B)), w_0 the
    centre value — the front position of the rectangle with the same mass.  Free of the sub-site
    interpolation error of :func:`front_position` (the fronts are ~1/λ ≈ 0.3 site wide)."""
    N = w.size
    return float((w - w_B).sum() / (2.0 * (w[N // 2] - w_B)))


def front_position(w: np.ndarray, n: np.ndarray, w_B: float) -> float:
    """Discrete right front (sites): linear interpolation of where w crosses the midpoint between
    w_B and the centre value w(n = 0), searching outward from the centre."""
    i0 = int(np.argmin(np.abs(n)))
    mid = 0.5 * (w_B + w[i0])
    s = np.sign(w[i0:] - mid)
    k = np.nonzero(s != s[0])[0]
    if k.size == 0:
        return math.nan
    i = i0 + int(k[0])
    return float(n[i - 1] + (mid - w[i - 1]) / (w[i] - w[i - 1]))


# =============================================================================== the family


# =============================================================================== the route
@dataclass(frozen=True)
class PlateauPath:
    """Outcome of :func:`continue_in_mass`.  x : state at V (None if the start wave was lost);
    V : the velocity of x (the target, or the closest V reached); converged : whether the path
    reached the target; note : how; points : (δ, M, front sites) along the path; start_delta :
    δ = |V − V_SK| of the start wave."""

    x: np.ndarray | None
    V: float
    converged: bool
    note: str
    points: tuple
    start_delta: float


def start_delta(spec: Spec, sgn: float, gx: float) -> float:
    """δ on the side sgn of V_SK (of spec's w₊) where the QC half-plateau γ·x_f equals gx
    (bisection in ln δ)."""
    v_sk = spec.v_sk
    (a, b), (c, d) = spec.intervals()
    far = (b - a) if sgn < 0 else (d - c)
    lo, hi = math.log(1e-15 * v_sk), math.log(0.5 * far)

    def h(s):
        return qc_half_plateau(spec.at(v_sk + sgn * math.exp(s)).qcw) - gx

    if h(hi) > 0 or h(lo) < 0:
        return math.exp(hi) if h(hi) > 0 else math.exp(lo)
    return math.exp(brentq(h, lo, hi, xtol=1e-3))


def translate_fronts(S: WaveSystem, x: np.ndarray, delta: float) -> np.ndarray:
    """Move both fronts outward by delta sites (|delta| < 1) using the wave's own motion: a
    traveling wave has w_n(t) = W(n − V t), so W(n − Δ) = w_n(ΔT) and W(n + Δ) = w_{n+1}((1−Δ)T).
    Right half (n ≥ 0) ← W(n − Δ), left half ← W(n + Δ) (swapped for Δ < 0): the exact shape of
    the discrete front, spliced in the flat plateau at n = 0 (symmetry centre of the pinning)."""
    d = abs(delta)
    if d == 0.0:
        return x.copy()
    w, wd = x[0::2], x[1::2]
    a = pm.integrate(S.law, w, wd, d * S.T, S.m, S.w_left, S.w_right)  # W(n − d)
    b = pm.integrate(S.law, w, wd, (1.0 - d) * S.T, S.m, S.w_left, S.w_right)  # W(n + 1 − d)
    N = S.N
    back_w, back_wd = np.append(b.w[1:], S.w_right), np.append(b.wd[1:], 0.0)  # W(n + d)
    out_w, out_wd = (a.w, a.wd) if delta > 0 else (back_w, back_wd)
    in_w, in_wd = (back_w, back_wd) if delta > 0 else (a.w, a.wd)
    y = np.empty_like(x)
    h = N // 2
    y[0::2] = np.concatenate([in_w[:h], out_w[h:]])
    y[1::2] = np.concatenate([in_wd[:h], out_wd[h:]])
    return y


def continue_in_mass(
    spec: Spec, x0, V0, N, m, K, tol, deadline, max_steps: int = 40
) -> PlateauPath:
    """March in plateau mass M from the converged wave (x0, V0) to V_target = spec.V (same side
    of V_SK, same w₊) on N sites with m RK steps, window K; tol : residual tolerance; deadline :
    time limit on the :func:`~fpucore.budget.work_clock`.

    Predictor: both discrete fronts translated by ΔM/(2A) sites (:func:`translate_fronts`; the
    QC-difference and linear-tangent predictors were measured to allow only |Δs| ≲ 1 per step,
    this one ≈ 3); corrector: bordered Newton at M + ΔM, ΔM = Δs/(ds/dM) from the exact tangent,
    then from the secant on s = ln δ.  |Δs| ≤ min(DS_MAX, 1.6λ), halved on failure.  Stops when
    the ordinary residual at V_target of the current state is ≤ tol/4 (then the caller's fixed-V
    polish takes no step) or when the secant cannot move M any more (round-off floor of the
    plateau length)."""
    V_target, v_sk = spec.V, spec.v_sk
    sgn = 1.0 if V_target > v_sk else -1.0
    fam = PlateauFamily(spec.law, spec.w_plus, v_sk, sgn, N, m, K)
    n = np.arange(N) - N // 2
    s = fam.s(V0)
    M = float(x0[0::2].sum() - N * fam.w_B(V0))
    o = bordered_newton(fam, x0, s, M, tol, deadline=deadline)
    if not o.converged:
        return PlateauPath(None, V0, False, "plateau route: start wave lost", (), abs(V0 - v_sk))
    x, s = o.x, o.s
    pts = [(math.exp(s), M, front_position(x[0::2], n, fam.w_B(fam.V(s))))]
    s_t = fam.s(V_target)
    S_t = fam.system(V_target)
    lam = wt.decay_rate(spec.law, x[N], V0)
    ds_max = min(DS_MAX, 1.6 * lam)  # front step |Δ| = |Δs|/(2λ) ≤ 0.8 site
    ds_cap = ds_max
    prev, steps, floor = None, 0, ""
    best, extra = None, 0  # (residual at V_target, x, s): secant steps continue to the floor
    while steps < max_steps and work_clock() < deadline:
        res_t = float(np.max(np.abs(S_t.residual(x)[0])))
        if best is None or res_t < best[0]:
            best = (res_t, x, s)
        if best[0] <= 0.25 * tol:
            extra += 1
            if best[0] <= 1e-2 * tol or extra > 3:
                note = f"mass continuation: {steps} steps from |V-V_SK|={pts[0][0]:.2g}"
                return PlateauPath(best[1], fam.V(best[2]), True, note, tuple(pts), pts[0][0])
        tg = mass_tangent(fam, x, s)
        if tg is None:
            break
        dsdM = tg[1]
        if prev is not None and abs(s - prev[0]) > 1e-9:  # secant slope between exact points
            sec = (s - prev[0]) / (M - prev[1])
            if abs(s - prev[0]) >= SECANT_SPAN and not abs(sec / dsdM - 1.0) <= SECANT_AGREE:
                floor = unresolved_note(math.exp(s), sec, dsdM)
                break  # ln δ no longer follows M: the round-off floor of the plateau length
            dsdM = sec  # (a short secant at the target is noisy; FRONT_STEP bounds its step)
        ds = max(-ds_cap, min(ds_cap, s_t - s))
        dM = ds / dsdM
        if abs(dM) < 1e-13 * max(1.0, abs(M)):
            break  # the secant cannot move M further: round-off floor reached
        A_signed = x[N] - fam.w_B(fam.V(s))  # w(n = 0) − w_B: the plateau height
        shift = dM / (2.0 * A_signed)  # sites each front moves
        if abs(shift) > FRONT_STEP:  # translate_fronts moves by less than one site
            dM *= FRONT_STEP / abs(shift)
            ds, shift = dM * dsdM, math.copysign(FRONT_STEP, shift)
        pred = translate_fronts(fam.system(fam.V(s)), x, shift)
        o = bordered_newton(fam, pred, s + ds, M + dM, tol, max_iter=12, deadline=deadline)
        steps += 1
        if o.converged:
            prev = (s, M)
            x, s, M = o.x, o.s, M + dM
            pts.append((math.exp(s), M, front_position(x[0::2], n, fam.w_B(fam.V(s)))))
            ds_cap = min(ds_max, 1.5 * ds_cap)
        else:
            ds_cap *= 0.5
            if ds_cap < 1e-3:
                break
    if best is not None and best[0] <= 0.25 * tol:
        note = f"mass continuation: {steps} steps from |V-V_SK|={pts[0][0]:.2g}"
        return PlateauPath(best[1], fam.V(best[2]), True, note, tuple(pts), pts[0][0])
    V = fam.V(s)
    done = abs(s - s_t) < 1e-2
    note = f"mass continuation {'reached' if done else 'stopped at'} |V-V_SK|={abs(V - v_sk):.3g}"
    return PlateauPath(x, V, done, note + f" in {steps} steps{floor}", tuple(pts), pts[0][0])


def unresolved_note(delta: float, secant: float, tangent: float) -> str:
    """Why the mass continuation stopped short of V: below some |V − V_SK| the velocity no longer
    follows the plateau mass in double precision (∂F/∂ln δ ∝ δ sinks to the residual's
    round-off), seen as the secant of ln δ against M leaving the exact tangent."""
    return (
        f"; the plateau length is not resolved in double precision below |V-V_SK| = "
        f"{delta:.2g} (d ln|V-V_SK| / d mass: secant {secant:.3g}, tangent {tangent:.3g})"
    )


# =============================================================================== error bar
@dataclass(frozen=True)
class FrontUncertainty:
    """Front-position error bar from round-off along the near-null direction (sites).

    sigma_min : smallest singular value of the fixed-V Jacobian (inverse iteration, banded LU);
    residual_2 : ‖F‖₂ at the solution (round-off floor); sites : residual_2/σ_min converted to
    front displacement (|Σ_n v_w,n| / (2A) sites per unit step along the singular vector v);
    sites_at_tol : the same at the acceptance level tol_abs (what any accepted solution may be
    off by); amplitude : A = |w_plateau − w_B|."""

    sigma_min: float
    residual_2: float
    sites: float
    sites_at_tol: float
    sites_per_unit: float


def front_uncertainty(S: WaveSystem, x: np.ndarray, tol_abs: float, iters: int = 4):
    ab, kl, ku, _, F, _ = S.jacobian_banded(x)
    lu, piv, info = lapack.dgbtrf(ab, kl, ku)
    if info != 0:
        return None
    N = S.N
    v = np.zeros(2 * N)
    v[0::2] = 1.0  # the plateau mode changes the mass: start with the mass direction
    for _ in range(iters):
        u, _ = lapack.dgbtrs(lu, kl, ku, v.reshape(-1, 1), piv, trans=1)
        v, _ = lapack.dgbtrs(lu, kl, ku, u, piv)
        v = v[:, 0] / np.linalg.norm(v)
    sig = float(np.linalg.norm(band_matvec(ab, kl, ku, v)))
    w = x[0::2]
    A = abs(w[N // 2] - S.w_left)
    per = abs(v[0::2].sum()) / (2.0 * A)
    r2 = float(np.linalg.norm(F))
    return FrontUncertainty(sig, r2, r2 / sig * per, tol_abs / sig * per, per)
