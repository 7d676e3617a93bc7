"""Three-way classification of a Floquet spectrum (issue 12): stable / finite_size / unstable.

References: a genuinely unstable constant state (f′ < 0) whose multipliers and growth rate are
derived here in closed form; synthetic point sets with a known law for the fits.  The paper's
waves (superkink V = 5.2, 5.75, solitary waves) are in tests/paper/test_floquet_paper.py.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from fpucore import floquet as fq
from fpucore import wave
from fpucore.cli import main as cli_main
from fpucore.errors import ParameterError
from fpucore.floquet import finite_size as fs
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def _set_distance(a: np.ndarray, b: np.ndarray) -> float:
    d = np.abs(a[:, None] - b[None, :])
    return float(max(d.min(axis=0).max(), d.min(axis=1).max()))


@pytest.mark.parametrize("w0, V, N", [(7.0, 5.0, 40), (-0.2, 2.0, 48)])
def test_unstable_constant_state_with_known_growth_rate(w0, V, N):
    """w0 outside (α, β): f′(w0) < 0, ÿ = f′Δy has growing modes e^{σt}, σ = 2√(−f′)|sin(k/2)|.
    Derived here: the fastest mode k = π (on the grid for even N) gives |μ| = e^{2√(−f′)/V} at
    every even N, so the excess does not shrink with N: a genuine instability."""
    fp = -3.0 * w0**2 + 20.0 * w0 + 1.0  # f′ of f = −w³ + 10w² + w
    assert fp < 0 and fp == pytest.approx(float(LAW.df(w0)), rel=1e-14)
    sigma = 2.0 * math.sqrt(-fp)
    k = 2 * np.pi * np.arange(N) / N
    s = 2 * math.sqrt(-fp) * np.abs(np.sin(k / 2)) / V
    exact = np.concatenate([np.exp(1j * k + s), np.exp(1j * k - s)])

    fr = fq.spectrum(fq.HomogeneousState(LAW, w0, V, N, convex=False))
    assert _set_distance(fr.multipliers, exact) < 1e-9 * np.abs(exact).max()
    assert fr.max_modulus == pytest.approx(math.exp(sigma / V), rel=1e-12)
    assert fr.growth_rate == pytest.approx(sigma, rel=1e-11)
    assert fr.classification == "unstable" and fr.finite_size_checked
    assert list(fr.finite_size_N) == fq.chain_lengths(N) + [N]
    assert np.allclose(fr.finite_size_excess, math.exp(sigma / V) - 1.0, rtol=1e-11)
    assert abs(fr.finite_size_exponent) < 1e-6  # no decay with N at all
    assert fr.extrapolated_excess == pytest.approx(math.exp(sigma / V) - 1.0, rel=1e-9)
    assert fr.verdict.startswith("unstable:") and "does not shrink" in fr.verdict


def test_stable_constant_state_is_stable_without_extra_spectra():
    fr = fq.spectrum(fq.HomogeneousState(LAW, 1.0, 5.0, 40))
    assert fr.classification == "stable" and fr.verdict.startswith("stable:")
    assert list(fr.finite_size_N) == [40] and math.isnan(fr.finite_size_exponent)
    assert fr.finite_size_s < 0.01


def test_homogeneous_state_refuses_degenerate_or_nonconvex_by_default():
    with pytest.raises(ParameterError, match="w0"):
        fq.HomogeneousState(LAW, 7.0, 5.0, 40)  # convex=True by default
    alpha = float(LAW.alpha)
    with pytest.raises(ParameterError, match="w0"):
        fq.HomogeneousState(LAW, alpha, 5.0, 40, convex=False)  # f′ = 0 exactly
    with pytest.raises(ParameterError, match="w0"):
        fq.homogeneous_multipliers(LAW, alpha, 5.0, 40)


def test_finite_size_off_says_so():
    fr = fq.spectrum(fq.HomogeneousState(LAW, 7.0, 5.0, 40, convex=False), finite_size=False)
    assert fr.classification == "unstable" and not fr.finite_size_checked
    assert list(fr.finite_size_N) == [40]
    assert "not tested for a finite-size effect" in fr.verdict and "finite_size=False" in fr.verdict


# ----------------------------------------------------------------------------- the fits
def test_fits_recover_known_laws():
    N = np.array([250.0, 334.0, 500.0])
    err = np.full(3, 1e-13)
    p, dp = fs.fit_power_law(N, 0.28 / N, err)
    assert p == pytest.approx(1.0, abs=1e-12) and dp < 1e-6
    p, _ = fs.fit_power_law(N, 3.0 * N**-2.5, err)
    assert p == pytest.approx(2.5, abs=1e-12)
    e_inf, de = fs.extrapolate(N, 0.01 + 0.3 / N, err)
    assert e_inf == pytest.approx(0.01, abs=1e-12) and de < 1e-11


@pytest.mark.parametrize(
    "e, expected",
    [
        (0.28 / np.array([250, 334, 500]), "finite_size"),  # the paper's 1/N law
        (np.array([1e-3, 1e-3, 1e-3]), "unstable"),  # does not shrink
        (0.01 + 0.3 / np.array([250, 334, 500]), "unstable"),  # shrinks to a positive limit
        (np.array([2e-3, 9e-4, 1e-13]), "stable"),  # within the error bar at the requested N
        (np.array([3e-5, 7e-5, 6e-5]), "unstable"),  # grows (quartets emerging/rejoining)
        (np.array([1.9e-4, 1e-14, 1.8e-4]), "finite_size"),  # absent on a shorter ring
    ],
)
def test_classify_synthetic(e, expected):
    N = np.array([250, 334, 500])
    assert fs.classify(N, e, np.full(3, 2e-13))["classification"] == expected


def test_classify_needs_three_lengths():
    out = fs.classify(np.array([250, 500]), np.array([2e-3, 1e-3]), np.full(2, 1e-13))
    assert out["classification"] == "unstable" and not out["checked"]


def test_chain_lengths_cost_no_more_than_requested():
    for N in (80, 100, 128, 160, 200, 500, 1000):
        ns = fs.chain_lengths(N, 64)
        assert len(ns) == 2 and all(64 <= n < N and n % 2 == 0 for n in ns)
        if N >= 160:  # below, the shortest wave chain (64) is > 0.4N: small, cheap spectra
            assert sum((n / N) ** 3 for n in ns) <= 0.6  # dense eig ∝ N³
    assert fs.chain_lengths(64, 64) == [] and fs.chain_lengths(500) == [200, 300]


# ----------------------------------------------------------------------------- waves
def test_smaller_chain_waves_equal_fresh_solves():
    """The truncated-wave predictor gives the same N_k wave as a solve from the QC guess."""
    r = wave.solve_superkink(LAW, 5.3, N=200)
    rk, why = fs.base_at(r, 100)
    assert rk is not None and rk.converged, why
    ref = wave.solve_superkink(LAW, 5.3, N=100)
    assert np.max(np.abs(rk.w - ref.w)) < 1e-10 and rk.N == 100


def test_short_chain_superkink_is_classified_with_evidence():
    r = wave.solve_superkink(LAW, 5.2, N=128)
    fr = fq.spectrum(r)
    assert fr.classification == "finite_size", fr.verdict
    assert list(fr.finite_size_N) == [64, 96, 128]
    assert np.all(np.diff(fr.finite_size_excess) < 0)
    assert 0.5 < fr.finite_size_exponent < 1.5  # ~1/N (measured 0.95–1.05 at N = 128 … 500)


def test_cli_json_has_classification(capsys):
    assert cli_main(["floquet", "superkink", "--V", "5.2", "--N", "128", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["classification"] == "finite_size"
    assert 0.5 < d["finite_size_exponent"] < 1.5
    assert d["finite_size_N"] == [64, 96, 128] and len(d["finite_size_excess"]) == 3
    for k in ("extrapolated_excess", "extrapolated_excess_error", "finite_size_exponent_error",
              "growth_rate", "verdict", "finite_size_checked"):  # fmt: skip
        assert k in d
    assert cli_main(["floquet", "superkink", "--V", "5.2", "--N", "128", "--json",
                     "--no-finite-size"]) == 0  # fmt: skip
    d = json.loads(capsys.readouterr().out)
    assert d["finite_size_N"] == [128] and not d["finite_size_checked"]
