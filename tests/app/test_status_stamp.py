"""State first, stamp after: the parameter line under a scene's status changes only together
with the result it describes, and a request in flight names its own parameters on a
"computing …" line beside the spinner (the issue: after Paper → Riemann1, then Paper → stabSW,
the Riemann run's velocities stood for seconds under stabSW's parameter line)."""

from __future__ import annotations

import html
import re
import time

import pytest

pytest.importorskip("panel")

from app.explorer import Explorer  # noqa: E402


def sample(sc, timeout: float = 300.0) -> list[tuple[str, bool, str]]:
    """(status, computing line visible, computing text) every few ms until the scene is idle."""
    seen = []
    t_end = time.monotonic() + timeout
    while time.monotonic() < t_end:
        seen.append((sc.status.object, sc.busy_shown, sc.computing_text.object))
        with sc._lock:
            if not sc._running and not sc._pending:
                break
        time.sleep(0.005)
    seen.append((sc.status.object, sc.busy_shown, sc.computing_text.object))
    return seen


def stamp_of(status: str) -> str:
    """The parameter line as the reader sees it (Markdown escapes undone)."""
    return html.unescape(status.rsplit("Parameters:", 1)[-1].replace("\\", ""))


def test_a_figure_after_a_figure_never_shows_a_result_under_the_others_stamp():
    ex = Explorer(lazy=True)
    ex.scene("paper").open("Riemann1")
    sc = ex.scene("simulation")
    assert sc.wait_idle(300.0) and sc.last_message is None, sc.last_message
    assert "run: riemann" in stamp_of(sc.status.object)
    ex.scene("paper").open("stabSW")
    seen = sample(sc)
    assert "TW-seeded" in seen[-1][0] and "run: seeded" in stamp_of(seen[-1][0])
    for status, _, _ in seen:
        if "Riemann data" in status:  # the previous result: its own parameters, all of them
            stamp = stamp_of(status)
            assert "run: riemann" in stamp and "w_left=4.6" in stamp and "L=3600" in stamp
        if "TW-seeded" in status:
            assert "run: seeded" in stamp_of(status) and "V=5.2174919476" in stamp_of(status)


def untimed(status: str) -> str:
    return re.sub(r"server [0-9.]+ (ms|s)", "server …", status)


def test_a_run_in_flight_names_its_parameters_while_the_last_result_keeps_its_own():
    ex = Explorer(lazy=True)
    ex.scene("paper").open("SWdyn")  # Gaussian, t_end = 200
    sc = ex.scene("simulation")
    assert sc.wait_idle(300.0) and sc.last_message is None, sc.last_message
    before = sc.status.object
    assert "t_end=200.0" in stamp_of(before)
    sc.t_end.value = 400.0  # a new run (not cached), twice as long: longer than the spinner's
    # delay (0.25 s) also with a warm JIT (t_end = 150 once ran within it in a full-suite run)
    sc._want_run = True  # the "Run simulation" button
    sc.request()
    seen = sample(sc)
    in_flight = [s for s in seen if s[1]]
    assert in_flight, "no computing line was shown while the run was in flight"
    for status, _, computing in in_flight:
        # the last result and its stamp, unchanged (a repaint of it from the cache may time
        # its own drawing anew: the server time is not part of the result)
        assert untimed(status) == untimed(before)
        assert computing.startswith("computing … for ") and "t_end=400.0" in computing
    assert "t_end=400.0" in stamp_of(seen[-1][0]) and not seen[-1][1]


def test_a_state_moved_during_a_render_is_never_drawn_under_the_old_stamp(monkeypatch):
    """The Diagrams scene takes its stamp when a render starts and reads the current point
    (w₊, V) later: a V set in between (a second slider event handled while the render runs) was
    drawn under the previous state's parameter line.  Such a render is not shown; the render
    of the new state that follows is.  Checked at every status written: the current point is
    the stamp's (w₊, V)."""
    from app import compute
    from app.state import ExplorerState

    ex = Explorer(ExplorerState(tab="diagram"), lazy=True)
    sc = ex.scene("diagram")
    original = compute.run
    moved = []

    def run(lw, req, *a, **kw):  # the existence diagram: after the stamp, before the point
        if isinstance(req, compute.ExistenceRequest) and not moved:
            moved.append(True)
            ex.state.V = 5.1  # as the server's event loop does while the worker renders
        return original(lw, req, *a, **kw)

    monkeypatch.setattr(compute, "run", run)
    shown = []
    write = sc._write_status

    def write_status(info, t0, partial=False):
        data = sc.exist_point[1].data
        shown.append((stamp_of_plain(sc._stamp), list(data["x"]), list(data["y"])))
        write(info, t0, partial)

    monkeypatch.setattr(sc, "_write_status", write_status)
    sc.request()
    assert sc.wait_idle(120.0) and sc.last_message is None, sc.last_message
    assert moved and shown, (moved, shown)
    for stamp, x, y in shown:
        assert x == [stamp["w_plus"]] and y == [stamp["V"]], (stamp, x, y)
    assert shown[-1][0]["V"] == 5.1


def stamp_of_plain(stamp: str) -> dict:
    """w_plus and V of a state stamp (app.views.formatting.state_stamp)."""
    parts = dict(p.split("=", 1) for p in stamp.split() if "=" in p)
    return {"w_plus": float(parts["w_plus"]), "V": float(parts["V"])}
