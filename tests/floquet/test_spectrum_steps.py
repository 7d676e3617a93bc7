"""``floquet.spectrum`` is its steps (:mod:`fpucore.floquet.spectrum_steps`): run one by one they
give the spectrum's own numbers, and the error bar the steps compute bounds the true error of
the largest multiplier (closed form of a constant state outside the convex interval)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fpucore import floquet as fq
from fpucore import wave
from fpucore.errors import ParameterError
from fpucore.floquet.spectrum_steps import (
    convergence,
    eigen_solve,
    error_bars,
    monodromy_pair,
    prepare,
)
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def _steps(r, method: str):
    base = prepare(r, None)
    pair = monodromy_pair(base, check=True)
    eig = eigen_solve(base, pair.mono, method)
    bars = error_bars(base, eig, pair.mono, pair.integrator_error, method, None)
    return base, pair, eig, bars, convergence(base, pair.mono, bars)


@pytest.mark.parametrize("method", fq.METHODS)
@pytest.mark.parametrize("which", ["superkink", "homogeneous"])
def test_the_steps_give_the_spectrum(method, which):
    r = (wave.solve_superkink(LAW, 5.6, N=64) if which == "superkink"
         else fq.HomogeneousState(LAW, 0.3, 4.0, 32))  # fmt: skip
    fr = fq.spectrum(r, method=method)
    base, pair, eig, bars, (converged, msgs) = _steps(r, method)
    assert base.m == fr.m and pair.mono.K == fr.K and eig.route == fr.route
    assert np.array_equal(bars.mu, fr.multipliers) and np.array_equal(bars.trivial, fr.trivial)
    assert (bars.error, bars.symmetry_error, pair.integrator_error) == (
        fr.error, fr.symmetry_error, fr.integrator_error)  # fmt: skip
    assert bars.max_modulus_away_from_1 == fr.max_modulus_away_from_1
    assert converged == fr.converged and all(m in fr.message for m in msgs)


def test_the_error_bar_bounds_the_largest_multiplier():
    """w0 = 7 lies beyond the convex interval (f′(7) = −6): the largest multiplier is exactly
    e^{2√6 / V} (k = π, :func:`fpucore.floquet.homogeneous_multipliers`)."""
    V = 1.5
    state = fq.HomogeneousState(LAW, 7.0, V, 32, convex=False)
    exact = math.exp(2.0 * math.sqrt(-float(LAW.df(7.0))) / V)
    for method in fq.METHODS:
        *_, bars, _ = _steps(state, method)
        assert abs(bars.max_modulus_away_from_1 - exact) <= bars.error, method
        assert abs(abs(bars.unstable[0]) - exact) <= bars.error, method


def test_prepare_refuses_a_bad_step_count():
    r = fq.HomogeneousState(LAW, 0.3, 4.0, 32)
    for m in (1, 2.5, 30_000):
        with pytest.raises(ParameterError) as e:
            prepare(r, m)
        assert e.value.name == "m"
