"""``fpucore.atlas.sweep`` as a one-row atlas on the execution layer: several chunks on a
process pool give the rows of single ``wave``/``floquet`` calls within their error bars, the
public columns stay, and the inputs that used to give NaN rows are refused."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from fpucore import atlas, wave
from fpucore import floquet as fq
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.parallel import Executor

LAW = CubicLaw(-1.0, 10.0)


def test_pool_sweep_equals_single_calls(tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    V = [4.9, 5.1, 5.3, 5.5, 5.6, 5.7, 5.75]  # 3 chunks of fsw.CHUNK = 3
    with Executor("process", workers=2) as ex:
        s = atlas.sweep(LAW, "superkink", V, N=64, executor=ex)
    assert s.converged and not s.cached.any() and len(s.rows) == len(V)
    # a row is V and the point's atlas record, under the atlas's names
    assert all(tuple(r) == ("V", *atlas.FIELDS) for r in s.rows)
    assert all(r["status"] == "ok" and r["converged"] and r["floquet_converged"] for r in s.rows)
    for j, v in enumerate(V):
        fr = fq.spectrum(wave.solve_superkink(LAW, v, N=64))
        # the wave's own error (residual <= 1e-12, conditioned ~1e3) on top of the two bars
        assert abs(s.max_modulus[j] - fr.max_modulus) <= s.max_modulus_error[j] + fr.error + 1e-9
        assert s.rows[j]["max_modulus_error"] == s.max_modulus_error[j]
        assert s.rows[j]["verdict"].split(":")[0] == fr.verdict.split(":")[0]
        assert s.classification[j] == fr.classification
        assert s.rows[j]["headline"] == fr.decision.headline


@pytest.mark.parametrize(
    "kw, name",
    [({"tol": 0.0}, "tol"), ({"N": 10**6}, "N"), ({"time_budget_s": -1.0}, "time_budget_s")],
)
def test_inputs_that_gave_nan_rows_are_refused(kw, name, tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    args = {"N": 64, **kw}
    with pytest.raises(ParameterError) as e:
        atlas.sweep(LAW, "superkink", [5.5], **args)
    assert e.value.name == name


def test_time_budget_stops_with_a_message(tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    s = atlas.sweep(LAW, "superkink", [5.5, 5.6, 5.7, 5.8], N=64, time_budget_s=1e-9,
                 use_cache=False)  # fmt: skip
    assert "time budget" in s.message and s.status == "stopped" and not s.converged
    assert all(np.isnan(s.max_modulus)) or s.floquet_converged.sum() < 4
    missing = [r for r in s.rows if r["status"] == ""]  # never computed: said so, at the sweep's N
    assert missing and all("time budget" in r["message"] and r["N"] == 64 for r in missing)


def test_the_sweep_lives_in_the_atlas_only():
    """The sweep is named once, in the atlas stage: ``floquet.sweep`` (an alias that ran back up
    from the floquet stage to the atlas) is gone, and importing fpucore.floquet loads no atlas."""
    for name in ("sweep", "SweepResult", "sweeps"):
        assert not hasattr(fq, name), name
    with pytest.raises(AttributeError):
        fq.sweep  # noqa: B018
    probe = "import sys, fpucore.floquet; print('fpucore.atlas' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True, timeout=120)  # fmt: skip
    assert out.stdout.split() == ["False"]
