"""The structured half-size spectrum against closed forms and the dense reference.

References: the constant state's multipliers in closed form (stable and f′ < 0), and dense
LAPACK eigvals on the same monodromy over the paper's families (superkinks over their velocity
range, solitary waves at w₊ = 1 and 6).  The extreme laws are in tests/extreme/.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fpucore import floquet as fq
from fpucore import wave
from fpucore.errors import ParameterError
from fpucore.floquet import arnoldi_kernels as ak
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def _set_distance(a: np.ndarray, b: np.ndarray) -> float:
    d = np.abs(a[:, None] - b[None, :])
    return float(max(d.min(axis=0).max(), d.min(axis=1).max()))


@pytest.fixture(params=["reversible", "arnoldi"])
def route(request, monkeypatch):
    """Both structured routes: the reversible one the waves below take, and the isotropic
    Arnoldi one (every non-reversible wave's), forced by hiding the reversor."""
    if request.param == "arnoldi":
        monkeypatch.setattr(fq.spectrum_steps, "reversor_of", lambda *a: None)
    return request.param


@pytest.mark.parametrize("w0, V, N, convex", [(1.0, 5.0, 40, True), (0.3, 4.0, 64, True),
                                              (7.0, 5.0, 40, False)])  # fmt: skip
def test_constant_state_closed_form(w0, V, N, convex, route):
    """μ = e^{ik} e^{±iωT} (f′ > 0) or e^{ik} e^{±σT} (f′ < 0), k = 2πj/N, derived here.  The
    homogeneous ring has degenerate λ (k and −k), so the Arnoldi process restarts."""
    c2 = float(LAW.df(w0))
    k = 2 * np.pi * np.arange(N) / N
    s = 2 * math.sqrt(abs(c2)) * np.abs(np.sin(k / 2)) / V
    ph = 1j * s if c2 > 0 else s
    exact = np.concatenate([np.exp(1j * k + ph), np.exp(1j * k - ph)])
    fr = fq.spectrum(fq.HomogeneousState(LAW, w0, V, N, convex=convex), method="structured")
    assert fr.method == "structured" and fr.route == route and fr.converged, fr.message
    assert _set_distance(fr.multipliers, exact) < 1e-7 * np.abs(exact).max()
    if convex:  # elliptic multipliers exactly on the unit circle (the structure is kept)
        assert np.max(np.abs(np.abs(fr.multipliers[2:]) - 1.0)) < 1e-15
        assert fr.classification == "stable"
    else:
        assert fr.growth_rate == pytest.approx(2 * math.sqrt(-c2), rel=1e-11)
        assert fr.classification == "unstable"


CASES = [
    ("superkink", 4.8, None),
    ("superkink", 5.2, None),
    ("superkink", 5.5, None),
    ("superkink", 5.85, None),
    ("solitary", 4.5, 1.0),
    ("solitary", 5.3, 1.0),
    ("solitary", 5.0, 6.0),
    ("solitary", 5.3, 6.0),
]


@pytest.mark.parametrize("kind, V, w_plus", CASES)
def test_agrees_with_dense_over_the_paper_families(kind, V, w_plus, route):
    N = 200
    if kind == "superkink":
        r = wave.solve_superkink(LAW, V, N=N)
    else:
        r = wave.solve_solitary(LAW, w_plus, V, N=N)
    a = fq.spectrum(r, finite_size=False, method="dense")
    b = fq.spectrum(r, finite_size=False, method="structured")
    assert b.converged and b.route == route, b.message
    assert abs(a.max_modulus_away_from_1 - b.max_modulus_away_from_1) <= max(a.error, b.error)
    assert a.n_unstable == b.n_unstable and a.n_trivial == b.n_trivial
    assert a.excess_significant == b.excess_significant
    away = np.abs(a.multipliers - 1.0) > 1e-2
    d = np.abs(b.multipliers[None, :] - a.multipliers[away][:, None]).min(axis=1)
    assert d.max() < 1e-9  # every multiplier away from 1 is found by both
    assert b.error < 1e-9 and b.structure_error < 1e-10
    assert np.max(np.abs(b.multipliers[:2] - a.multipliers[:2])) < 1e-13  # conservation pair


def test_same_classification_with_finite_size_test(route):
    r = wave.solve_solitary(LAW, 1.0, 5.3, N=200)
    a = fq.spectrum(r, method="dense")
    b = fq.spectrum(r, method="structured")
    assert a.classification == b.classification == "finite_size"
    assert np.allclose(a.finite_size_excess, b.finite_size_excess, rtol=1e-9, atol=1e-12)


def test_bands_of_the_monodromy_match_the_dense_matrix():
    r = wave.solve_superkink(LAW, 5.2, N=120)
    mono = fq.monodromy(r)
    d0, bands = fq.structured.band_of(mono.matrix, r.N, mono.K)
    d0b, bands_b = fq.structured.band_of(mono.matrix, r.N)  # from the non-zero pattern
    assert (d0, bands.shape) == (d0b, bands_b.shape) and np.array_equal(bands, bands_b)
    x = np.random.default_rng(0).standard_normal(2 * r.N)
    out = np.empty(2 * r.N)
    fq.structured_kernels.band_mv(bands, d0, r.N, x, out)
    assert np.max(np.abs(out - mono.matrix @ x)) < 1e-13 * np.abs(mono.matrix).sum(1).max()
    fq.structured_kernels.band_mtv(bands, d0, r.N, x, out)
    assert np.max(np.abs(out - mono.matrix.T @ x)) < 1e-13 * np.abs(mono.matrix).sum(0).max()


def test_bad_method():
    with pytest.raises(ParameterError, match="method="):
        fq.spectrum(fq.HomogeneousState(LAW, 1.0, 5.0, 16), method="qr")


def test_hessenberg_eigvals_closed_form():
    """tridiag(1, 2, 1) of size n (Hessenberg): eigenvalues 2 + 2 cos(jπ/(n+1)), j = 1 … n."""
    n = 60
    h = 2.0 * np.eye(n) + np.eye(n, k=1) + np.eye(n, k=-1)
    h[0, 5] = 0.0
    ev = np.sort(fq.hessenberg.hessenberg_eigvals(h.copy()).real)
    exact = np.sort(2.0 + 2.0 * np.cos(np.arange(1, n + 1) * np.pi / (n + 1)))
    assert np.max(np.abs(ev - exact)) < 1e-13


@pytest.mark.parametrize("V", [5.2, 5.85])
def test_arnoldi_relation_and_reported_dropped_part(V):
    """The delayed-reorthogonalisation Arnoldi (arnoldi_kernels.dcgs2_steps) against its own
    definition, checked with W applied anew: V orthonormal and isotropic to round-off, the
    relation W Vᵀ = Vᵀ H + J Vᵀ G with G = (J V) W Vᵀ, and the reported ‖G‖ (the part the
    half-size problem drops) at least the true one.  V = 5.85 is next to V_SK, where the
    one-pass projections cancel most (|a| up to 1e-9 at N = 500) and the J-part is pushed
    through W."""
    r = wave.solve_superkink(LAW, V, N=160)
    N = r.N
    mono = fq.monodromy(r)
    d0, bands = fq.structured.band_of(mono.matrix, N, mono.K)
    Vb, H, g_norm, _ = fq.structured.isotropic_arnoldi(bands, d0, N, np.random.default_rng(3))
    m = N - 1
    JV = np.concatenate([Vb[:, N:], -Vb[:, :N]], axis=1)
    WV = np.empty_like(Vb)
    t = [np.empty(2 * N) for _ in range(4)]
    for i in range(m):
        fq.structured_kernels.w_apply(bands, d0, N, Vb[i], WV[i], *t)
    G = JV @ WV.T
    scale = np.linalg.norm(WV, 2)
    assert np.abs(Vb @ Vb.T - np.eye(m)).max() < 1e-13
    assert np.abs(Vb @ JV.T).max() < 1e-13
    assert np.allclose(np.tril(H, -2), 0.0)  # Hessenberg
    assert np.linalg.norm(WV.T - Vb.T @ H - JV.T @ G, 2) < 1e-12 * scale
    assert np.linalg.norm(G) <= g_norm < 1e-10 * scale


def test_sweep_kernels_against_numpy():
    """coefficients / project_out / project_out_z / hessenberg products (arnoldi_kernels)
    against the same quantities written with numpy, for odd and even row counts."""
    rng = np.random.default_rng(5)
    n, m = 37, 11
    V = rng.standard_normal((m, 2 * n))
    JV = np.concatenate([V[:, n:], -V[:, :n]], axis=1)
    x0, x1 = rng.standard_normal(2 * n), rng.standard_normal(2 * n)
    HT = np.triu(rng.standard_normal((m, m)), -1).T.copy()  # HT = Hᵀ, H upper Hessenberg
    for k in (m - 1, m - 2):  # the process calls them for k < m
        c = np.zeros((m, 4))
        ak.coefficients(V, k, x0, x1, n, c)
        ref = np.stack([V[:k] @ x0, JV[:k] @ x0, V[:k] @ x1, JV[:k] @ x1], axis=1)
        assert np.abs(c[:k] - ref).max() < 1e-12
        y0, y1, z0, z1, z = x0.copy(), x1.copy(), x0.copy(), x1.copy(), np.empty(2 * n)
        ak.project_out(V, k, c, n, y0, y1)
        ak.project_out_z(V, k, c, n, z0, z1, z)
        e0 = x0 - V[:k].T @ c[:k, 0] - JV[:k].T @ c[:k, 1]
        e1 = x1 - V[:k].T @ c[:k, 2] - JV[:k].T @ c[:k, 3]
        for got in (y0, z0):
            assert np.abs(got - e0).max() < 1e-12
        for got in (y1, z1):
            assert np.abs(got - e1).max() < 1e-12
        assert np.abs(z - V[:k].T @ c[:k, 1]).max() < 1e-12
        out = np.empty(2 * n)
        ak.hessenberg_times(HT, k, c, 0, out)
        assert np.abs(out[: k + 1] - HT.T[: k + 1, :k] @ c[:k, 0]).max() < 1e-12
        c2 = c.copy()
        ak.hessenberg_t_times(HT, k, np.ascontiguousarray(c[:, 1]), c2, 3)
        assert np.abs(c2[:k, 3] - (c[:k, 3] - HT.T[:k, :k].T @ c[:k, 1])).max() < 1e-12
