"""One rule per kind of input, whichever entry point takes it: counts are integers (a whole float
such as 500.0 is refused everywhere, as the wave solver always did), a wave tolerance lies in
errors.TOL_RANGE, a time budget in (0, 1e9] seconds; the refusal names the argument and reads
the same from the wave solver, the sweep and the atlas."""

from __future__ import annotations

import pytest

from fpucore import atlas, simulate, wave
from fpucore.errors import TOL_RANGE, ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def refusal(fn, *args, **kw) -> ParameterError:
    with pytest.raises(ParameterError) as e:
        fn(*args, **kw)
    return e.value


@pytest.mark.parametrize("name", ["n_snapshots", "max_sites_out", "n_probe_t", "max_steps"])
def test_a_whole_float_is_not_a_count(name):
    e = refusal(simulate.riemann, LAW, 2.0, 0.5, 200, 1.0, **{name: 500.0})
    assert e.name == name and "an integer in" in e.valid


def test_a_whole_float_is_not_a_chain_length():
    assert refusal(simulate.riemann, LAW, 2.0, 0.5, 200.0, 1.0).name == "L"
    assert refusal(simulate.riemann, LAW, 2.0, 0.5, float("inf"), 1.0).name == "L"


@pytest.mark.parametrize("tol", [0.0, TOL_RANGE[0] / 2, TOL_RANGE[1] * 2, float("nan"), "1e-12"])
def test_tolerance_refused_alike(tol, tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    calls = [
        (wave.solve_superkink, (LAW, 5.5), {}),
        (atlas.sweep, (LAW, "superkink", [5.5]), {"N": 64, "use_cache": False}),
        (atlas.run, (LAW, "superkink"), {"rows": ["lower"], "V": [5.5], "N": 64}),
    ]
    texts = {str(refusal(fn, *a, tol=tol, **kw)) for fn, a, kw in calls}
    assert len(texts) == 1 and next(iter(texts)).startswith("tol=")


@pytest.mark.parametrize("budget", [0.0, -1.0, 2e9, float("inf"), True])
def test_time_budget_refused_alike(budget, tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    for fn, a, kw in [
        (wave.solve_superkink, (LAW, 5.5), {}),
        (wave.solve_solitary, (LAW, 1.0, 5.0), {}),
        (atlas.sweep, (LAW, "superkink", [5.5]), {"N": 64, "use_cache": False}),
        (atlas.run, (LAW, "superkink"), {"rows": ["lower"], "V": [5.5], "N": 64}),
    ]:
        e = refusal(fn, *a, time_budget_s=budget, **kw)
        assert e.name == "time_budget_s" and "(0, 1e9]" in e.valid
