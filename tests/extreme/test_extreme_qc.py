"""QC layer: closed forms at the edges of parameter space, each checked independently
(jump-condition residuals, first integral, quadrature of the energy, the mirror symmetry)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from fpucore import CubicLaw, ParameterError, qc

LAWS = {
    "paper": CubicLaw(-1.0, 10.0),
    "stiff b=100": CubicLaw(-1.0, 100.0),  # f' up to ~3300, short periods
    "tiny |a|": CubicLaw(-0.01, 10.0),  # huge strains (w* ~ 333)
    "weak b": CubicLaw(-5.0, 0.2),  # nearly symmetric cubic
}


def _energy_quad(law, sw):
    def g(x):
        w, d = sw.profile(x), sw.dprofile(x)
        V = sw.V
        return float(
            0.5 * V**2 * (w * w - sw.w_B**2) + V**2 / 24 * d * d + law.phi(w) - law.phi(sw.w_B)
        )

    pts = np.linspace(-70 / sw.gamma, 70 / sw.gamma, 15)
    return sum(quad(g, a, b, epsabs=0, epsrel=1e-11, limit=400)[0] for a, b in zip(pts, pts[1:]))


@pytest.mark.parametrize("name", list(LAWS))
@pytest.mark.parametrize("t", [0.001, 0.3, 0.7, 0.999])  # position of w+ in (alpha, beta)
def test_superkink_across_the_admissible_range(name, t):
    law = LAWS[name]
    w_plus = law.alpha + t * (law.beta - law.alpha)
    sk = qc.superkink_from_w_plus(law, w_plus)
    assert sk.rayleigh_residual < 1e-12 and sk.driving_force < 1e-10
    lo, hi = qc.superkink_velocity_bounds(law)
    assert lo < sk.V < hi
    # supersonic w.r.t. both states even where f'(w+-) -> 0 at the interval's ends
    assert sk.V**2 > float(law.df(sk.w_plus)) and sk.V**2 > float(law.df(sk.w_minus))


@pytest.mark.parametrize("name", list(LAWS))
@pytest.mark.parametrize("where", ["near c+", "mid below", "near V_SK-", "near V_SK+", "near c-"])
def test_solitary_energy_at_the_edges(name, where):
    law = LAWS[name]
    w_plus = law.alpha + 0.25 * (law.beta - law.alpha)
    (cp, vsk), (_, cm) = qc.solitary_intervals(law, w_plus)
    V = {
        "near c+": cp + 1e-6 * (vsk - cp),
        "mid below": 0.5 * (cp + vsk),
        "near V_SK-": vsk - 1e-8 * (vsk - cp),
        "near V_SK+": vsk + 1e-8 * (cm - vsk),
        "near c-": cm - 1e-6 * (cm - vsk),
    }[where]
    sw = qc.solitary(law, w_plus, V)
    assert sw.first_integral_residual < 1e-12
    assert np.isfinite([sw.energy, sw.gamma, sw.amplitude]).all()
    ref = _energy_quad(law, sw)
    assert abs(sw.energy - ref) <= 1e-8 * abs(ref) + 1e3 * sw.energy_error


def test_vanishing_family_as_w_plus_to_w_star():
    """The intervals shrink like (w+ - w*)^2 and the amplitudes like |w+ - w*|."""
    law = LAWS["paper"]
    ds = 10.0 ** -np.arange(1, 7)
    widths, amps = [], []
    for d in ds:
        (cp, vsk), (_, cm) = qc.solitary_intervals(law, law.w_star - d)
        widths.append(cm - cp)
        amps.append(qc.superkink_from_w_plus(law, law.w_star - d).amplitude)
    assert np.polyfit(np.log(ds), np.log(widths), 1)[0] == pytest.approx(2.0, abs=0.01)
    assert np.polyfit(np.log(ds), np.log(amps), 1)[0] == pytest.approx(1.0, abs=1e-6)
    with pytest.raises(ParameterError, match="degenerate"):
        qc.solitary_intervals(law, law.w_star)


def test_flat_top_waves_at_the_papers_velocities():
    """Fig. stabSW: V = 5.21749194749 (compressive) and 5.2174919476 (tensile) at w+ = 6."""
    law = LAWS["paper"]
    below = qc.solitary(law, 6.0, 5.21749194749)
    above = qc.solitary(law, 6.0, 5.2174919476)
    assert below.kind == "compressive" and above.kind == "tensile"
    sk = qc.superkink_from_w_plus(law, 6.0)
    for sw in (below, above):
        # flat top: the middle of the wave sits at the superkink's other state
        assert sw.amplitude == pytest.approx(sk.amplitude, rel=2e-5)
        assert sw.gamma == pytest.approx(2 * sk.p, rel=1e-5)
        # plateau half-length ~ log(1/dV)/gamma: about ten lattice sites
        assert 5 < math.log(1 / abs(sw.V - sk.V)) / sw.gamma < 200


@pytest.mark.parametrize("bad", [(-1e-300, 1.0), (-1.0, 1e308), (-1e308, 1.0)])
def test_extreme_law_coefficients_either_compute_or_refuse(bad):
    """Overflowing coefficients: every number is finite or the request is refused clearly."""
    try:
        law = CubicLaw(*bad)
        w_plus = law.alpha + 0.3 * (law.beta - law.alpha)
        sk = qc.superkink_from_w_plus(law, w_plus)
    except (ParameterError, OverflowError, ZeroDivisionError) as e:
        assert str(e)
        return
    vals = [sk.V, sk.w_minus, sk.p]
    assert all(math.isfinite(v) for v in vals) or pytest.fail(f"non-finite result {vals}")
