"""Floquet spectrum of discrete traveling waves (paper §6, eqs. linear, linear_map).

A traveling wave ŵ_n(t) = w(n − Vt) is periodic modulo shift, ŵ_{n+1}(t + T) = ŵ_n(t) with
T = 1/V (eq. period).  Perturbations y_n obey the linearized chain (eq. linear)

    ÿ_n = f′(ŵ_{n+1}) y_{n+1} − 2 f′(ŵ_n) y_n + f′(ŵ_{n−1}) y_{n−1},   n = −N/2 … N/2−1,

with the paper's periodic boundary conditions y_{N/2} = y_{−N/2}, y_{−N/2−1} = y_{N/2−1}.
The monodromy matrix 𝓜 (eq. linear_map) is the fundamental matrix Ψ(T) of the first-order
system in (y, ẏ) with the rows of each N-block shifted up by one (last row ← first), so that
𝓜 maps {y_n(0), ẏ_n(0)} onto {y_{n+1}(T), ẏ_{n+1}(T)}.  Its 2N eigenvalues are the Floquet
multipliers μ; |μ| > 1 is instability.

Structure used here (all exact for the ring, whatever the base state):

* Σ_n ẏ_n is conserved and Σ_n y_n grows linearly, so the two linear functionals "sum of y" and
  "sum of ẏ" span a left-invariant subspace of 𝓜 with the action [[1, T], [0, 1]]: a Jordan
  block at μ = 1.  Round-off splits such a block by √ε ≈ 1e-8, the paper's "O(1e-8)" excess.
  We deflate it *exactly* with a Householder reflection that maps the constant vector onto the
  last coordinate of each block; 𝓜 becomes block-triangular, the 2×2 quotient block carries
  the two conservation multipliers and the (2N−2)-block carries the rest.  Any remaining
  multipliers in a small disc around 1 are reported as the trivial cluster, and max |μ| is
  reported with and without it.  For a superkink translation changes the total strain
  (Σ ẇ_n ≠ 0), so the translation mode *is* the conservation block and nothing is left at 1
  (measured split < 1e-15); a solitary wave keeps a translation/velocity pair in the rest
  (measured split 1e-9 … 4e-7, √ of the wave's residual).
* On the zero-sum subspace the flow is Hamiltonian (ẏ = v, v̇ = ΔF y = J∇H with
  J = [[0, −Δ], [Δ, 0]], H = ½ yᵀFy + ½ vᵀ(−Δ)⁻¹v), and the shift commutes with Δ, so the
  multipliers come in quartets (μ, μ̄, 1/μ, 1/μ̄).  The integrator is not symplectic; its
  violation of the quartet symmetry is measured and is the error bar of |μ|.

The fundamental matrix comes from the tangent kernel of :mod:`fpucore.period_map` (fixed-step
8th-order RK along the stored base trajectory, columns on local windows with periodic wrap).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from numba import njit

from .errors import ParameterError, require_finite
from .floquet_checks import (  # noqa: F401  (part of this module's API)
    HomogeneousState,
    homogeneous_multipliers,
    phonon_gap,
    quartet_symmetry_error,
)

# --------------------------------------------------------------------------- Numba kernels


@njit(cache=True, nogil=True)
def shift_rows(psi: np.ndarray, n: int, out: np.ndarray) -> None:
    """𝓜 from Ψ(T) (eq. linear_map): in each N-block of rows, row i ← row i+1, last ← first.

    psi, out : (2N, 2N) float64, rows/columns ordered [y_{−N/2} … y_{N/2−1}, ẏ_{−N/2} … ].
    """
    m = psi.shape[1]
    for blk in range(2):
        o = blk * n
        for i in range(n):
            src = o + (i + 1 if i + 1 < n else 0)
            for j in range(m):
                out[o + i, j] = psi[src, j]


@njit(cache=True, nogil=True)
def deflate_sums(a: np.ndarray, n: int, u: np.ndarray, beta: float) -> None:
    """In place a ← P a P with P = diag(H, H), H = I − β u uᵀ (Householder, symmetric, H² = I).

    H maps the normalised constant vector of an N-block onto that block's last coordinate, so
    after the transform index N−1 carries Σ y_n/√N and index 2N−1 carries Σ ẏ_n/√N.
    a : (2N, 2N) float64;  u : (N,) float64;  β = 2 / uᵀu.
    """
    m = 2 * n
    tmp = np.empty(m)
    # left: each row block B ← H B  (B − β u (uᵀ B))
    for blk in range(2):
        o = blk * n
        for j in range(m):
            tmp[j] = 0.0
        for i in range(n):
            ui = u[i]
            if ui != 0.0:
                for j in range(m):
                    tmp[j] += ui * a[o + i, j]
        for i in range(n):
            c = beta * u[i]
            if c != 0.0:
                for j in range(m):
                    a[o + i, j] -= c * tmp[j]
    # right: each column block C ← C H  (C − β (C u) uᵀ)
    for blk in range(2):
        o = blk * n
        for i in range(m):
            s = 0.0
            for j in range(n):
                s += a[i, o + j] * u[j]
            s *= beta
            for j in range(n):
                a[i, o + j] -= s * u[j]


@njit(cache=True, nogil=True)
def scatter_shifted(out: np.ndarray, cols: np.ndarray, n: int, k_half: int, mat: np.ndarray):
    """Place tangent window columns into 𝓜 with the index shift of eq. linear_map.

    out : (nc, 2, W) window columns from period_map.tangent_columns (periodic=True), window row k
    is site (c mod N) − K + k (mod N).  Ψ row s lands in 𝓜 row s − 1 (mod N) of its block, which
    is "rows up by one, last row replaced by the first".  mat : (2N, 2N), zero outside windows.
    """
    nc, _, w = out.shape
    for ci in range(nc):
        c = cols[ci]
        s0 = c % n - k_half
        for k in range(w):
            r = (s0 + k - 1) % n
            mat[r, c] = out[ci, 0, k]
            mat[n + r, c] = out[ci, 1, k]


@njit(cache=True, nogil=True)
def extract_deflated(a: np.ndarray, n: int, out: np.ndarray) -> float:
    """Copy the (2N−2) block of the deflated 𝓜 without rows/cols N−1, 2N−1 into out (F-order
    is fine) and return the largest |entry| of the two sum rows outside the 2×2 quotient block
    (exactly 0 for the ring: the conservation defect of the integration)."""
    m = 2 * n
    defect = 0.0
    for j in range(m):
        if j != n - 1 and j != m - 1:
            defect = max(defect, abs(a[n - 1, j]), abs(a[m - 1, j]))
    ii = 0
    for i in range(m):
        if i == n - 1 or i == m - 1:
            continue
        jj = 0
        for j in range(m):
            if j == n - 1 or j == m - 1:
                continue
            out[ii, jj] = a[i, j]
            jj += 1
        ii += 1
    return defect


# --------------------------------------------------------------------------- monodromy
_HW_DEFAULT = 0.12  # h·ω_max of the tangent integration (DOP853): quartets to ~1e-13, see bench
_SPREAD_LEVEL = 1e-18  # window half-width: neglected part of every column below this
MAX_N = 2500  # 5000² dense eig: minutes, 400 MB


@dataclass(frozen=True)
class Monodromy:
    """Shifted monodromy matrix 𝓜 (eq. linear_map) of one base state.

    matrix : (2N, 2N) float64, ordering [y_{−N/2} … y_{N/2−1}, ẏ_{−N/2} … ẏ_{N/2−1}].
    T = 1/V, m : RK steps per period, K : window half-width (sites) of the tangent columns,
    truncation : largest |δ| on a window edge (neglected part of a column), elapsed_s : wall time.
    """

    matrix: np.ndarray
    N: int
    T: float
    m: int
    K: int
    truncation: float
    elapsed_s: float


def _base_state(r):
    """(law, w, wd, V, N, w_left, w_right) from a wave result (duck-typed, see module doc)."""
    try:
        law, V = r.law, float(r.V)
        w = np.ascontiguousarray(r.w, dtype=np.float64)
        wd = np.ascontiguousarray(r.wdot, dtype=np.float64)
        wl, wr = float(r.w_left), float(r.w_right)
    except AttributeError as exc:
        raise ParameterError(
            "r", type(r).__name__, "a wave result with law, V, w, wdot, w_left, w_right",
            str(exc),
        ) from None  # fmt: skip
    N = w.size
    if N > MAX_N:
        raise ParameterError("N", N, f"N <= {MAX_N}",
                             "the dense eigenvalue call costs O(N^3) time")  # fmt: skip
    if not (V > 0 and math.isfinite(V)):
        raise ParameterError("V", V, "V > 0")
    if N < 4 or N % 2 or wd.shape != w.shape:
        raise ParameterError("N", N, "an even number >= 4 with w, wdot of equal length")
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(wd))):
        raise ParameterError("r.w/r.wdot", "non-finite entries", "finite arrays")
    return law, w, wd, V, N, wl, wr


def default_steps(law, V: float) -> int:
    """RK steps per period with h·ω_max ≤ 0.12 for ω_max = 2 c_max (the top linear frequency)."""
    from . import period_map as pm

    return pm.rk_steps_for(V, law.c_max, hw=_HW_DEFAULT)


def monodromy(r, m: int | None = None) -> Monodromy:
    """𝓜 of eq. linear_map for the base state r (wave result or :class:`HomogeneousState`).

    The base trajectory is re-integrated from (r.w, r.wdot) with the fixed boundary strains of
    eq. fixedBCs (DOP853, m steps, f′ stored at every stage); the perturbation columns use the
    paper's periodic BCs (index wrap) on windows of ±K sites, K chosen so that the neglected part
    of each column is below 1e-18; then rows are shifted.  Cost O(N·K·m), all in Numba.
    """
    from . import period_map as pm

    t0 = time.perf_counter()
    law, w, wd, V, N, wl, wr = _base_state(r)
    if m is None:
        m = default_steps(law, V)
    res = pm.integrate(law, w, wd, 1.0 / V, int(m), wl, wr, periodic=False, store_df=True)
    K = pm.spread_radius(res, level=_SPREAD_LEVEL) + 1
    K = min(K, N // 2)
    cols = np.arange(2 * N, dtype=np.int64)
    out, edge = pm.tangent_columns(res, cols, K, periodic=True)
    k_eff = N // 2 if out.shape[2] == N else K
    mat = np.zeros((2 * N, 2 * N))
    scatter_shifted(out, cols, N, k_eff, mat)
    return Monodromy(
        mat, N, 1.0 / V, int(m), int(k_eff), float(edge.max(initial=0.0)),
        time.perf_counter() - t0,
    )  # fmt: skip


def _householder(n: int) -> tuple[np.ndarray, float]:
    """u, β of H = I − β u uᵀ with H 1/√N = e_{N−1}."""
    u = np.full(n, 1.0 / math.sqrt(n))
    u[-1] -= 1.0
    return u, 2.0 / float(u @ u)


def multipliers_of(mat: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, float]:
    """All 2N eigenvalues of 𝓜 with the conservation block deflated exactly.

    Returns (mu_rest (2N−2,), mu_sums (2,), conservation_defect).  mu_sums are the diagonal of
    the 2×2 quotient block [[1, T], [0, 1]] (Σy, Σẏ); mu_rest come from one dense LAPACK dgeev
    call on the (2N−2)-block.  conservation_defect is the largest coupling of the sum rows to the
    rest (exactly 0 for an exact ring integration; round-off level here).
    """
    a = np.array(mat, dtype=np.float64, order="C", copy=True)
    u, beta = _householder(n)
    deflate_sums(a, n, u, beta)
    b = np.empty((2 * n - 2, 2 * n - 2), order="F")
    defect = extract_deflated(a, n, b)
    mu_rest = scipy.linalg.eigvals(b, overwrite_a=True, check_finite=False)
    mu_sums = np.array([a[n - 1, n - 1], a[2 * n - 1, 2 * n - 1]], dtype=complex)
    return mu_rest, mu_sums, float(defect)


# --------------------------------------------------------------------------- spectrum
@dataclass(frozen=True)
class FloquetResult:
    """Floquet spectrum of one traveling wave (paper §6).

    multipliers : (2N,) complex, all eigenvalues of 𝓜 (the two conservation multipliers first).
    max_modulus : max |μ| over all.  max_modulus_away_from_1 : max |μ| outside the trivial cluster.
    trivial : multipliers of the cluster at μ = 1 (the exact conservation pair + those within
    ``trivial_radius``); n_trivial = len(trivial); trivial_split = max |μ − 1| inside it.
    symmetry_error : max relative mismatch of the quartet symmetry μ ↔ 1/μ̄ (see
    :func:`quartet_symmetry_error`); conjugate_error : the same for μ ↔ μ̄ (0 for real 𝓜).
    integrator_error : ‖𝓜_m − 𝓜_2m‖₂ bound (step doubling of the tangent integration).
    error : max(symmetry_error, integrator_error, round-off floor) — the error bar of |μ|.
    excess : max_modulus_away_from_1 − 1; excess_significant : excess > error.
    unstable : multipliers (away from 1) with |μ| − 1 > error.  verdict : "unstable" |
    "stable within error".  monodromy_s / check_s / eig_s / elapsed_s : wall times (s).
    """

    multipliers: np.ndarray
    max_modulus: float
    max_modulus_away_from_1: float
    trivial: np.ndarray
    n_trivial: int
    trivial_radius: float
    trivial_split: float
    symmetry_error: float
    conjugate_error: float
    integrator_error: float
    conservation_defect: float
    error: float
    excess: float
    excess_significant: bool
    unstable: np.ndarray
    verdict: str
    phonon_gap: float
    N: int
    V: float
    m: int
    K: int
    monodromy_s: float
    check_s: float
    eig_s: float
    elapsed_s: float
    converged: bool
    message: str
    wave: dict = field(default_factory=dict)

    @property
    def status(self) -> str:
        return "ok" if self.converged else "warning"

    @property
    def n_unstable(self) -> int:
        return int(self.unstable.size)

    def quartets(self) -> list[np.ndarray]:
        """The instability modes as quartets (μ, μ̄, 1/μ, 1/μ̄) — real pairs (μ, 1/μ) for real μ —
        one per unstable μ with Im μ ≥ 0, partners taken as the nearest multipliers."""
        mu_all = self.multipliers
        groups = []
        for mu in self.unstable:
            if mu.imag < 0:
                continue
            real = abs(mu.imag) <= 1e-12 * abs(mu)
            want = [1 / mu] if real else [np.conj(mu), 1 / np.conj(mu), 1 / mu]
            g = [mu] + [mu_all[int(np.argmin(np.abs(mu_all - x)))] for x in want]
            groups.append(np.array(g))
        return groups

    def as_dict(self) -> dict:
        """JSON-ready summary (the CLI's --json object)."""
        mu = self.multipliers
        return {
            "max_modulus": self.max_modulus,
            "max_modulus_away_from_1": self.max_modulus_away_from_1,
            "excess": self.excess,
            "excess_significant": self.excess_significant,
            "verdict": self.verdict,
            "symmetry_error": self.symmetry_error,
            "conjugate_error": self.conjugate_error,
            "integrator_error": self.integrator_error,
            "conservation_defect": self.conservation_defect,
            "error": self.error,
            "n_trivial": self.n_trivial,
            "trivial_radius": self.trivial_radius,
            "trivial_split": self.trivial_split,
            "trivial_re": self.trivial.real,
            "trivial_im": self.trivial.imag,
            "n_unstable": self.n_unstable,
            "unstable_re": self.unstable.real,
            "unstable_im": self.unstable.imag,
            "phonon_gap": self.phonon_gap,
            "N": self.N,
            "V": self.V,
            "m": self.m,
            "K": self.K,
            "multipliers_re": mu.real,
            "multipliers_im": mu.imag,
            "monodromy_s": self.monodromy_s,
            "check_s": self.check_s,
            "eig_s": self.eig_s,
            "elapsed_s": self.elapsed_s,
            "converged": self.converged,
            "status": self.status,
            "message": self.message,
            "wave": self.wave,
        }


def _wave_summary(r) -> dict:
    keys = ("kind", "V", "N", "w_left", "w_right", "residual", "dropped_residual", "converged",
            "iterations", "amplitude", "energy", "integrator_error", "tail_error", "elapsed_s",
            "message")  # fmt: skip
    out = {k: getattr(r, k) for k in keys if hasattr(r, k)}
    if hasattr(r, "w_plus"):
        out["w_plus"] = r.w_plus
    return out


def _background_states(r, law) -> list[float]:
    """Strains the chain tends to at its ends (where the continuous spectrum lives)."""
    w = np.asarray(r.w)
    return [float(w[0]), float(w[-1])]


def spectrum(
    r,
    m: int | None = None,
    trivial_radius: float | None = None,
    check: bool = True,
) -> FloquetResult:
    """Floquet multipliers of the traveling wave r (from ``wave.solve_superkink/solve_solitary``,
    or a :class:`HomogeneousState`), with their error bars and the trivial cluster at 1.

    m : RK steps per period for the tangent integration (default: max(r.m, h·ω_max ≤ 0.12)).
    trivial_radius : radius of the disc around μ = 1 counted as the trivial (symmetry) cluster;
    default min(phonon_gap/10, max(1e-6, 100 √ε)), ε = max(error bar, wave residual) (a Jordan
    block perturbed by ε splits by ~√ε; typically 1e-4), phonon_gap = distance from 1 of the
    nearest continuous-spectrum multiplier of the end states (:func:`phonon_gap`).
    check : also build 𝓜 with 2m steps and report ‖𝓜_m − 𝓜_2m‖ as integrator_error.
    """
    t0 = time.perf_counter()
    law, w, wd, V, N, wl, wr = _base_state(r)
    if m is None:
        m = max(int(getattr(r, "m", 0) or 0), default_steps(law, V))
    elif not (isinstance(m, (int, np.integer)) and 2 <= m <= 20000):
        raise ParameterError("m", m, "an integer in [2, 20000]", "RK steps per period")
    mono = monodromy(r, int(m))
    check_s, integ = 0.0, math.nan
    if check:
        tc = time.perf_counter()
        mono2 = monodromy(r, 2 * int(m))
        d = np.abs(mono.matrix - mono2.matrix)
        integ = float(math.sqrt(d.sum(axis=0).max() * d.sum(axis=1).max()))  # ≥ ‖δ𝓜‖₂
        check_s = time.perf_counter() - tc
    te = time.perf_counter()
    mu_rest, mu_sums, defect = multipliers_of(mono.matrix, N)
    eig_s = time.perf_counter() - te
    if not np.all(np.isfinite(mu_rest)):
        raise ParameterError("r", "non-finite monodromy", "a bounded base trajectory")
    mu = np.concatenate([mu_sums, mu_rest])
    sym, conj = quartet_symmetry_error(mu)
    norm = float(np.abs(mono.matrix).sum(axis=0).max())
    floor = 64.0 * np.finfo(float).eps * norm
    error = max(sym, integ if math.isfinite(integ) else 0.0, floor)

    gap = min(phonon_gap(law, wb, V, N) for wb in _background_states(r, law))
    # a Jordan block at 1 perturbed by ε splits by ~√ε: ε = the error bar or the wave's residual
    split_scale = math.sqrt(max(error, float(getattr(r, "residual", 0.0) or 0.0)))
    if trivial_radius is None:
        trivial_radius = min(0.1 * gap, max(1e-6, 100.0 * split_scale))
    trivial_radius = require_finite("trivial_radius", trivial_radius)
    if not trivial_radius >= 0:
        raise ParameterError("trivial_radius", trivial_radius, "a radius >= 0")
    near = np.abs(mu_rest - 1.0) < trivial_radius
    trivial = np.concatenate([mu_sums, mu_rest[near]])
    away = mu_rest[~near]
    max_mod = float(np.abs(mu).max())
    max_away = float(np.abs(away).max(initial=0.0))
    excess = max_away - 1.0
    unstable = away[np.abs(away) - 1.0 > error]
    unstable = unstable[np.argsort(-np.abs(unstable))]
    msgs = []
    converged = True
    if not getattr(r, "converged", True):
        converged = False
        msgs.append("the base wave did not converge: its spectrum describes no traveling wave")
    if mono.truncation > 1e-14:
        converged = False
        msgs.append(f"tangent window truncation {mono.truncation:.1e} (increase K)")
    if trivial_radius > 0.5 * gap or gap < 10.0 * split_scale:
        converged = False
        msgs.append(
            f"phonon gap {gap:.1e} (nearest continuous-spectrum multiplier to 1) is not well "
            f"outside the round-off split {split_scale:.0e} of the trivial cluster / its radius "
            f"{trivial_radius:.0e}: cluster and continuous spectrum overlap (increase N or move "
            "V away from the sound speed)"
        )
    if (trivial.size % 2) != 0:
        msgs.append(
            f"odd trivial cluster size {trivial.size}: radius {trivial_radius:.1e} cuts a pair"
        )
    if sym > 1e-6:
        converged = False
        msgs.append(f"quartet symmetry violated by {sym:.1e} (increase m)")
    verdict = "unstable" if unstable.size else "stable within error"
    msgs.insert(
        0,
        f"max|mu|-1 away from 1 = {excess:.3e} {'>' if excess > error else '<='} error "
        f"{error:.1e}: {verdict}",
    )
    return FloquetResult(
        multipliers=mu,
        max_modulus=max_mod,
        max_modulus_away_from_1=max_away,
        trivial=trivial,
        n_trivial=int(trivial.size),
        trivial_radius=trivial_radius,
        trivial_split=float(np.abs(trivial - 1.0).max(initial=0.0)),
        symmetry_error=sym,
        conjugate_error=conj,
        integrator_error=integ,
        conservation_defect=defect,
        error=error,
        excess=excess,
        excess_significant=bool(excess > error),
        unstable=unstable,
        verdict=verdict,
        phonon_gap=gap,
        N=N,
        V=V,
        m=mono.m,
        K=mono.K,
        monodromy_s=mono.elapsed_s,
        check_s=check_s,
        eig_s=eig_s,
        elapsed_s=time.perf_counter() - t0,
        converged=converged,
        message="; ".join(msgs),
        wave=_wave_summary(r),
    )


def sweep(law, kind: str, V_values, w_plus=None, N: int = 500, progress=None, **kw):
    """max |μ| along a wave family; see :func:`fpucore.floquet_sweep.sweep` (cached, progress)."""
    from .floquet_sweep import sweep as _sweep

    return _sweep(law, kind, V_values, w_plus=w_plus, N=N, progress=progress, **kw)
