"""Explicit compact discrete waves of the degenerate (zero-modulus) PL laws: eq. TW_discrete's
residual, and an independent check by integrating the lattice over one period (scipy DOP853,
restarted at every breakpoint crossing) and comparing with the shifted wave."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fpucore import ParameterError
from fpucore.law import TrilinearLaw
from fpucore.wave.compact import compact_wave, residual, v_max

E1_ZERO = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)
E3_ZERO = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.0)


def lattice_period(law, w0, dw0, wB, T):
    """ẅ_n = f(w_{n+1}) − 2f(w_n) + f(w_{n−1}) (eq. FPUstrain) on a finite chain with the
    background fixed beyond both ends, from t = 0 to T; every crossing of a breakpoint by any
    site is located (terminal event) and the integration restarted there."""
    n = w0.size
    fB = float(law.f(wB))

    def rhs(t, y):
        g = np.concatenate(([fB], law.f(y[:n]), [fB]))
        return np.concatenate((y[n:], g[2:] - 2 * g[1:-1] + g[:-2]))

    pairs = [(i, b) for i in range(n) for b in law.breakpoints]
    last = {}  # direction of the last crossing of each (site, breakpoint): the next is opposite

    def make(k):
        i, b = pairs[k]
        ev = lambda t, y: y[i] - b  # noqa: E731
        ev.terminal, ev.direction = True, -last.get(k, 0.0)
        return ev

    t, y, crossings = 0.0, np.concatenate((w0, dw0)), 0
    while t < T:
        events = [make(k) for k in range(len(pairs))]
        sol = solve_ivp(rhs, (t, T), y, method="DOP853", rtol=1e-13, atol=1e-15, events=events)
        assert sol.success
        if sol.status == 1:
            for k, te in enumerate(sol.t_events):
                if te.size:
                    i = pairs[k][0]
                    last[k] = math.copysign(1.0, sol.y_events[k][0][n + i])
                    crossings += 1
        t, y = sol.t[-1], sol.y[:, -1]
    return y[:n], y[n:], crossings


@pytest.mark.parametrize("law, wB", [(E1_ZERO, 0.2), (E1_ZERO, -0.4), (E3_ZERO, 1.8)])
def test_explicit_wave_solves_the_advance_delay_equation(law, wB):
    vm = v_max(law, wB)
    for V in (0.2 * vm, 0.6 * vm, 0.97 * vm):
        w = compact_wave(law, V, wB)
        xi = np.linspace(-2.5, 2.5, 2001)
        r = residual(w, xi)
        assert np.max(np.abs(r)) <= 1e-13 * abs(w.C) * w.E
        # compact: exactly the background outside [−1 − a, 1 + a]
        far = np.abs(xi) >= 1 + w.a + 1e-12
        assert np.all(w.profile(xi[far]) == wB)
        assert w.converged


def test_wrong_amplitude_is_detected():
    """The checks can fail: C off by 1e-6 (relative) breaks the matching at the junctions
    (the piecewise residual alone is linear in C and would not see it) and the lattice period."""
    from dataclasses import replace

    from fpucore.wave.compact import junction_defect

    w = compact_wave(E1_ZERO, 0.5, 0.2)
    bad = replace(w, C=w.C * (1 + 1e-6))
    assert junction_defect(w) <= 1e-13 and junction_defect(bad) > 1e-8 * abs(w.C)
    sites = np.arange(-5, 6)
    wT, _, _ = lattice_period(E1_ZERO, *bad.lattice(sites, 0.3137), 0.2, 1.0 / bad.V)
    assert np.max(np.abs(wT - bad.lattice(sites - 1, 0.3137)[0])) > 1e-8


@pytest.mark.parametrize("law, wB, frac", [(E1_ZERO, 0.2, 0.3), (E1_ZERO, 0.2, 0.9),
                                           (E3_ZERO, 1.8, 0.5)])  # fmt: skip
def test_lattice_period_shift_reproduces_the_wave(law, wB, frac):
    V = frac * v_max(law, wB)
    w = compact_wave(law, V, wB)
    sites = np.arange(-5, 6)
    phase = 0.3137  # a generic position of the lattice under the wave
    w0, dw0 = w.lattice(sites, phase)
    wT, dwT, crossings = lattice_period(law, w0, dw0, wB, 1.0 / V)
    assert crossings >= 2  # the core sites enter and leave the zero-modulus regime
    # after one period every site carries its left neighbour's state: w_{n+1}(T) = w_n(0)
    wref, dwref = w.lattice(sites - 1, phase)
    assert np.max(np.abs(wT - wref)) <= 1e-11
    assert np.max(np.abs(dwT - dwref)) <= 1e-10
    # amplitude, support and mass against the lattice values and the profile's quadrature
    xi = np.linspace(-2, 2, 400001)
    assert w.amplitude == pytest.approx(np.max(np.abs(w.profile(xi) - wB)), rel=1e-9)
    mass = np.trapezoid(w.profile(xi) - wB, xi)
    assert w.mass == pytest.approx(mass, rel=1e-8)


def test_localizes_at_the_lattice_scale_as_V_to_zero():
    amps, cores = [], []
    for V in (0.4, 0.1, 0.025):
        w = compact_wave(E1_ZERO, V, 0.2)
        amps.append(abs(w.C))
        cores.append(2 * w.a)
    assert cores == pytest.approx([math.pi * V / math.sqrt(8.0) for V in (0.4, 0.1, 0.025)])
    # |C| = |δ| / (ω − π/2) ~ δ V/√(2E) as V → 0 (δ = 0.3, E = 4): the crest vanishes with V
    assert amps[0] > amps[1] > amps[2]
    assert amps[2] / 0.025 == pytest.approx(0.3 / math.sqrt(8.0), rel=0.02)


def test_refusals():
    with pytest.raises(ParameterError) as e:
        compact_wave(E1_ZERO, 1.5 * v_max(E1_ZERO, 0.2), 0.2)
    assert e.value.name == "V" and "lattice space" in str(e.value)
    with pytest.raises(ParameterError) as e:
        compact_wave(E1_ZERO, 0.3, 0.7)  # background outside the zero-modulus regime
    assert e.value.name == "w_B"
    with pytest.raises(ParameterError) as e:
        compact_wave(TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2), 0.3, 0.2)
    assert e.value.name == "law"
