"""Flat-top solitary waves next to V_SK (paper Fig. stabSW, w₊ = 6, a = −1, b = 10) at the chain
size the user picks: N = 200 and the explorer's (and the paper's) N = 500.

Reference (independent of the solve on N): the wave on 128 sites refined in 80-bit long double with
4× the RK steps (:func:`test_error_bounds.reference`, its own accuracy = its last refinement step),
padded with the background state (its tails at the 128-site ends are < 1e-12; the exact wave lies
closer still to w_B farther out).  Each bound must cover the true error measured against it.
"""

from __future__ import annotations

import importlib.util
import math
import pathlib
import re

import numpy as np
import pytest

from fpucore import floquet, qc, wave
from fpucore.law import CubicLaw

# the long-double reference of the error-bound suite (tests use --import-mode=importlib)
_src = pathlib.Path(__file__).with_name("test_error_bounds.py")
_mod = importlib.util.spec_from_file_location("_wave_ld_reference", _src)
_ld = importlib.util.module_from_spec(_mod)
_mod.loader.exec_module(_ld)
reference = _ld.reference

LAW = CubicLaw(-1.0, 10.0)
V_SK6 = 7 * math.sqrt(5) / 3
# the paper's two velocities (δ = −9.5e-12 and +1.0e-10) and 1e-11 above V_SK
CASES = [5.21749194749, V_SK6 + 1e-11, 5.2174919476]
N_REF = 128


# Equally accurate re-solves (tighter tol: the mass continuation stops at another point of the
# round-off floor) — independent realisations of the plateau's round-off error.  That error is
# one signed number times the plateau mode (test_error_bounds.test_bounds_slow_cases); a single
# realisation can be arbitrarily small, so sharpness is judged against the largest.  Measured on
# the 2-core AMD EPYC: with OpenBLAS's Haswell kernels (its default here; bitwise the same with
# 1 or 2 threads and under load) the solve at the user's N alone gave bound/error 880
# (paper-below) and 106 (V_SK + 1e-11); OPENBLAS_CORETYPE=SandyBridge, Prescott or Nehalem move
# the wave by up to 3.1e-3 (the plateau mode) and give 14 and 35 — which machine passed depended
# on its BLAS kernel.  Over the three solves the ratio stays within 12 … 80 on every kernel.
RESOLVE_TOLS = (5e-13, 2e-13)
SHARP = 100.0


@pytest.fixture(scope="module", params=CASES, ids=["paper-below", "V_SK+1e-11", "paper-above"])
def flat_top(request):
    V = request.param
    spec = wave.solitary_spec(LAW, 6.0, V)
    r64 = wave.solve_solitary(LAW, 6.0, V, N=64)
    assert r64.converged, r64.message
    xl, off, acc = reference(LAW, spec, r64, N_REF, 4 * r64.m)
    w_ref = np.asarray(xl[0::2], float)
    resolves = [wave.solve_solitary(LAW, 6.0, V, N=64, tol=t) for t in RESOLVE_TOLS]
    errors = []
    for r in resolves:  # each covered by its own bound
        assert r.converged, r.message
        true = float(np.max(np.abs(r.w - _reference_on(r.N, w_ref, spec.w_left))))
        assert r.profile_error >= true + acc, (r.profile_error, true, acc)
        errors.append(true)
    return V, spec, w_ref, acc, r64, errors


def _reference_on(N, w_ref, w_B):
    """The reference on the N sites of a chain centred like it (padded with w_B, or cut)."""
    if N <= N_REF:
        return w_ref[N_REF // 2 - N // 2 : N_REF // 2 + N // 2]
    out = np.full(N, w_B)
    c = N // 2
    out[c - N_REF // 2 : c + N_REF // 2] = w_ref
    return out


@pytest.mark.parametrize("N", [200, 500])
def test_flat_tops_converge_at_the_users_N_with_covering_bounds(flat_top, N):
    V, spec, w_ref, acc, r64, errors = flat_top
    assert acc <= 2e-5, acc  # the reference resolves the errors measured (~1e-4 … 2e-3)
    r = wave.solve_solitary(LAW, 6.0, V, N=N)
    assert r.converged, r.message
    assert r.N == N and r.w.size == N
    true = float(np.max(np.abs(r.w - _reference_on(N, w_ref, spec.w_left))))
    assert r.profile_error >= true + acc, (r.profile_error, true, acc)
    largest = max(true, *errors)  # over equally accurate solves (RESOLVE_TOLS)
    assert r.profile_error <= SHARP * max(largest, acc), (r.profile_error, true, errors)
    amp_ref = abs(w_ref[N_REF // 2] - spec.w_left)
    assert r.amplitude_error >= abs(r.amplitude - amp_ref) - acc
    # the same wave as on the chain it needs (N = 64), and no worse a bound
    assert r.profile_error <= r64.profile_error * (1 + 1e-12)
    assert 0 < r.front_uncertainty < 1.0
    assert f"padded with w_B to N = {N}" in r.route


def test_distance_to_V_SK_is_printed_with_its_sign_and_never_as_a_negative_modulus():
    V = CASES[0]
    r = wave.solve_solitary(LAW, 6.0, V, N=200)
    v_sk = qc.sound_speeds(LAW, 6.0)[1]
    assert abs(v_sk - V_SK6) <= 1e-15 * V_SK6
    assert not re.search(r"\|V-V_SK\|\s*=\s*-", r.message), r.message
    assert f"V - V_SK = {V - V_SK6:+.2g}" in r.message  # −9.5e-12, the true distance
    assert "-9.5e-12" in r.message


def test_the_explorers_tolerance_at_N_64_is_no_worse_than_the_cli_default():
    """The explorer solves at tol 1e-10; at N = 64 this gave profile_error 0.65 against the
    CLI's 0.0499 (`fpu wave solitary --w-plus 6 --V 5.21749194749`): flat tops are now always
    solved to 1e-12 (their plateau length is fixed only by the residual's last digits)."""
    cli = wave.solve_solitary(LAW, 6.0, CASES[0])
    for N in (64, 500):
        r = wave.solve_solitary(LAW, 6.0, CASES[0], N=N, tol=1e-10)
        assert r.converged, r.message
        assert r.profile_error <= cli.profile_error * (1 + 1e-12), (N, r.profile_error)


@pytest.mark.parametrize("V", [CASES[0], CASES[2]], ids=["paper-below", "paper-above"])
def test_floquet_spectrum_of_the_papers_flat_tops_at_N_500(V):
    """Paper §6 (Fig. floquet_cubicSW(b), Fig. stabSW): max|μ| ≤ 1.001 at N = 500 and steady
    propagation.  The spectrum must compute, with its error bar and a classification."""
    r = wave.solve_solitary(LAW, 6.0, V, N=500)
    assert r.converged, r.message
    fr = floquet.spectrum(r)
    assert fr.multipliers.size == 2 * 500
    assert math.isfinite(fr.error) and fr.error < 1e-8
    assert fr.max_modulus <= 1.0015 + fr.error  # the paper's 1.001, printed to 3 decimals
    assert fr.classification != "unstable", fr.verdict
