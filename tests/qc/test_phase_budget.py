"""phase_plane(n_grid=100000) asked for 74.5 GiB: refused before allocating,
with the estimate and the memory budget."""

import tracemalloc

import pytest

from fpucore import CubicLaw
from fpucore.errors import ParameterError
from fpucore.qc import phase


def test_huge_phase_plane_grid_refused_before_allocating():
    tracemalloc.start()
    try:
        with pytest.raises(ParameterError) as e:
            phase.phase_plane(CubicLaw(-1.0, 10.0), 1.0, 5.0, n_grid=100_000)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert e.value.name == "n_grid" and e.value.value == 100_000
    assert "GiB" in str(e.value) and "memory estimate is <=" in str(e.value)
    assert peak < 16 * 2**20


def test_phase_plane_grid_within_budget_still_runs(monkeypatch):
    monkeypatch.setenv("FPU_MEMORY_BUDGET", "64MiB")
    pp = phase.phase_plane(CubicLaw(-1.0, 10.0), 1.0, 5.0, n_grid=241)  # ~3.7 MB
    assert pp.H.shape == (241, 241)
    with pytest.raises(ParameterError):
        phase.phase_plane(CubicLaw(-1.0, 10.0), 1.0, 5.0, n_grid=2000)  # ~256 MB
