"""Runs seeded with computed discrete traveling waves (paper Figs. stabSK, stabSW): the wave must
propagate over ≥ 50 periods with velocity within 1e-8 of the prescribed value (the paper's check)
and its shape preserved.  Reference: the prescribed V and the initial profile itself — after K whole
periods an exact traveling wave is the initial profile shifted by K sites (eq. period)."""

import pytest

from fpucore import simulate
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

wave = pytest.importorskip("fpucore.wave")  # skip ONLY if the discrete-waves module is absent

LAW = CubicLaw(-1.0, 10.0)


@pytest.fixture(scope="module")
def superkink():
    r = wave.solve_superkink(LAW, 5.2)
    assert r.converged, r.message
    return r


@pytest.fixture(scope="module")
def solitary():
    r = wave.solve_solitary(LAW, 1.0, 5.0)
    assert r.converged, r.message
    return r


@pytest.mark.parametrize("which", ["superkink", "solitary"])
def test_seeded_wave_keeps_velocity_and_shape(which, superkink, solitary):
    r = superkink if which == "superkink" else solitary
    s = simulate.seeded(r, t_end=60.0 / r.V)  # 60 periods
    assert s.success, s.message
    d = s.details
    assert d["periods"] >= 50
    assert d["n_sites_timed"] >= 50
    assert d["velocity_error"] < 1e-8
    assert abs(d["V_measured"] - r.V) < 1e-8
    assert d["phase_error_max"] < 1e-8
    assert d["shape_error"] < 1e-8
    assert s.energy_drift < 1e-10
    assert s.boundary == "fixed_strain"
    # the tracker finds exactly this wave, moving right with the prescribed velocity
    assert len(s.waves) == 1
    w = s.waves[0]
    assert w.kind == ("superkink" if which == "superkink" else "solitary")
    assert w.velocity == pytest.approx(r.V, abs=1e-6)
    assert w.left_state == pytest.approx(r.w_left, abs=1e-6)
    assert w.right_state == pytest.approx(r.w_right, abs=1e-6)


def test_seeded_symplectic_converges_at_fourth_order(solitary):
    runs = [simulate.seeded(solitary, method="symplectic", dt=dt) for dt in (0.02, 0.01)]
    for s in runs:
        assert s.success
        # the step-doubling estimate matches the actual shape error after 50 periods
        assert s.error_estimate / 3 < s.details["shape_error"] < 3 * s.error_estimate
    for key in ("velocity_error", "shape_error"):
        ratio = runs[0].details[key] / runs[1].details[key]
        assert 8 < ratio < 32, key  # 2^4
    assert runs[1].details["velocity_error"] < 1e-5


def test_seeded_superkink_cannot_hold_end_particles(superkink):
    # a superkink carries a velocity jump v+ − v− = −V(w+ − w−): both ends cannot be at rest
    with pytest.raises(ParameterError) as e:
        simulate.seeded(superkink, boundary="fixed_particles")
    assert e.value.name == "boundary"


def test_seeded_chain_too_short(solitary):
    with pytest.raises(ParameterError) as e:
        simulate.seeded(solitary, L=solitary.N)
    assert e.value.name == "L"
