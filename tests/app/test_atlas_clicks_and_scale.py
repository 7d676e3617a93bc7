"""The Atlas scene: a click on a blank cell (no wave) leaves the state valid and says why (it set
an invalid V, and every scene then said "out of range"); max |μ| − 1, which spans decades, is
drawn on the log scale its colour bar names."""

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
    # w₊ = 6: V_SK = 7√5/3 ≈ 5.2175, and c₋(6) < 5.6: V = 5.6 lies beyond both ranges (blank)
    out = tmp_path_factory.mktemp("atlas") / "a.zarr"
    atlas.run(CubicLaw(-1.0, 10.0), "solitary", rows=[1.0, 6.0], V=[4.6, 5.0, 5.6], N=64,
              floquet=True, finite_size=False, out=out, backend="inline")  # fmt: skip
    return out


@pytest.fixture(autouse=True)
def root(store, monkeypatch):
    monkeypatch.setenv("FPU_ATLAS_ROOT", str(store.parent))


def shown(store) -> tuple[ExplorerState, AtlasScene]:
    st = ExplorerState()
    sc = AtlasScene(st)
    sc.store.value = str(store)
    sc.wait_idle(120)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    return st, sc


def test_a_click_on_a_blank_cell_keeps_the_state_and_says_why(store):
    st, sc = shown(store)
    d = sc.atlas_data
    blank = np.argwhere(~d.ok)
    assert blank.size, "the fixture needs a blank cell"
    i, j = blank[0]
    before = (st.w_plus, st.V)
    assert not sc.pick(float(d.w_plus[i]), float(d.V[j]))
    assert (st.w_plus, st.V) == before and st.problem() is None
    sc.wait_idle(60)
    assert sc.alert.visible and "No wave at the cell" in sc.alert.object


def test_the_excess_is_drawn_on_a_log_scale(store):
    _, sc = shown(store)
    z = sc.last_z
    img = np.asarray(sc.src.data["image"][0]).T
    ok = np.isfinite(z)
    np.testing.assert_allclose(img[ok], np.log10(np.maximum(z[ok], 1e-16)))
    assert sc.colorbar.title.startswith("log₁₀(max |μ| − 1)")
    assert (sc.mapper.low, sc.mapper.high) == (img[ok].min(), img[ok].max())
