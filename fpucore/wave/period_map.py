"""One period of the FPU chain and its exact tangent map (paper §5, eqs. FPUstrain, period,
nonlin_map, fixedBCs; §6 eq. linear for the tangent).

State: N strains ``w[0..N-1]`` (sites n = −N/2 … N/2−1) and their rates ``wd``.  The chain

    ẅ_n = f(w_{n+1}) − 2 f(w_n) + f(w_{n−1})                                    (eq. FPUstrain)

is integrated as the first-order system (w, ẇ)′ = (ẇ, Δf(w)) over exactly one period T = 1/V with
``m`` fixed steps of an explicit RK tableau (default DOP853, order 8), landing exactly on T.
Boundary strains are fixed, w_{−N/2−1} = ``w_left``, w_{N/2} = ``w_right`` (eq. fixedBCs), or the
index wraps (``periodic=True``).  The integrator's own error is the step-doubling difference
|Φ_m − Φ_2m| (:func:`step_doubling_error`).

Tangent map.  Differentiating the RK map itself gives RK applied to the variational equations
δẅ_n = f′(w_{n+1})δw_{n+1} − 2f′(w_n)δw_n + f′(w_{n−1})δw_{n−1} (eq. linear) with f′ evaluated at
the *stage* values of the base integration.  :func:`integrate` can store those f′ values
(array ``dfs`` of shape (m, s, N)); :func:`tangent_columns` then integrates one unit perturbation
per requested column, in parallel over columns, giving the derivative of the discrete map to
round-off (no finite differences).  In one period a perturbation spreads only a few tens of sites,
so each column is integrated on a window of ±K sites around its own site (zero outside); the
largest |δ| reached on a window edge is returned as the truncation estimate.  With
``periodic=True`` and 2K+1 ≥ N the window is the whole ring and the columns are exact —
:func:`fundamental_matrix` uses this to build the full Ψ(T) for Floquet analysis.

Piecewise-linear laws (event location).  For a law with breakpoints :func:`integrate` takes
the event-located route of :mod:`.period_events` (nominal steps cut at every located crossing,
each site's regime frozen per sub-step) and stores each sub-step's size and frozen f′.  The
tangent map follows the same sub-steps with those f′.  Why no jump term: f is continuous and
only f′ jumps at a breakpoint b, so the vector field F = (ẇ, Δf(w)) is continuous across the
switching surface w_n = b; at a transversal crossing (ẇ_n ≠ 0) the saltation matrix
S = I + (F₊ − F₋) ∇gᵀ / (∇g·F₋) is the identity (F₊ = F₋ on the surface), so δ is continuous
and the variational equations only switch f′ of the crossing site at the located crossing.
The derivative of the discrete located map differs from this by the crossing time's
dependence on x times the difference of the two regimes' sub-steps from the crossing, which
agree there to the method's local error.  Measured against central differences of the
event-located map across crossings: agreement to ≤ 1e-7 relative (the differences' own
error), against ≥ 1e-4 for the tangent of the plain fixed-step map
(tests/wave/test_tangent_events.py).

Column convention: column c < N perturbs w at site c, column c ≥ N perturbs ẇ at site c − N
(the ordering [w; ẇ] of eq. nonlin_map).  A window row k ∈ [0, W) is the site (c mod N) − K + k
(mod N if periodic).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from fpucore import law as _law
from fpucore.errors import ParameterError, require_finite
from fpucore.tableaux.rk import DOP853, Tableau
from fpucore.wave.period_checks import check_m, check_state
from fpucore.wave.period_events import integrate_events


# --------------------------------------------------------------------------- kernels
@njit(cache=True, nogil=True)
def _rk_period_kernel(
    w0, wd0, T, m, A, B, law_id, p, w_left, w_right, periodic, store, w, wd, dfs, kw, kwd, yw, g
):
    """Integrate (w, ẇ) over [0, T] with m RK steps.  Fills w, wd (final state) and, if store,
    dfs[step, stage, n] = f′(stage strain).  Work arrays: kw, kwd (s, N); yw (N,); g (N+2,)."""
    N = w0.size
    s = B.size
    h = T / m
    for n in range(N):
        w[n] = w0[n]
        wd[n] = wd0[n]
    fl = _law.force(law_id, p, w_left)
    fr = _law.force(law_id, p, w_right)
    for step in range(m):
        for i in range(s):
            # stage strains Y_w (stage rates Y_wd are k_w[i] itself: ẇ′ = f-Laplacian, w′ = ẇ)
            for n in range(N):
                yw[n] = w[n]
                kw[i, n] = wd[n]
            for j in range(i):
                a = A[i, j] * h
                if a != 0.0:
                    for n in range(N):
                        yw[n] += a * kw[j, n]
                        kw[i, n] += a * kwd[j, n]
            for n in range(N):
                g[n + 1] = _law.force(law_id, p, yw[n])
            if periodic:
                g[0] = g[N]
                g[N + 1] = g[1]
            else:
                g[0] = fl
                g[N + 1] = fr
            for n in range(N):
                kwd[i, n] = g[n + 2] - 2.0 * g[n + 1] + g[n]
            if store:
                for n in range(N):
                    dfs[step, i, n] = _law.dforce(law_id, p, yw[n])
        for i in range(s):
            b = B[i] * h
            if b != 0.0:
                for n in range(N):
                    w[n] += b * kw[i, n]
                    wd[n] += b * kwd[i, n]


@njit(cache=True, nogil=True, parallel=True)
def _tangent_kernel(dfs, hs, A, B, cols, K, periodic, out, edge):
    """Integrate unit perturbations of the given columns over one period on ±K-site windows.

    dfs : (k, s, N) stage values of f′ from the base integration, or (k, 1, N) one value per
    (sub-)step for every stage (frozen regimes of a PL law); hs : (k,) the (sub-)step sizes.
    cols : (nc,) int64 column ids.  out : (nc, 2, W) filled with (δw, δẇ) on the window;
    edge : (nc,) largest |δ| on a window edge that truncates the chain (0 where the edge is a
    fixed boundary or the window is the ring).
    """
    m, s1, N = dfs.shape
    s = B.size
    ring = periodic and 2 * K + 1 >= N
    W = N if ring else 2 * K + 1
    nc = cols.size
    for ci in prange(nc):
        c = cols[ci]
        site0 = c % N
        sites = np.empty(W, np.int64)
        live = np.empty(W, np.bool_)
        for k in range(W):
            sn = site0 - K + k
            if periodic:
                sn = sn % N
                live[k] = True
            else:
                live[k] = 0 <= sn < N
            sites[k] = sn
        dw = np.zeros(W)
        dwd = np.zeros(W)
        kw = np.zeros((s, W))
        kwd = np.zeros((s, W))
        yw = np.empty(W)
        g = np.zeros(W + 2)
        if c < N:
            dw[K] = 1.0
        else:
            dwd[K] = 1.0
        for step in range(m):
            h = hs[step]
            for i in range(s):
                si = i if s1 > 1 else 0
                for k in range(W):
                    yw[k] = dw[k]
                    kw[i, k] = dwd[k]
                for j in range(i):
                    a = A[i, j] * h
                    if a != 0.0:
                        for k in range(W):
                            yw[k] += a * kw[j, k]
                            kw[i, k] += a * kwd[j, k]
                for k in range(W):
                    g[k + 1] = dfs[step, si, sites[k]] * yw[k] if live[k] else 0.0
                if ring:
                    g[0] = g[W]
                    g[W + 1] = g[1]
                else:  # outside the window: exactly 0 at a fixed end, truncation otherwise
                    g[0] = 0.0
                    g[W + 1] = 0.0
                for k in range(W):
                    kwd[i, k] = (g[k + 2] - 2.0 * g[k + 1] + g[k]) if live[k] else 0.0
            for i in range(s):
                b = B[i] * h
                if b != 0.0:
                    for k in range(W):
                        dw[k] += b * kw[i, k]
                        dwd[k] += b * kwd[i, k]
        e = 0.0
        if not ring:
            if live[0] and (periodic or sites[0] > 0):
                e = max(e, abs(dw[0]), abs(dwd[0]))
            if live[W - 1] and (periodic or sites[W - 1] < N - 1):
                e = max(e, abs(dw[W - 1]), abs(dwd[W - 1]))
        edge[ci] = e
        for k in range(W):
            out[ci, 0, k] = dw[k]
            out[ci, 1, k] = dwd[k]


# --------------------------------------------------------------------------- Python API
@dataclass(frozen=True)
class PeriodResult:
    """Final state of one period.  w, wd : (N,) at t = T; dfs : (m, s, N) stage f′ or None.

    A piecewise-linear law's period (event location, :mod:`.period_events`) is taken in
    k ≥ m sub-steps: hs (k,) their sizes and dfs (k, 1, N) the frozen f′ of each; crossings
    counts the located breakpoint crossings and crossing_speed is the smallest |ẇ| of a site at
    its located crossing (transversality).  hs None: m equal steps T/m."""

    w: np.ndarray
    wd: np.ndarray
    dfs: np.ndarray | None
    T: float
    m: int
    tableau: Tableau
    hs: np.ndarray | None = None
    crossings: int = 0
    crossing_speed: float = math.inf  # smallest |ẇ| at a located crossing (transversality)

    def step_sizes(self) -> np.ndarray:
        """(k,) the (sub-)step sizes of the integration."""
        return self.hs if self.hs is not None else np.full(self.m, self.T / self.m)


def integrate(
    law,
    w0,
    wd0,
    T: float,
    m: int,
    w_left: float = 0.0,
    w_right: float = 0.0,
    periodic: bool = False,
    store_df: bool = False,
    tableau: Tableau = DOP853,
    events: bool | None = None,
) -> PeriodResult:
    """Integrate eq. FPUstrain over [0, T] with m fixed RK steps (h = T/m, landing exactly on T).

    law : force law (``law.law_id``, ``law.params``).  w0, wd0 : (N,) strains and strain rates at
    t = 0 for sites −N/2 … N/2−1.  w_left, w_right : fixed boundary strains (eq. fixedBCs), ignored
    if ``periodic``.  store_df : keep f′ at every stage, (m, s, N), for :func:`tangent_columns`.
    events : locate the breakpoint crossings of a piecewise-linear law (None: exactly when the
    law has breakpoints; False only to compare with plain fixed steps).  The m nominal steps are
    then cut at every crossing (:func:`fpucore.wave.period_events.integrate_events`) and the
    tangent map of :func:`tangent_columns` follows the same sub-steps (module doc).
    """
    if events is None:
        events = bool(getattr(law, "breakpoints", ()))
    if events:
        e = integrate_events(law, w0, wd0, T, m, w_left, w_right, periodic, True, tableau, store_df)
        return PeriodResult(
            e.w, e.wd, e.dfs, e.T, e.m, tableau, e.hs, e.crossings, e.crossing_speed
        )
    w0, wd0 = check_state(w0, wd0)
    T = require_finite("T", T)
    if T <= 0:
        raise ParameterError("T", T, "T > 0")
    m = check_m(m)
    w_left, w_right = require_finite("w_left", w_left), require_finite("w_right", w_right)
    N, s = w0.size, tableau.stages
    w, wd = np.empty(N), np.empty(N)
    dfs = np.empty((m, s, N)) if store_df else np.empty((1, 1, 1))
    _rk_period_kernel(
        w0,
        wd0,
        T,
        m,
        tableau.A,
        tableau.B,
        law.law_id,
        law.params,
        w_left,
        w_right,
        bool(periodic),
        bool(store_df),
        w,
        wd,
        dfs,
        np.empty((s, N)),
        np.empty((s, N)),
        np.empty(N),
        np.empty(N + 2),
    )
    return PeriodResult(w, wd, dfs if store_df else None, T, m, tableau)


def period_map(law, x, V: float, m: int, w_left: float, w_right: float, periodic=False, **kw):
    """Φ_T(x) for x = [w; ẇ] (2N,), T = 1/V, *without* the index shift of eq. nonlin_map."""
    x = np.asarray(x, dtype=np.float64)
    N = x.size // 2
    r = integrate(law, x[:N], x[N:], 1.0 / V, m, w_left, w_right, periodic, **kw)
    return np.concatenate([r.w, r.wd])


def step_doubling_error(
    law, w0, wd0, T, m, w_left=0.0, w_right=0.0, periodic=False, tableau: Tableau = DOP853
) -> float:
    """Integrator error estimate max|Φ_m − Φ_2m| (max-norm over w and ẇ) at the state (w0, wd0)."""
    a = integrate(law, w0, wd0, T, m, w_left, w_right, periodic, tableau=tableau)
    b = integrate(law, w0, wd0, T, 2 * m, w_left, w_right, periodic, tableau=tableau)
    return float(max(np.max(np.abs(a.w - b.w)), np.max(np.abs(a.wd - b.wd))))


def roundoff_level(law, w: np.ndarray, wd: np.ndarray, T: float, m: int) -> tuple[float, float]:
    """Round-off level (absolute, max-norm) of one period map at the state (w, ẇ): (on w, on ẇ).

    Model: ε√m · (3 max|w|) on the strains, ε√m · (max|ẇ| + 4T max|f(w)|) on the rates — the
    second difference of f(w) cancels digits when |f| ≫ |Δf| (stiff laws: b = 1000 gives
    |f| ≈ 2e7 at w ≈ 170).  Calibrated against the same map in 80-bit long double
    (tests/wave/ld_reference.py) for b = 10, 100, 1000 at m = 16: measured/model = 0.4–0.75 on w,
    0.2–0.6 on ẇ."""
    e = np.finfo(float).eps * math.sqrt(max(1, m))
    wmax = float(np.max(np.abs(w)))
    fmax = float(np.max(np.abs(law.f(w))))
    return 3.0 * e * wmax, e * (float(np.max(np.abs(wd))) + 4.0 * T * fmax)


def tangent_columns(
    res: PeriodResult, cols, K: int, periodic: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Columns of the exact derivative of the period map on ±K-site windows.

    res : a :class:`PeriodResult` from ``integrate(..., store_df=True)``.
    cols : (nc,) column ids (c < N: ∂/∂w_c, c ≥ N: ∂/∂ẇ_{c−N}).  K : window half-width (sites).
    periodic : wrap the perturbation's index (Floquet BCs of §6) instead of δw = 0 at the ends.

    Returns ``(out, edge)``: out (nc, 2, W) holds (δw, δẇ) at t = T on window rows k = 0 … W−1,
    i.e. sites (c mod N) − K + k (mod N if periodic; rows outside 0 … N−1 are 0 for fixed ends);
    W = 2K+1, or W = N (the whole ring, exact) if periodic and 2K+1 ≥ N.  edge (nc,) is the
    largest |δ| on a truncating window edge — the Jacobian truncation estimate.
    """
    if res.dfs is None:
        raise ParameterError("res", "PeriodResult without dfs", "integrate(..., store_df=True)")
    m, s, N = res.dfs.shape
    cols = np.ascontiguousarray(cols, dtype=np.int64)
    if cols.ndim != 1 or (cols.size and (cols.min() < 0 or cols.max() >= 2 * N)):
        raise ParameterError("cols", "out-of-range ids", f"integers in [0, {2 * N})")
    if not (isinstance(K, (int, np.integer)) and K >= 1):
        raise ParameterError("K", K, "an integer >= 1")
    K = int(K)
    if periodic and 2 * K + 1 >= N:
        K = N // 2  # the whole ring
    elif not periodic:
        K = min(K, N)  # a wider window than the chain only adds dead rows
    ring = periodic and 2 * K + 1 >= N
    W = N if ring else 2 * K + 1
    out = np.empty((cols.size, 2, W))
    edge = np.empty(cols.size)
    tab = res.tableau
    hs = np.ascontiguousarray(res.step_sizes(), dtype=np.float64)
    _tangent_kernel(res.dfs, hs, tab.A, tab.B, cols, K, bool(periodic), out, edge)
    return out, edge


