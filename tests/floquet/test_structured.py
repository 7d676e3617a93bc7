"""The structured half-size spectrum (issue 17) against closed forms and the dense reference.

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
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def _set_distance(a: np.ndarray, b: np.ndarray) -> float:
    d = np.abs(a[:, None] - b[None, :])
    return float(max(d.min(axis=0).max(), d.min(axis=1).max()))


@pytest.mark.parametrize("w0, V, N, convex", [(1.0, 5.0, 40, True), (0.3, 4.0, 64, True),
                                              (7.0, 5.0, 40, False)])  # fmt: skip
def test_constant_state_closed_form(w0, V, N, convex):
    """μ = e^{ik} e^{±iωT} (f′ > 0) or e^{ik} e^{±σT} (f′ < 0), k = 2πj/N, derived here.  The
    homogeneous ring has degenerate λ (k and −k), so the Arnoldi process restarts."""
    c2 = float(LAW.df(w0))
    k = 2 * np.pi * np.arange(N) / N
    s = 2 * math.sqrt(abs(c2)) * np.abs(np.sin(k / 2)) / V
    ph = 1j * s if c2 > 0 else s
    exact = np.concatenate([np.exp(1j * k + ph), np.exp(1j * k - ph)])
    fr = fq.spectrum(fq.HomogeneousState(LAW, w0, V, N, convex=convex), method="structured")
    assert fr.method == "structured" and fr.converged, fr.message
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
def test_agrees_with_dense_over_the_paper_families(kind, V, w_plus):
    N = 200
    if kind == "superkink":
        r = wave.solve_superkink(LAW, V, N=N)
    else:
        r = wave.solve_solitary(LAW, w_plus, V, N=N)
    a = fq.spectrum(r, finite_size=False)
    b = fq.spectrum(r, finite_size=False, method="structured")
    assert b.converged, b.message
    assert abs(a.max_modulus_away_from_1 - b.max_modulus_away_from_1) <= max(a.error, b.error)
    assert a.n_unstable == b.n_unstable and a.n_trivial == b.n_trivial
    assert a.excess_significant == b.excess_significant
    away = np.abs(a.multipliers - 1.0) > 1e-2
    d = np.abs(b.multipliers[None, :] - a.multipliers[away][:, None]).min(axis=1)
    assert d.max() < 1e-9  # every multiplier away from 1 is found by both
    assert b.error < 1e-9 and b.structure_error < 1e-10
    assert np.max(np.abs(b.multipliers[:2] - a.multipliers[:2])) < 1e-13  # conservation pair


def test_same_classification_with_finite_size_test():
    r = wave.solve_solitary(LAW, 1.0, 5.3, N=200)
    a = fq.spectrum(r)
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
