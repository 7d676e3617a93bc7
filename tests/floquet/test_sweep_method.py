"""Sweeps take the structured route by default: the same rows as the dense reference
route within the error bars, the same classification, and their own cache entries."""

from __future__ import annotations

import numpy as np
import pytest

from fpucore import atlas
from fpucore.atlas import sweeps
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.parallel import Executor

LAW = CubicLaw(-1.0, 10.0)


@pytest.mark.parametrize("kind, V, w_plus", [
    ("superkink", [4.85, 5.1, 5.4, 5.6, 5.8], None),
    ("solitary", [4.6, 5.0, 5.3], 6.0),
])  # fmt: skip
def test_structured_sweep_equals_the_dense_sweep(kind, V, w_plus, tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    run = lambda method: atlas.sweep(LAW, kind, V, w_plus=w_plus, N=160, method=method,  # noqa: E731
                                  executor=Executor(backend="inline"))  # fmt: skip
    s, d = run("structured"), run("dense")
    assert s.method == "structured" and d.method == "dense"
    assert s.converged and d.converged
    bar = np.maximum(s.max_modulus_error, d.max_modulus_error)
    assert np.all(np.abs(s.max_modulus - d.max_modulus) <= bar)
    assert s.classification == d.classification
    assert np.array_equal(s.n_unstable, d.n_unstable)
    assert any(c != "stable" for c in s.classification)  # the families' unstable part is in
    # a λ-route bar is wider than the quartet-symmetry bar
    assert np.all(d.max_modulus_error < s.max_modulus_error)


def test_the_method_is_part_of_the_cache_key_and_checked():
    args = (LAW, "superkink", [5.5], 64, None, "lower", None, 1e-12)
    assert sweeps.cache_key(*args, "dense") != sweeps.cache_key(*args, "structured")
    with pytest.raises(ParameterError) as e:
        atlas.sweep(LAW, "superkink", [5.5], N=64, method="eig")
    assert e.value.name == "method"
    with pytest.raises(ParameterError) as e:
        atlas.run(LAW, "superkink", V=[5.5], N=64, floquet=True, floquet_method="eig")
    assert e.value.name == "floquet_method"
