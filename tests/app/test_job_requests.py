"""The typed parameters of the app's jobs (app/compute/requests.py): refused when made with a
ParameterError naming the argument, frozen and hashable, keyed exactly (one ulp apart is two
keys), and each one's Call is the fpucore function itself, whose code text runs the very same
call."""

from __future__ import annotations

import dataclasses
import math
import types

import numpy as np
import pytest

from app import compute
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
    assert compute.job_key(LAW, a) != compute.job_key(LAW, b)
    sim_a = compute.SeededRequest(wave=a, L=1000, t_end=40.0)
    sim_b = compute.SeededRequest(wave=b, L=1000, t_end=40.0)
    assert compute.job_key(LAW, sim_a) != compute.job_key(LAW, sim_b)
    assert compute.job_key(LAW, sim_a) == compute.job_key(
        LAW, compute.SeededRequest(wave=a, L=1000, t_end=40.0)
    )
    r = compute.RiemannRequest(w_left=4.6, w_right=0.0, L=300, t_end=2.0)
    g = compute.GaussianRequest(w_B=4.6, A=0.0, L=300, t_end=2.0)  # the same numbers
    assert compute.job_key(LAW, r) != compute.job_key(LAW, g)
    # -0.0 == 0.0 as floats, but two keys (the cache keys on repr)
    assert compute.job_key(LAW, r) != compute.job_key(
        LAW, compute.RiemannRequest(w_left=4.6, w_right=-0.0, L=300, t_end=2.0)
    )


def test_the_wave_call_is_the_fpucore_function_and_its_code_runs_the_same_call():
    req = compute.WaveRequest("solitary", 1.0, 5.0, 200, 1e-10)
    call = req.call(LAW)
    assert call.fn is wave.solve_solitary and call.code() == (
        "wave.solve_solitary(law, 1.0, 5.0, N=200, tol=1e-10)"
    )
    sk = compute.WaveRequest("superkink", 1.0, 0.0, 200, 1e-10).call(LAW)
    ref = qc.superkink_from_w_plus(LAW, 1.0)  # V follows from w₊ (the request's V unused)
    assert sk.fn is wave.solve_superkink and sk.args == (ref.V,)
    assert dict(sk.kwargs)["branch"] == ref.branch
    r = req.job(LAW)
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
    job = req.job(LAW)
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


@pytest.mark.parametrize("make, name", [
    (lambda: compute.SweepRequest("kink", 1.0, (5.0,), 200), "kind"),
    (lambda: compute.SweepRequest("solitary", math.nan, (5.0,), 200), "w_plus"),
    (lambda: compute.SweepRequest("solitary", 1.0, (), 200), "V_values"),
    (lambda: compute.SweepRequest("solitary", 1.0, (5.0, math.inf), 200), "V_values"),
    (lambda: compute.SweepRequest("solitary", 1.0, (5.0,), 10), "N"),
    (lambda: compute.SweepRequest("superkink", None, (5.0,), 200, "middle"), "branch"),
    (lambda: compute.FamilyRequest(1.0, "fast", 200, 1e-10), "V_values"),
    (lambda: compute.FamilyRequest(1.0, (5.0,), 200, 0.0), "tol"),
])  # fmt: skip
def test_sweep_and_family_requests_are_refused_when_made(make, name):
    assert refused(make).name == name


def test_a_sweep_request_is_the_fpucore_sweep_its_code_shows_and_its_own_key():
    """The sweep is its request: the key tells one ulp apart, the code is atlas.sweep's call
    with every float by repr, and the job (run inline as in a worker) equals that code run."""
    Vs = (5.0, 5.3)
    req = compute.SweepRequest("solitary", 1.0, Vs, 64)
    near = compute.SweepRequest("solitary", 1.0, (5.0, np.nextafter(5.3, 6.0)), 64)
    assert compute.job_key(LAW, req) != compute.job_key(LAW, near)
    assert compute.job_key(LAW, req) == compute.job_key(LAW, compute.SweepRequest(
        "solitary", 1, [5, 5.3], 64, "lower"))  # fmt: skip
    call = req.call()
    assert call.fn is atlas.sweep and call.code() == (
        "atlas.sweep(law, kind='solitary', V_values=[5.0, 5.3], w_plus=1.0, N=64, branch='lower')"
    )
    job = req.job(LAW)
    direct = eval(call.code(), {"atlas": atlas, "law": LAW})  # noqa: S307 - the app's own text
    assert np.array_equal(job.V, direct.V) and list(job.classification) == list(
        direct.classification
    )
    assert np.array_equal(job.max_modulus, direct.max_modulus, equal_nan=True)


