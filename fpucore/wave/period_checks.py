"""Validation of the period maps' inputs (shared by :mod:`fpucore.wave.period_map` and
:mod:`fpucore.wave.period_events`, which the former calls for laws with breakpoints)."""

from __future__ import annotations

import numpy as np

from fpucore.errors import ParameterError


def check_state(w0, wd0) -> tuple[np.ndarray, np.ndarray]:
    w0 = np.ascontiguousarray(w0, dtype=np.float64)
    wd0 = np.ascontiguousarray(wd0, dtype=np.float64)
    if w0.ndim != 1 or w0.shape != wd0.shape or w0.size < 2:
        raise ParameterError("w0/wd0", (w0.shape, wd0.shape), "two 1-D arrays of equal size >= 2")
    if not (np.all(np.isfinite(w0)) and np.all(np.isfinite(wd0))):
        raise ParameterError("w0/wd0", "non-finite entries", "finite arrays")
    return w0, wd0


def check_m(m) -> int:
    if not (isinstance(m, (int, np.integer)) and 1 <= m <= 100_000):
        raise ParameterError("m", m, "an integer in [1, 100000]", "number of RK steps per period")
    return int(m)
