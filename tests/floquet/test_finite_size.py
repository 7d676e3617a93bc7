"""The stability decision of a Floquet spectrum: stable / finite_size / unstable / undetermined.

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
    assert fr.decision.spread < 1e-9  # no change with N at all
    assert fr.extrapolated_excess == pytest.approx(math.exp(sigma / V) - 1.0, rel=1e-9)
    assert fr.verdict.startswith("unstable:") and "on every ring" in fr.verdict
    assert fr.decision.reason == "persists" and fr.decision.next_step == ""


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
    """Without the test an excess is not called unstable: "undetermined", saying what was not
    run and what would decide it."""
    fr = fq.spectrum(fq.HomogeneousState(LAW, 7.0, 5.0, 40, convex=False), finite_size=False)
    assert fr.classification == "undetermined" and not fr.finite_size_checked
    assert list(fr.finite_size_N) == [40]
    assert "was not run (finite_size=False)" in fr.verdict
    assert fr.decision.next_step and fr.decision.next_step in fr.verdict


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


def test_chain_lengths_span_half_to_N():
    for N in (128, 160, 200, 500, 1000):
        ns = fs.chain_lengths(N, 64)
        assert len(ns) == fs.WINDOW - 1 and ns == sorted(ns)
        assert all(64 <= n < N and n % 2 == 0 for n in ns)
        assert ns[0] == max(64, N // 2 + (N // 2) % 2) or abs(ns[0] - N / 2) <= 1
    assert fs.chain_lengths(500) == [250, 300, 350, 400, 450]
    # a window narrower than [3N/4, N] is no test
    assert fs.chain_lengths(64, 64) == [] and fs.chain_lengths(80, 64) == []


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
    ns, full = list(fr.finite_size_N), fs.chain_lengths(128, 64)
    # shortest first; the window stops once an absent excess or a dip has decided it
    assert ns[-1] == 128 and ns[:-1] == full[: len(ns) - 1] and ns[0] == 64
    assert len(ns) == len(full) + 1 or fr.decision.reason in ("absent", "dips")


def test_cli_json_has_classification(capsys):
    assert cli_main(["floquet", "superkink", "--V", "5.2", "--N", "128", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["classification"] == "finite_size"
    assert d["finite_size_N"][0] == 64 and d["finite_size_N"][-1] == 128
    assert len(d["finite_size_excess"]) == len(d["finite_size_N"])
    dec = d["decision"]
    assert dec["classification"] == d["classification"] and dec["sentence"] == d["verdict"]
    assert dec["headline"].startswith("finite-size artefact")
    for k in ("extrapolated_excess", "extrapolated_excess_error", "finite_size_exponent_error",
              "growth_rate", "verdict", "finite_size_checked"):  # fmt: skip
        assert k in d
    assert cli_main(["floquet", "superkink", "--V", "5.2", "--N", "128", "--json",
                     "--no-finite-size"]) == 0  # fmt: skip
    d = json.loads(capsys.readouterr().out)
    assert d["finite_size_N"] == [128] and not d["finite_size_checked"]
    assert cli_main(["floquet", "superkink", "--V", "5.2", "--N", "128", "--json",
                     "--method", "structured"]) == 0  # fmt: skip
    d = json.loads(capsys.readouterr().out)
    assert d["method"] == "structured" and d["classification"] == "finite_size"
