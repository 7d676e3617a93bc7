"""Discrete waves, Floquet spectra and simulations of smooth laws (one compiled Chebyshev kernel,
LAW_CHEB), checked against a second method and measured convergence:

* the paper's cubic typed as a :class:`SmoothLaw` (so every kernel call goes through the
  Chebyshev representation) gives the cubic's own superkink (LAW_CUBIC, validated against the
  paper elsewhere) within the two error bars, and the same Floquet spectrum;
* a superkink of the exponential preset computed on N = 400 and N = 600 sites agrees at the
  central sites within the sum of the two profile bounds (convergence in N);
* the presets go through Floquet (verdict), Riemann and Gaussian runs and a TW-seeded run; a
  run that reaches the end of the represented interval is stopped with a message naming it."""

from __future__ import annotations

import numpy as np
import pytest

from fpucore import CubicLaw, floquet, simulate, wave
from fpucore.law import SmoothLaw
from fpucore.law.presets import preset_law
from fpucore.qc import superkink_velocity_bounds


@pytest.fixture(scope="module")
def cubic_pair():
    cubic = CubicLaw(-1.0, 10.0)
    smooth = SmoothLaw("a*w**3 + b*w**2 + w", {"a": -1.0, "b": 10.0})
    return cubic, smooth


def test_cubic_as_smooth_law_gives_the_cubic_superkink(cubic_pair):
    cubic, smooth = cubic_pair
    r0 = wave.solve_superkink(cubic, 5.2, N=400)
    r1 = wave.solve_superkink(smooth, 5.2, N=400)
    assert r0.converged and r1.converged
    diff = float(np.max(np.abs(r0.w - r1.w)))
    assert diff <= r0.profile_error + r1.profile_error, (diff, r0.profile_error, r1.profile_error)
    s0 = floquet.spectrum(r0, finite_size=False)
    s1 = floquet.spectrum(r1, finite_size=False)
    assert abs(s0.max_modulus - s1.max_modulus) <= s0.error + s1.error + 1e-9


def test_exponential_superkink_converges_in_N():
    law = preset_law("exponential")
    lo, hi = superkink_velocity_bounds(law, "lower")
    V = lo + 0.6 * (hi - lo)
    a = wave.solve_superkink(law, V, N=400)
    b = wave.solve_superkink(law, V, N=600)
    assert a.converged and b.converged
    # same pinning (the centre site); compare the sites both chains hold
    ia = {int(n): k for k, n in enumerate(a.n)}
    common = [(ia[int(n)], k) for k, n in enumerate(b.n) if int(n) in ia and abs(n) <= 100]
    d = max(abs(a.w[i] - b.w[k]) for i, k in common)
    assert d <= a.profile_error + b.profile_error, (d, a.profile_error, b.profile_error)


@pytest.mark.parametrize("name", ["tanh", "rational"])
def test_presets_superkink_and_verdict(name):
    law = preset_law(name)
    lo, hi = superkink_velocity_bounds(law, "lower")
    V = lo + 0.6 * (hi - lo)
    r = wave.solve_superkink(law, V, N=300)
    assert r.converged and np.all((r.w > law.alpha) & (r.w < law.beta))
    s = floquet.spectrum(r, finite_size=False)
    assert s.status == "ok" and s.verdict


def test_solitary_wave_energy_error_covers_the_representation():
    law = preset_law("exponential")
    from fpucore.qc import sound_speeds

    w_plus = 1.0
    cp, vsk, _ = sound_speeds(law, w_plus)
    r = wave.solve_solitary(law, w_plus, cp + 0.5 * (vsk - cp), N=300)
    assert r.converged and np.isfinite(r.energy)
    assert r.energy_error >= float(np.sum(np.abs(r.w - w_plus))) * law.representation_error.f


@pytest.mark.parametrize("name", ["exponential", "tanh", "rational"])
def test_riemann_and_gaussian_runs_conserve_energy(name):
    law = preset_law(name)
    w_hi = law.w_star + 0.5 * (law.beta - law.w_star)
    res = simulate.riemann(law, w_hi, 0.2 * law.w_star, L=200, t_end=10.0)
    assert res.status == "ok", res.message
    assert res.energy_drift <= 1e-7
    g = simulate.gaussian(law, 0.2 * law.w_star, 0.3 * law.w_star, L=200, t_end=10.0)
    assert g.status == "ok", g.message


def test_seeded_run_follows_the_wave():
    law = preset_law("exponential")
    lo, hi = superkink_velocity_bounds(law, "lower")
    r = wave.solve_superkink(law, lo + 0.6 * (hi - lo), N=200)
    res = simulate.seeded(r, t_end=5.0)
    assert res.status == "ok", res.message


def test_bounded_guard_stops_at_the_represented_interval():
    law = preset_law("tanh")
    lo, hi = simulate.restoring_interval(law)
    assert law.interval[0] <= lo < law.alpha and law.beta < hi <= law.interval[1]


def test_floquet_refuses_a_state_outside_the_represented_interval():
    from fpucore.errors import ParameterError

    law = preset_law("exponential")
    hi = law.interval[1]
    state = floquet.HomogeneousState(law, 1.0, 5.0, 16)
    fake = type("R", (), {})()
    for k in ("law", "V", "N", "m"):
        setattr(fake, k, getattr(state, k, None))
    fake.law, fake.V = law, 5.0
    fake.w = np.full(16, 1.0)
    fake.w[3] = hi + 0.5
    fake.wdot = np.zeros(16)
    fake.w_left = fake.w_right = 1.0
    with pytest.raises(ParameterError, match="represented interval"):
        floquet.monodromy(fake, 16)
