"""The Atlas scene (app/views/atlas.py), without a browser: it shows a store written by
``fpucore.atlas`` (the heat map's values are the store's), refuses what it cannot show with a
message, reads stores only below the atlas root, and a click on a cell picks that cell's (w₊, V)
and the atlas's N and marks the cell."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("panel")

from app.state import ExplorerState, parse_url, url_query  # noqa: E402
from app.views.atlas import AtlasScene  # noqa: E402
from fpucore import atlas  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    out = tmp_path_factory.mktemp("atlas") / "a.zarr"
    atlas.run(CubicLaw(-1.0, 10.0), "solitary", rows=[1.0, 6.0], V=[4.6, 5.0, 5.3], N=64,
              floquet=True, finite_size=False, out=out, backend="inline")  # fmt: skip
    return out


@pytest.fixture(autouse=True)
def root(store, monkeypatch):
    """Stores are read below FPU_ATLAS_ROOT (the server's directory when unset)."""
    monkeypatch.setenv("FPU_ATLAS_ROOT", str(store.parent))
    return store.parent


def test_scene_shows_the_store(store):
    sc = AtlasScene(ExplorerState())
    assert sc.refresh() is None and "atlas store" in sc.last_message  # nothing to show yet
    sc.store.value = str(store)
    sc.wait_idle(120)
    info = sc.refresh()
    assert info is not None and any(k == "max residual" for k, _ in info.errors)
    z = sc.last_z  # the image on screen
    ds = sc.dataset
    ref = np.where(ds.status.values == "ok", ds.max_modulus.values - 1.0, np.nan)
    assert np.allclose(np.sort(z[np.isfinite(z)]), np.sort(ref[np.isfinite(ref)]), rtol=0, atol=0)


def test_click_picks_the_nearest_cell(store):
    st = ExplorerState()
    sc = AtlasScene(st)
    sc.store.value = str(store)
    sc.wait_idle(120)
    assert sc.pick(5.9, 5.02)
    assert st.w_plus == 6.0 and st.V == 5.0


def test_missing_store_is_a_message(root):
    sc = AtlasScene(ExplorerState())
    sc.store.value = str(root / "nothing.zarr")
    sc.wait_idle(60)
    sc.refresh()
    assert "no atlas store" in sc.last_message


def test_a_relative_path_is_read_below_the_root_and_goes_into_the_url(store):
    st = ExplorerState()
    sc = AtlasScene(st)
    sc.store.value = store.name  # "a.zarr", relative to the root
    sc.wait_idle(120)
    assert sc.refresh() is not None, sc.last_message
    assert st.atlas == store.name and url_query(st)["atlas"] == store.name
    values, errors = parse_url({"atlas": store.name, "tab": "atlas"})
    assert not errors and values["atlas"] == store.name
    sc2 = AtlasScene(ExplorerState(**values))  # the link opens the same store
    assert sc2.store.value == store.name and sc2.refresh() is not None


@pytest.mark.parametrize("path", ["../elsewhere.zarr", "/etc", "~/x.zarr"])
def test_a_path_outside_the_root_is_refused(path, root):
    sc = AtlasScene(ExplorerState())
    sc.store.value = path
    sc.wait_idle(60)
    assert sc.refresh() is None
    assert f"a path below {root.resolve()}" in sc.last_message
    _, errors = parse_url({"atlas": path})
    assert len(errors) == 1 and "atlas" in errors[0]


def test_click_sets_the_atlas_N_marks_the_cell_and_keeps_the_header_the_atlas_s(store):
    st = ExplorerState(N=500, tol=1e-10)
    sc = AtlasScene(st)
    sc.store.value = str(store)
    sc.wait_idle(120)
    sc.refresh()
    assert sc.pick(1.1, 4.62)
    sc.wait_idle(60)
    assert st.N == 64 and (st.w_plus, st.V) == (1.0, 4.6)  # the atlas's own wave
    sc.refresh()
    (l,), (r,), (b,), (t,) = (sc.pick_src.data[k] for k in "lrbt")
    assert l < 1.0 < r and b < 4.6 < t
    _, buf = sc.download_data()
    header = [ln for ln in buf.getvalue().splitlines() if ln.startswith("#")]
    assert "# N=64" in header and "# tol=" + repr(float(sc.dataset.attrs["tol"])) in header
    assert not any("N=500" in ln for ln in header)


def test_the_run_time_stays_after_a_click(store, monkeypatch):
    """A re-render of the background run (after a click) keeps what the run cost."""
    import xarray as xr

    ds = xr.open_zarr(store, consolidated=False).load()
    fake = SimpleNamespace(dataset=ds, n_computed=6, workers=2, backend="process", elapsed_s=1.25)
    monkeypatch.setattr(atlas, "run", lambda *a, **k: fake)
    sc = AtlasScene(ExplorerState())
    sc._want_run = True
    info = sc.refresh()
    assert info is not None and info.timings[0][1] == 1.25
    assert sc.pick(6.0, 5.0)
    sc.wait_idle(60)
    again = sc.refresh()
    label, c = again.timings[0]
    assert label.startswith("atlas run (6 points") and c.elapsed_s == 1.25 and c.cached
