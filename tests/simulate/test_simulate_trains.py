"""Trains of compact solitary waves in the degenerate trilinear law's Riemann problem with a
velocity jump (fpucore.simulate.impact.velocity_jump), tracked by
fpucore.simulate.trains.track_train.

References, independent of the simulation: every tracked wave against the EXPLICIT compact wave
of the same measured V (fpucore.wave.compact, derived from eq. TW_discrete): its crest b + C,
with the tracker's error bars covering the difference; the train's velocity against the mass
balance V M(V) = P |v_left|/2 solved in closed form (train_velocity) with P = 2; the count of
waves against the excess strain Σ(w_n − w_B) behind the train divided by one wave's mass."""

import numpy as np
import pytest

from fpucore import ParameterError
from fpucore.law import TrilinearLaw
from fpucore.simulate.impact import velocity_jump
from fpucore.simulate.trains import track_train, train_velocity
from fpucore.wave.compact import compact_wave

E1_ZERO = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)  # sonic vacuum below w1 = 0.5
E3_ZERO = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.0)  # sonic vacuum above w2 = 1.5 (mirrored case)
L, T = 200, 60.0
PROBES = list(range(L // 2 + 4, L // 2 + 16))


def run(law, w_B, v_left, t_end=T):
    return velocity_jump(law, w_B, w_B, v_left, L, t_end, guard="bounded", probes=PROBES,
                         n_probe_t=int(t_end * 100) + 1)  # fmt: skip


def crest_slope(law, V, w_B, h=1e-6):
    """d(crest)/dV of the explicit wave (central difference), to carry the velocity's error bar."""
    a, b = compact_wave(law, V + h, w_B), compact_wave(law, V - h, w_B)
    return ((a.b + a.C) - (b.b + b.C)) / (2 * h)


@pytest.mark.parametrize(
    "law, w_B, v_left",
    [(E1_ZERO, 0.0, -0.3), (E1_ZERO, 0.2, -0.1), (E1_ZERO, 0.4, -0.05), (E3_ZERO, 2.0, 0.3)],
)
def test_each_wave_of_the_train_is_the_explicit_compact_wave(law, w_B, v_left):
    r = run(law, w_B, v_left)
    assert r.converged and r.energy_drift < 1e-10
    tr = track_train(r, law, side=1)
    assert tr.converged and tr.n_tracked >= 2, tr.message
    for V, dV, c, dc in zip(tr.velocities, tr.velocity_errors, tr.crests, tr.crest_errors):
        cw = compact_wave(law, V, w_B)
        assert abs((cw.b + cw.C) - c) <= dc + abs(crest_slope(law, V, w_B)) * dV
        assert dc < 1e-6 and dV < 1e-6  # the bars are tight enough to mean something
    assert abs(tr.background - w_B) <= tr.background_error + 1e-14


@pytest.mark.parametrize("w_B, v_left", [(0.0, -0.3), (0.2, -0.1)])
def test_train_velocity_and_spacing_follow_the_mass_balance(w_B, v_left):
    tr = track_train(run(E1_ZERO, w_B, v_left), E1_ZERO, side=1)
    assert abs(tr.spacing - 2.0) <= tr.spacing_error
    assert abs(tr.velocity - train_velocity(E1_ZERO, w_B, v_left)) <= tr.velocity_error + 1e-12
    # the wrong spacing is seen: P = 3 predicts another velocity, far outside the bar
    assert abs(tr.velocity - train_velocity(E1_ZERO, w_B, v_left, 3.0)) > 100 * tr.velocity_error


def test_the_count_matches_the_mass_behind_the_train():
    w_B, v_left = 0.2, -0.1
    r = run(E1_ZERO, w_B, v_left)
    tr = track_train(r, E1_ZERO, side=1)
    mass = compact_wave(E1_ZERO, tr.velocity, w_B).mass
    excess = float(np.sum(r.final_w[L // 2 :] - w_B))  # Σ(w_n − w_B) right of the jump
    assert tr.n_waves >= 8
    assert abs(excess / mass - tr.n_waves) <= 1.0  # the wave straddling the jump: ±1


def test_the_left_train_mirrors_the_right_one():
    w_B, v_left = 0.2, -0.1
    probes = list(range(L // 2 - 15, L // 2 - 3))
    r = velocity_jump(E1_ZERO, w_B, w_B, v_left, L, T, guard="bounded", probes=probes,
                      n_probe_t=6001)  # fmt: skip
    tr = track_train(r, E1_ZERO, side=-1)
    assert tr.converged
    V = train_velocity(E1_ZERO, w_B, v_left)
    assert abs(tr.velocity + V) <= tr.velocity_error + 1e-12


def test_data_at_rest_in_the_sonic_vacuum_do_not_move():
    # no force below w1: a strain jump alone (particles at rest) is an equilibrium
    r = velocity_jump(E1_ZERO, 0.1, 0.4, 0.0, 64, 5.0, guard="bounded")
    assert np.array_equal(r.final_w[:32], np.full(32, 0.1))
    assert np.array_equal(r.final_w[32:], np.full(32, 0.4))


@pytest.mark.parametrize(
    "kw, name",
    [
        ({"v_left": float("nan")}, "v_left"),
        ({"v_left": 101.0}, "v_left"),
        ({"v_left": 0.0}, "v_left"),  # no jump at all
        ({"L": 65}, "L"),
        ({"boundary": "fixed_particles"}, "boundary"),
    ],
)
def test_bad_velocity_jump_data_are_refused_naming_the_argument(kw, name):
    args = {"law": E1_ZERO, "w_left": 0.2, "w_right": 0.2, "v_left": -0.1, "L": 64, "t_end": 1.0,
            "guard": "bounded"} | kw  # fmt: skip
    with pytest.raises(ParameterError) as e:
        velocity_jump(**args)
    assert e.value.name == name


def test_track_train_refuses_bad_side_and_runs_without_probes():
    r = velocity_jump(E1_ZERO, 0.2, 0.2, -0.1, 64, 1.0, guard="bounded")
    with pytest.raises(ParameterError) as e:
        track_train(r, E1_ZERO, side=0)
    assert e.value.name == "side"
    with pytest.raises(ParameterError) as e:
        track_train(r, E1_ZERO)
    assert e.value.name == "result.probe_sites"
    with pytest.raises(ParameterError) as e:
        track_train(r, TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2))
    assert e.value.name == "law"
