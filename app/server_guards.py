"""Process-wide guards around Panel/Bokeh's server (installed by app/main.py, idempotent).

* :func:`tolerate_long_url_values`: a URL value longer than CPython's int-string limit is kept as
  text by Panel's Location (the limit itself stays on for the whole server);
* :func:`serve_document_locally`: every stylesheet of a session's document resolves to this
  server from the start of its build, never to cdn.holoviz.org;
* :func:`tolerate_detached_sessions`: a websocket closing after its session was discarded is
  no traceback;
* :func:`schedule_callbacks_in_order`: a next-tick callback reaches the event loop when it is
  added, in the order added, also while the document is on hold (model updates from worker
  threads are applied in the order the threads queued them; none is lost).
"""

from __future__ import annotations

import logging
import urllib.parse

import panel.io.location as pn_location
from bokeh.document.callbacks import DocumentCallbackManager, invoke_with_curdoc
from bokeh.document.events import SessionCallbackAdded, SessionCallbackRemoved
from bokeh.server.views.ws import WSHandler
from panel.io.resources import LOCAL_DIST

log = logging.getLogger("fpu-explorer")

_panel_parse_query = pn_location.parse_query


def _parse_query_tolerant(query: str) -> dict:
    """Panel's ``parse_query``, except that a value it cannot convert stays a string."""
    try:
        return _panel_parse_query(query)
    except ValueError:
        return dict(urllib.parse.parse_qsl(query[1:]))


def tolerate_long_url_values() -> None:
    """Panel's Location converts every URL value itself (``int(v)`` for digits); a value longer
    than CPython's int-string limit (4300 digits) made that a traceback at every location sync
    (the server once lifted the limit for the whole process instead).  The app reads its own
    parameters from the raw query and refuses values longer than app.state.MAX_URL_VALUE, so
    Panel's parse keeps such a value as text; CPython's guard against quadratic-time
    conversions stays on for everything else."""
    pn_location.parse_query = _parse_query_tolerant


def serve_document_locally(doc) -> None:
    """Panel resolves a component's stylesheets against ``doc._template_variables['dist_url']``
    and falls back to cdn.holoviz.org while it is unset — i.e. until the page's HTML is written,
    after the build.  A model created in that window by another thread (a scene's render, the
    spinner's loading.css, a law's answer) kept a CDN URL (seen in 7 of 36 sessions: loading.css,
    loadingspinner.css, bootstrap.css).  Set it to this server's path at the start of the build
    (the value Panel's page writer sets for ``BOKEH_RESOURCES=server``)."""
    doc._template_variables.setdefault("dist_url", LOCAL_DIST)


_bokeh_on_close = WSHandler.on_close


def _on_close(self) -> None:
    connection = getattr(self, "connection", None)
    if connection is not None and getattr(connection, "_session", True) is None:
        # Bokeh detaches a connection's session only in ``client_lost``, i.e. this close's
        # bookkeeping already ran (a second close event); its on_close would assert on the
        # missing session.  Nothing is left to notify or release: safe to stop here.
        log.debug("websocket closed after its session was released")
        return
    _bokeh_on_close(self)


def tolerate_detached_sessions() -> None:
    """Bokeh's ``WSHandler.on_close`` reads ``connection.session``, which asserts once the
    session was detached; 17-22 such tracebacks were logged per ten-session run as browsers
    closed.  The patched handler returns early in exactly that case (see :func:`_on_close`)."""
    WSHandler.on_close = _on_close


_bokeh_trigger_on_change = DocumentCallbackManager.trigger_on_change


def trigger_on_change_in_order(self, event) -> None:
    if not hasattr(self, "_change_callbacks"):
        # the document was destroyed (its browser left): a worker thread that finishes later
        # changes models nobody shows; Bokeh's own trigger would raise on the deleted table
        return
    if not isinstance(event, SessionCallbackAdded | SessionCallbackRemoved):
        _bokeh_trigger_on_change(self, event)
        return
    # never held: the session schedules (or drops) the callback on its loop now
    doc = self._document()
    if doc is None:
        return

    def dispatch() -> None:
        for cb in self.change_callbacks():
            cb(event)

    invoke_with_curdoc(doc, dispatch)


def schedule_callbacks_in_order() -> None:
    """Bokeh tells the server session about a new next-tick callback with a document event, and
    while the document is on hold it keeps that event with the held model changes until the
    hold ends: the callback is not on the event loop yet.  Panel holds a served document on
    the loop (around each of its model updates) and from its handler threads (around each
    batch of browser events, released by a next-tick callback; it lifts the hold for a moment
    to queue that release).  The scenes' worker threads queue their plot updates and Panel
    their status texts with next-tick callbacks at any time, so

    * a callback queued while the hold was lifted ran before one queued earlier and held: the
      state walk's diagram showed the previous step's current point (its data applied last)
      under the status text of the new step, and stayed so;
    * a worker thread appending its event while the loop took the held events away (Bokeh's
      ``unhold``, Panel's ``unlocked``: copy, then replace the list) lost it: the callback
      never ran.

    Here the session hears of a callback (added or removed) at once, hold or not, so callbacks
    run in the order they were queued, whichever thread queued them; model changes are still
    held as before."""
    DocumentCallbackManager.trigger_on_change = trigger_on_change_in_order
