"""The quarter-size reversible route (:mod:`fpucore.floquet.reversible`).

References: the pseudo-inverse and the basis built here from their definitions (numpy ``pinv``,
dense J and reflection), dense LAPACK eigvals on the same monodromy (every λ = μ + 1/μ within
the bound the route claims for it), and the isotropic Arnoldi route for the waves that are not
reversible.
"""

from __future__ import annotations

import types

import numpy as np
import pytest

from fpucore import floquet as fq
from fpucore import wave
from fpucore.errors import ParameterError
from fpucore.floquet import reversible as rv
from fpucore.floquet import reversible_kernels as rk
from fpucore.floquet.structured import mu_from_lambda
from fpucore.law import CubicLaw, law_from_expression

LAW = CubicLaw(-1.0, 10.0)
QUARTIC = law_from_expression("w + 10*w**2 - w**3 - 0.01*w**4")


def _dense_basis(n: int, c: int) -> np.ndarray:
    blk, ia, ib, ca, cb, _ = rv.pairing_basis(n, c)
    q = np.zeros((2 * n, 2 * n))
    for k in range(2 * n):
        q[blk[k] * n + ia[k], k] += ca[k]
        q[blk[k] * n + ib[k], k] += cb[k]
    return q


@pytest.mark.parametrize("n, c", [(12, 0), (12, 1), (12, 5), (10, 9)])
def test_basis_is_the_reversors_lagrangian_splitting(n, c):
    """Q orthogonal; Q₊ = the +1 eigenspace of ρ(u, p) = (−P u, P p), P u_i = u_{c+1−i};
    Q₊ Lagrangian; the second half is J Q₊; v is the constant-p direction."""
    q = _dense_basis(n, c)
    assert np.allclose(q.T @ q, np.eye(2 * n), atol=1e-15)
    p = np.zeros((n, n))
    p[np.arange(n), (c + 1 - np.arange(n)) % n] = 1.0
    rho = np.block([[-p, np.zeros((n, n))], [np.zeros((n, n)), p]])
    j = np.block([[np.zeros((n, n)), np.eye(n)], [-np.eye(n), np.zeros((n, n))]])
    qp, qm = q[:, :n], q[:, n:]
    assert np.allclose(rho @ qp, qp) and np.allclose(rho @ qm, -qm)
    assert np.allclose(qp.T @ j @ qp, 0.0) and np.allclose(j @ qp, qm)
    v = rv.pairing_basis(n, c)[5]
    assert np.allclose(qp @ v, np.r_[np.zeros(n), np.full(n, 1 / np.sqrt(n))])


@pytest.mark.parametrize("n, c", [(12, 0), (12, 3), (14, 13)])
def test_kernels_give_q_transpose_s_q(n, c):
    """The three row-wise kernels against Qᵀ R⁺ 𝓜 R Q with R⁺ = numpy's pseudo-inverse of
    diag(D, D), on a random 𝓜."""
    rng = np.random.default_rng(n + c)
    mat = rng.standard_normal((2 * n, 2 * n))
    d = np.roll(np.eye(n), 1, axis=1) - np.eye(n)  # (Du)_i = u_{i+1} − u_i
    r = np.block([[d, np.zeros((n, n))], [np.zeros((n, n)), d]])
    q = _dense_basis(n, c)
    want = q.T @ np.linalg.pinv(r) @ mat @ r @ q
    blk, ia, ib, ca, cb, _ = rv.pairing_basis(n, c)
    y = np.empty((2 * n, 2 * n))
    rk.m_times_rq(mat, n, blk, ia, ib, ca, cb, y)
    assert np.allclose(y, mat @ r @ q, atol=1e-13)
    rk.rpinv_rows(y, n, np.empty(2 * n), np.empty(2 * n))
    out = np.empty((2 * n, 2 * n))
    rk.qt_times(y, n, blk, ia, ib, ca, cb, out)
    assert np.max(np.abs(out - want)) < 1e-12 * np.abs(want).max()


def _roll(r, k: int):
    keep = ("law", "V", "w_left", "w_right", "m", "residual", "converged", "N")
    return types.SimpleNamespace(**{a: getattr(r, a) for a in keep},
                                 w=np.roll(r.w, k), wdot=np.roll(r.wdot, k))  # fmt: skip


def test_reversor_of_the_families_and_a_relabelled_ring():
    sw = wave.solve_solitary(LAW, 6.0, 5.0, N=120)
    sk = wave.solve_superkink(LAW, 5.2, N=120)
    c_sw, c_sk = fq.reversor_of(LAW, sw.w, sw.wdot), fq.reversor_of(LAW, sk.w, sk.wdot)
    for r, c in ((sw, c_sw), (sk, c_sk)):
        assert c is not None
        idx = (c - np.arange(r.N)) % r.N
        assert np.allclose(LAW.df(r.w), LAW.df(r.w[idx]), rtol=0, atol=1e-9)
    rolled = _roll(sw, 7)  # the same wave, sites relabelled: the centre moves by 2·7
    assert fq.reversor_of(LAW, rolled.w, rolled.wdot) == (c_sw + 14) % sw.N
    # the quartic law's superkink has no centre of reflection (f′ is not even about any w*)
    q = wave.solve_superkink(QUARTIC, 5.2, N=120)
    assert fq.reversor_of(QUARTIC, q.w, q.wdot) is None


