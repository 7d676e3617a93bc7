"""The paper's Floquet statements at N = 500, a = −1, b = 10 (§6.1, §6.2; Figs. floquet_SK,
Floquet_example, floquet_cubicSW).  Six dense 1000 × 1000 spectra (~1 s each on an idle core);
the full sweeps live in benchmarks/bench_floquet.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from fpucore import floquet as fq
from fpucore import qc, wave
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)
N = 500
_CACHE: dict = {}


def _spec(kind: str, V: float, w_plus: float | None = None, n: int = N) -> fq.FloquetResult:
    key = (kind, V, w_plus, n)
    if key not in _CACHE:
        if kind == "superkink":
            r = wave.solve_superkink(LAW, V, N=n)
        else:
            r = wave.solve_solitary(LAW, w_plus, V, N=n)
        assert r.converged and r.residual < 1e-11, r.message
        _CACHE[key] = fq.spectrum(r)
    return _CACHE[key]


def _common(fr: fq.FloquetResult) -> None:
    """Structure every spectrum must show: quartets to 1e-9, the trivial multipliers at 1."""
    assert fr.multipliers.size == 2 * N
    assert fr.symmetry_error <= 1e-9
    assert fr.conjugate_error <= 1e-12
    assert fr.integrator_error <= 1e-9
    assert fr.n_trivial in (2, 4)
    assert fr.trivial_split < 1e-5
    assert np.all(np.abs(fr.multipliers[:2] - 1.0) < 1e-12)
    assert fr.converged, fr.message


def test_velocity_range_is_the_papers():
    lo, hi = qc.superkink_velocity_bounds(LAW)
    assert lo == pytest.approx(4.78423, abs=1e-5) and hi == pytest.approx(5.85947, abs=1e-5)


@pytest.mark.parametrize("V", [5.74, 5.75, 5.85])
def test_superkink_fast_end_stable_within_integrator_error(V):
    """§6.1 / Fig. floquet_SK: for V ≥ 5.74 max |μ| exceeds 1 by O(1e-8) at most, "linearly
    stable within the accuracy of numerical computation" — classified "stable"."""
    fr = _spec("superkink", V)
    _common(fr)
    assert fr.max_modulus - 1.0 <= 1e-8
    assert fr.max_modulus_away_from_1 - 1.0 <= fr.error  # below the error bar: not significant
    assert fr.classification == "stable" and fr.n_unstable == 0
    assert fr.verdict.startswith("stable:")


def test_superkink_mild_instability_bound_at_5_57():
    """|μ| < 1.0001 for V ≥ 5.57."""
    fr = _spec("superkink", 5.57)
    _common(fr)
    assert fr.max_modulus < 1.0001


def test_superkink_oscillatory_instability_at_5_2():
    """Fig. Floquet_example: at V = 5.2 complex quartets leave the unit circle (mildly)."""
    fr = _spec("superkink", 5.2)
    _common(fr)
    assert fr.n_unstable > 0 and fr.excess_significant
    assert 1.0 + 1e3 * fr.error < fr.max_modulus < 1.005
    quartets = fr.quartets()
    assert quartets and all(len(g) == 4 for g in quartets)  # oscillatory: non-real μ
    for g in quartets:
        mu = g[0]
        assert abs(mu.imag) > 1e-3
        assert np.allclose(g[1:], [np.conj(mu), 1 / np.conj(mu), 1 / mu], rtol=1e-9, atol=0)


def test_superkink_5_2_is_a_finite_size_artefact():
    """§6.1: "the Floquet multipliers associated with the oscillatory instabilities ... decrease
    as the chain size is increased ... a spurious artifact of the finite chain size".  The
    excess on the window 250 … 500 shrinks ∝ N^−p with p ≈ 1 (measured 0.99 ± 0.04)."""
    fr = _spec("superkink", 5.2)
    assert fr.classification == "finite_size", fr.verdict
    assert list(fr.finite_size_N) == [250, 300, 350, 400, 450, 500]
    assert np.all(np.diff(fr.finite_size_excess) < 0)
    assert 0.8 < fr.finite_size_exponent < 1.2
    assert fr.decision.reason == "decays" and fr.decision.headline.startswith("finite-size")
    assert fr.verdict.startswith("finite-size artefact")


def test_superkink_slow_end_below_1_005():
    """max |μ| grows toward the lower velocity bound but stays below 1.005."""
    fr = _spec("superkink", 4.8)
    _common(fr)
    assert fr.max_modulus < 1.005
    assert fr.max_modulus > _spec("superkink", 5.2).max_modulus  # overall growth as V decreases


def test_spurious_instability_shrinks_with_N():
    """The oscillatory instabilities are a finite-chain artifact: smaller at larger N.  At
    a fixed V quartets can also emerge and rejoin as N changes (e.g. V = 5.6); at V = 5.2 the
    leading quartet persists for N = 250 … 500 and its excess scales like 1/N."""
    big = _spec("superkink", 5.2)
    small = _spec("superkink", 5.2, n=250)
    assert small.symmetry_error <= 1e-9
    assert small.excess > 1.3 * big.excess
    # roughly 1/N (measured N·excess ≈ 0.27–0.28 for N = 250 … 500 at this V)
    assert 1.4 < small.excess / big.excess < 2.8


@pytest.mark.parametrize(
    "w_plus, V, bound",
    [(1.0, 5.38, 1.0006), (6.0, 5.21, 1.001)],  # just past / below V_SK, where the max is reached
)
def test_solitary_waves_below_paper_bounds(w_plus, V, bound):
    """Fig. floquet_cubicSW: max |μ| ≤ 1.0006 (w₊ = 1) and ≤ 1.001 (w₊ = 6)."""
    fr = _spec("solitary", V, w_plus)
    _common(fr)
    assert fr.n_trivial == 4  # sums + translation/velocity pair of a localized wave
    assert fr.max_modulus < bound
    # §6.2: "spurious oscillatory instabilities that are similar to the ones we saw in the case
    # of superkinks": the excess shrinks with N
    assert fr.classification == "finite_size", fr.verdict
    assert fr.decision.reason in ("absent", "dips", "decays")