def fundamental_matrix(res: PeriodResult, periodic: bool = True) -> np.ndarray:
    """Dense Ψ(T) (2N, 2N) in the [w; ẇ] ordering, every column integrated on the full chain.

    With ``periodic=True`` the perturbation's index wraps (paper §6: y_{N/2} = y_{−N/2},
    y_{−N/2−1} = y_{N/2−1}); otherwise δw = 0 at the fixed ends.  The Floquet monodromy matrix of
    eq. linear_map is Ψ with the rows of each half rolled up by one: ``np.roll`` of each block.
    """
    N = res.dfs.shape[2] if res.dfs is not None else 0
    K = N // 2 if periodic else N
    out, _ = tangent_columns(res, np.arange(2 * N), K, periodic)
    return scatter_dense(out, N, K, periodic)


def scatter_dense(out: np.ndarray, N: int, K: int, periodic: bool) -> np.ndarray:
    """Place window columns from :func:`tangent_columns` (all 2N columns, in order) into a dense
    (2N, 2N) matrix."""
    W = out.shape[2]
    ring = periodic and 2 * K + 1 >= N
    Psi = np.zeros((2 * N, 2 * N))
    k = np.arange(W)
    for c in range(2 * N):
        sites = (c % N) - K + k
        if periodic or ring:
            sites = sites % N
            ok = np.ones(W, bool)
        else:
            ok = (sites >= 0) & (sites < N)
        Psi[sites[ok], c] = out[c, 0, ok]
        Psi[N + sites[ok], c] = out[c, 1, ok]
    return Psi


