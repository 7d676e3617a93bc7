"""The atlas with a smooth law (LAW_CHEB, a SmoothLaw pickled to the workers without SymPy): the
Dask backend (dask and distributed are dependencies of the atlas extra) and the process pool
give the same records bit for bit, and each point equals a single ``wave``/``floquet`` call in
this process within its error bars."""

from __future__ import annotations

import numpy as np
import pytest

from fpucore import atlas, floquet, qc, wave
from fpucore.law.presets import preset_law

pytest.importorskip("distributed")

LAW = preset_law("exponential")
N = 64


def grid():
    lo, hi = qc.superkink_w_plus_range(LAW, "lower")
    w_plus = 0.5 * (max(lo, LAW.alpha) + hi)
    cp, vsk, cm = qc.sound_speeds(LAW, w_plus)
    # below c+ (no wave), a tensile and a compressive wave
    return [w_plus], [0.9 * cp, cp + 0.5 * (vsk - cp), vsk + 0.5 * (cm - vsk)]


def test_dask_and_pool_agree_and_equal_single_calls(tmp_path):
    rows, Vs = grid()
    kw = dict(rows=rows, V=Vs, N=N, floquet=True, finite_size=False, chunk=2)
    dask = atlas.run(LAW, "solitary", backend="dask", workers=2, out=tmp_path / "d.zarr", **kw)
    pool = atlas.run(LAW, "solitary", backend="process", workers=2, out=tmp_path / "p.zarr", **kw)
    assert dask.backend == "dask" and pool.backend == "process"
    a, b = dask.dataset, pool.dataset
    assert list(a.status.values[0]) == ["no_wave", "ok", "ok"], a.status.values
    assert (a.status.values == b.status.values).all()
    for k in ("amplitude", "energy", "max_modulus"):
        assert np.array_equal(a[k].values, b[k].values, equal_nan=True), k
    for j, V in enumerate(Vs[1:], start=1):
        r = wave.solve_solitary(LAW, rows[0], V, N=N)
        fr = floquet.spectrum(r, finite_size=False)
        bar = 1e-9 * max(1.0, abs(r.energy))
        assert abs(a.amplitude.values[0, j] - r.amplitude) <= max(r.amplitude_error, bar)
        assert abs(a.energy.values[0, j] - r.energy) <= max(r.energy_error, bar)
        mu_bar = a.max_modulus_error.values[0, j] + fr.error + 1e-9
        assert abs(a.max_modulus.values[0, j] - fr.max_modulus) <= mu_bar
