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

The fundamental matrix comes from the tangent kernel of :mod:`fpucore.wave.period_map` (fixed-step
8th-order RK along the stored base trajectory, columns on local windows with periodic wrap).
For a piecewise-linear law the base trajectory is event-located (steps cut at every breakpoint
crossing, regimes frozen per sub-step) and the tangent follows the same sub-steps: f is
continuous, so the saltation matrix of a transversal crossing is the identity and only f′ of
the crossing site switches there (:mod:`fpucore.wave.period_map`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import scipy.linalg

from fpucore.errors import ParameterError, require_int
from fpucore.floquet.checks import require_velocity
from fpucore.floquet.kernels import deflate_sums, extract_deflated, scatter_shifted
from fpucore.law import require_law
from fpucore.parallel.threads import on_budget
from fpucore.wave import period_map as pm

if TYPE_CHECKING:
    from fpucore.law.base import HardeningSofteningLaw
    from fpucore.wave.driver import WaveResult

_HW_DEFAULT = 0.12  # h·ω_max of the tangent integration (DOP853): quartets to ~1e-13, see bench
_SPREAD_LEVEL = 1e-18  # window half-width: neglected part of every column below this
MAX_N = 2500  # 5000² dense eig: minutes, 400 MB
MAX_STEPS = 20_000  # RK steps per period (m) of any monodromy
V_SPAN = 1e3  # base states with c_max / V_SPAN <= V <= V_SPAN c_max
GROWTH_MAX = 200.0  # largest log|μ| bound 2√(−f′)/V of a base state (|μ| <= e^200 ~ 1e87)


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


def _attr(r, name: str, convert):
    """convert(r.<name>), or ParameterError naming ``r.<name>`` (missing, or not numbers)."""
    try:
        x = getattr(r, name)
    except AttributeError:
        raise ParameterError(
            "r",
            type(r).__name__,
            "a wave result with law, V, w, wdot, w_left, w_right",
            f"no attribute {name!r}",
        ) from None
    if isinstance(x, (str, bytes, bool, np.bool_)):
        raise ParameterError(f"r.{name}", x, "real numbers")
    try:
        return convert(x)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(f"r.{name}", type(x).__name__, "real numbers") from None


def _strain_array(x) -> np.ndarray:
    a = np.ascontiguousarray(x, dtype=np.float64)
    if a.ndim != 1:
        raise ValueError("not a 1-d array")
    return a


def base_state(r):
    """(law, w, wd, V, N, w_left, w_right) from a wave result (duck-typed, see module doc).

    Refused (ParameterError naming the attribute): missing attributes or non-numbers; N odd,
    < 4 or > MAX_N; V outside [c_max/1000, 1000 c_max] (a period 1/V of ~1e16 steps, or an
    overflowing one); non-finite entries; strains whose perturbations grow by more than e^200
    per period (w = 1e6 once overflowed the monodromy, which reached LAPACK as "illegal
    value")."""
    law = require_law(_attr(r, "law", lambda x: x), "r.law")
    V = _attr(r, "V", float)
    w = _attr(r, "w", _strain_array)
    wd = _attr(r, "wdot", _strain_array)
    wl, wr = _attr(r, "w_left", float), _attr(r, "w_right", float)
    N = w.size
    if N > MAX_N:
        raise ParameterError("N", N, f"N <= {MAX_N}", "the dense eigenvalue call costs O(N^3) time")
    if N < 4 or N % 2 or wd.shape != w.shape:
        raise ParameterError("N", N, "an even number >= 4 with w, wdot of equal length")
    c = law.c_max
    if not (math.isfinite(V) and c / V_SPAN <= V <= c * V_SPAN):
        raise ParameterError(
            "V",
            V,
            f"[{c / V_SPAN:.6g}, {c * V_SPAN:.6g}]",
            f"velocities within a factor {V_SPAN:g} of c_max",
        )
    for name, x in (("r.w", w), ("r.wdot", wd), ("r.w_left/r.w_right", np.array([wl, wr]))):
        if not np.all(np.isfinite(x)):
            raise ParameterError(name, "non-finite entries", "finite real numbers")
    # Perturbations of a strain with f′(w) < 0 grow like exp(√(−f′) t): over one period
    # |μ| <= exp(2√(−f′)/V).  Beyond exp(GROWTH_MAX) the monodromy over- or underflows, which
    # reached LAPACK as "illegal value" (w = 1e6); unstable states short of it (the
    # homogeneous w0 = -0.2 of the finite-size tests) are fine.
    iv = getattr(law, "interval", None)  # a smooth law: its kernels end at [lo, hi]
    for name, x in (("r.w", w), ("r.w_left/r.w_right", np.array([wl, wr]))):
        if iv and np.any((x < iv[0]) | (x > iv[1])):
            bad = float(x[(x < iv[0]) | (x > iv[1])][0])
            raise ParameterError(
                name,
                bad,
                f"[{iv[0]:.10g}, {iv[1]:.10g}]",
                "the state left the represented interval of the smooth law "
                "(its kernels are not defined beyond it)",
            )
    for name, x in (("r.w", w), ("r.w_left/r.w_right", np.array([wl, wr]))):
        with np.errstate(over="ignore", invalid="ignore"):
            growth = 2.0 * np.sqrt(np.maximum(-law.df(x), 0.0)) / V
            bad = ~np.isfinite(law.f(x)) | ~(growth <= GROWTH_MAX)
        if np.any(bad):
            raise ParameterError(
                name,
                float(x[bad][0]),
                f"strains with 2 sqrt(-f'(w))/V <= {GROWTH_MAX:g}",
                "a perturbation would grow by more than exp(200) in one period",
            )
    # |ẇ| of a traveling wave is V |w′| <= V x (strain range): far beyond it is no wave
    wd_max = V_SPAN * V * (float(np.ptp(np.concatenate([w, [wl, wr]]))) + law.beta - law.alpha)
    if np.any(np.abs(wd) > wd_max):
        raise ParameterError(
            "r.wdot",
            float(np.max(np.abs(wd))),
            f"|wdot| <= {wd_max:.6g}",
            "strain rates of a traveling wave are V |w'|",
        )
    return law, w, wd, V, N, wl, wr


def default_steps(law: HardeningSofteningLaw, V: float) -> int:
    """RK steps per period with h·ω_max ≤ 0.12 for ω_max = 2 c_max (the top linear frequency).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law (its largest sound speed c_max, sites per unit time).
    V : float
        Wave velocity, sites per unit time (period T = 1/V), in [1e-150, 1e150].

    Returns
    -------
    int
        The step count m per period (step h = T/m, time units).

    Raises
    ------
    ParameterError
        When ``law`` or ``V`` is invalid.
    """
    law, V = require_law(law), require_velocity(V)
    return pm.rk_steps_for(V, law.c_max, hw=_HW_DEFAULT)


@on_budget
def monodromy(r: WaveResult, m: int | None = None) -> Monodromy:
    """𝓜 of eq. linear_map for the base state r (wave result or :class:`HomogeneousState`).

    The base trajectory is re-integrated from (r.w, r.wdot) with the fixed boundary strains of
    eq. fixedBCs (DOP853, m steps, f′ stored at every stage); the perturbation columns use the
    paper's periodic BCs (index wrap) on windows of ±K sites, K chosen so that the neglected part
    of each column is below 1e-18; then rows are shifted.  Cost O(N·K·m), all in Numba.

    Parameters
    ----------
    r : WaveResult or HomogeneousState
        The base state: law, V (sites per unit time), N sites (even, in [4, MAX_N]), w and
        wdot of shape (N,), boundary strains w_left, w_right.
    m : int or None
        RK steps per period, in [2, 20000]; None: :func:`default_steps`.

    Returns
    -------
    Monodromy
        ``matrix`` (2N, 2N) float64, T = 1/V, m, K (window half-width, sites), truncation and
        elapsed_s (wall time, s).

    Raises
    ------
    ParameterError
        When an attribute of ``r`` is missing or invalid (N odd, < 4 or > MAX_N; V outside
        [c_max/1000, 1000 c_max]; non-finite entries; perturbations growing by more than e^200
        per period), or ``m`` is out of range.
    """
    t0 = time.perf_counter()
    law, w, wd, V, N, wl, wr = base_state(r)
    if m is None:
        m = default_steps(law, V)
    m = require_int("m", m, 2, MAX_STEPS)  # the one rule for counts: an integer, not 2.0
    res = pm.integrate(law, w, wd, 1.0 / V, int(m), wl, wr, periodic=False, store_df=True)
    K = pm.spread_radius(res, level=_SPREAD_LEVEL) + 1
    K = min(K, N // 2)
    cols = np.arange(2 * N, dtype=np.int64)
    out, edge = pm.tangent_columns(res, cols, K, periodic=True)
    k_eff = N // 2 if out.shape[2] == N else K
    mat = np.zeros((2 * N, 2 * N))
    scatter_shifted(out, cols, N, k_eff, mat)
    return Monodromy(
        mat,
        N,
        1.0 / V,
        int(m),
        int(k_eff),
        float(edge.max(initial=0.0)),
        time.perf_counter() - t0,
    )


def _householder(n: int) -> tuple[np.ndarray, float]:
    """u, β of H = I − β u uᵀ with H 1/√N = e_{N−1}."""
    u = np.full(n, 1.0 / math.sqrt(n))
    u[-1] -= 1.0
    return u, 2.0 / float(u @ u)


@on_budget
def multipliers_of(mat: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, float]:
    """All 2N eigenvalues of 𝓜 with the conservation block deflated exactly.

    Returns (mu_rest (2N−2,), mu_sums (2,), conservation_defect).  mu_sums are the diagonal of
    the 2×2 quotient block [[1, T], [0, 1]] (Σy, Σẏ); mu_rest come from one dense LAPACK dgeev
    call on the (2N−2)-block.  conservation_defect is the largest coupling of the sum rows to the
    rest (exactly 0 for an exact ring integration; round-off level here).

    Parameters
    ----------
    mat : ndarray, shape (2N, 2N)
        The shifted monodromy 𝓜 (``Monodromy.matrix``), finite.
    n : int
        N, the number of sites (half the matrix order).

    Returns
    -------
    mu_rest : ndarray, shape (2N−2,), complex
        Multipliers of the deflated block.
    mu_sums : ndarray, shape (2,), complex
        Multipliers of the conserved sums Σy, Σẏ (both ≈ 1).
    conservation_defect : float
        Largest coupling of the sum rows to the rest (dimensionless).

    Raises
    ------
    ParameterError
        When ``mat`` is not a finite square (2N, 2N) matrix or ``n`` is not N.
    """
    mat = np.asarray(mat)
    if mat.ndim != 2 or mat.shape[0] != mat.shape[1] or mat.shape[0] % 2:
        raise ParameterError("mat", f"shape {mat.shape}", "a square (2N, 2N) matrix")
    n = require_int("n", n, 2, mat.shape[0] // 2)
    if mat.shape[0] != 2 * n:
        raise ParameterError("n", n, f"N = {mat.shape[0] // 2}, half the matrix order")
    if not np.isfinite(mat).all():
        raise ParameterError("mat", "non-finite entries", "a finite matrix")
    a, b, defect = deflate(mat, n)
    mu_rest = scipy.linalg.eigvals(b, overwrite_a=True, check_finite=False)
    mu_sums = np.array([a[n - 1, n - 1], a[2 * n - 1, 2 * n - 1]], dtype=complex)
    return mu_rest, mu_sums, float(defect)


def deflate(mat: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, float]:
    """(a, b, defect): a = 𝓜 after the exact Householder deflation of the two sums, (2N, 2N);
    b its (2N−2)² block without them (Fortran order, what dgeev gets); defect the sum rows'
    coupling to the rest (see :func:`multipliers_of`)."""
    a = np.array(mat, dtype=np.float64, order="C", copy=True)
    u, beta = _householder(n)
    deflate_sums(a, n, u, beta)
    b = np.empty((2 * n - 2, 2 * n - 2), order="F")
    defect = extract_deflated(a, n, b)
    return a, b, float(defect)
