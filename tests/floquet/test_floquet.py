"""Floquet spectrum (paper §6, eqs. linear, linear_map): closed forms and structure, small N.

The paper's N = 500 statements are in tests/test_floquet_paper.py.
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import linear_sum_assignment

from fpucore import floquet as fq
from fpucore import wave
from fpucore.atlas import sweeps as fsw
from fpucore.cli import main as cli_main
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def _match(a: np.ndarray, b: np.ndarray) -> float:
    """Largest distance of the optimal one-to-one matching of two multiplier sets."""
    c = np.abs(a[:, None] - b[None, :])
    i, j = linear_sum_assignment(c)
    return float(c[i, j].max())


# ----------------------------------------------------------------------------- homogeneous state
@pytest.mark.parametrize(
    "w0, V, N",
    [(1.0, 5.3, 40), (0.3, 4.0, 64), (6.0, 5.0, 100), (-0.04, 1.7, 30), (3.3, 5.9, 48)],
)
@pytest.mark.parametrize("method", fq.METHODS)
def test_homogeneous_state_matches_dispersion_relation(w0, V, N, method):
    """Constant strain: μ = exp(i(k ± ωT)), ω² = 4 f′(w0) sin²(k/2), k = 2πj/N, T = 1/V.
    Dense: every μ to 1e-11.  Structured: every μ within its route's bound on μ,
    δλ / max(|μ − 1/μ|, √δλ) ≤ √δλ (δλ = structure_error; measured 1.1e-11 next to μ = 1 at
    w0 = 3.3, more than dense's 1e-11), and |μ| = 1 exactly as dense."""
    fr = fq.spectrum(fq.HomogeneousState(LAW, w0, V, N), method=method)
    exact = fq.homogeneous_multipliers(LAW, w0, V, N)
    assert np.allclose(np.abs(exact), 1.0, atol=1e-15)
    bound = 1e-11 if method == "dense" else math.sqrt(fr.structure_error)
    assert _match(fr.multipliers, exact) < bound
    assert abs(fr.max_modulus - 1.0) < 1e-12
    assert fr.symmetry_error < 1e-12
    assert fr.classification == "stable" and fr.n_unstable == 0
    # the conservation pair is exactly 1 (deflated), the quotient block is [[1, T], [0, 1]]
    assert np.all(np.abs(fr.multipliers[:2] - 1.0) < 1e-13)
    assert fr.multipliers.size == 2 * N


def test_homogeneous_monodromy_equals_matrix_exponential():
    """Second method: Ψ(T) = expm(A T) for ÿ = c²Δy on the ring; 𝓜 = rows shifted up by one."""
    w0, V, N = 0.7, 5.1, 24
    c2 = float(LAW.df(w0))
    eye = np.eye(N)
    lap = -2 * eye + np.roll(eye, 1, 0) + np.roll(eye, -1, 0)
    A = np.block([[np.zeros((N, N)), eye], [c2 * lap, np.zeros((N, N))]])
    psi = scipy.linalg.expm(A / V)
    M_ref = np.vstack([np.roll(psi[:N], -1, axis=0), np.roll(psi[N:], -1, axis=0)])
    mono = fq.monodromy(fq.HomogeneousState(LAW, w0, V, N), m=40)
    assert np.max(np.abs(mono.matrix - M_ref)) < 1e-12
    # and the derivation of the closed form itself, against the exact exponential
    assert _match(scipy.linalg.eigvals(M_ref), fq.homogeneous_multipliers(LAW, w0, V, N)) < 1e-7


def test_phonon_gap_closed_form_and_subsonic_warning():
    # supersonic: nearest phonon multiplier at k = 2π/N, |μ−1| ≈ (2π/N)(1 − c/V)
    w0, V, N = 1.0, 6.0, 400
    c = math.sqrt(float(LAW.df(w0)))
    assert fq.phonon_gap(LAW, w0, V, N) == pytest.approx(2 * np.pi / N * (1 - c / V), rel=1e-3)
    # subsonic V = phase velocity of the mode j = 5 (ω/k): that phonon's multiplier is exactly
    # 1, so the trivial cluster cannot be told from the continuous spectrum — reported, not hidden
    N, j = 40, 5
    k = 2 * np.pi * j / N
    V = 2 * c * np.sin(k / 2) / k
    assert fq.phonon_gap(LAW, w0, V, N) < 1e-12
    fr = fq.spectrum(fq.HomogeneousState(LAW, w0, V, N))
    assert not fr.converged and "phonon gap" in fr.message
    assert fq.spectrum(fq.HomogeneousState(LAW, w0, 6.0, N)).converged


# ----------------------------------------------------------------------------- structure measures
def test_quartet_symmetry_error_measures_violation():
    mu = 1.01 * np.exp(0.3j)
    q = np.array([mu, np.conj(mu), 1 / mu, 1 / np.conj(mu), np.exp(1j), np.exp(-1j)])
    sym, conj = fq.quartet_symmetry_error(q)
    assert sym < 1e-15 and conj == 0.0
    d = 1e-7
    sym, _ = fq.quartet_symmetry_error(np.concatenate([q, [(1 + d) * np.exp(2j)]]))
    assert sym == pytest.approx(2 * d, rel=1e-3)  # elliptic multiplier off the circle: 2δ
    bad = q.copy()
    bad[2] *= 1 + 1e-6
    sym, _ = fq.quartet_symmetry_error(bad)
    assert 5e-7 < sym < 2e-6


def test_deflation_keeps_the_spectrum():
    rng = np.random.default_rng(1)
    N = 12
    M = rng.standard_normal((2 * N, 2 * N))
    # impose the ring's conservation laws: Σ rows of each block → [[1, T], [0, 1]] on the sums
    T = 0.2
    ones = np.ones(N)
    for j in range(2 * N):
        e_y, e_v = (1.0 if j < N else 0.0), (1.0 if j >= N else 0.0)
        M[:N, j] += ((e_y + T * e_v) - ones @ M[:N, j]) / N
        M[N:, j] += (e_v - ones @ M[N:, j]) / N
    rest, sums, defect = fq.multipliers_of(M, N)
    assert defect < 1e-13
    assert np.allclose(sums, 1.0, atol=1e-13)
    assert _match(np.concatenate([rest, sums]), scipy.linalg.eigvals(M)) < 1e-6


# ----------------------------------------------------------------------------- traveling waves
@pytest.fixture(scope="module")
def solitary_small():
    r = wave.solve_solitary(LAW, 1.0, 5.0, N=80)
    assert r.converged
    return r


@pytest.fixture(scope="module")
def superkink_small():
    r = wave.solve_superkink(LAW, 5.5, N=80)
    assert r.converged
    return r


def test_time_derivative_of_the_wave_is_a_multiplier_one_eigenvector(solitary_small):
    """(ẇ, ẅ) of the base orbit is mapped to itself by the shifted monodromy (translation)."""
    r = solitary_small
    mono = fq.monodromy(r)
    wp = np.concatenate([[r.w_left], r.w, [r.w_right]])
    g = LAW.f(wp)
    xi = np.concatenate([r.wdot, g[2:] - 2 * g[1:-1] + g[:-2]])
    assert np.max(np.abs(mono.matrix @ xi - xi)) < 1e-9 * np.max(np.abs(xi))


def test_monodromy_matches_scipy_variational_integration():
    """Second method: scipy DOP853 on the base orbit + the dense variational matrix (ring BC)."""
    from scipy.integrate import solve_ivp

    r = wave.solve_superkink(LAW, 5.2, N=64)
    N, law = r.N, r.law

    def rhs(t, y):
        w, wd = y[:N], y[N : 2 * N]
        Y = y[2 * N :].reshape(2 * N, 2 * N)
        f = law.f(np.concatenate(([r.w_left], w, [r.w_right])))
        G = law.df(w)[:, None] * Y[:N]
        dY = np.concatenate([Y[N:], np.roll(G, -1, 0) - 2.0 * G + np.roll(G, 1, 0)])
        return np.concatenate((wd, f[2:] - 2.0 * f[1:-1] + f[:-2], dY.ravel()))

    y0 = np.concatenate((r.w, r.wdot, np.eye(2 * N).ravel()))
    sol = solve_ivp(rhs, (0.0, 1.0 / r.V), y0, method="DOP853", rtol=1e-12, atol=1e-14)
    psi = sol.y[2 * N :, -1].reshape(2 * N, 2 * N)
    M_ref = np.vstack([np.roll(psi[:N], -1, axis=0), np.roll(psi[N:], -1, axis=0)])
    M = fq.monodromy(r).matrix
    assert np.max(np.abs(M - M_ref)) < 1e-9 * np.max(np.abs(M_ref))
    fr = fq.spectrum(r)
    assert _match(fr.multipliers, scipy.linalg.eigvals(M_ref)) < 1e-6


def test_trivial_cluster_solitary(solitary_small):
    fr = fq.spectrum(solitary_small)
    assert fr.n_trivial == 4
    d = np.sort(np.abs(fr.trivial - 1.0))
    assert d[1] < 1e-13  # the exactly deflated conservation pair
    assert d[3] < 1e-5  # translation / velocity pair, split by round-off only
    assert fr.symmetry_error <= 1e-9
    away = fr.multipliers[np.abs(fr.multipliers - 1.0) >= fr.trivial_radius]
    assert fr.max_modulus_away_from_1 == pytest.approx(np.abs(away).max(), rel=0, abs=0)


def test_trivial_cluster_superkink(superkink_small):
    """For a kink, translation changes the total strain: the translation mode *is* the
    conservation Jordan block, so deflating the sums leaves nothing at 1."""
    fr = fq.spectrum(superkink_small)
    assert fr.n_trivial == 2
    assert fr.trivial_split < 1e-13
    assert np.min(np.abs(fr.multipliers[2:] - 1.0)) > 10 * fr.trivial_radius
    # without the deflation the same block is split by round-off (the paper's O(1e-8))
    raw = scipy.linalg.eigvals(fq.monodromy(superkink_small).matrix)
    split = np.sort(np.abs(raw - 1.0))[:2]
    assert np.all(split < 1e-5)


def test_result_fields_and_quartets(superkink_small):
    fr = fq.spectrum(superkink_small)
    assert fr.multipliers.dtype == complex and fr.multipliers.size == 2 * superkink_small.N
    assert fr.elapsed_s > 0 and fr.eig_s > 0 and fr.monodromy_s > 0
    assert fr.integrator_error < 1e-10 and fr.error >= fr.symmetry_error
    assert fr.max_modulus >= fr.max_modulus_away_from_1
    for g in fr.quartets():
        mu = g[0]
        assert abs(mu) - 1 > fr.error
        assert np.allclose(g[1:], [np.conj(mu), 1 / np.conj(mu), 1 / mu], atol=1e-9)
    d = fr.as_dict()
    for k in ("max_modulus", "max_modulus_away_from_1", "multipliers_re", "multipliers_im",
              "symmetry_error", "elapsed_s", "wave"):  # fmt: skip
        assert k in d


def test_bad_input():
    with pytest.raises(ParameterError, match="r="):
        fq.spectrum(object())
    with pytest.raises(ParameterError, match="m="):
        fq.spectrum(fq.HomogeneousState(LAW, 1.0, 5.0, 10), m=0)
    with pytest.raises(ParameterError, match="w0"):
        fq.HomogeneousState(LAW, 100.0, 5.0, 10)
    with pytest.raises(ParameterError, match="N="):
        fq.HomogeneousState(LAW, 1.0, 5.0, 7)


# ----------------------------------------------------------------------------- sweep and cache
def test_cache_key_covers_inputs_and_code(tmp_path, monkeypatch):
    """The on-disk sweep cache is keyed on the inputs and the code version."""
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    k1 = fsw.cache_key(LAW, "superkink", [5.5], 80, None, "lower", None, 1e-12)
    k2 = fsw.cache_key(LAW, "superkink", [np.nextafter(5.5, 6.0)], 80, None, "lower", None, 1e-12)
    assert k1 != k2 and fsw.cache_path(k1) != fsw.cache_path(k2)
    monkeypatch.setattr(fsw, "source_hash", lambda: "0123456789ab")  # an edited copy of fpucore
    k3 = fsw.cache_key(LAW, "superkink", [5.5], 80, None, "lower", None, 1e-12)
    assert k3["fpucore_source"] != k1["fpucore_source"] and fsw.cache_path(k3) != fsw.cache_path(k1)


def test_sweep_is_cached_and_reports_progress(tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    calls = []
    V = [5.45, 5.5]
    s1 = fsw.sweep(LAW, "superkink", V, N=64, progress=lambda *a: calls.append(a))
    assert [c[0] for c in calls] == [1, 2] and not s1.cached.any()
    assert s1.converged and s1.status == "ok" and np.all(np.isfinite(s1.max_modulus))
    assert np.all(s1.max_modulus_error < 1e-9)
    s2 = fsw.sweep(LAW, "superkink", V, N=64)
    assert s2.cached.all()
    assert np.array_equal(s1.max_modulus, s2.max_modulus)
    monkeypatch.setattr(fsw, "source_hash", lambda: "0123456789ab")  # the code changed: a miss
    s3 = fsw.sweep(LAW, "superkink", V, N=64)
    assert not s3.cached.any() and np.array_equal(s1.max_modulus, s3.max_modulus)
    out = tmp_path / "t.csv"
    s2.to_csv(out)
    lines = out.read_text().splitlines()
    assert lines[0].split(",") == [*fsw.COLUMNS, "cached"] and len(lines) == 3
    assert "max_modulus_error" in fsw.COLUMNS and "error" not in fsw.COLUMNS  # the atlas's names


def test_sweep_bad_input():
    with pytest.raises(ParameterError, match="w_plus"):
        fsw.sweep(LAW, "solitary", [5.0])
    with pytest.raises(ParameterError, match="V="):
        fsw.sweep(LAW, "superkink", [5.5, 7.0], N=64)
    with pytest.raises(ParameterError, match="kind"):
        fsw.sweep(LAW, "breather", [5.5])


# ----------------------------------------------------------------------------- CLI
def test_cli_json(capsys):
    assert cli_main(["floquet", "solitary", "--w-plus", "6", "--V", "4.5", "--N", "64",
                     "--json"]) == 0  # fmt: skip
    d = json.loads(capsys.readouterr().out)
    for k in ("max_modulus", "max_modulus_away_from_1", "multipliers_re", "multipliers_im",
              "symmetry_error", "elapsed_s", "wave", "verdict", "error"):  # fmt: skip
        assert k in d
    assert len(d["multipliers_re"]) == 128 and d["wave"]["kind"] == "compressive"
    assert d["symmetry_error"] < 1e-9


def test_cli_bad_input(capsys):
    assert cli_main(["floquet", "superkink", "--V", "9.0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("fpu: error: V=9") and "\n" not in err


def test_cli_sweep_csv(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "c"))
    out = tmp_path / "s.csv"
    rc = cli_main(["floquet", "sweep", "superkink", "--V", "5.5", "--N", "64", "80",
                   "--out", str(out), "--no-progress"])  # fmt: skip
    assert rc == 0
    with open(out) as fh:  # one header, then a row per (N, V), under the atlas's names
        rows = list(csv.DictReader(fh))
    got = [(r["N"], r["V"], r["status"]) for r in rows]
    assert got == [("64", "5.5", "ok"), ("80", "5.5", "ok")]
    assert all(float(r["max_modulus_error"]) < 1e-9 for r in rows)
