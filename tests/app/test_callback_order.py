"""Next-tick callbacks of a served document reach the session when queued, in order, none lost —
also while the document is on hold (app.server_guards.schedule_callbacks_in_order).

The scenes' worker threads queue their plot updates, and Panel the status texts they write, as
next-tick callbacks; Bokeh kept the notice of a callback queued during a hold until the hold
ended.  The state walk's diagram then showed the previous step's current point under the new
step's status text.  A recording receiver stands in for the server session (which puts each
callback it is told about on its event loop, first told, first run)."""

from __future__ import annotations

import sys
import threading

import pytest
from bokeh.document import Document
from bokeh.document.callbacks import DocumentCallbackManager
from bokeh.models import ColumnDataSource

from app import server_guards


class Session:
    """Records what the server session is told: callbacks (in order) and model changes."""

    def __init__(self):
        self.callbacks: list = []
        self.patches: list = []

    def _session_callback_added(self, event) -> None:
        self.callbacks.append(event.callback)

    def _document_patched(self, event) -> None:
        self.patches.append(event)


@pytest.fixture
def guarded(monkeypatch):
    monkeypatch.setattr(
        DocumentCallbackManager, "trigger_on_change", server_guards.trigger_on_change_in_order
    )


def served() -> tuple[Document, Session]:
    doc, session = Document(), Session()
    doc.callbacks.on_change_dispatch_to(session)
    return doc, session


def test_a_callback_queued_during_a_hold_reaches_the_session_at_once(guarded):
    doc, session = served()
    src = ColumnDataSource({"y": [1.0]})
    doc.add_root(src)
    session.patches.clear()
    doc.hold("combine")
    src.data = {"y": [2.0]}
    cb = doc.add_next_tick_callback(lambda: None)
    assert session.callbacks == [cb]
    assert session.patches == []  # model changes are still held until the hold ends
    doc.unhold()
    assert len(session.patches) == 1


def test_callbacks_run_in_the_order_queued_when_a_hold_is_lifted_in_between(guarded):
    """Panel's handler thread ends its hold by lifting it for a moment to queue the release
    (panel.io.document.hold); a worker's callback queued in that moment was told to the session
    before one the worker had queued earlier, during the hold: the older plot update ran last."""
    doc, session = served()
    doc.hold("combine")

    first = doc.add_next_tick_callback(lambda: None)
    doc.callbacks._hold = None  # Panel: "Clear the hold around scheduling the callback"
    second = doc.add_next_tick_callback(lambda: None)
    doc.callbacks._hold = "combine"
    doc.unhold()
    assert session.callbacks == [first, second]


def test_no_callback_is_lost_while_another_thread_holds_and_releases(guarded):
    """A worker queues callbacks while the loop holds and releases the document; Bokeh's release
    copies the held events and then replaces the list, so an event appended in between was lost
    (without the guard 1-5 of 3000 per run here)."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads often: the window is a few bytecodes wide
    try:
        lost = []
        for _ in range(5):
            doc, session = served()
            n, done = 3000, threading.Event()

            def worker(doc=doc, n=n, done=done):
                for _ in range(n):
                    doc.add_next_tick_callback(lambda: None)
                done.set()

            t = threading.Thread(target=worker)
            t.start()
            while not done.is_set():
                doc.hold("combine")
                doc.unhold()
            t.join()
            lost.append(n - len(session.callbacks))
    finally:
        sys.setswitchinterval(old)
    assert lost == [0] * 5
