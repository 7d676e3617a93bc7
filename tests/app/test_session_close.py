"""A scene whose browser session has closed stops quietly.

When a browser leaves, Bokeh destroys the session's document and clears every model's
properties (they read as class defaults afterwards: a figure's Range1d becomes a DataRange1d,
a renderer loses its glyph).  A render still running for that session used to write into those
emptied models and log a traceback ("unexpected attribute 'reset_start' to DataRange1d").  Here
the document is served (it has a session context) and then destroyed as Bokeh does it.
"""

from __future__ import annotations

import logging
import weakref

import pytest

pytest.importorskip("panel")

from bokeh.document import Document  # noqa: E402
from panel.io.state import set_curdoc  # noqa: E402

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


class _Request:
    arguments: dict = {}
    cookies: dict = {}
    headers: dict = {}


class _SessionContext:
    """What Panel reads of a served session's context while a page is built."""

    request = _Request()
    id = "test-session"
    server_context = None


def served(key: str, ctx: _SessionContext, **params):
    """A scene built inside a document that a (fake) server session holds."""
    doc = Document()
    doc._session_context = weakref.ref(ctx)
    with set_curdoc(doc):
        st = ExplorerState(**params)
        sc = BY_KEY[key](st)
        doc.add_root(sc.panel.get_root(doc))
    return doc, st, sc


def close(doc: Document) -> None:
    """Bokeh's own teardown of a session's document (ServerSession.destroy)."""

    def subscriber(event):
        return None

    doc.on_change(subscriber)
    doc.destroy(subscriber)


@pytest.mark.parametrize("key", ["force", "phase", "diagram"])
def test_render_after_the_session_closed_logs_nothing(key, caplog):
    ctx = _SessionContext()
    doc, st, sc = served(key, ctx, w_plus=1.0, V=5.0)
    assert sc.refresh() is not None and sc.last_message is None
    assert not sc.session_closed and not sc.superseded()
    close(doc)
    assert sc.session_closed
    assert sc.superseded()  # a running job of this session is abandoned (the pool is freed)
    st.V = 5.1
    with caplog.at_level(logging.WARNING):
        assert sc.refresh() is None
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING], caplog.text
    assert sc.last_message is None  # nobody is left to read a message


def test_request_after_the_session_closed_starts_no_render(caplog):
    ctx = _SessionContext()
    doc, st, sc = served("phase", ctx, w_plus=1.0, V=5.0)
    sc.refresh()
    renders = sc.renders
    close(doc)
    with caplog.at_level(logging.WARNING):
        st.V = 5.2
        sc.request()
        assert sc.wait_idle(10.0)
    assert sc.renders == renders
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING], caplog.text


def test_a_job_stopped_by_the_server_shutting_down_logs_no_traceback(caplog):
    """The server stopping (SIGTERM: atexit shuts the worker pool down) while a Floquet job
    runs for a session: the scene says it was stopped, and the log has no 'scene failed'
    traceback (it had one in the server log of every run stopped mid-job)."""
    import time

    from app import compute

    sc = BY_KEY["floquet"](ExplorerState(N=1200, tol=1e-10))
    sc.request()
    t_end = time.monotonic() + 240
    while not sc.busy_shown and time.monotonic() < t_end:
        time.sleep(0.05)
    assert compute.workers.jobs_in_flight() >= 1
    with caplog.at_level(logging.ERROR, logger="fpu-explorer"):
        compute.workers.shutdown_executor()
        assert sc.wait_idle(30)
    assert not [r for r in caplog.records if r.levelno >= logging.ERROR], caplog.text
    assert (sc.last_message or "").startswith("Stopped: the server's worker processes"), (
        sc.last_message
    )


class _ServerSession:
    """The part of Bokeh's ServerSession the scene reads: its open websocket connections."""

    connection_count = 0


def test_a_job_stops_as_soon_as_the_browser_leaves():
    """The browser closes the page mid-job: its websocket goes (connection count 1 → 0) long
    before Bokeh destroys the session (unused for 15 s, checked every 17 s).  The job is
    abandoned — and its worker freed — within a second, not half a minute later."""
    import time

    from app import compute

    ctx = _SessionContext()
    ctx._session = _ServerSession()
    doc, st, sc = served("floquet", ctx, w_plus=1.0, V=5.0, N=1300, tol=1e-10)
    assert not sc.session_closed  # built, not yet connected: a page being loaded is not gone
    ctx._session.connection_count = 1  # the page's websocket
    cancelled = compute.workers.CANCELLED[0]
    sc.request()
    t_end = time.monotonic() + 240
    while not sc.busy_shown and time.monotonic() < t_end:
        time.sleep(0.05)
    assert compute.workers.jobs_in_flight() >= 1 and not sc.session_closed
    ctx._session.connection_count = 0  # the browser left; the session is not destroyed yet
    t0 = time.perf_counter()
    assert sc.wait_idle(10)
    assert time.perf_counter() - t0 < 1.0
    assert (
        sc.session_closed and compute.workers.CANCELLED[0] == cancelled + 1
    )  # its worker was freed
