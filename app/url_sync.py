"""The page ↔ its URL: the session's query read and validated into the state, and the address
bar kept equal to the state.

(a, b, law, w_plus, V, mode, tab, N, tol, atlas) live in the URL query string.  A URL is
validated like any input (:func:`app.url_state.parse_url`): an invalid value is named with its
valid range in the sidebar, every other value is kept, and the address bar is rewritten to what
is shown.  A URL's law still being built when the page is (``URL_LAW_WAIT_S``) is shown or named
once the law worker answers (:meth:`app.explorer.Explorer.url_law_checked`).

Kept apart from the page (:mod:`app.explorer`): only a served session has a URL; an Explorer
built in a test or a notebook never touches it.
"""

from __future__ import annotations

import logging
import urllib.parse

import panel as pn
from panel.io.state import set_curdoc

from . import compute
from .explorer import Explorer
from .state import STATE_PARAMS, URL_PARAMS
from .url_state import state_from_url, url_query
from .widgets import document_gone

log = logging.getLogger("fpu-explorer")


def session_query() -> dict[str, str]:
    """The page's URL query as {name: first value} (server sessions; empty otherwise)."""
    args = pn.state.session_args or {}
    out = {}
    for k, v in args.items():
        if k in URL_PARAMS and v:
            raw = v[0]
            out[k] = raw.decode("utf-8", "replace") if isinstance(raw, bytes) else str(raw)
    return out


def from_url(lazy: bool = True) -> Explorer:
    """The session's Explorer built from its validated URL (one state, no default-then-URL
    double render), with the URL rewritten to the state and kept in sync with it; ``lazy``:
    a hidden scene is built when its tab is opened (see Explorer)."""
    state, errors = state_from_url(session_query())
    text = state.expression
    # a law still being built (see parse_url_value): the page is built meanwhile, and once the
    # law's outcome is known (maybe during this build) the explorer shows it or names it
    pending = bool(text) and compute.laws.lookup_law(text) is None
    explorer = Explorer(state, url_errors=errors, lazy=lazy)
    if pending:
        doc = pn.state.curdoc

        def built(fut) -> None:  # in the law worker's watcher thread (or here, if done)
            if document_gone(doc):
                return  # the browser left before the law was built
            try:
                with set_curdoc(doc):
                    explorer.url_law_checked(text, fut.result())
            except Exception:  # noqa: BLE001 - the session may have closed meanwhile
                if not document_gone(doc):
                    log.exception("applying the URL's law %r", text[:60])

        compute.laws.request_law(text).add_done_callback(built)
    loc = pn.state.location
    if loc is not None:
        st = explorer.state

        def wanted() -> str:
            # the whole query is rewritten (not Location.update_query, which parses the old
            # query — and raises on a 5000-digit value)
            return "?" + urllib.parse.urlencode(url_query(st))

        def push(*_):
            loc.search = wanted()

        def reassert(event):
            # The browser's Location view reports its own (original) search once it starts;
            # under load that report can arrive after the onload push, and would leave the
            # address bar stale.  Any search that is not the state's is answered with the state's.
            if event.new != wanted():
                push()

        push()
        pn.state.onload(push)  # again once the browser's own location has been synced
        st.param.watch(push, list(STATE_PARAMS))
        loc.param.watch(reassert, ["search"])
    return explorer
