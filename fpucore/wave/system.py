"""The fixed-point system of paper §5 (eqs. period, nonlin_map, nonlin_system, fixedBCs) and its
damped Newton solver.

Unknowns x = {w_n(0), ẇ_n(0)}, n = −N/2 … N/2−1 (array index i = n + N/2).  With Φ_T the
one-period map of :mod:`fpucore.wave.period_map` (fixed boundary strains w_{−N/2−1} = w_left,
w_{N/2} = w_right) the 2N equations are

    w_{n+1}(T) − w_n(0) = 0        n = −N/2 … N/2−1   (for n = N/2−1: w_{N/2}(T) = w_right)
    ẇ_{n+1}(T) − ẇ_n(0) = 0        n = −N/2 … N/2−2
    pinning:  w_1(T) = w*  (superkink)   or   ẇ_1(T) = 0  (solitary wave)

and the dropped equation ẇ_{N/2}(T) − ẇ_{N/2−1}(0) = −ẇ_{N/2−1}(0) is checked afterwards.

Ordering.  Unknowns are interleaved per site, (w_0, ẇ_0, w_1, ẇ_1, …), and each equation is
placed next to the site it is centred on (the pinning row next to site 1), so the Jacobian is
banded with half-bandwidths ≈ 2K+3, K the spread of a perturbation in one period (~10–20 sites).
It is factorised with LAPACK's banded LU (dgbtrf/dgbtrs): O(N K²), no dense 2N × 2N work.

Jacobians.  ``"exact"``: tangent columns of the RK map from :func:`period_map.tangent_columns`
(derivative of the discrete map to round-off).  ``"fd"``: the paper's route — forward finite
differences of the map, one column per unknown (2N extra period integrations) — kept as an
option for comparison; it is assembled densely and solved with dense LU, as in the paper.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from scipy.linalg import lapack, lu_factor, lu_solve

from fpucore.budget import work_clock
from fpucore.law import interval_note
from fpucore.tableaux.rk import DOP853, Tableau
from fpucore.wave import period_map as pm

if TYPE_CHECKING:
    from fpucore.law.base import HardeningSofteningLaw

_PLANS: dict = {}  # assembly plans by (N, K, pin): pure index arrays, shared across solves


@dataclass
class WaveSystem:
    """The 2N equations of eq. nonlin_system for one (law, V, N, boundary strains, pinning).

    pin : "w" (w_1(T) = pin_value, superkink) or "wd" (ẇ_1(T) = 0, solitary wave).
    m : RK steps per period; K : tangent window half-width (sites).
    """

    law: HardeningSofteningLaw
    V: float
    N: int
    w_left: float
    w_right: float
    pin: str
    pin_value: float
    m: int
    K: int = 24
    tableau: Tableau = DOP853
    # row positions (filled in __post_init__)
    row_w: np.ndarray = field(init=False, repr=False)
    row_wd: np.ndarray = field(init=False, repr=False)
    row_pin: int = field(init=False, repr=False)
    i_pin: int = field(init=False, repr=False)

    def __post_init__(self):
        N = self.N
        self.i_pin = N // 2 + 1  # site n = 1
        slot = self.i_pin - 1
        i = np.arange(N)
        self.row_w = 2 * i + (i >= slot)
        self.row_wd = (2 * i + 1 + (i >= slot))[: N - 1]
        self.row_pin = 2 * slot

    @property
    def T(self) -> float:
        return 1.0 / self.V

    # ------------------------------------------------------------------ residual
    def integrate(self, x: np.ndarray, store_df=False, m=None) -> pm.PeriodResult:
        return pm.integrate(
            self.law,
            x[0::2],
            x[1::2],
            self.T,
            m or self.m,
            self.w_left,
            self.w_right,
            store_df=store_df,
            tableau=self.tableau,
        )

    def residual_from(self, x: np.ndarray, r: pm.PeriodResult) -> tuple[np.ndarray, float]:
        """(F, dropped): F (2N,) in row order, dropped = the omitted equation's residual."""
        N = self.N
        w, wd = x[0::2], x[1::2]
        F = np.empty(2 * N)
        F[self.row_w[: N - 1]] = r.w[1:] - w[:-1]
        F[self.row_w[N - 1]] = self.w_right - w[N - 1]
        F[self.row_wd] = r.wd[1:] - wd[:-1]
        F[self.row_pin] = (
            (r.w[self.i_pin] - self.pin_value) if self.pin == "w" else r.wd[self.i_pin]
        )
        return F, float(-wd[N - 1])

    def residual(self, x: np.ndarray, m=None) -> tuple[np.ndarray, float]:
        return self.residual_from(x, self.integrate(x, m=m))

    def roundoff_rows(self, x: np.ndarray) -> np.ndarray:
        """(2N,) round-off level of each equation of F at x, in row order (absolute): the period
        map's level (:func:`period_map.roundoff_level`) on the w rows, and on the ẇ rows (and the
        pinning row of a solitary wave)."""
        lw, lwd = pm.roundoff_level(self.law, x[0::2], x[1::2], self.T, self.m)
        rows = np.full(2 * self.N, lw)
        rows[self.row_wd] = lwd
        if self.pin == "wd":
            rows[self.row_pin] = lwd
        return rows

    def residual_floor(self, x: np.ndarray) -> float:
        """Max-norm round-off level of F at x: no residual below it can be asked for."""
        return float(np.max(self.roundoff_rows(x)))

    def correction_norm(self, dx: np.ndarray) -> float:
        """Size of a change of x in strain units: max(|δw|, T|δẇ|) (ẇ·T is a strain per period)."""
        return float(max(np.max(np.abs(dx[0::2])), self.T * np.max(np.abs(dx[1::2]))))

    # ------------------------------------------------------------------ exact banded Jacobian
    def _assembly_plan(self):
        """Index arrays (computed once per system) that scatter tangent windows into band
        storage: every (row, column) pair from the tangent part is distinct, and so is every
        pair of the −I part, so two plain fancy assignments replace a slow np.add.at."""
        key = (self.N, self.K, self.pin)
        if key in _PLANS:
            return _PLANS[key]
        N, K = self.N, self.K
        W = 2 * min(K, N) + 1
        c = np.arange(2 * N)
        site_c = c % N
        ucol = 2 * site_c + (c >= N)  # interleaved unknown index of each tangent column
        sites = site_c[:, None] - min(K, N) + np.arange(W)[None, :]  # (2N, W)
        rows, cols, src = [], [], []
        ci, ki = np.nonzero((sites >= 1) & (sites <= N - 1))  # W[site] enters equation site−1
        s1 = sites[ci, ki] - 1
        rows += [self.row_w[s1], self.row_wd[s1]]
        cols += [ucol[ci], ucol[ci]]
        src += [
            np.ravel_multi_index((ci, 0, ki), (2 * N, 2, W)),
            np.ravel_multi_index((ci, 1, ki), (2 * N, 2, W)),
        ]
        ci, ki = np.nonzero(sites == self.i_pin)
        rows.append(np.full(ci.size, self.row_pin))
        cols.append(ucol[ci])
        src.append(np.ravel_multi_index((ci, 0 if self.pin == "w" else 1, ki), (2 * N, 2, W)))
        rows, cols, src = np.concatenate(rows), np.concatenate(cols), np.concatenate(src)
        i = np.arange(N)
        id_rows = np.concatenate([self.row_w, self.row_wd])
        id_cols = np.concatenate([2 * i, 2 * i[: N - 1] + 1])
        kl = int(max((rows - cols).max(), (id_rows - id_cols).max(), 0))
        ku = int(max((cols - rows).max(), (id_cols - id_rows).max(), 0))
        shape = (2 * kl + ku + 1, 2 * N)
        dst = np.ravel_multi_index((kl + ku + rows - cols, cols), shape)
        id_dst = np.ravel_multi_index((kl + ku + id_rows - id_cols, id_cols), shape)
        if len(_PLANS) > 16:
            _PLANS.clear()
        _PLANS[key] = (shape, kl, ku, dst, src, id_dst)
        return _PLANS[key]

    def jacobian_banded(self, x: np.ndarray):
        """Exact Jacobian in LAPACK band storage.  Returns (ab, kl, ku, truncation, F, dropped):
        truncation = largest |δ| on a tangent-window edge (the neglected part is below it)."""
        shape, kl, ku, dst, src, id_dst = self._assembly_plan()
        r = self.integrate(x, store_df=True)
        F, dropped = self.residual_from(x, r)
        out, edge = pm.tangent_columns(r, np.arange(2 * self.N), self.K)
        ab = np.zeros(shape)
        flat = ab.reshape(-1)
        flat[dst] = out.reshape(-1)[src]
        flat[id_dst] -= 1.0
        return ab, kl, ku, float(edge.max(initial=0.0)), F, dropped

    def dense_from_banded(self, ab, kl, ku) -> np.ndarray:
        n = ab.shape[1]
        J = np.zeros((n, n))
        for j in range(n):
            i0, i1 = max(0, j - ku), min(n, j + kl + 1)
            J[i0:i1, j] = ab[kl + ku + np.arange(i0, i1) - j, j]
        return J

    # ------------------------------------------------------------------ FD Jacobian (paper)
    def jacobian_fd(self, x: np.ndarray, F0: np.ndarray | None = None) -> np.ndarray:
        """Dense forward-difference Jacobian, h_j = √ε · max(1, |x_j|) (the paper's route)."""
        if F0 is None:
            F0, _ = self.residual(x)
        n = x.size
        J = np.empty((n, n))
        for j in range(n):
            h = math.sqrt(np.finfo(float).eps) * max(1.0, abs(x[j]))
            xp = x.copy()
            xp[j] += h
            J[:, j] = (self.residual(xp)[0] - F0) / (xp[j] - x[j])
        return J


