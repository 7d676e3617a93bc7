"""Process-wide guards around Panel/Bokeh's server (installed by app/main.py, idempotent).

* :func:`tolerate_long_url_values`: a URL value longer than CPython's int-string limit is kept as
  text by Panel's Location (the limit itself stays on for the whole server);
* :func:`serve_document_locally`: every stylesheet of a session's document resolves to this
  server from the start of its build, never to cdn.holoviz.org;
* :func:`tolerate_detached_sessions`: a websocket closing after its session was discarded is
  no traceback.
"""

from __future__ import annotations

import logging
import urllib.parse

import panel.io.location as pn_location
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
