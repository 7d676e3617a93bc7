"""Structure-preserving half-size Floquet spectrum (``spectrum(r, method="structured")``).

The dense route (:func:`fpucore.floquet.multipliers_of`) calls LAPACK ``dgeev`` on the deflated
(2N−2)² block.  This route uses the symplectic structure of the shifted monodromy 𝓜 instead:

1. Canonical coordinates.  With y = D u, v = D p (D the forward difference on the ring) the
   linearized chain is Hamiltonian in (u, p) with the standard J = [[0, I], [−I, 0]]; the flow
   and the index shift keep the Poisson tensor Π = R J Rᵀ, R = diag(D, D): 𝓜 Π 𝓜ᵀ = Π.  On the
   zero-sum subspace (the one the Householder deflation keeps, dimension 2n, n = N − 1)
   S = R⁺ 𝓜 R is symplectic, S J Sᵀ = J, with the same multipliers as the deflated block.
   R⁺ is a cumulative sum (O(N)); block means are removed from every pseudo-inverse input and
   every Krylov vector (otherwise the constant directions, outside the working space, grow and
   destroy the basis after a few hundred steps).
2. Half size.  W = S − J Sᵀ J (= S + S⁻¹ for symplectic S) is skew-Hamiltonian; its eigenvalues
   λ = μ + 1/μ are double, and every Krylov space of one vector is isotropic.  A full-length
   isotropic Arnoldi process (SHIRA-type: Gram–Schmidt against V and J V, every vector projected
   twice, the second pass delayed by one step so that each step reads the basis twice instead
   of four times, :mod:`fpucore.floquet.arnoldi_kernels`) gives an n×n Hessenberg H with
   W V = V H + J V G; G = 0 in exact arithmetic, ‖G‖ is measured (the backward error of W),
   plus a bound of the round-off-sized terms the delayed pass leaves out.  One LAPACK
   ``dhseqr`` on H (n×n instead of 2n×2n; called directly, :mod:`fpucore.floquet.hessenberg`,
   since H is Hessenberg already).
   𝓜 is periodic-banded (tangent windows of ±K sites), so a product with W costs O(N·K).
3. μ solves μ² − λμ + 1 = 0.  Real λ ∈ [−2, 2] gives μ = e^{±iθ} exactly on the unit circle
   (no round-off quartet splitting), complex λ the quartet.

Error bar.  The quartet symmetry holds by construction, so it no longer measures the error;
instead: η = measured non-symplecticity of S (random probes, ‖x + S J Sᵀ J x‖/‖x‖), the dropped
J-part ‖G‖ and the Hessenberg round-off give a bound δλ = ‖G‖ + (64ε + η)‖H‖ on λ; the bound on
each μ is δλ/max(|μ − 1/μ|, √δλ) (``mu_error``; large only next to μ = ±1).

Reversible waves (every solitary wave, the cubic law's superkinks) take a shorter route first:
:mod:`fpucore.floquet.reversible` (one (N−1)² eigenvalue call, ~0.2× dense at N = 500); this
isotropic Arnoldi process is the route for every other base state.

Prototype and its measured table: research report r17 (max|μ| within 8e-14 of dense eigvals in
20 cases, same unstable counts).  Timings: benchmarks/bench_floquet.py part E (at N = 500 the
Arnoldi process is ~2/3 of the time, bound by memory bandwidth: the 4 MB basis outgrows L2;
``dhseqr`` on H the other third).
"""

from __future__ import annotations

import math
import time

import numpy as np

from fpucore.errors import ParameterError, require_int
from fpucore.floquet.arnoldi_kernels import dcgs2_steps
from fpucore.floquet.hessenberg import hessenberg_eigvals
from fpucore.floquet.monodromy import MAX_N
from fpucore.floquet.reversible import reversible_lambdas
from fpucore.floquet.structured_kernels import (
    extract_bands,
    j_apply,
    remove_means,
    s_apply,
    st_apply,
)
from fpucore.parallel.threads import on_budget

