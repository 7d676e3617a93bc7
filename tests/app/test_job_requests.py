"""The typed parameters of the app's jobs (app/compute/requests.py): refused when made with a
ParameterError naming the argument, frozen and hashable, keyed exactly (one ulp apart is two
keys), and each one's Call is the fpucore function itself, whose code text runs the very same
call."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from app import compute
from app.compute.jobs import simulation_job, wave_job
from fpucore import atlas, qc, simulate, wave
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def refused(make) -> ParameterError:
    with pytest.raises(ParameterError) as e:
        make()
    return e.value


@pytest.mark.parametrize("kw, name", [
    ({"mode": "kink"}, "mode"),
    ({"w_plus": math.nan}, "w_plus"),
    ({"V": "5.0"}, "V"),
    ({"N": 200.0}, "N"),  # a count given as a float
    ({"N": 10}, "N"),
    ({"tol": 0.0}, "tol"),
])  # fmt: skip
def test_a_wave_request_is_refused_when_made(kw, name):
    args = {"mode": "solitary", "w_plus": 1.0, "V": 5.0, "N": 200, "tol": 1e-10, **kw}
    assert refused(lambda: compute.WaveRequest(**args)).name == name


@pytest.mark.parametrize("make, name", [
    (lambda: compute.RiemannRequest(w_left=4.6, w_right=0.0, L=300.0, t_end=2.0), "L"),
    (lambda: compute.RiemannRequest(w_left=4.6, w_right=0.0, L=300, t_end=-1.0), "t_end"),
    (lambda: compute.GaussianRequest(w_B=1.0, A=6.0, L=300, t_end=2.0, guard="none"), "guard"),
    (lambda: compute.GaussianRequest(w_B=1.0, A=math.inf, L=300, t_end=2.0), "A"),
    (lambda: compute.RiemannRequest(w_left=4.6, w_right=0.0, L=300, t_end=2.0,
                                    probes=("100",)), "probes"),
    (lambda: compute.SeededRequest(wave={"N": 200}, L=1000, t_end=2.0), "wave"),
    (lambda: compute.AtlasRequest(0.1, 6.5, 61, 8, 200), "n_w"),
    (lambda: compute.AtlasRequest(6.5, 0.1, 8, 8, 200), "w_hi"),
    (lambda: compute.AtlasRequest(0.1, 6.5, 8, 8, 2000), "N"),
])  # fmt: skip
def test_simulation_and_atlas_requests_are_refused_when_made(make, name):
    assert refused(make).name == name


def test_requests_are_frozen_hashable_and_keyed_exactly():
    a = compute.WaveRequest("solitary", 1.0, 5.0, 200, 1e-10)
    b = compute.WaveRequest("solitary", 1.0, np.nextafter(5.0, 6.0), 200, 1e-10)
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.V = 5.1
    assert a == compute.WaveRequest("solitary", 1, 5, 200, 1e-10)  # numbers stored as floats
    assert len({a, b, compute.WaveRequest("solitary", 1.0, 5.0, 200, 1e-10)}) == 2
    assert compute.wave_key(LAW, a) != compute.wave_key(LAW, b)
    sim_a = compute.SeededRequest(wave=a, L=1000, t_end=40.0)
    sim_b = compute.SeededRequest(wave=b, L=1000, t_end=40.0)
    assert compute.simulation_key(LAW, sim_a) != compute.simulation_key(LAW, sim_b)
    assert compute.simulation_key(LAW, sim_a) == compute.simulation_key(
        LAW, compute.SeededRequest(wave=a, L=1000, t_end=40.0)
    )
    r = compute.RiemannRequest(w_left=4.6, w_right=0.0, L=300, t_end=2.0)
    g = compute.GaussianRequest(w_B=4.6, A=0.0, L=300, t_end=2.0)  # the same numbers
    assert compute.simulation_key(LAW, r) != compute.simulation_key(LAW, g)
    # -0.0 == 0.0 as floats, but two keys (the cache keys on repr)
    assert compute.simulation_key(LAW, r) != compute.simulation_key(
        LAW, compute.RiemannRequest(w_left=4.6, w_right=-0.0, L=300, t_end=2.0)
    )


def test_the_wave_call_is_the_fpucore_function_and_its_code_runs_the_same_call():
    req = compute.WaveRequest("solitary", 1.0, 5.0, 200, 1e-10)
    call = compute.wave_call(LAW, req)
    assert call.fn is wave.solve_solitary and call.code() == (
        "wave.solve_solitary(law, 1.0, 5.0, N=200, tol=1e-10)"
    )
    sk = compute.wave_call(LAW, compute.WaveRequest("superkink", 1.0, 0.0, 200, 1e-10))
    ref = qc.superkink_from_w_plus(LAW, 1.0)  # V follows from w₊ (the request's V unused)
    assert sk.fn is wave.solve_superkink and sk.args == (ref.V,)
    assert dict(sk.kwargs)["branch"] == ref.branch
    r = wave_job(LAW, req)
    again = eval(call.code(), {"wave": wave, "law": LAW})  # noqa: S307 - the app's own text
    assert r.converged and np.array_equal(r.w, again.w) and r.V == again.V == 5.0


def test_a_simulation_job_is_the_fpucore_call_its_code_shows():
    req = compute.RiemannRequest(w_left=4.6, w_right=0.0, L=200, t_end=2.0, probes=(50,))
    code = req.call().code()
    assert code == (
        "simulate.riemann(law, 4.6, 0.0, L=200, t_end=2.0, guard='bounded', probes=(50,), "
        "max_sites_out=200)"
    )
    assert req.params() == {"L": 200, "t_end": 2.0, "guard": "bounded", "probes": (50,),
                            "max_sites_out": 200, "w_left": 4.6, "w_right": 0.0}  # fmt: skip
    job = simulation_job(LAW, req)
    direct = eval(code, {"simulate": simulate, "law": LAW})  # noqa: S307
    assert np.array_equal(job.snapshots, direct.snapshots) and len(job.waves) == len(direct.waves)
    seeded = compute.SeededRequest(
        wave=compute.WaveRequest("solitary", 1.0, 5.0, 200, 1e-10), L=1000, t_end=40.0
    )
    assert seeded.call().code("r") == (
        "simulate.seeded(r, L=1000, t_end=40.0, guard='bounded', max_sites_out=1000)"
    )
    assert seeded.params() == {"L": 1000, "t_end": 40.0, "guard": "bounded",
                               "max_sites_out": 1000, "mode": "solitary",
                               "w_plus": 1.0, "V": 5.0, "N": 200, "tol": 1e-10}  # fmt: skip


def test_the_atlas_request_is_a_call_of_fpucore_atlas_run():
    req = compute.AtlasRequest(0.1, 6.5, 3, 4, 200)
    call = req.call()
    assert call.fn is atlas.run and req.n_points == 12
    assert call.code() == (
        "atlas.run(law, 'solitary', rows='0.1:6.5:3', V=4, N=200, floquet=True, finite_size=False)"
    )