@dataclass(frozen=True)
class NewtonOutcome:
    """Result of :func:`newton`.  x : (2N,) interleaved solution (last iterate if not converged)."""

    x: np.ndarray
    converged: bool
    residual: float
    dropped_residual: float
    iterations: int
    residual_history: tuple
    jacobians: int
    jacobian_truncation: float
    message: str
    elapsed_s: float
    correction: float = math.nan  # size of the next Newton correction at x (correction_norm)
    factorization: tuple | None = field(default=None, repr=False)  # for solve_with


def solve_with(fact: tuple, b: np.ndarray, trans: int = 0) -> np.ndarray:
    """J⁻¹b (trans=0) or J⁻ᵀb (trans=1) with a factorization kept by :func:`newton`:
    ("band", (lu, ipiv, kl, ku)) from LAPACK dgbtrf or ("dense", scipy lu_factor output)."""
    kind, f = fact
    if kind == "band":
        lu, ipiv, kl, ku = f
        x, _ = lapack.dgbtrs(lu, kl, ku, np.asarray(b, float).reshape(-1, 1), ipiv, trans=trans)
        return x[:, 0]
    return lu_solve(f, b, trans=trans, check_finite=False)


def newton(
    sys: WaveSystem,
    x0: np.ndarray,
    tol: float = 1e-12,
    max_iter: int = 40,
    jacobian: str = "exact",
    time_budget_s: float = 120.0,
    chord_ratio: float = 0.25,
    step_tol: float | None = None,
) -> NewtonOutcome:
    """Damped Newton for F(x) = 0 (eq. nonlin_system).

    Stopping rule.  Converged means max-norm residual ≤ ``tol``.  With ``step_tol`` set (the
    solver's default) Newton does not stop there: it computes the next correction δ = −J⁻¹F
    (with the current factorisation, no new Jacobian) and keeps stepping until
    ``sys.correction_norm(δ)`` ≤ step_tol or the corrections stop shrinking (by half per step:
    the round-off floor, where ‖δ‖ ≈ ‖J⁻¹‖·round-off).  A small residual is not a small error
    when J is ill-conditioned (near-sonic waves: ‖J⁻¹‖ ∝ 1/λ²); the correction measures the error
    through the conditioning.  The last correction and the factorisation are returned
    (``correction``, ``factorization``) for the a-posteriori bounds of :mod:`.bounds`.
    With ``step_tol=None`` Newton stops on the residual alone (continuation predictors).

    The Jacobian is refreshed every iteration unless the previous step contracted the residual
    by at least ``chord_ratio`` (then the factorisation is reused: a chord step costs one period
    integration instead of 2N tangent columns).  Steps are damped by backtracking (λ = 1, ½, …)
    until the residual decreases.  Budgets: ``max_iter`` iterations, ``time_budget_s`` seconds.
    """
    t0, w0 = time.perf_counter(), work_clock()
    x = np.array(x0, dtype=float)
    F, dropped = sys.residual(x)
    res = float(np.max(np.abs(F)))
    hist = [res]
    fact = None
    njac, trunc, it = 0, 0.0, 0
    reuse = False
    msg = ""
    corr, prev_corr = math.nan, math.inf
    if not math.isfinite(res):
        return NewtonOutcome(
            x,
            False,
            res,
            abs(dropped),
            0,
            tuple(hist),
            0,
            0.0,
            "initial guess gives a non-finite residual" + interval_note(sys.law),
            0.0,
        )
    while res > tol or step_tol is not None:
        done = res <= tol  # only refining the correction from here on
        if not done and it >= max_iter:
            msg = (
                f"no convergence in {max_iter} Newton iterations (residual {res:.3g}); "
                "try continuation in V from a nearby converged wave or a smaller N"
            )
            break
        if not done and work_clock() - w0 > time_budget_s:  # CPU s: load-independent
            msg = (
                f"time budget {time_budget_s:g} s exhausted after {it} iterations "
                f"(residual {res:.3g}); try a smaller N"
            )
            break
        if not done:
            it += 1
        if fact is None or not (reuse or done):
            if jacobian == "exact":
                ab, kl, ku, tr, F, dropped = sys.jacobian_banded(x)
                trunc = max(trunc, tr)
                lu, ipiv, info = lapack.dgbtrf(ab, kl, ku)
                fact = ("band", (lu, ipiv, kl, ku))
            else:
                J = sys.jacobian_fd(x, F)
                fact = ("dense", lu_factor(J, check_finite=False))
                info = 0
            njac += 1
            if info != 0:
                fact = None
                msg = "singular Jacobian (LU pivot zero); the pinning may not select a wave here"
                break
        dx = solve_with(fact, -F)
        if not np.all(np.isfinite(dx)):
            msg = "non-finite Newton step (ill-conditioned Jacobian)" + interval_note(sys.law)
            break
        if done:
            corr = sys.correction_norm(dx)
            stalled = corr > 0.5 * prev_corr  # round-off: corrections no longer shrink
            if corr <= step_tol or stalled or it >= max_iter:  # type: ignore[operator]
                break
            prev_corr = corr
            xt = x + dx
            Ft, dt = sys.residual(xt)
            rt = float(np.max(np.abs(Ft)))
            if not (math.isfinite(rt) and rt <= tol):
                break  # keep the accepted iterate; corr is its correction
            it += 1
            x, F, dropped, res = xt, Ft, dt, rt
            hist.append(res)
            continue
        lam, accepted = 1.0, False
        while lam >= 1.0 / 64:
            xt = x + lam * dx
            Ft, dt = sys.residual(xt)
            rt = float(np.max(np.abs(Ft)))
            if math.isfinite(rt) and rt < (1.0 - 0.1 * lam) * res:
                accepted = True
                break
            lam *= 0.5
        if not accepted:
            if reuse:  # a stale factorisation: retry the iteration with a fresh Jacobian
                reuse = False
                continue
            if res < 1e3 * tol:  # stagnation at round-off level just above tol
                msg = f"stagnated at residual {res:.3g} (round-off floor above tol={tol:g})"
            else:
                msg = (
                    f"damped Newton step failed to reduce the residual ({res:.3g}); "
                    "the initial guess is too far: use continuation in V"
                )
            break
        reuse = jacobian == "exact" and lam == 1.0 and rt < chord_ratio * res
        x, F, dropped, res = xt, Ft, dt, rt
        hist.append(res)
    converged = res <= tol
    if converged:
        msg = f"converged: residual {res:.3g} <= tol {tol:g} in {it} iterations"
    return NewtonOutcome(
        x,
        converged,
        res,
        abs(dropped),
        it,
        tuple(hist),
        njac,
        trunc,
        msg,
        time.perf_counter() - t0,
        corr,
        fact,
    )