def test_a_family_request_is_the_fpucore_family_its_code_shows():
    req = compute.FamilyRequest(1.0, (5.0, 5.2), 200, 1e-10)
    assert req.call().code() + ".results" == (
        "wave.solitary_family(law, 1.0, [5.0, 5.2], N=200, tol=1e-10).results"
    )
    rows = req.job(LAW)
    direct = eval(req.call().code() + ".results", {"wave": wave, "law": LAW})  # noqa: S307
    assert [r.V for r in rows] == [5.0, 5.2] == [r.V for r in direct]
    assert all(np.array_equal(a.w, b.w) for a, b in zip(rows, direct))


#: what app.compute exposes beside its requests: the road (run, is_cached, job_key), the
#: cache and its results, the errors.  Everything else lives in a namespace (compute.laws,
#: compute.workers, compute.cache, compute.requests, compute.energy), never beside the road.
ROAD = {"run", "is_cached", "job_key", "Computed", "CACHE",
        "ParameterError", "CancelledError", "Superseded"}  # fmt: skip
#: about 25 (the 8 names of the road and 17 requests): room for a few new requests; a longer
#: list means names that belong in a namespace (the 57 names before the QC requests)
MAX_PUBLIC = 30


def public_names(module) -> set[str]:
    """Every public name of ``module`` that is not a submodule (a namespace)."""
    return {n for n in dir(module) if not n.startswith("_")
            and not isinstance(getattr(module, n), types.ModuleType)}  # fmt: skip


def beside_the_road(module) -> list[str]:
    """The public names of ``module`` that are neither the road nor a request class."""
    requests = {n for n in public_names(module) if isinstance(getattr(module, n), type)
                and issubclass(getattr(module, n), compute.Request)}  # fmt: skip
    return sorted(public_names(module) - requests - ROAD)


def test_app_compute_grows_requests_not_functions():
    """A new computation is a new request class (app/compute/requests.py, qc_requests.py,
    energy.py), run by compute.run: app.compute's public names are its requests and the road
    — a per-computation function (``qc_wave(...)``, ``floquet_spectrum(...)``,
    ``sweep_key(...)``) beside them fails here, and so does a long list of names."""
    public = public_names(compute)
    assert public == set(compute.__all__)
    assert ROAD <= public
    assert {"WaveRequest", "SpectrumRequest", "QCWaveRequest", "EnergyRequest",
            "AtlasRequest"} <= public  # fmt: skip
    beside = beside_the_road(compute)
    assert not beside, f"per-computation names beside the request road: {beside}"
    assert len(public) <= MAX_PUBLIC, sorted(public)


def test_a_function_added_beside_the_road_is_caught():
    """The check above on a copy of app.compute that grew ``def qc_wave(...)`` (what it
    exported before the QC requests): caught, whether or not ``__all__`` names it."""
    grown = types.ModuleType("grown")
    grown.__dict__.update({n: getattr(compute, n) for n in public_names(compute)})

    def qc_wave(lw, mode, w_plus, V):
        return compute.run(lw, compute.QCWaveRequest(mode, w_plus, V))

    grown.qc_wave = qc_wave
    assert beside_the_road(grown) == ["qc_wave"]
    grown.law_key = compute.laws.law_key  # a namespace's function re-exported: caught too
    assert beside_the_road(grown) == ["law_key", "qc_wave"]


def test_only_the_road_submits_jobs():
    """Views and other modules never call run_job (a hand-built key and job) themselves: the
    only caller is app/compute/heavy.py's run (heavy requests and the Floquet spectrum)."""
    import ast
    from pathlib import Path

    root = Path(compute.__file__).resolve().parents[1]
    callers = set()
    for path in root.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call):
                f = node.func
                name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
                if name == "run_job":
                    callers.add(path.relative_to(root.parent).as_posix())
    assert callers == {"app/compute/heavy.py"}, callers