def spread_radius(res: PeriodResult, level: float = 1e-17, K_probe: int = 40) -> int:
    """Sites a unit perturbation reaches above ``level`` in one period (worst case over probes).

    Probes the columns (w and ẇ) at the site of largest f′ and at both ends; K from this is the
    window half-width for which the neglected part of each Jacobian column is below ``level``.
    """
    m, s, N = res.dfs.shape  # type: ignore[union-attr]
    i_max = int(np.argmax(res.dfs[0, 0]))  # type: ignore[index]
    sites = np.unique(np.array([i_max, N // 2, 0, N - 1]))
    cols = np.concatenate([sites, sites + N])
    K_probe = int(min(K_probe, max(1, N)))
    while True:
        out, _ = tangent_columns(res, cols, K_probe, periodic=False)
        mag = np.max(np.abs(out), axis=(0, 1))  # (W,)
        dist = np.abs(np.arange(mag.size) - K_probe)
        above = dist[mag > level]
        r = int(above.max()) + 1 if above.size else 1
        if r <= K_probe or K_probe >= N:  # not saturated (or the whole chain is covered)
            return min(r, max(1, N))
        K_probe = min(2 * K_probe, N)


def rk_steps_for(V: float, c_max: float, hw: float = 0.35) -> int:
    """A step count with h·ω_max ≤ hw, ω_max = 2 c_max the top linear frequency (a starting
    guess only: callers measure the error by step doubling and refine)."""
    return max(2, int(math.ceil(2.0 * c_max / (V * hw))))
