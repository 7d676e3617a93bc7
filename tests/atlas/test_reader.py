"""Reading an atlas back (fpucore.atlas.open_atlas, atlas_data): the typed arrays are what the
run computed and what its store holds, for a solitary and a superkink atlas; what is not an
atlas store is refused with one line naming the path."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
import zarr

from fpucore import atlas
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)
TYPED = ("amplitude", "energy", "residual", "max_modulus", "max_modulus_error")


@pytest.fixture(scope="module")
def solitary(tmp_path_factory):
    out = tmp_path_factory.mktemp("reader") / "s.zarr"
    # w₊ = 1 at V = 4.0 lies below c₊: a no-wave point among the others
    res = atlas.run(LAW, "solitary", rows=[1.0, 6.0], V=[4.0, 4.6, 5.0], N=64, floquet=True,
                    finite_size=False, out=out, backend="inline")  # fmt: skip
    return res, out


def test_the_reader_gives_what_the_run_wrote(solitary):
    res, out = solitary
    data = atlas.open_atlas(out)
    raw = zarr.open_group(out, mode="r", zarr_format=2)  # the store's arrays, read raw
    mem = res.dataset  # the run's own table in memory
    assert data.kind == "solitary" and data.path == str(out) and data.shape == (2, 3)
    assert np.array_equal(data.w_plus, [1.0, 6.0]) and np.array_equal(data.V, [4.0, 4.6, 5.0])
    assert np.array_equal(data.status, raw["status"][:])
    assert np.array_equal(data.status, mem["status"].values)
    assert data.done.all() and data.ok.sum() == res.n_ok
    assert data.counts() == {"ok": res.n_ok, "not_converged": res.n_not_converged,
                             "no_wave": res.n_no_wave, "failed": res.n_failed}  # fmt: skip
    assert data.status[0, 0] == "no_wave" and np.isnan(data.amplitude[0, 0])
    for name in TYPED:
        assert np.array_equal(getattr(data, name), raw[name][:], equal_nan=True), name
        assert np.array_equal(getattr(data, name), mem[name].values, equal_nan=True), name
    assert np.nanmax(data.residual[data.ok]) == res.max_residual
    assert np.nanmax(data.max_modulus_error[data.ok]) == res.max_modulus_error
    assert data.N == 64 and data.tol == 1e-12 and data.floquet
    assert data.parameters["N"] == 64 and data.parameters["a"] == -1.0
    assert "created" in data.parameters  # a store's, not a run's in memory
    from_run = atlas.atlas_data(mem)
    assert from_run.path is None and "created" not in from_run.parameters
    for name in TYPED:
        assert np.array_equal(getattr(from_run, name), getattr(data, name), equal_nan=True)


def test_a_superkink_atlas_has_branches_for_rows(tmp_path):
    out = tmp_path / "sk.zarr"
    atlas.run(LAW, "superkink", rows=["lower"], V=[5.5, 5.7], N=64, out=out, backend="inline")
    data = atlas.open_atlas(out)
    assert data.kind == "superkink" and list(data.rows) == ["lower"] and data.shape == (1, 2)
    assert data.ok.all() and data.N == 64 and not data.floquet
    assert np.isnan(data.max_modulus).all()  # computed without Floquet
    with pytest.raises(ParameterError, match="superkink atlas is over V only"):
        _ = data.w_plus


def test_what_is_not_an_atlas_store_is_refused_naming_the_path(tmp_path):
    with pytest.raises(ParameterError, match="no atlas store at") as e:
        atlas.open_atlas(tmp_path / "missing.zarr")
    assert e.value.name == "path" and "missing.zarr" in str(e.value)
    other = tmp_path / "other.zarr"
    xr.Dataset({"x": (("t",), np.zeros(3))}).to_zarr(other, zarr_format=2, consolidated=False)
    with pytest.raises(ParameterError, match="has dimensions") as e:
        atlas.open_atlas(other)
    assert e.value.name == "path" and str(other) in str(e.value)
    (tmp_path / "empty.zarr").mkdir()
    with pytest.raises(ParameterError, match="cannot read"):
        atlas.open_atlas(tmp_path / "empty.zarr")