def test_relabelled_ring_has_the_same_spectrum():
    sw = wave.solve_solitary(LAW, 6.0, 5.0, N=120)
    a = fq.spectrum(sw, finite_size=False, method="structured")
    b = fq.spectrum(_roll(sw, 7), finite_size=False, method="structured")
    assert a.route == b.route == "reversible"
    assert abs(a.max_modulus - b.max_modulus) <= max(a.error, b.error)
    assert a.n_unstable == b.n_unstable


FAMILIES = [
    (LAW, "superkink", 4.8, None),
    (LAW, "superkink", 5.5, None),
    (LAW, "superkink", 5.85, None),
    (LAW, "solitary", 4.5, 1.0),
    (LAW, "solitary", 5.3, 6.0),
    (QUARTIC, "solitary", 5.0, 1.0),
]


def _check_against_dense(mono, N: int, c: int, dense_error: float) -> dict:
    """Every λ_k of the route within δλ_k (its own claimed bound) plus the dense route's error of
    a λ from dense eigvals on the same 𝓜, and every dense λ found.  Multipliers within 1e-3 of 1
    are left out: dense eigvals splits the Jordan block there by √ε, so it is no reference."""
    out = rv.reversible_lambdas(mono.matrix, N, c)
    assert out is not None
    lam, per_k, info = out
    mu_d = np.linalg.eigvals(mono.matrix)
    mu_d = mu_d[np.abs(mu_d - 1.0) > 1e-3]
    lam_d = mu_d + 1.0 / mu_d
    d = np.abs(lam[:, None] - lam_d[None, :])
    mine = np.abs(mu_from_lambda(lam)[: lam.size] - 1.0) > 2e-3  # λ of multipliers away from 1
    assert mine.sum() >= lam_d.size // 2 - 2
    assert np.all(d.min(axis=1)[mine] <= per_k[mine] + 2.0 * dense_error)
    assert d.min(axis=0).max() <= per_k.max() + 2.0 * dense_error
    return info


@pytest.mark.parametrize("law, kind, V, w_plus", FAMILIES)
def test_every_lambda_within_its_bound_of_dense(law, kind, V, w_plus):
    N = 160
    r = (wave.solve_superkink(law, V, N=N) if kind == "superkink"
         else wave.solve_solitary(law, w_plus, V, N=N))  # fmt: skip
    mono = fq.monodromy(r)
    c = fq.reversor_of(law, r.w, r.wdot)
    mu_s, sums, _, info = fq.structured_multipliers(mono.matrix, N, mono.K, reversor=c)
    assert info["route"] == "reversible" and info["reversor"] == c
    a = fq.spectrum(r, finite_size=False, method="dense")
    rinfo = _check_against_dense(mono, N, c, a.error)
    assert info["lam_error"] < 1e-10 and rinfo["irreversibility"] < 1e-8 * rinfo["A_norm"]
    assert np.allclose(sums, a.multipliers[:2], atol=1e-13)


@pytest.mark.parametrize("eps", [1e-10, 1e-9])
def test_bound_holds_when_the_base_state_is_not_quite_reversible(eps):
    """A base state perturbed off symmetry (no longer a wave; its shifted monodromy is still
    symplectic): ‖G‖ + ‖F‖ grows ~100×–1000×, the first-order part of it cancels in A = S₁₁ + S₂₂ᵀ
    and the second-order remainder is covered.  With 2 S₁₁ (𝓜 + ρ𝓜ρ compressed) in place of A
    this fails: its λ move by ~‖G‖ + ‖F‖."""
    r = wave.solve_solitary(LAW, 6.0, 5.0, N=120)
    pert = eps * np.random.default_rng(1).standard_normal(r.N)
    rr = _roll(r, 0)
    rr.w = r.w + pert
    info = _check_against_dense(fq.monodromy(rr), r.N, 0, 1e-13)
    info0 = rv.reversible_lambdas(fq.monodromy(r).matrix, r.N, 0)[2]
    assert info["irreversibility"] > 30 * info0["irreversibility"]


def test_a_wrong_centre_falls_back_to_the_arnoldi_route():
    sk = wave.solve_superkink(LAW, 5.2, N=120)
    mono = fq.monodromy(sk)
    c = fq.reversor_of(LAW, sk.w, sk.wdot)
    assert rv.reversible_lambdas(mono.matrix, sk.N, (c + 1) % sk.N) is None
    mu1, _, _, i1 = fq.structured_multipliers(mono.matrix, sk.N, mono.K, reversor=(c + 1) % sk.N)
    mu0, _, _, i0 = fq.structured_multipliers(mono.matrix, sk.N, mono.K)
    assert i1["route"] == i0["route"] == "arnoldi"
    assert np.array_equal(mu1, mu0)


def test_the_non_reversible_quartic_superkink_takes_the_arnoldi_route():
    r = wave.solve_superkink(QUARTIC, 5.2, N=120)
    a = fq.spectrum(r, finite_size=False, method="dense")
    b = fq.spectrum(r, finite_size=False, method="structured")
    assert b.route == "arnoldi" and a.route == "dense"
    assert abs(a.max_modulus - b.max_modulus) <= max(a.error, b.error)
    assert a.n_unstable == b.n_unstable


@pytest.mark.parametrize("bad", [2.5, "0", True])
def test_a_reversor_that_is_no_site_index_is_refused(bad):
    mono = fq.monodromy(fq.HomogeneousState(LAW, 1.0, 5.0, 16))
    with pytest.raises(ParameterError) as e:
        fq.structured_multipliers(mono.matrix, 16, mono.K, reversor=bad)
    assert e.value.name == "reversor" and "integer" in str(e.value)