_RESTART_TRIES = 8
# |a_J| above which the delayed pass's J-part is pushed through W (arnoldi_kernels.dcgs2_steps);
# below it, ‖W‖·|a_J| is round-off and is added to the bound instead
_TOL_J = 1e-14


def band_of(mat: np.ndarray, n: int, K: int | None = None) -> tuple[int, np.ndarray]:
    """(d0, bands) of the periodic band of 𝓜's four N×N blocks.  K : tangent window half-width
    of :class:`fpucore.floquet.Monodromy` (the band is rows −K−1 … K−1 around each column after
    the shift); None: found from the non-zero pattern."""
    if K is not None and 2 * K + 1 < n:
        d0, w = -K - 1, 2 * K + 1
    else:
        r, c = np.nonzero(mat)
        d = (r % n - c % n) % n
        d = np.where(d > n // 2, d - n, d)
        d0, w = int(d.min(initial=0)), int(d.max(initial=0) - d.min(initial=0) + 1)
        if w >= n:
            d0, w = -(n // 2), n
    bands = np.empty((4, w, n))
    extract_bands(np.ascontiguousarray(mat, dtype=np.float64), n, d0, bands)
    return d0, bands


def _fresh(V: np.ndarray, k: int, N: int, rng) -> np.ndarray:
    """A unit mean-free vector orthogonal to V[:k] and J V[:k] (restart after a breakdown)."""
    jv = np.empty(2 * N)
    for _ in range(_RESTART_TRIES):
        x = rng.standard_normal(2 * N)
        remove_means(x, N)
        for _pass in range(2):
            if k:
                x -= V[:k].T @ (V[:k] @ x)
                j_apply(x, N, jv)  # J x ;  (J V)ᵀ x = −Vᵀ J x  →  x −= J V (−Vᵀ J x)
                c = V[:k] @ jv
                y = V[:k].T @ c
                x[:N] += y[N:]  # J y = (y_p, −y_u); x += J y
                x[N:] -= y[:N]
            remove_means(x, N)
        nr = float(np.linalg.norm(x))
        if nr > 1e-8:
            return x / nr
    raise RuntimeError("isotropic Arnoldi: no restart direction found")


def mu_from_lambda(lam: np.ndarray) -> np.ndarray:
    """Both roots of μ² − λμ + 1 = 0 per λ, the one with |μ| ≥ 1 first: (2·len(λ),) complex.
    Real λ ∈ [−2, 2]: μ = e^{±iθ}, 2 cos θ = λ, exactly on the unit circle."""
    lam = np.asarray(lam, dtype=complex)
    s = np.sqrt(lam * lam - 4.0)
    a, b = 0.5 * (lam + s), 0.5 * (lam - s)
    big = np.where(np.abs(a) >= np.abs(b), a, b)
    ell = (lam.imag == 0.0) & (np.abs(lam.real) <= 2.0)
    on = np.exp(1j * np.arccos(np.clip(lam.real, -2.0, 2.0) / 2.0))
    big = np.where(ell, on, big)
    small = np.where(ell, np.conj(on), 1.0 / big)
    return np.concatenate([big, small])


def symplectic_defect(bands, d0: int, N: int, probes: int = 4, seed: int = 7) -> float:
    """η = max over random mean-free probes x of ‖x + S J Sᵀ J x‖ / ‖x‖ (0 for symplectic S)."""
    rng = np.random.default_rng(seed)
    t1, t2, a, b = (np.empty(2 * N) for _ in range(4))
    worst = 0.0
    for _ in range(probes):
        x = rng.standard_normal(2 * N)
        remove_means(x, N)
        j_apply(x, N, a)
        st_apply(bands, d0, N, a, b, t1, t2)
        j_apply(b, N, a)
        s_apply(bands, d0, N, a, b, t1, t2)
        worst = max(worst, float(np.linalg.norm(x + b) / np.linalg.norm(x)))
    return worst


def isotropic_arnoldi(bands, d0: int, N: int, rng) -> tuple[np.ndarray, np.ndarray, float, int]:
    """Full-length isotropic Arnoldi on W (module doc): V (N−1, 2N) orthonormal isotropic rows,
    H (N−1, N−1) upper Hessenberg (Fortran order) with W Vᵀ = Vᵀ H + J Vᵀ G, ‖G‖_F plus the
    bound of the J-parts below _TOL_J left out of W products (the dropped part), restarts.

    Gram–Schmidt against V and J V with delayed reorthogonalisation (DCGS2,
    :mod:`fpucore.floquet.arnoldi_kernels`): two sweeps over the basis per step instead of
    CGS2's four; every vector still gets two projections.  A breakdown (an invariant subspace:
    degenerate λ, e.g. a homogeneous ring) restarts with a random vector orthogonal to V and
    J V.  Measured and not used (benchmarks/README.md, part E): CGS2 through BLAS (the previous
    route, 1.3–1.6× slower here), a DGKS "second pass only if needed" test (needed at every step).
    """
    m = N - 1
    V = np.zeros((m, 2 * N))
    HT = np.zeros((m, m))
    GT = np.zeros((m, m))
    C = np.zeros((m, 4))
    u, w, z, wz, t1, t2, t3, t4 = (np.empty(2 * N) for _ in range(8))
    scal = np.zeros(1)
    restarts, k = 0, 0
    u[:] = _fresh(V, 0, N, rng)
    while k < m:
        k = dcgs2_steps(
            bands, d0, N, V, HT, GT, C, u, w, z, wz, t1, t2, t3, t4, k, 1e-10, _TOL_J, scal
        )
        if k < m:  # breakdown: W V[:k] ⊂ span(V, JV) to round-off
            restarts += 1
            u[:] = _fresh(V, k, N, rng)
    H = HT.T
    dropped = float(np.abs(H).max()) * math.sqrt(m) * math.sqrt(scal[0])  # ‖W‖·(Σ|a_J|²/β²)^½
    return V, H, float(np.linalg.norm(GT)) + dropped, restarts


def sums_and_defect(mat: np.ndarray, N: int) -> tuple[np.ndarray, float]:
    """The two conservation multipliers (sum of y, sum of ẏ) and their coupling to the rest: the
    column sums of each N-block of 𝓜 must be constant (defect = largest deviation / √N)."""
    mu_sums = np.array([mat[:N, :N].sum() / N, mat[N:, N:].sum() / N], dtype=complex)
    cs = [mat[:N, :N].sum(0), mat[:N, N:].sum(0), mat[N:, :N].sum(0), mat[N:, N:].sum(0)]
    defect = max(float(np.abs(c - c.mean()).max()) for c in cs) / math.sqrt(N)
    return mu_sums, defect


@on_budget
def structured_multipliers(
    mat: np.ndarray, n: int, K: int | None = None, seed: int = 12345, reversor: int | None = None
) -> tuple[np.ndarray, np.ndarray, float, dict]:
    """All 2N multipliers of the shifted monodromy 𝓜 (the *full* 2N×2N matrix, not the deflated
    block: the deflation destroys the band) by the half-size route (module doc), or — when
    ``reversor`` (the centre c of a reflection i → c − i of the base wave,
    :func:`fpucore.floquet.reversible.reversor_of`) is given and 𝓜 is reversible about it — by
    the quarter-size route of :mod:`fpucore.floquet.reversible` (one (N−1)² eigenvalue call).

    Returns (mu_rest (2N−2,), mu_sums (2,), conservation_defect, info) like
    :func:`fpucore.floquet.multipliers_of` plus info: route ("reversible" | "arnoldi");
    reversor (c or None); lam (N−1,) λ = μ + 1/μ; lam_error δλ (largest over λ); mu_error
    (2N−2,) per-multiplier bound; symplectic_defect η; irreversibility ‖G‖+‖F‖ (reversible
    route) or G_norm (dropped J-part, Arnoldi route); restarts; width (band); band_s /
    reduce_s / arnoldi_s / eig_s / elapsed_s (wall times, s).

    Parameters
    ----------
    mat : ndarray, shape (2N, 2N)
        The full shifted monodromy 𝓜 (``Monodromy.matrix``), finite.
    n : int
        N, the number of sites, in [2, MAX_N].
    K : int or None
        Tangent window half-width (sites) of :class:`fpucore.floquet.Monodromy`; None: the
        band is found from the non-zero pattern.
    seed : int
        Seed of the Arnoldi start vector.
    reversor : int or None
        Centre c of the reflection i → c − i, or None for the Arnoldi route.

    Returns
    -------
    mu_rest : ndarray, shape (2N−2,), complex
        Multipliers other than the conserved sums.
    mu_sums : ndarray, shape (2,), complex
        Multipliers of the conserved sums Σy, Σẏ.
    conservation_defect : float
        Coupling of the sum rows to the rest (dimensionless).
    info : dict
        The route's diagnostics listed above (errors dimensionless, times in s).

    Raises
    ------
    ParameterError
        When ``n`` is out of range, ``mat`` is not a finite (2N, 2N) matrix, or ``reversor``
        is not None or an integer.
    """
    t0 = time.perf_counter()
    N = require_int("n", n, 2, MAX_N)
    mat = np.asarray(mat, dtype=float)
    if mat.shape != (2 * N, 2 * N) or not np.all(np.isfinite(mat)):
        raise ParameterError(
            "mat",
            f"<array {mat.shape}>",
            f"a finite (2n, 2n) = ({2 * N}, {2 * N}) matrix (the shifted monodromy of n sites)",
        )
    m = N - 1
    mu_sums, defect = sums_and_defect(mat, N)
    info: dict = {
        "route": "arnoldi",
        "reversor": None,
        "band_s": 0.0,
        "reduce_s": 0.0,
        "arnoldi_s": 0.0,
        "G_norm": math.nan,
        "irreversibility": math.nan,
        "restarts": 0,
        "width": 0,
    }
    if reversor is not None and (
        isinstance(reversor, (bool, np.bool_)) or not isinstance(reversor, (int, np.integer))
    ):
        raise ParameterError(
            "reversor",
            reversor,
            "None or an integer site index",
            "the centre c of the reflection i -> c - i (reversor_of)",
        )
    rev = reversible_lambdas(mat, N, reversor) if reversor is not None else None
    if rev is not None:
        lam, lam_err_k, rinfo = rev
        info.update(rinfo, route="reversible", reversor=int(reversor))  # type: ignore[arg-type]
    else:
        t1 = time.perf_counter()
        d0, bands = band_of(mat, N, K)
        t2 = time.perf_counter()
        rng = np.random.default_rng(seed)
        V, H, g_norm, restarts = isotropic_arnoldi(bands, d0, N, rng)
        t3 = time.perf_counter()
        hnorm = float(np.abs(H).max()) * math.sqrt(m)
        lam = hessenberg_eigvals(H)  # LAPACK dhseqr: H is Hessenberg already (overwritten)
        t4 = time.perf_counter()
        eta = symplectic_defect(bands, d0, N)
        lam_err_k = np.full(lam.size, g_norm + (64.0 * np.finfo(float).eps + eta) * hnorm)
        info.update(
            G_norm=g_norm,
            symplectic_defect=eta,
            restarts=restarts,
            width=int(bands.shape[1]),
            band_s=t2 - t1,
            arnoldi_s=t3 - t2,
            eig_s=t4 - t3,
        )
    mu = mu_from_lambda(lam)
    err2 = np.concatenate([lam_err_k, lam_err_k])  # mu_from_lambda's order: big roots, then small
    sep = np.abs(mu - 1.0 / mu)
    info.update(
        lam=lam,
        lam_error=float(lam_err_k.max(initial=0.0)),
        mu_error=err2 / np.maximum(sep, np.sqrt(err2)),
        elapsed_s=time.perf_counter() - t0,
    )
    return mu, mu_sums, defect, info
