"""Every resource of the page from the server itself (no CDN: the dashboard works offline).

The server runs with ``BOKEH_RESOURCES=server``, but Panel 1.9 decides "CDN or server" per
stylesheet from a *process-wide* setting that its page renderer switches temporarily
(``panel.io.resources.set_resource_mode``) while it writes a page.  A scene rendering in its
worker thread at that moment (e.g. the loading spinner's ``loading.css``, a Markdown pane's
``markdown.css``) got cdn.holoviz.org URLs — seen as failed requests offline in 2 of 5 tab walks.
:func:`serve_locally` pins that decision to "server" for this process.
"""

from __future__ import annotations

import os

import panel.io.resources as pn_resources
import panel.template.base as pn_template_base


def never_cdn() -> bool:
    """Replacement of Panel's ``use_cdn``: this server serves its own resources."""
    return False


def serve_locally() -> None:
    """Pin Panel's resource resolution to this server (idempotent)."""
    os.environ.setdefault("BOKEH_RESOURCES", "server")
    pn_resources.use_cdn = never_cdn
    pn_template_base.use_cdn = never_cdn
