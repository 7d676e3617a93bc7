"""The Atlas scene (app/views/atlas.py), without a browser: it shows a store written by
``fpucore.atlas`` (the heat map's values are the store's), refuses what it cannot show with a
message, reads stores only below the atlas root, and a click on a cell picks that cell's (w₊, V)
and the atlas's N and marks the cell.  Its small atlas is a job of app.compute: in a worker
process, cached on its exact request, with progress, and Cancel answers within a second."""

from __future__ import annotations

import re
import time

import numpy as np
import pytest
import zarr

pytest.importorskip("panel")

from scene_checks import assert_cancel_answers_within  # noqa: E402 - tests/support

from app import compute  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.url_state import parse_url, url_query  # noqa: E402
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
    group = zarr.open_group(store, mode="r", zarr_format=2)  # the store as written, raw
    ref = np.where(group["status"][:] == "ok", group["max_modulus"][:] - 1.0, np.nan)
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
    # the valid range names the server's data directory, never its absolute path
    assert "a path below the server's data directory" in sc.last_message, sc.last_message
    assert str(root.resolve()) not in sc.last_message
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
    assert "# N=64" in header and "# tol=" + repr(sc.atlas_data.tol) in header
    assert not any("N=500" in ln for ln in header)


def small_run(sc: AtlasScene, n_w: int, n_V: int, N: int):
    sc.n_w.value, sc.n_V.value, sc.N_run.value = n_w, n_V, N
    sc._want_run = True  # the "Run a small atlas" button
    return sc.refresh()


def test_the_small_atlas_is_a_cached_job_and_its_code_reproduces_it():
    """The same atlas asked again (by this session or another) is answered from the cache:
    the same entry, with what the run cost; the Python shown recomputes the very numbers.
    (The cache is emptied first: another test of the session may have run this atlas.)"""
    compute.CACHE.clear()
    sc = AtlasScene(ExplorerState())
    info = small_run(sc, 2, 3, 80)
    assert info is not None, sc.last_message
    label, c = info.timings[0]
    assert label == "atlas run (6 points)" and not c.cached
    req = sc.atlas_request()
    assert compute.is_cached(compute.laws.law(-1.0, 10.0), req)
    first = sc.atlas_data
    t0 = time.perf_counter()
    again = small_run(AtlasScene(ExplorerState()), 2, 3, 80)  # another session, same request
    assert time.perf_counter() - t0 < 5.0  # no worker involved (a run here takes longer)
    label2, c2 = again.timings[0]
    assert label2 == label and c2.cached and c2.elapsed_s == c.elapsed_s
    assert c2.value is c.value  # the cached result itself: nothing was recomputed
    # the shown code, run here (its own pool), gives the scene's numbers bit for bit
    scope: dict = {}
    exec(sc.python_code(), scope)  # noqa: S102 - the app's own generated code
    data = scope["data"]
    assert np.array_equal(data.status, first.status)
    for name in ("amplitude", "energy", "residual", "max_modulus", "max_modulus_error"):
        assert np.array_equal(getattr(data, name), getattr(first, name), equal_nan=True), name


def test_the_run_time_stays_after_a_click():
    """A re-render of the background run (after a click) keeps what the run cost."""
    sc = AtlasScene(ExplorerState())
    info = small_run(sc, 2, 3, 80)
    assert info is not None, sc.last_message
    label, c = info.timings[0]
    w, V = sc.atlas_data.w_plus, sc.atlas_data.V
    assert sc.pick(w[1], V[0])
    sc.wait_idle(60)
    again = sc.refresh()
    label2, c2 = again.timings[0]
    assert label2 == label and label.startswith("atlas run (6 points")
    assert c2.elapsed_s == c.elapsed_s and c2.cached


def test_a_running_atlas_shows_its_progress_and_cancel_frees_its_worker_within_a_second():
    sc = AtlasScene(ExplorerState())
    seen: list[float] = []
    show = sc.set_progress
    sc.set_progress = lambda done, *a, **k: (seen.append(done), show(done, *a, **k))
    sc.n_w.value, sc.n_V.value, sc.N_run.value = 6, 4, 400  # rows of 4 spectra at N = 400
    cancelled = compute.workers.CANCELLED[0]
    sc._want_run = True
    sc.request()
    t_end = time.monotonic() + 300
    while not any(0 < x < 1 for x in seen) and time.monotonic() < t_end:
        time.sleep(0.05)
    assert any(0 < x < 1 for x in seen), seen  # a row done: the bar moved
    assert seen == sorted(seen)
    assert re.match(r"atlas points: \d+ %", sc.progress_text.object), sc.progress_text.object
    assert compute.workers.jobs_in_flight() == 1 and sc.busy_shown
    assert_cancel_answers_within(sc, 1.0)
    assert compute.workers.CANCELLED[0] == cancelled + 1 and compute.workers.jobs_in_flight() == 0
    assert not compute.is_cached(compute.laws.law(-1.0, 10.0), sc.atlas_request())
    assert sc.atlas_data is None  # nothing half-done on screen


def test_a_superkink_atlas_is_drawn_against_V_and_a_click_opens_that_superkink(root):
    """A superkink store (rows: branches, over V only; the README's ``sk.zarr``) was refused
    ("no (w₊, V) map").  Now each branch's max |μ| − 1 is drawn against V (the store's values,
    on log₁₀), and a click on a point sets superkink mode and the w₊ of that V on its branch:
    eq. wpm_cubic, w₊ = w* ∓ √((c_max² − V²)/|a|), evaluated here."""
    out = root / "sk.zarr"
    Vs = [4.9, 5.3, 5.7]
    atlas.run(CubicLaw(-1.0, 10.0), "superkink", rows=["lower", "upper"], V=Vs, N=64,
              floquet=True, finite_size=False, out=out, backend="inline")  # fmt: skip
    st = ExplorerState()
    sc = AtlasScene(st)
    sc.store.value = str(out)
    sc.wait_idle(120)
    info = sc.refresh()
    assert info is not None and sc.last_message is None, sc.last_message
    assert sc.fig_sk.visible and not sc.fig.visible
    group = zarr.open_group(out, mode="r", zarr_format=2)
    ok = group["status"][:] == "ok"
    for i, branch in enumerate(["lower", "upper"]):
        src = sc.sk_points[branch][1]
        ref = group["max_modulus"][:][i] - 1.0
        keep = ok[i]
        assert np.array_equal(np.asarray(src.data["x"]), np.asarray(Vs)[keep])
        assert np.allclose(src.data["y"], np.log10(np.maximum(ref[keep], 1e-16)), rtol=0, atol=0)
    # a click at V = 5.3 on the upper branch's point
    y_upper = sc.sk_points["upper"][1].data["y"][1]
    assert sc.pick_superkink(5.31, y_upper)
    a, b, V = -1.0, 10.0, 5.3
    w_star, c_max2 = b / (3 * abs(a)), 1 + b * b / (3 * abs(a))
    assert st.mode == "superkink"
    assert abs(st.w_plus - (w_star + ((c_max2 - V * V) / abs(a)) ** 0.5)) < 1e-12
    assert abs(st.V - V) < 1e-12 and st.N == 64
