"""One result protocol for every result object: status vocabulary, elapsed_s, error fields, a
generated as_dict, and strictness on request (ConvergenceError)."""

import dataclasses
import json

import numpy as np
import pytest

from fpucore import ConvergenceError, CubicLaw, atlas, floquet, qc, simulate, wave
from fpucore.parallel import Executor
from fpucore.result import STATUSES, Result, jsonable

LAW = CubicLaw()


def _results():
    r = wave.solve_superkink(LAW, 5.2, N=64)
    return {
        "qc_superkink": qc.superkink_from_w_plus(LAW, 1.0),
        "qc_solitary": qc.solitary(LAW, 1.0, 5.0),
        "wave": r,
        "floquet": floquet.spectrum(floquet.HomogeneousState(LAW, 1.0, 5.0, 16)),
        "simulation": simulate.riemann(LAW, 4.6, 0.0, L=40, t_end=0.5, n_snapshots=4),
        "family": wave.superkink_family(LAW, [5.2, 5.3], N=64),
        "sweep": atlas.sweep(
            LAW, "superkink", [5.2, 5.3], N=64, use_cache=False, executor=Executor("inline")
        ),
    }


@pytest.fixture(scope="module")
def results():
    return _results()


def test_every_result_speaks_the_protocol(results):
    for name, res in results.items():
        assert isinstance(res, Result), name
        assert res.status in STATUSES and res.converged == (res.status == "ok"), name
        assert isinstance(res.message, str) and res.elapsed_s >= 0, name
        assert res.ERROR_FIELDS and all(np.isfinite(v) for v in res.errors().values()), name
        d = res.as_dict()
        for k in ("status", "elapsed_s", *res.ERROR_FIELDS):
            assert k in d, (name, k)
        json.dumps(jsonable(d))  # JSON-ready
        assert res.require_converged() is res


def test_as_dict_follows_the_fields_without_a_hand_kept_list(results):
    r = results["wave"]
    d = r.as_dict()
    for f in dataclasses.fields(r):
        if f.name not in r.EXCLUDE:
            assert f.name in d or f"{f.name}_re" in d, f.name
    assert "w" not in r.as_dict(profile=False)
    fr = results["floquet"]
    assert {"multipliers_re", "multipliers_im", "n_unstable"} <= set(fr.as_dict())


def test_strictness_on_request_raises_convergence_error():
    r = wave.solve_superkink(LAW, 5.2, N=64, max_iter=1)
    if r.converged:  # one Newton step is not enough from the QC guess (checked here)
        pytest.skip("converged in one iteration")
    with pytest.raises(ConvergenceError, match="not_converged"):
        r.require_converged()
