"""Floquet layer at the edges of parameter space: spectra on stiff and extreme laws, checked
against closed forms
(constant states, computed here from the dispersion relation) and the quartet structure."""

import math

import numpy as np
import pytest

from fpucore import CubicLaw, ParameterError, floquet, qc, wave

STIFF = CubicLaw(-1.0, 100.0)  # f'(w*) = 3334: periods ~ 0.017, frequencies ~ 115
TINY_A = CubicLaw(-0.01, 10.0)
fq_classes = floquet.CLASSES  # w* = 333: strains in the hundreds


def _exact_constant_state(law, w0, V, N):
    """μ = exp(i(k ± ωT)), ω = 2√f'(w0)|sin(k/2)|, k = 2πj/N, T = 1/V (derived here, not read
    from the code): the shifted monodromy of the linear chain ÿ = f'(w0) Δy on the ring."""
    c = math.sqrt(float(law.df(w0)))
    k = 2 * np.pi * np.arange(N) / N
    om = 2 * c * np.abs(np.sin(k / 2))
    return np.concatenate([np.exp(1j * (k + om / V)), np.exp(1j * (k - om / V))])


def _set_distance(a, b):
    d_ab = np.max(np.min(np.abs(a[:, None] - b[None, :]), axis=1))
    d_ba = np.max(np.min(np.abs(b[:, None] - a[None, :]), axis=1))
    return max(d_ab, d_ba)


@pytest.mark.parametrize(
    "law,w0,V",
    [
        (STIFF, STIFF.w_star, 1.02 * math.sqrt(float(STIFF.df(STIFF.w_star)))),  # c ≈ 57.7
        (STIFF, 0.5 * STIFF.w_star, 60.0),
        (TINY_A, 0.9 * TINY_A.w_star, 60.0),
        (CubicLaw(-1.0, 10.0), 0.001, 1.05),  # soft end of the convex interval
    ],
)
def test_constant_state_spectrum_matches_dispersion_relation(law, w0, V):
    N = 48
    fr = floquet.spectrum(floquet.HomogeneousState(law, w0, V, N))
    exact = _exact_constant_state(law, w0, V, N)
    assert _set_distance(fr.multipliers, exact) < 1e-9
    assert abs(fr.max_modulus - 1.0) < 1e-9
    assert fr.symmetry_error < 1e-9
    assert fr.classification == "stable" and fr.verdict.startswith("stable:")


@pytest.mark.parametrize("law,frac", [(STIFF, 0.5), (TINY_A, 0.5), (CubicLaw(-1, 10), 0.02)])
def test_superkink_spectrum_on_extreme_laws(law, frac):
    """Quartet symmetry (independent of the integrator's own estimate) and a finite, bounded
    spectrum; frac places V inside (V_lo, V_hi) (0.02: w± near the edges, f'(w±) -> 0)."""
    lo, hi = qc.superkink_velocity_bounds(law)
    V = lo + frac * (hi - lo)
    r = wave.solve_superkink(law, V, N=96)
    assert r.converged, r.message
    fr = floquet.spectrum(r)
    assert np.all(np.isfinite(fr.multipliers)) and fr.multipliers.size == 2 * r.N
    assert fr.symmetry_error < 1e-9
    assert fr.error < 1e-6
    # the |μ| excess is either real (beyond the error bar, listed as unstable) or noise
    assert fr.excess_significant == (fr.n_unstable > 0)
    # and decided with its evidence: stable, or the window of rings in [N/2, N] (from the
    # shortest ring the wave solver accepts, 64)
    assert fr.classification in fq_classes
    if fr.classification != "stable":
        ns, full = list(fr.finite_size_N), floquet.chain_lengths(r.N, 64)
        assert ns[-1] == r.N and ns[:-1] == full[: len(ns) - 1]  # shortest first, may stop
    assert fr.max_modulus_away_from_1 < 1.05


def test_refusals():
    r = wave.solve_superkink(CubicLaw(), 5.2, N=64)
    with pytest.raises(ParameterError, match="m="):
        floquet.spectrum(r, m=1)
    with pytest.raises(ParameterError, match="N="):
        floquet.HomogeneousState(CubicLaw(), 1.0, 5.0, 7)
    with pytest.raises(ParameterError, match="w0="):
        floquet.HomogeneousState(CubicLaw(), 50.0, 5.0, 16)


def test_huge_chain_is_refused_before_any_work():
    """Dense eig is O(N^3): above the cap the request is refused (no hang), naming N."""
    with pytest.raises(ParameterError, match=r"N=2600 .*N <= 2500"):
        floquet.spectrum(floquet.HomogeneousState(CubicLaw(), 1.0, 5.0, 2600))


@pytest.mark.parametrize("route", ["reversible", "arnoldi"])
@pytest.mark.parametrize("law,frac", [(STIFF, 0.2), (STIFF, 0.6), (TINY_A, 0.5),
                                      (CubicLaw(-1, 10), 0.02)])  # fmt: skip
def test_structured_route_agrees_with_dense_on_extreme_laws(law, frac, route, monkeypatch):
    """Both structured routes (the quarter-size reversible one these superkinks take,
    and the half-size Arnoldi one, forced by hiding the reversor) against dense eigvals on the
    same 𝓜 — max|μ| within the error bar, the same unstable multipliers and classification."""
    if route == "arnoldi":
        monkeypatch.setattr(floquet.spectrum_steps, "reversor_of", lambda *a: None)
    lo, hi = qc.superkink_velocity_bounds(law)
    r = wave.solve_superkink(law, lo + frac * (hi - lo), N=96)
    a = floquet.spectrum(r, method="dense")
    b = floquet.spectrum(r, method="structured")
    assert b.route == route
    assert b.converged == a.converged, b.message
    assert abs(a.max_modulus_away_from_1 - b.max_modulus_away_from_1) <= max(a.error, b.error)
    assert a.n_unstable == b.n_unstable
    assert a.classification == b.classification


def test_unstable_constant_state_on_the_stiff_law():
    """f′(w0) < 0 beyond β of the stiff law: |μ| = e^{2√(−f′)/V} (derived in
    tests/floquet/test_finite_size.py), classified unstable by both routes."""
    w0 = 1.05 * float(STIFF.beta)
    fp = float(STIFF.df(w0))
    assert fp < 0
    V = 60.0
    for method in ("dense", "structured"):
        fr = floquet.spectrum(floquet.HomogeneousState(STIFF, w0, V, 32, convex=False),
                              method=method)  # fmt: skip
        assert fr.classification == "unstable"
        assert fr.growth_rate == pytest.approx(2 * math.sqrt(-fp), rel=1e-9)
