"""The tangent (variational) map of a piecewise-linear law follows the event-located base map:
f is continuous, so the saltation matrix at a transversal crossing is the identity and the
variational equations only switch f′ of the crossing site at the located crossing.  Reference:
central differences of the EVENT-LOCATED base map (a second, independent route), on states whose
period crosses breakpoints; the tangent of the plain fixed-step map (no location) misses them."""

import numpy as np
import pytest

from fpucore.law import TrilinearLaw
from fpucore.wave import period_map as pm
from fpucore.wave.compact import compact_wave

DEGENERATE = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)  # E1 = 0: the explicit compact wave
GENERAL = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.3)


def compact_state():
    w = compact_wave(DEGENERATE, 0.5, 0.2)
    w0, wd0 = w.lattice(np.arange(-8, 8), 0.3137)
    return DEGENERATE, 0.5, 0.2, w0, wd0


def bump_state():
    """A pulse on w_B = 0.2 into the hard regime of a non-degenerate law (a crossing)."""
    n = np.arange(-10, 10)
    w0 = 0.2 + 1.1 / np.cosh(0.8 * n)
    wd0 = -1.6 * np.gradient(w0)
    return GENERAL, 1.6, 0.2, w0, wd0


def jacobians(state, m, events, d=1e-6, periodic=False):
    law, V, wB, w0, wd0 = state
    N = w0.size
    r = pm.integrate(law, w0, wd0, 1 / V, m, wB, wB, periodic, store_df=True, events=events)
    K = N // 2 if periodic else N
    out, _ = pm.tangent_columns(r, np.arange(2 * N), K, periodic)
    J = pm.scatter_dense(out, N, K, periodic)
    x0 = np.concatenate([w0, wd0])
    Jfd = np.empty_like(J)
    for j in range(2 * N):
        e = np.zeros(2 * N)
        e[j] = d
        a = pm.period_map(law, x0 + e, V, m, wB, wB, periodic)  # event-located (the default)
        b = pm.period_map(law, x0 - e, V, m, wB, wB, periodic)
        Jfd[:, j] = (a - b) / (2 * d)
    return r, J, Jfd


@pytest.mark.parametrize("state", [compact_state, bump_state])
@pytest.mark.parametrize("m", [8, 24])
def test_tangent_matches_central_differences_of_the_event_located_map(state, m):
    r, J, Jfd = jacobians(state(), m, events=None)
    assert r.crossings >= 1  # the period crosses breakpoints
    assert r.hs is not None and r.hs.size == r.dfs.shape[0] > m  # cut at the crossings
    assert abs(r.hs.sum() - r.T) <= 1e-13 * r.T
    scale = np.max(np.abs(J))
    assert np.max(np.abs(J - Jfd)) <= 1e-7 * scale


@pytest.mark.parametrize("state", [compact_state, bump_state])
def test_without_event_location_the_tangent_misses_the_crossings(state):
    _, J, Jfd = jacobians(state(), 8, events=False)
    assert np.max(np.abs(J - Jfd)) > 1e-4 * np.max(np.abs(J))  # 1000x the located bound


def test_periodic_tangent_matches_central_differences():
    """The Floquet route: the ring (indices wrap) with the event-located base map."""
    r, J, Jfd = jacobians(bump_state(), 12, events=None, periodic=True)
    assert r.crossings >= 1
    assert np.max(np.abs(J - Jfd)) <= 1e-7 * np.max(np.abs(J))


def test_smooth_laws_take_equal_steps():
    from fpucore.law import CubicLaw

    r = pm.integrate(CubicLaw(), np.full(6, 0.1), np.zeros(6), 2.0, 7, 0.1, 0.1, store_df=True)
    assert r.hs is None and r.crossings == 0 and r.dfs.shape == (7, 12, 6)
    assert np.allclose(r.step_sizes(), 2.0 / 7)
