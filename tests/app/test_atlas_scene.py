"""The Atlas scene (app/views/atlas.py), without a browser: it shows a store written by
``fpucore.atlas`` (the heat map's values are the store's), refuses what it cannot show with a
message, and a click on a cell picks that cell's (w₊, V)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")

from app.state import ExplorerState  # noqa: E402
from app.views.atlas import AtlasScene  # noqa: E402
from fpucore import atlas  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    out = tmp_path_factory.mktemp("atlas") / "a.zarr"
    atlas.run(CubicLaw(-1.0, 10.0), "solitary", rows=[1.0, 6.0], V=[4.6, 5.0, 5.3], N=64,
              floquet=True, finite_size=False, out=out, backend="inline")  # fmt: skip
    return out


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


def test_missing_store_is_a_message(tmp_path):
    sc = AtlasScene(ExplorerState())
    sc.store.value = str(tmp_path / "nothing.zarr")
    sc.wait_idle(60)
    sc.refresh()
    assert "no atlas store" in sc.last_message
