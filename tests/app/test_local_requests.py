"""The in-process requests (QC waves, families, phase plane, existence diagram, the energy
criterion, app/compute/qc_requests.py and energy.py): refused when made with a ParameterError
naming the argument, keyed exactly, run by compute.run like every request, and each one's value
is the fpucore call its "Copy as Python" line shows (computed again here, not pasted)."""

from __future__ import annotations

import numpy as np
import pytest

from app import compute
from fpucore import floquet, qc
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.qc import diagram, phase

LAW = CubicLaw(-1.0, 10.0)
NS = {"qc": qc, "diagram": diagram, "phase": phase, "floquet": floquet, "law": LAW}


@pytest.mark.parametrize("make, name", [
    (lambda: compute.QCWaveRequest("kink", 1.0, 5.0), "mode"),
    (lambda: compute.QCWaveRequest("solitary", float("nan"), 5.0), "w_plus"),
    (lambda: compute.QCWaveRequest("solitary", 1.0, None), "V"),
    (lambda: compute.QCFamilyRequest(1.0, n=1), "n"),
    (lambda: compute.ExistenceRequest(n=4.0), "n"),
    (lambda: compute.PhasePlaneRequest(1.0, 5.0, n_grid=True), "n_grid"),
    (lambda: compute.PhaseOrbitRequest(1.0, 5.0, 0.5, 0.0, (0.0,)), "window"),
    (lambda: compute.EnergyRequest("1"), "w_plus"),
    (lambda: compute.SampledEnergyRequest(
        compute.SweepRequest("superkink", None, [0.7], 100)), "source"),
])  # fmt: skip
def test_a_local_request_is_refused_when_made(make, name):
    with pytest.raises(ParameterError) as e:
        make()
    assert e.value.name == name


@pytest.mark.parametrize("req", [
    compute.QCWaveRequest("solitary", 1.0, 5.0),
    compute.QCWaveRequest("superkink", 1.0),
    compute.QCFamilyRequest(1.0, n=40),
    compute.ExistenceRequest(n=50),
    compute.PhasePlaneRequest(1.0, 5.0, n_grid=41),
    compute.PhaseOrbitRequest(1.0, 5.0, 0.5, 0.0, (0.0, 2.0)),
], ids=lambda r: type(r).__name__)  # fmt: skip
def test_a_local_request_is_the_fpucore_call_its_code_shows(req):
    compute.CACHE.clear()
    c = compute.run(LAW, req)
    assert not c.cached and compute.is_cached(LAW, req)
    again = eval(req.call().code(), NS)  # the "Copy as Python" line, run on its own
    a, b = c.value, again
    names = [n for n in ("V", "amplitude", "w_plus", "c_plus", "V_SK", "w", "wp", "level")
             if hasattr(b, n)]  # fmt: skip
    assert names and type(a) is type(b)
    for name in names:
        x, y = (np.asarray(getattr(r, name), float) for r in (a, b))
        assert np.array_equal(x, y, equal_nan=True), name  # NaN: where a branch breaks
    assert compute.run(LAW, req).value is c.value  # then from the cache


def test_superkinks_at_one_w_plus_share_one_entry_and_solitary_waves_are_keyed_exactly():
    sk = compute.QCWaveRequest("superkink", 1.0, 5.0)
    assert sk.V is None and sk == compute.QCWaveRequest("superkink", 1.0)
    a = compute.job_key(LAW, compute.QCWaveRequest("solitary", 1.0, 5.0))
    b = compute.job_key(LAW, compute.QCWaveRequest("solitary", 1.0, 5.0 + 1e-15))
    assert a != b
    assert compute.run(LAW, sk).value.V == qc.superkink_from_w_plus(LAW, 1.0).V


def test_the_energy_request_is_fpucores_energy_criterion_and_its_grid_follows_the_law():
    req = compute.EnergyRequest(1.0)
    code = req.call(LAW).code()
    assert code == f"floquet.energy_criterion(law, 1.0, qc_samples={floquet.energy.QC_SAMPLES})"
    ec = compute.run(LAW, req).value
    ref = eval(code, NS)
    assert np.array_equal(ec.qc_extrema_V, ref.qc_extrema_V)


def test_a_sampled_energy_request_waits_for_its_source():
    fam = compute.FamilyRequest(1.0, [5.0, 5.2], 100, 1e-8)
    compute.CACHE.clear()
    assert compute.run(LAW, compute.SampledEnergyRequest(fam)) is None  # never computes it
    assert not compute.is_cached(LAW, fam)
