"""Floquet spectra of a trilinear superkink: the monodromy is integrated along the event-located
base trajectory (identity saltation, f′ switched at each located crossing).  Checks that can
fail: the quartet symmetry of a Hamiltonian flow, the step-halving change of every multiplier
against the reported error bar, and the finite-size verdict (the excess decays with N)."""

import numpy as np
import pytest

import fpucore as F
from fpucore.law import TrilinearLaw

LAW = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)


@pytest.fixture(scope="module")
def wave():
    r = F.wave.solve_superkink(LAW, 1.6, N=128)
    assert r.converged
    return r


def test_trilinear_superkink_spectrum_passes_its_checks(wave):
    fr = F.floquet.spectrum(wave)
    assert fr.symmetry_error <= 1e-12  # μ ↔ 1/μ̄ (Hamiltonian) holds across the crossings
    assert fr.error <= 1e-11
    # the excess shrinks as the ring grows: the phonon splitting of a finite ring (measured
    # 2.0e-2 at N = 64, 1.0e-2 at N = 128), not an instability of the wave
    assert fr.classification == "finite_size", fr.verdict


@pytest.mark.parametrize("method", ["dense", "structured"])
def test_step_halving_moves_every_multiplier_by_less_than_the_error_bar(wave, method):
    a = F.floquet.spectrum(wave, method=method, finite_size=False)
    b = F.floquet.spectrum(wave, m=2 * a.m, method=method, finite_size=False)
    moved = max(float(np.min(np.abs(b.multipliers - mu))) for mu in a.multipliers)
    assert moved <= a.error
    assert abs(np.max(np.abs(a.multipliers)) - np.max(np.abs(b.multipliers))) <= a.error


def test_trilinear_solitary_wave_spectrum_passes_its_checks():
    """A solitary wave (continued from V_SK by the solver) on N = 128: quartet symmetry, step
    halving within the bar, no multiplier off the circle beyond a finite-ring artefact."""
    r = F.wave.solve_solitary(LAW, 0.3, 1.4, N=128)
    assert r.converged
    a = F.floquet.spectrum(r)
    assert a.symmetry_error <= 1e-12 and a.error <= 1e-11
    assert a.classification in ("stable", "finite_size"), a.verdict
    b = F.floquet.spectrum(r, m=2 * a.m, finite_size=False)
    # outside the trivial cluster at 1 (the translation/velocity pair splits by ~√residual, the
    # reason the cluster is reported apart: measured 2e-8 here)
    # The bar is one of |μ| (FloquetResult.error): the modulus of each multiplier's partner
    # after halving (an elliptic one's angle moved by 1.1e-12 here, its modulus by < the bar).
    away = a.multipliers[np.abs(a.multipliers - 1) > a.trivial_radius]
    partner = [b.multipliers[np.argmin(np.abs(b.multipliers - mu))] for mu in away]
    assert np.max(np.abs(np.abs(away) - np.abs(partner))) <= a.error
    assert a.n_trivial >= 2 and a.trivial_split <= a.trivial_radius
